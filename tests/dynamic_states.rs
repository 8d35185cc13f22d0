//! Dynamic state selection: where the static choice of states becomes singular during
//! the motion (a four-bar at a dead centre, a pendulum in Cartesian coordinates), the
//! solver changes the states and runs on; checked against closed forms and invariants.

#![allow(missing_docs)]

#[path = "support/mechanics.rs"]
mod mechanics;

use mechanics::{MassProps, body_energy, relative_drift};
use multibody::DynamicStates;
use multibody::joints::{Revolute, RevolutePlanarLoopConstraint};
use multibody::parts::{BodyShape, FixedTranslation};
use multibody::prelude::*;
use multibody::rotational::{Damper, Inertia};
use multibody::world::World;
use multibody::{SimplifyOptions, structural_simplify_with};

fn options(mode: DynamicStates) -> SimplifyOptions {
    SimplifyOptions {
        dynamic_state_selection: mode,
        ..Default::default()
    }
}

fn tight(rtol: f64) -> SolverOptions {
    SolverOptions {
        rtol,
        atol: rtol * 1e-2,
        ..Default::default()
    }
}

/// Inertia of the bars' bodies (BodyShape's default, diagonal 0.001).
const I_BAR: [[f64; 3]; 3] = [[0.001, 0.0, 0.0], [0.0, 0.001, 0.0], [0.0, 0.0, 0.001]];

/// The energy of BodyShapes of mass 1 along `r` at the given paths.
fn bars_energy(sol: &Solution, bars: &[(&str, [f64; 3])], g: f64) -> Vec<f64> {
    let mut total = vec![0.0; sol.t().len()];
    for &(path, r) in bars {
        let p = MassProps {
            m: 1.0,
            r_cm: [r[0] / 2.0, r[1] / 2.0, r[2] / 2.0],
            inertia: I_BAR,
        };
        let e = body_energy(sol, &format!("{path}.body"), p, g, [0.0, -1.0, 0.0]);
        for (t, e) in total.iter_mut().zip(e) {
            *t += e;
        }
    }
    total
}

// ---------------------------------------------------------------------------------------
// The seed tutorial's planar four-bar without damping.

const L: f64 = 1.5;
const G_N: f64 = 9.80665;

system! {
    /// The tutorial's four-bar (a rhombus of bars of length 1.5, free to turn about the
    /// world) with both dampers at 0.
    fn rhombus() -> Rhombus {
        name: "fourbar";
        world = World::default();
        j1 = Revolute { axisflange: true };
        j2 = Revolute { axisflange: true };
        j3 = Revolute::default();
        j4 = RevolutePlanarLoopConstraint::default();
        j5 = Revolute::default();
        b1 = BodyShape { m: 1.0, r: [L, 0.0, 0.0], radius: 0.03 };
        b2 = BodyShape { m: 1.0, r: [0.0, L, 0.0], radius: 0.03 };
        b3 = BodyShape { m: 1.0, r: [-L, 0.0, 0.0], radius: 0.03 };
        b4 = BodyShape { m: 1.0, r: [0.0, -L, 0.0], radius: 0.03 };
        damper1 = Damper { d: 0.0 };
        damper2 = Damper { d: 0.0 };
        connect(world.frame_b, j1.frame_a);
        connect(j1.frame_b, b1.frame_a);
        connect(b1.frame_b, j2.frame_a);
        connect(j2.frame_b, b2.frame_a);
        connect(b2.frame_b, j3.frame_a);
        connect(j3.frame_b, b3.frame_a);
        connect(b3.frame_b, j4.frame_a);
        connect(j4.frame_b, b4.frame_a);
        connect(b4.frame_b, j5.frame_a);
        connect(j5.frame_b, world.frame_b);
        connect(j1.axis, damper1.flange_a);
        connect(j1.support, damper1.flange_b);
        connect(j2.axis, damper2.flange_a);
        connect(j2.support, damper2.flange_b);
    }
}

