//! The residual is specialized to each problem's parameter values before integrating
//! (`SolverOptions::specialize_parameters`): a problem with other values must see those
//! values, and the specialized functions must integrate the same trajectory as the
//! general ones.

use std::f64::consts::{FRAC_PI_2, PI};

use multibody::joints::Revolute;
use multibody::parts::BodyShape;
use multibody::prelude::*;
use multibody::world::World;
use multibody::{LinearSolver, SimplifyOptions, structural_simplify_with};

const G: f64 = 9.80665;
const I_ZZ: f64 = 0.001;

/// `n` revolute joints about z, each link a BodyShape with its mass at the tip.
fn chain(n: usize, length: f64) -> System {
    chain_of(
        n,
        &BodyShape {
            r: [length, 0.0, 0.0],
            r_CM: Some([length, 0.0, 0.0]),
            m: 1.0,
            I_diag: [I_ZZ, I_ZZ, I_ZZ],
            ..Default::default()
        },
    )
}

/// `n` revolute joints about z, each link a copy of `link`.
fn chain_of(n: usize, link: &BodyShape) -> System {
    let mut m = System::new(format!("chain{n}"));
    let world = m.add_typed("world", &World::default());
    let mut prev = world.frame_b;
    for k in 1..=n {
        let joint = m.add_typed(&format!("rev{k}"), &Revolute::default());
        let link = m.add_typed(&format!("link{k}"), link);
        m.connect_handles(&prev, &joint.frame_a);
        m.connect_handles(&joint.frame_b, &link.frame_a);
        prev = link.frame_b;
    }
    m
}

/// Period of the small oscillation of `rev1.phi` about -pi/2, from the first and the
/// third upward crossing of the equilibrium (bisection on the interpolated solution).
fn period(sol: &Solution, t_end: f64) -> f64 {
    let f = |t: f64| sol.at("rev1.phi", t).unwrap() + FRAC_PI_2;
    let mut crossings = Vec::new();
    let dt = 1e-3;
    let mut t = dt;
    while t < t_end && crossings.len() < 3 {
        let (a, b) = (f(t - dt), f(t));
        if a < 0.0 && b >= 0.0 {
            let (mut lo, mut hi) = (t - dt, t);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if f(mid) < 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            crossings.push(0.5 * (lo + hi));
        }
        t += dt;
    }
    assert_eq!(
        crossings.len(),
        3,
        "fewer than three crossings before {t_end}"
    );
    (crossings[2] - crossings[0]) / 2.0
}

/// The small-oscillation period of a point mass `m` at distance `l` with inertia
/// `I_ZZ` about its centre, amplitude `amp` (first-order amplitude correction).
fn analytic_period(m: f64, l: f64, amp: f64) -> f64 {
    2.0 * PI * ((m * l * l + I_ZZ) / (m * G * l)).sqrt() * (1.0 + amp * amp / 16.0)
}

