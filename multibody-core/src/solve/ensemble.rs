//! Ensembles: one compiled system solved for many sets of values in parallel, on a
//! thread pool of rayon; the system is shared by every solve, not copied.

use rayon::prelude::*;

use crate::Error;
use crate::simplify::SimplifiedSystem;

use super::error::SolveError;
use super::options::SolverOptions;
use super::problem::DaeProblem;
use super::solution::Solution;

/// Options of [`solve_ensemble`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EnsembleOptions {
    /// Threads to solve on (default 0: one per core, rayon's global pool).
    pub threads: usize,
}

/// Solves the problem of `sys` over `tspan` for each entry of `values` (parameter values
/// and fixed start values by name, as [`DaeProblem::new`] takes them), in parallel;
/// the results are in the order of `values`, each the solution or the error of that
/// problem (initialization or integration).
///
/// ```
/// use multibody_core::model::System;
/// use multibody_core::simplify::structural_simplify;
/// use multibody_core::solve::{EnsembleOptions, SolverOptions, solve_ensemble};
///
/// // x' = -k x for three values of k.
/// let mut sys = System::new("decay");
/// let x = sys.var("x");
/// let k = sys.param("k", 1.0);
/// sys.equation(x.der(), -k * x);
/// let ssys = structural_simplify(&sys)?;
/// let values: Vec<Vec<(String, f64)>> = [1.0, 2.0, 3.0]
///     .iter()
///     .map(|&k| vec![("k".to_string(), k), ("x".to_string(), 1.0)])
///     .collect();
/// let solutions = solve_ensemble(&ssys, (0.0, 1.0), &values, &SolverOptions::default(), &EnsembleOptions::default())?;
/// for (s, k) in solutions.iter().zip([1.0, 2.0, 3.0]) {
///     let x1 = s.as_ref().unwrap().final_value("x")?;
///     assert!((x1 - (-k as f64).exp()).abs() < 1e-4);
/// }
/// # Ok::<(), multibody_core::Error>(())
/// ```
///
/// # Errors
/// The outer result fails only where the thread pool cannot be built.
pub fn solve_ensemble(
    sys: &SimplifiedSystem,
    tspan: (f64, f64),
    values: &[Vec<(String, f64)>],
    options: &SolverOptions,
    ensemble: &EnsembleOptions,
) -> Result<Vec<Result<Solution, Error>>, Error> {
    let solve_one = |v: &Vec<(String, f64)>| -> Result<Solution, Error> {
        let named: Vec<(&str, f64)> = v.iter().map(|(n, x)| (n.as_str(), *x)).collect();
        DaeProblem::new(sys, &named, tspan)?.solve(options)
    };
    let solve_all = || values.par_iter().map(solve_one).collect::<Vec<_>>();
    if ensemble.threads == 0 {
        return Ok(solve_all());
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(ensemble.threads)
        .build()
        .map_err(|e| SolveError {
            model: sys.name().to_string(),
            t: tspan.0,
            flag: "THREADS".into(),
            message: format!("cannot start {} threads: {e}", ensemble.threads),
        })?;
    Ok(pool.install(solve_all))
}
