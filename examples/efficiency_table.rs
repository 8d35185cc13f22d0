//! The seed's efficiency table, made by this library: for the seed's experiments (the
//! pendulum, the double pendulum, the crane crab, the gyroscope with Cardan angles and
//! with quaternions, a planar loop and the centrifugal governor), the sizes of the
//! linear and nonlinear systems after tearing and the steps of a solve, beside the
//! seed's MultiBody and Mechanics3D columns.
//!
//! `cargo run --release --example efficiency_table` prints the table (Markdown). Our
//! columns: the linear systems solved inside the compiled model after tearing (the
//! tearing variables of each; `LU n` for a block solved by the sparse LU with `n`
//! unknowns left after pre-elimination), the nonlinear systems (tearing variables of
//! each; those left to the integrator as algebraic unknowns are counted there too), the
//! states, and the steps (and residual evaluations: a step of IDA takes one or two, one
//! of Verner 8(7) about thirteen) of IDA and of `Method::Auto` at rtol 1e-6 over each
//! example's time span. The seed does not give its time spans or tolerances: its steps are not
//! comparable one to one, the sizes are.

#[path = "crane_crab.rs"]
#[allow(dead_code)]
mod crane_crab;
#[path = "double_pendulum.rs"]
#[allow(dead_code)]
mod double_pendulum;
#[path = "fourbar.rs"]
#[allow(dead_code)]
mod fourbar;
#[path = "governor.rs"]
#[allow(dead_code)]
mod governor;
#[path = "gyroscope.rs"]
#[allow(dead_code)]
mod gyroscope;
#[path = "pendulum.rs"]
#[allow(dead_code)]
mod pendulum;

use multibody::prelude::*;
use multibody::{Method, Statistics};

/// One experiment: its name, the compiled model, start values, time span, and the seed's
/// columns (MultiBody: linear, nonlinear, steps; Mechanics3D: the same).
struct Experiment {
    name: &'static str,
    ssys: SimplifiedSystem,
    values: Vec<(&'static str, f64)>,
    t_end: f64,
    seed: [&'static str; 6],
}

fn experiments() -> Result<Vec<Experiment>, multibody::Error> {
    use gyroscope::{CHOICES, top};
    Ok(vec![
        Experiment {
            name: "Pendulum",
            ssys: structural_simplify(&pendulum::pendulum())?,
            values: vec![("rev.phi", 0.0), ("rev.w", 0.0)],
            t_end: 5.0,
            seed: ["0", "0", "207", "0", "0", "207"],
        },
        Experiment {
            name: "Double pendulum",
            ssys: structural_simplify(&double_pendulum::double_pendulum())?,
            values: vec![
                ("revolute1.phi", 0.0),
                ("revolute1.w", 0.0),
                ("revolute2.phi", 0.0),
                ("revolute2.w", 0.0),
            ],
            t_end: 3.0,
            seed: ["2", "0", "549", "2", "0", "549"],
        },
        Experiment {
            name: "Crane crab",
            ssys: structural_simplify(&crane_crab::crane_crab())?,
            values: vec![
                ("rail.s", 0.0),
                ("rail.v", 0.0),
                ("hook.phi", 0.3),
                ("hook.w", 0.0),
            ],
            t_end: 6.0,
            seed: ["2", "0", "205", "4", "0", "205"],
        },
        Experiment {
            name: "Gyroscope, Cardan angles",
            ssys: structural_simplify(&top(CHOICES[0].1, CHOICES[0].2))?,
            values: vec![],
            t_end: gyroscope::T_END,
            seed: ["2,2", "0", "294", "3,2", "0", "294"],
        },
        Experiment {
            name: "Gyroscope, quaternions",
            ssys: structural_simplify(&top(CHOICES[1].1, CHOICES[1].2))?,
            values: vec![],
            t_end: gyroscope::T_END,
            seed: ["4,3", "4", "24438", "4,2", "4", "25574"],
        },
        Experiment {
            name: "Planar loop (four-bar)",
            ssys: structural_simplify(&fourbar::fourbar())?,
            values: vec![("j1.phi", 0.1)],
            t_end: 10.0,
            seed: ["8,2", "2", "372", "6,2,2", "2", "372"],
        },
        Experiment {
            name: "Centrifugal governor",
            ssys: structural_simplify(&governor::governor())?,
            values: vec![("shaft.phi", 0.0), ("hinge1.w", 0.0), ("hinge2.w", 0.0)],
            t_end: 20.0,
            seed: ["10,2,2", "2,2", "70", "16,2,2", "2,2", "70"],
        },
    ])
}

/// Sizes as the seed writes them (`2,2`), `0` for none.
fn list(sizes: &[String]) -> String {
    if sizes.is_empty() {
        "0".into()
    } else {
        sizes.join(",")
    }
}

/// Our linear and nonlinear columns.
fn sizes(s: &Statistics) -> (String, String) {
    let mut linear: Vec<String> = s
        .linear_inline
        .iter()
        .map(|&(_, torn)| torn.to_string())
        .collect();
    linear.extend(
        s.linear_sparse
            .iter()
            .map(|&(_, left)| format!("LU {left}")),
    );
    linear.extend(s.linear_solver.iter().map(|n| n.to_string()));
    let nonlinear: Vec<String> = s
        .nonlinear
        .iter()
        .map(|&(_, torn)| torn.to_string())
        .collect();
    (list(&linear), list(&nonlinear))
}

/// Steps and residual evaluations of a solve by `method`, as `steps (evaluations)`.
fn steps(e: &Experiment, method: Method) -> Result<String, multibody::Error> {
    let sol = DaeProblem::new(&e.ssys, &e.values, (0.0, e.t_end))?.solve(&SolverOptions {
        method,
        max_steps: 5_000_000,
        ..SolverOptions::default()
    })?;
    let s = sol.statistics();
    Ok(format!("{} ({})", s.steps, s.residual_evals))
}

fn main() -> Result<(), multibody::Error> {
    println!(
        "| experiment | seed MultiBody: linear / nonlinear / steps | seed Mechanics3D: linear / nonlinear / steps | ours: linear | ours: nonlinear | states, algebraic | steps IDA | steps Auto |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for e in experiments()? {
        let s = e.ssys.statistics();
        let (linear, nonlinear) = sizes(s);
        println!(
            "| {} | {} / {} / {} | {} / {} / {} | {linear} | {nonlinear} | {}, {} | {} (t = 0..{}) | {} |",
            e.name,
            e.seed[0],
            e.seed[1],
            e.seed[2],
            e.seed[3],
            e.seed[4],
            e.seed[5],
            s.states,
            s.algebraic,
            steps(&e, Method::Ida)?,
            e.t_end,
            steps(&e, Method::Auto)?,
        );
    }
    Ok(())
}