#[test]
fn the_tutorial_four_bar_without_damping_runs_through_every_fold_keeping_its_energy() {
    let ssys = structural_simplify(&rhombus()).unwrap();
    // The static choice (the dampers' relative angles, that is j1 and j2) is watched.
    assert_eq!(ssys.state_candidates().len(), 1);
    let sol = DaeProblem::new(&ssys, &[("j1.phi", 0.1)], (0.0, 10.0))
        .unwrap()
        .solve(&tight(1e-9))
        .expect("runs the 10 s");
    assert_eq!(*sol.t().last().unwrap(), 10.0);
    // It changed states on the way (the static choice is singular where the rhombus
    // folds flat).
    assert!(
        sol.segments().len() > 3,
        "{} segments",
        sol.segments().len()
    );
    // No damping, no work: the energy stays what it was, to 1e-6 of itself.
    let bars = [
        ("b1", [L, 0.0, 0.0]),
        ("b2", [0.0, L, 0.0]),
        ("b3", [-L, 0.0, 0.0]),
        ("b4", [0.0, -L, 0.0]),
    ];
    let energy = bars_energy(&sol, &bars, G_N);
    let drift = relative_drift(&energy, energy[0]);
    assert!(drift < 1e-6, "relative energy drift {drift:e}");
    // The rhombus stays a parallelogram (opposite angles equal): j3 = -j2 and
    // j5 = -(j1 + j2), at every reported point, to round-off.
    let j: Vec<Vec<f64>> = ["j1.phi", "j2.phi", "j3.phi", "j5.phi"]
        .iter()
        .map(|n| sol.get(n).unwrap())
        .collect();
    let wrap = |a: f64| {
        (a + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI
    };
    for k in 0..sol.t().len() {
        assert!(wrap(j[2][k] + j[1][k]).abs() < 1e-7, "t = {}", sol.t()[k]);
        assert!(
            wrap(j[3][k] + j[0][k] + j[1][k]).abs() < 1e-7,
            "t = {}",
            sol.t()[k]
        );
    }
}

#[test]
fn without_dynamic_states_the_four_bar_stops_at_its_first_fold() {
    let ssys = structural_simplify_with(&rhombus(), &options(DynamicStates::Off)).unwrap();
    let err = DaeProblem::new(&ssys, &[("j1.phi", 0.1)], (0.0, 10.0))
        .unwrap()
        .solve(&tight(1e-9))
        .unwrap_err();
    // The rhombus folds flat (all bars in line) at about 1.09 s.
    assert!(
        err.to_string().contains("the solver failed at t = 1.09"),
        "{err}"
    );
}

// ---------------------------------------------------------------------------------------
// A family of four-bars whose every link swings between dead centres.

system! {
    /// A four-bar with ground link `d` (from `world` to the rocker's pivot), crank `a`,
    /// coupler `b` and rocker `c`, in no gravity.
    fn non_grashof(a: f64, b: f64, c: f64, d: f64) -> NonGrashof {
        name: "nongrashof";
        world = World { g: 0.0 };
        ground = FixedTranslation { r: [d, 0.0, 0.0] };
        j1 = Revolute::default();
        j2 = Revolute::default();
        j3 = Revolute::default();
        j4 = RevolutePlanarLoopConstraint::default();
        crank = BodyShape { m: 1.0, r: [a, 0.0, 0.0] };
        coupler = BodyShape { m: 1.0, r: [b, 0.0, 0.0] };
        rocker = BodyShape { m: 1.0, r: [c, 0.0, 0.0] };
        connect(world.frame_b, j1.frame_a);
        connect(j1.frame_b, crank.frame_a);
        connect(crank.frame_b, j2.frame_a);
        connect(j2.frame_b, coupler.frame_a);
        connect(coupler.frame_b, j3.frame_a);
        connect(j3.frame_b, rocker.frame_a);
        connect(rocker.frame_b, j4.frame_a);
        connect(world.frame_b, ground.frame_a);
        connect(ground.frame_b, j4.frame_b);
    }
}

#[test]
fn non_grashof_four_bars_pass_their_dead_centres() {
    // Links with s + l > p + q: no link turns fully; set going, each swings between its
    // dead centres, where the other two moving links are in line. The crank's are where
    // coupler and rocker are stretched: cos(phi) = (a^2 + d^2 - (b + c)^2) / (2 a d).
    for (a, b, c, d, phi0) in [
        (2.0, 1.6, 2.2, 3.0, 1.2),
        (1.0, 1.2, 1.1, 2.5, 1.0),
        (1.5, 1.5, 1.5, 2.0, 0.9),
    ] {
        let name = format!("a {a}, b {b}, c {c}, d {d}");
        let model = non_grashof(a, b, c, d);
        let values = [("j1.phi", phi0), ("j1.w", 3.0)];
        let guesses = [("j2.phi", 1.0), ("j3.phi", -1.0)];
        // The static choice (the crank angle) stops at the first dead centre ...
        let fixed = structural_simplify_with(&model, &options(DynamicStates::Off)).unwrap();
        assert!(
            DaeProblem::new_with_guesses(&fixed, &values, &guesses, (0.0, 10.0))
                .unwrap()
                .solve(&tight(1e-9))
                .is_err(),
            "{name}: the static choice passes?"
        );
        // ... dynamic states run through all of them.
        let ssys = structural_simplify(&model).unwrap();
        let sol = DaeProblem::new_with_guesses(&ssys, &values, &guesses, (0.0, 10.0))
            .unwrap()
            .solve(&tight(1e-9))
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(sol.segments().len() > 4, "{name}");
        // No gravity, no loss: the kinetic energy is constant (rtol 1e-9 lets it drift
        // by about 1e-6 over 10 s and many restarts).
        let bars = [
            ("crank", [a, 0.0, 0.0]),
            ("coupler", [b, 0.0, 0.0]),
            ("rocker", [c, 0.0, 0.0]),
        ];
        let energy = bars_energy(&sol, &bars, 0.0);
        let drift = relative_drift(&energy, energy[0]);
        assert!(drift < 5e-6, "{name}: energy drift {drift:e}");
        // The crank reaches its dead centres, +-phi_max (reported at every step; at a
        // dead centre the crank stands still, so a step lands within (h w')^2).
        let phi_max = ((a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d)).acos();
        let j1 = sol.get("j1.phi").unwrap();
        let (lo, hi) = j1
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
                (l.min(v), h.max(v))
            });
        assert!(
            (hi - phi_max).abs() < 1e-4,
            "{name}: {hi} against {phi_max}"
        );
        assert!(
            (lo + phi_max).abs() < 1e-4,
            "{name}: {lo} against {}",
            -phi_max
        );
        // The loop stays closed: the rocker's end is at the ground pivot (d, 0).
        let end = mechanics::vector(&sol, "rocker.frame_b.r_0");
        for (k, p) in end.iter().enumerate() {
            let gap = ((p[0] - d).powi(2) + p[1].powi(2) + p[2].powi(2)).sqrt();
            assert!(gap < 1e-9, "{name}: gap {gap:e} at t = {}", sol.t()[k]);
        }
    }
}

