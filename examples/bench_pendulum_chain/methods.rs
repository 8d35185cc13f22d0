//! The rows per integration method: the compiled chain solved by each method, and for
//! the explicit methods the hand-written articulated-body algorithm of [`super::aba`]
//! integrated by the same ARKODE method in this process (its ratio is ours over it).

use std::time::Instant;

use multibody::prelude::*;
use multibody::{Method, SimplifiedSystem};
use multibody_core::solve::ida::{IdaSettings, OutputMode};
use multibody_core::solve::ode::{self, OdeMethod};

use super::aba::Aba;
use super::stiff_chain::stiff_chain;
use super::{ATOL, G, RTOL, T_CHECK, T_END, links};

/// The methods compared, with the ARKODE table of the explicit ones.
const METHODS: [(Method, Option<&str>); 8] = [
    (Method::Ida, None),
    (Method::CvodeBdf, None),
    (Method::CvodeAdams, None),
    (Method::DormandPrince5, Some("ARKODE_DORMAND_PRINCE_7_4_5")),
    (Method::Verner7, Some("ARKODE_VERNER_10_6_7")),
    (Method::Verner8, Some("ARKODE_VERNER_13_7_8")),
    (Method::Verner9, Some("ARKODE_VERNER_16_8_9")),
    (Method::Auto, None),
];

/// The baseline by `table`: its solve time, steps and `q1` at `T_CHECK`.
fn baseline(n: usize, table: &'static str) -> (f64, u64, f64) {
    let mut f = Aba::new(links(n), [0.0, -G, 0.0]);
    let settings = IdaSettings {
        rtol: RTOL,
        atol: ATOL,
        ..IdaSettings::default()
    };
    let (mut ts, mut q1s, mut w1s) = (Vec::new(), Vec::new(), Vec::new());
    let t0 = Instant::now();
    let r = ode::integrate_monitored(
        &mut f,
        OdeMethod::Explicit(table),
        0.0,
        &vec![0.0; 2 * n],
        &settings,
        &OutputMode::EveryStep { t_end: T_END },
        &mut |t, y, ydot| {
            ts.push(t);
            q1s.push(y[0]);
            w1s.push(ydot[0]);
            true
        },
        None,
    )
    .expect("baseline solve");
    let elapsed = t0.elapsed().as_secs_f64();
    // Cubic Hermite between the steps around T_CHECK, as `Solution::at` does.
    let k = ts.partition_point(|&t| t < T_CHECK).max(1);
    let (ta, tb) = (ts[k - 1], ts[k]);
    let h = tb - ta;
    let s = (T_CHECK - ta) / h;
    let (h00, h10, h01, h11) = (
        2.0 * s.powi(3) - 3.0 * s * s + 1.0,
        s.powi(3) - 2.0 * s * s + s,
        -2.0 * s.powi(3) + 3.0 * s * s,
        s.powi(3) - s * s,
    );
    let q1 = h00 * q1s[k - 1] + h10 * h * w1s[k - 1] + h01 * q1s[k] + h11 * h * w1s[k];
    (elapsed, r.stats.steps, q1)
}

/// Prints a row per method for the chain of `n` links compiled as `ssys`; `reps`
/// interleaved repetitions, the fastest counts.
pub fn rows(n: usize, ssys: &SimplifiedSystem, reps: usize) -> Result<(), multibody::Error> {
    let problem = DaeProblem::new(ssys, &[], (0.0, T_END))?;
    for (method, table) in METHODS {
        // IDA and CVODE's BDF at 500 links take minutes on this machine.
        if n > 100 && matches!(method, Method::Ida | Method::CvodeBdf | Method::CvodeAdams) {
            continue;
        }
        let options = SolverOptions {
            rtol: RTOL,
            atol: ATOL,
            method,
            ..SolverOptions::default()
        };
        let mut best: Option<(f64, multibody::Solution)> = None;
        let mut base: Option<(f64, u64, f64)> = None;
        for _ in 0..reps {
            let t0 = Instant::now();
            let sol = problem.solve(&options)?;
            let s = t0.elapsed().as_secs_f64();
            if best.as_ref().is_none_or(|(b, _)| s < *b) {
                best = Some((s, sol));
            }
            if let Some(table) = table {
                let b = baseline(n, table);
                if base.is_none_or(|prev| b.0 < prev.0) {
                    base = Some(b);
                }
            }
        }
        let (solve_s, sol) = best.expect("at least one repetition");
        let stats = sol.statistics();
        let q1 = sol.at("rev1.phi", T_CHECK)?;
        let baseline_part = match base {
            Some((b, steps, bq1)) => {
                assert!(
                    (q1 - bq1).abs() < 1e-4 * (1.0 + q1.abs()),
                    "{method:?}: the two solutions disagree: {q1} vs {bq1}"
                );
                format!(
                    ", \"baseline_solve_s\": {b:.6}, \"baseline_steps\": {steps}, \"solve_ratio\": {:.3}",
                    solve_s / b
                )
            }
            None => String::new(),
        };
        println!(
            "{{\"n\": {n}, \"method\": \"{method:?}\", \"steps\": {}, \"rhs_evals\": {}, \"solve_s\": {solve_s:.6}{baseline_part}}}",
            stats.steps, stats.residual_evals
        );
    }
    Ok(())
}

/// Prints a row per method for the stiff chain of `n` masses over `T_END`.
pub fn stiff_rows(n: usize) -> Result<(), multibody::Error> {
    let ssys = structural_simplify(&stiff_chain(n, 1e4, 300.0, 50.0))?;
    let problem = DaeProblem::new(&ssys, &[], (0.0, T_END))?;
    for method in [
        Method::Ida,
        Method::CvodeBdf,
        Method::Kvaerno5,
        Method::Verner8,
        Method::Auto,
    ] {
        let options = SolverOptions {
            rtol: RTOL,
            atol: ATOL,
            method,
            ..SolverOptions::default()
        };
        let t0 = Instant::now();
        let sol = problem.solve(&options)?;
        let solve_s = t0.elapsed().as_secs_f64();
        let stats = sol.statistics();
        println!(
            "{{\"stiff_chain\": {n}, \"method\": \"{method:?}\", \"steps\": {}, \"rhs_evals\": {}, \"solve_s\": {solve_s:.6}}}",
            stats.steps, stats.residual_evals
        );
    }
    Ok(())
}