#[test]
fn each_problem_integrates_with_its_own_parameter_values() {
    let ssys = structural_simplify(&chain(1, 0.5)).unwrap();
    let amp = 0.02;
    let start = ("rev1.phi", -FRAC_PI_2 + amp);
    let opts = SolverOptions {
        rtol: 1e-9,
        atol: 1e-11,
        ..SolverOptions::default()
    };
    // Start and parameter values, and the mass and length they give.
    type Case<'a> = (&'a [(&'a str, f64)], f64, f64);
    let cases: [Case; 2] = [
        (&[start], 1.0, 0.5),
        (
            &[
                start,
                ("link1.translation.r[1]", 0.8),
                ("link1.body.r_CM[1]", 0.8),
                ("link1.body.m", 2.5),
            ],
            2.5,
            0.8,
        ),
    ];
    for (values, m, l) in cases {
        let want = analytic_period(m, l, amp);
        for specialize_parameters in [true, false] {
            let opts = SolverOptions {
                specialize_parameters,
                ..opts.clone()
            };
            let sol = DaeProblem::new(&ssys, values, (0.0, 8.0))
                .unwrap()
                .solve(&opts)
                .unwrap();
            let got = period(&sol, 8.0);
            assert!(
                (got - want).abs() < 1e-5 * want,
                "m = {m}, l = {l}, specialized {specialize_parameters}: period {got} against {want}"
            );
        }
    }
}

#[test]
fn specialized_and_general_functions_integrate_the_same_trajectory() {
    let ssys = structural_simplify(&chain(3, 0.5)).unwrap();
    let values = [("rev2.phi", 0.3), ("rev3.w", -0.5)];
    let solve = |specialize_parameters| {
        DaeProblem::new(&ssys, &values, (0.0, 1.0))
            .unwrap()
            .solve(&SolverOptions {
                rtol: 1e-9,
                atol: 1e-11,
                specialize_parameters,
                ..SolverOptions::default()
            })
            .unwrap()
    };
    let (a, b) = (solve(true), solve(false));
    for name in ["rev1.phi", "rev2.w", "rev3.phi", "link3.frame_b.r_0[2]"] {
        for t in [0.25, 0.5, 1.0] {
            let (x, y) = (a.at(name, t).unwrap(), b.at(name, t).unwrap());
            assert!(
                (x - y).abs() < 1e-6 * (1.0 + x.abs()),
                "{name} at {t}: {x} specialized, {y} general"
            );
        }
    }
}

/// A chain whose links have their centre of mass off the link's axis (`r_CM[2]`,
/// `r_CM[3]`), a product of inertia `I_21` and a frame offset `r[2]`: parameters that
/// are 0 in [`chain`].
fn offset_chain(n: usize) -> System {
    chain_of(
        n,
        &BodyShape {
            r: OFFSET_R,
            r_CM: Some(OFFSET_R_CM),
            m: 1.0,
            I_diag: [I_ZZ, I_ZZ, I_ZZ],
            I_offdiag: [OFFSET_I_21, 0.0, 0.0],
            ..Default::default()
        },
    )
}

const OFFSET_R: [f64; 3] = [0.5, 0.03, 0.0];
const OFFSET_R_CM: [f64; 3] = [0.5, 0.1, 0.05];
const OFFSET_I_21: f64 = 2e-4;

/// Pre-elimination of the acceleration block orders its eliminations as if the entries
/// that vanish at the default parameter values were absent, but keeps them. A tunable
/// chain long enough for that block to go to the sparse LU, given those parameters
/// nonzero, must follow the same chain compiled with the values folded in: its motion
/// and the reaction torques of its joints about x and y.
#[test]
fn parameters_that_are_zero_by_default_keep_their_terms() {
    let n = 20;
    let tunable = structural_simplify(&chain(n, 0.5)).unwrap();
    assert!(
        !tunable.statistics().linear_sparse.is_empty(),
        "{}",
        tunable.statistics()
    );
    let folded = structural_simplify_with(
        &offset_chain(n),
        &SimplifyOptions {
            evaluate_parameters: true,
            ..SimplifyOptions::default()
        },
    )
    .unwrap();
    let starts = [("rev2.phi", 0.3), ("rev5.w", -0.5)];
    let mut names: Vec<(String, f64)> = Vec::new();
    for k in 1..=n {
        for (i, (&r, &r_cm)) in OFFSET_R.iter().zip(&OFFSET_R_CM).enumerate().skip(1) {
            names.push((format!("link{k}.translation.r[{}]", i + 1), r));
            names.push((format!("link{k}.body.r_CM[{}]", i + 1), r_cm));
        }
        names.push((format!("link{k}.body.I_21"), OFFSET_I_21));
    }
    let mut values: Vec<(&str, f64)> = starts.to_vec();
    values.extend(names.iter().map(|(s, v)| (s.as_str(), *v)));
    let opts = SolverOptions {
        rtol: 1e-9,
        atol: 1e-11,
        ..SolverOptions::default()
    };
    let t_end = 0.5;
    let a = DaeProblem::new(&tunable, &values, (0.0, t_end))
        .unwrap()
        .solve(&opts)
        .unwrap();
    let b = DaeProblem::new(&folded, &starts, (0.0, t_end))
        .unwrap()
        .solve(&opts)
        .unwrap();
    // Angles and positions see `r[2]` and `r_CM[2]`; the out-of-plane offset `r_CM[3]`
    // and the product of inertia `I_21` only change reactions about x and y.
    let last = format!("link{n}.frame_b.r_0[1]");
    for name in [
        "rev1.phi",
        "rev2.w",
        "rev20.phi",
        last.as_str(),
        "rev1.frame_b.t[1]",
        "rev1.frame_b.t[2]",
        "rev10.frame_b.t[1]",
    ] {
        for t in [0.1, 0.25, 0.5] {
            let (x, y) = (a.at(name, t).unwrap(), b.at(name, t).unwrap());
            assert!(
                (x - y).abs() < 1e-6 * (1.0 + x.abs()),
                "{name} at {t}: {x} tunable, {y} folded"
            );
        }
    }
    // The offsets matter: the chain with them differs from the one without.
    let plain = DaeProblem::new(&tunable, &starts, (0.0, t_end))
        .unwrap()
        .solve(&opts)
        .unwrap();
    for name in ["rev1.phi", "rev1.frame_b.t[1]", "rev1.frame_b.t[2]"] {
        let (x, y) = (a.at(name, t_end).unwrap(), plain.at(name, t_end).unwrap());
        assert!(
            (x - y).abs() > 1e-3 * (1.0 + y.abs()),
            "{name}: the offsets changed nothing: {x} against {y}"
        );
    }
}

/// Compiling analyses no Jacobian, and a solve with specialized parameters (the default)
/// analyses the specialized residual's, not the compiled one's: on a 20-link chain the
/// extended Jacobian is then never built for the general residual. Without
/// specialization the solve analyses the compiled residual's (and uses the extended one
/// where it is worth it); a solver that never uses the extended Jacobian never builds
/// it.
#[test]
fn jacobians_are_analysed_on_first_use_only() {
    let ssys = structural_simplify(&chain(20, 0.5)).unwrap();
    assert_eq!(ssys.compiled().jacobians_analysed(), (false, false));
    let problem = DaeProblem::new(&ssys, &[("rev2.phi", 0.3)], (0.0, 0.05)).unwrap();
    let specialized = problem.solve(&SolverOptions::default()).unwrap();
    assert_eq!(ssys.compiled().jacobians_analysed(), (false, false));
    let general = problem
        .solve(&SolverOptions {
            specialize_parameters: false,
            ..SolverOptions::default()
        })
        .unwrap();
    assert!(ssys.compiled().jacobians_analysed().1);
    // A solver that never uses the extended Jacobian never analyses it.
    let ssys = structural_simplify(&chain(20, 0.5)).unwrap();
    let problem = DaeProblem::new(&ssys, &[("rev2.phi", 0.3)], (0.0, 0.05)).unwrap();
    for linear_solver in [LinearSolver::SparsePlain, LinearSolver::Dense] {
        problem
            .solve(&SolverOptions {
                specialize_parameters: false,
                linear_solver,
                ..SolverOptions::default()
            })
            .unwrap();
        assert_eq!(ssys.compiled().jacobians_analysed(), (true, false));
    }
    let (x, y) = (
        specialized.at("rev20.phi", 0.05).unwrap(),
        general.at("rev20.phi", 0.05).unwrap(),
    );
    assert!((x - y).abs() < 1e-6, "{x} specialized, {y} general");
}