// ---------------------------------------------------------------------------------------
// The pendulum in Cartesian coordinates.

/// A point mass on a massless rod of length 1 in Cartesian coordinates:
/// `x^2 + y^2 = 1`, `x'' = -lambda x`, `y'' = -lambda y - g`.
fn cartesian_pendulum() -> System {
    let mut m = System::new("cartesian");
    let x = m.variable(Variable::new("x").start(1.0));
    let y = m.variable(Variable::new("y"));
    let vx = m.var("vx");
    let vy = m.var("vy");
    let lambda = m.var("lambda");
    m.equation(x.der(), vx);
    m.equation(y.der(), vy);
    m.equation(vx.der(), -lambda * x);
    m.equation(vy.der(), -lambda * y - 9.81);
    m.equation(x * x + y * y, 1.0);
    m
}

/// theta(t) of `theta'' = -g sin(theta)` (theta from the downward vertical) from
/// `theta0` at rest, by classical Runge-Kutta with 2e5 steps per second.
fn pendulum_angle(theta0: f64, times: &[f64]) -> Vec<f64> {
    let f = |th: f64, om: f64| (om, -9.81 * th.sin());
    let h: f64 = 5e-6;
    let (mut t, mut th, mut om) = (0.0, theta0, 0.0);
    let mut out = Vec::new();
    for &target in times {
        while t < target - 1e-12 {
            let step = h.min(target - t);
            let (k1a, k1b) = f(th, om);
            let (k2a, k2b) = f(th + 0.5 * step * k1a, om + 0.5 * step * k1b);
            let (k3a, k3b) = f(th + 0.5 * step * k2a, om + 0.5 * step * k2b);
            let (k4a, k4b) = f(th + step * k3a, om + step * k3b);
            th += step / 6.0 * (k1a + 2.0 * k2a + 2.0 * k3a + k4a);
            om += step / 6.0 * (k1b + 2.0 * k2b + 2.0 * k3b + k4b);
            t += step;
        }
        out.push(th);
    }
    out
}

