//! Steady states: the states at which the derivatives vanish (or take given rates),
//! with some variables and parameters fixed, by Gauss-Newton iteration on the states
//! through consistent points and the exact linearization.

use nalgebra::{DMatrix, DVector};

use crate::Error;
use crate::simplify::SimplifiedSystem;

use super::error::SolveError;
use super::{DaeProblem, OperatingPoint, linearize};

/// Options of [`steady_state`].
#[derive(Clone, Debug, PartialEq)]
pub struct SteadyStateOptions {
    /// Largest derivative error accepted (absolute, in the states' units per second);
    /// default 1e-10.
    pub tolerance: f64,
    /// Iterations before giving up; default 50.
    pub max_iterations: usize,
}

impl Default for SteadyStateOptions {
    fn default() -> Self {
        SteadyStateOptions {
            tolerance: 1e-10,
            max_iterations: 50,
        }
    }
}

fn failed(sys: &SimplifiedSystem, message: String) -> Error {
    SolveError {
        model: sys.model.name.clone(),
        t: 0.0,
        flag: "STEADY_STATE".into(),
        message,
    }
    .into()
}

/// The steady state of `sys`: the states (of [`SimplifiedSystem::states`]) at which
/// each state's derivative is 0, or its rate in `rates` (a steady motion; a rate of
/// `f64::NAN` leaves it free, for a cyclic state such as a wheel's angle at constant
/// speed, whose value is then fixed in `values`). `values` fixes parameters and variables (a fixed state is
/// not solved for); `guesses` start the free states (else their start values). Fails
/// naming the states when the steady state is not unique (the derivatives do not
/// determine them) or is not found.
pub fn steady_state(
    sys: &SimplifiedSystem,
    values: &[(&str, f64)],
    guesses: &[(&str, f64)],
    rates: &[(&str, f64)],
    options: &SteadyStateOptions,
) -> Result<OperatingPoint, Error> {
    let states = sys.states();
    for (name, _) in rates {
        if !states.iter().any(|s| s == name) {
            return Err(failed(
                sys,
                format!("`{name}` has a rate but is not a state"),
            ));
        }
    }
    let fixed = |s: &str| values.iter().any(|(n, _)| *n == s);
    let free: Vec<usize> = (0..states.len()).filter(|&i| !fixed(&states[i])).collect();
    // Each state's unknown (the states are the differential unknowns, in order: the
    // states of the linearization too).
    let unknown: Vec<usize> = (0..sys.sorted.mass_matrix_diagonal.len())
        .filter(|&k| sys.sorted.mass_matrix_diagonal[k] == 1.0)
        .collect();
    let rate = |i: usize| {
        rates
            .iter()
            .find(|(n, _)| *n == states[i])
            .map_or(0.0, |&(_, r)| r)
    };
    // The derivatives to match: those without a free rate.
    let rows: Vec<usize> = (0..states.len()).filter(|&i| !rate(i).is_nan()).collect();
    if free.len() > rows.len() {
        return Err(failed(
            sys,
            format!(
                "the steady state is not unique: {} free states and {} derivatives to \
                 match (fix the cyclic ones with a value)",
                free.len(),
                rows.len()
            ),
        ));
    }
    // Start: the guesses, else the start values the initialization gives.
    let start = DaeProblem::new_with_guesses(sys, values, guesses, (0.0, 1.0))?.operating_point();
    let guess = |s: &str| guesses.iter().find(|(n, _)| *n == s).map(|&(_, v)| v);
    let mut x: Vec<f64> = free
        .iter()
        .map(|&i| guess(&states[i]).unwrap_or(start.u[unknown[i]]))
        .collect();
    let mut last = f64::INFINITY;
    for _ in 0..options.max_iterations {
        let mut with_x: Vec<(&str, f64)> = values.to_vec();
        for (&i, &v) in free.iter().zip(&x) {
            with_x.push((states[i].as_str(), v));
        }
        let point =
            DaeProblem::new_with_guesses(sys, &with_x, guesses, (0.0, 1.0))?.operating_point();
        let lin = linearize(sys, &point, &[], &[])?;
        let r = DVector::from_iterator(
            rows.len(),
            rows.iter().map(|&i| point.up[unknown[i]] - rate(i)),
        );
        last = if r.is_empty() { 0.0 } else { r.amax() };
        let jac = DMatrix::from_fn(rows.len(), free.len(), |row, col| {
            lin.a[(rows[row], free[col])]
        });
        let svd = jac.svd(true, true);
        let largest = svd.singular_values.max();
        let singular =
            !free.is_empty() && svd.singular_values.min() <= 1e-12 * largest.max(f64::MIN_POSITIVE);
        if singular {
            // The direction the derivatives do not see names the states it moves.
            let v_t = svd.v_t.as_ref().expect("asked for");
            let direction = v_t.row(svd.singular_values.imin());
            let names: Vec<&str> = free
                .iter()
                .zip(direction.iter())
                .filter(|(_, c)| c.abs() > 0.1)
                .map(|(&i, _)| states[i].as_str())
                .collect();
            return Err(failed(
                sys,
                if last <= options.tolerance {
                    format!(
                        "the steady state is not unique: the derivatives do not determine {} \
                         (fix one of them with a value)",
                        names.join(", ")
                    )
                } else {
                    format!(
                        "the derivatives do not determine {} at the iterate {x:?} (a point \
                         where the forces do not change with them): give other guesses",
                        names.join(", ")
                    )
                },
            ));
        }
        if last <= options.tolerance {
            return Ok(point);
        }
        let step = svd
            .solve(&(-r), 1e-14 * largest)
            .map_err(|e| failed(sys, e.to_string()))?;
        for (xi, d) in x.iter_mut().zip(step.iter()) {
            *xi += d;
        }
    }
    Err(failed(
        sys,
        format!(
            "no steady state found in {} iterations (largest derivative error {last})",
            options.max_iterations
        ),
    ))
}
