//! Linear blocks of structural size (transfer functions, state space, critical
//! damping, the discrete transfer function) against their closed-form step responses.

#![allow(missing_docs)]

mod common;

use common::tight_options as options;

use multibody::blocks::{
    Constant, CriticalDamping, DiscreteTransferFunction, Init, StateSpace, TransferFunction,
};
use multibody::prelude::*;

/// Solves `model` over `(0, t_end)` and checks `signal` against `exact` at 200 points.
fn check(
    model: &(impl AsRef<System> + ?Sized),
    signal: &str,
    t_end: f64,
    tol: f64,
    exact: impl Fn(f64) -> f64,
) {
    let ssys = structural_simplify(model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
        .unwrap()
        .solve(&options(t_end, 200))
        .unwrap();
    for k in 0..=200 {
        let t = k as f64 * t_end / 200.0;
        let got = sol.at(signal, t).unwrap();
        assert!(
            (got - exact(t)).abs() < tol,
            "{signal}({t}) = {got}, exact {}",
            exact(t)
        );
    }
}

#[test]
fn transfer_functions_give_their_step_responses() {
    let step = |b: Vec<f64>, a: Vec<f64>| {
        system! {
            name: "tf";
            one = Constant { k: 1.0 };
            tf = TransferFunction { b, a, init: Init::InitialState };
            connect(one.y, tf.u);
        }
    };
    // 1 / (s + 1)
    check(&step(vec![1.0], vec![1.0, 1.0]), "tf.y", 5.0, 1e-8, |t| {
        1.0 - (-t).exp()
    });
    // 4 / (s^2 + 2 s + 4): w = 2, zeta = 1/2.
    let wd = 3f64.sqrt();
    check(
        &step(vec![4.0], vec![1.0, 2.0, 4.0]),
        "tf.y",
        6.0,
        1e-8,
        |t| 1.0 - (-t).exp() * ((wd * t).cos() + (wd * t).sin() / wd),
    );
    // s / (s + 1): a feed-through of 1 decaying.
    check(
        &step(vec![1.0, 0.0], vec![1.0, 1.0]),
        "tf.y",
        5.0,
        1e-8,
        |t| (-t).exp(),
    );
    // A static gain.
    check(&step(vec![3.0], vec![2.0]), "tf.y", 1.0, 1e-12, |_| 1.5);
}

#[test]
fn state_space_oscillator_gives_its_step_response() {
    // x'' = -4 x + u, y = x: (1 - cos 2t) / 4.
    let model = system! {
        name: "ss";
        one = Constant { k: 1.0 };
        ss = StateSpace {
            A: vec![vec![0.0, 1.0], vec![-4.0, 0.0]],
            B: vec![0.0, 1.0],
            C: vec![1.0, 0.0],
            init: Init::InitialState,
        };
        connect(one.y, ss.u);
    };
    check(&model, "ss.y", 5.0, 1e-8, |t| (1.0 - (2.0 * t).cos()) / 4.0);
}

#[test]
fn critical_damping_has_no_overshoot_and_its_cut_off_where_asked() {
    // Two lags of 1 rad/s: 1 - (1 + t) e^-t.
    let model = system! {
        name: "cd";
        one = Constant { k: 1.0 };
        filter = CriticalDamping {
            n: 2, f: 1.0 / (2.0 * std::f64::consts::PI), normalized: false,
            init: Init::InitialState,
        };
        connect(one.y, filter.u);
    };
    check(&model, "filter.y", 8.0, 1e-8, |t| {
        1.0 - (1.0 + t) * (-t).exp()
    });
    // Normalized, each lag's corner is f / sqrt(2^(1/n) - 1): three lags of
    // w = 1 / 0.50982 rad/s.
    let alpha = (2f64.powf(1.0 / 3.0) - 1.0).sqrt();
    let w = 1.0 / alpha;
    let model = system! {
        name: "cd3";
        one = Constant { k: 1.0 };
        filter = CriticalDamping {
            n: 3, f: 1.0 / (2.0 * std::f64::consts::PI), init: Init::InitialState,
        };
        connect(one.y, filter.u);
    };
    check(&model, "filter.y", 8.0, 1e-8, |t| {
        let x = w * t;
        1.0 - (1.0 + x + x * x / 2.0) * (-x).exp()
    });
}

#[test]
fn discrete_transfer_function_follows_its_difference_equation() {
    // 1 / (z - 0.5) sampled every 0.1 s on u = 1: x_k = 1 + 0.5 x_(k-1) from x = 0, and
    // y_k = x_(k-1), held: 2 (1 - 0.5^k) on [0.1 k, 0.1 (k + 1)).
    let model = system! {
        name: "dtf";
        one = Constant { k: 1.0 };
        tf = DiscreteTransferFunction { b: vec![1.0], a: vec![1.0, -0.5], sample_period: 0.1 };
        connect(one.y, tf.u);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 1.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    // Between the instants (at an instant the solution has both limits).
    for k in 0..10 {
        let t = 0.1 * k as f64 + 0.05;
        let exact = 2.0 * (1.0 - 0.5f64.powi(k));
        let got = sol.at("tf.y", t).unwrap();
        assert!((got - exact).abs() < 1e-12, "y({t}) = {got}, exact {exact}");
    }
}