#[test]
fn a_cartesian_pendulum_released_level_swings_with_the_polar_solution() {
    // Released with the rod level (x = 1, y = 0): the static choice x is singular at
    // the start (y cannot be solved from x there), the dynamic one takes y, and the
    // pendulum swings through the bottom, where x is the good choice again.
    let ssys = structural_simplify(&cartesian_pendulum()).unwrap();
    let times: Vec<f64> = (1..=30).map(|k| 0.1 * k as f64).collect();
    let problem = DaeProblem::new(&ssys, &[("x", 1.0)], (0.0, 3.0)).unwrap();
    let sol = problem
        .solve(&SolverOptions {
            output_times: Some(times.clone()),
            ..tight(1e-10)
        })
        .unwrap();
    assert!(
        sol.segments().len() > 2,
        "{} segments",
        sol.segments().len()
    );
    let xy = sol.sample(&["x", "y"], &times).unwrap();
    let reference = pendulum_angle(std::f64::consts::FRAC_PI_2, &times);
    for (k, &t) in times.iter().enumerate() {
        let (x, y) = (xy[0][k], xy[1][k]);
        assert!((x * x + y * y - 1.0).abs() < 1e-9, "length at t = {t}");
        let theta = x.atan2(-y);
        assert!(
            (theta - reference[k]).abs() < 1e-6,
            "t = {t}: {theta} against {}",
            reference[k]
        );
    }
}

// ---------------------------------------------------------------------------------------
// A choice that is singular whatever the configuration.

#[test]
fn two_dampers_in_parallel_between_free_inertias_choose_solvable_states() {
    // The static choice keeps both dampers' relative angles (the same quantity twice),
    // which leaves the absolute angle undetermined; another choice is solvable. With
    // J1 = 1, J2 = 2 and d = d1 + d2 = 0.8 from w1 = 1, w2 = 0: the momentum
    // J1 w1 + J2 w2 = 1 is conserved and the relative speed decays as
    // exp(-d (1/J1 + 1/J2) t).
    let model = system! {
        name: "parallel";
        i1 = Inertia { J: 1.0, w_start: 1.0 };
        d1 = Damper { d: 0.5 };
        d2 = Damper { d: 0.3 };
        i2 = Inertia { J: 2.0 };
        connect(i1.flange_b, d1.flange_a);
        connect(i1.flange_b, d2.flange_a);
        connect(d1.flange_b, i2.flange_a);
        connect(d2.flange_b, i2.flange_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 2.0))
        .unwrap()
        .solve(&tight(1e-10))
        .unwrap();
    let times = [0.5, 1.0, 2.0];
    let w = sol.sample(&["i1.w", "i2.w", "i1.phi"], &times).unwrap();
    let rate = 0.8 * (1.0 + 0.5);
    for (k, &t) in times.iter().enumerate() {
        let relative = (-rate * t).exp();
        // w1 - w2 = relative, w1 + 2 w2 = 1.
        let (w1, w2) = ((1.0 + 2.0 * relative) / 3.0, (1.0 - relative) / 3.0);
        assert!(
            (w[0][k] - w1).abs() < 1e-7,
            "w1 at {t}: {} against {w1}",
            w[0][k]
        );
        assert!(
            (w[1][k] - w2).abs() < 1e-7,
            "w2 at {t}: {} against {w2}",
            w[1][k]
        );
        // phi1 = integral of w1 from 0 (phi1(0) = 0).
        let phi1 = t / 3.0 + 2.0 / 3.0 * (1.0 - relative) / rate;
        assert!(
            (w[2][k] - phi1).abs() < 1e-7,
            "phi1 at {t}: {} against {phi1}",
            w[2][k]
        );
    }
}

#[test]
fn dynamic_states_from_the_start_are_named_and_selected_from_the_candidates() {
    let ssys =
        structural_simplify_with(&cartesian_pendulum(), &options(DynamicStates::Always)).unwrap();
    assert_eq!(
        ssys.states(),
        ["dynamic_states1.x[1]", "dynamic_states1.xd[1]"]
    );
    let groups = ssys.state_candidates();
    assert_eq!(groups.len(), 1);
    let mut candidates = groups[0].candidates.clone();
    candidates.sort();
    assert_eq!(candidates, ["x", "y"]);
}
