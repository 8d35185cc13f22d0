//! Linearization against closed forms (a pendulum at its equilibria, a chain of masses
//! and springs) and against central differences of the nonlinear model.

#![allow(missing_docs)]

use std::f64::consts::PI;

use multibody::blocks::Constant;
use multibody::joints::Revolute;
use multibody::parts::Body;
use multibody::prelude::*;
use multibody::rotational::{Damper, Torque};
use multibody::translational::{Fixed, Mass, Spring};
use multibody::world::World;
use multibody::{LinearModel, OperatingPoint, linearize};

const G: f64 = 9.80665;

/// A body of 1 kg at 0.5 m from a revolute joint about z (gravity along -y), with a
/// damper `d` and a torque `tau` on the axis.
fn pendulum(d: f64) -> System {
    let model = system! {
        name: "pendulum";
        world = World::default();
        rev = Revolute { n: [0.0, 0.0, 1.0], axisflange: true };
        body = Body { m: 1.0, r_CM: [0.5, 0.0, 0.0] };
        damper = Damper { d };
        tau = Constant { k: 0.0 };
        torque = Torque { use_support: true };
        connect(world.frame_b, rev.frame_a);
        connect(rev.frame_b, body.frame_a);
        connect(damper.flange_b, rev.axis);
        connect(rev.support, damper.flange_a);
        connect(tau.y, torque.tau);
        connect(torque.flange, rev.axis);
        connect(torque.support, rev.support);
    };
    model.as_ref().clone()
}

/// The pendulum's moment of inertia about the axis: m l^2 + I_33.
const INERTIA: f64 = 0.25 + 0.001;

fn linearized(ssys: &SimplifiedSystem, phi: f64, w: f64) -> (LinearModel, OperatingPoint) {
    let problem = DaeProblem::new(ssys, &[("rev.phi", phi), ("rev.w", w)], (0.0, 1.0)).unwrap();
    let point = problem.operating_point();
    let lin = linearize(ssys, &point, &["tau.k"], &["rev.phi", "damper.tau"]).unwrap();
    (lin, point)
}

#[test]
fn a_pendulum_oscillates_below_and_falls_away_above() {
    let ssys = structural_simplify(&pendulum(0.0)).unwrap();
    let omega2 = 1.0 * G * 0.5 / INERTIA;
    // Hanging (r_CM along -y): +-i sqrt(m g l / I).
    let (lin, _) = linearized(&ssys, -PI / 2.0, 0.0);
    assert_eq!(lin.states.len(), 2, "{:?}", lin.states);
    let ev = lin.eigenvalues();
    assert!(ev.iter().all(|l| l.re.abs() < 1e-9), "{ev:?}");
    assert!((ev[0].im + omega2.sqrt()).abs() < 1e-9 && (ev[1].im - omega2.sqrt()).abs() < 1e-9);
    let poles = lin.poles();
    assert!((poles[0].frequency - omega2.sqrt()).abs() < 1e-9 && poles[0].damping.abs() < 1e-9);
    // Upright: +-sqrt(m g l / I).
    let (lin, _) = linearized(&ssys, PI / 2.0, 0.0);
    let ev = lin.eigenvalues();
    assert!((ev[0].re + omega2.sqrt()).abs() < 1e-9 && (ev[1].re - omega2.sqrt()).abs() < 1e-9);
    assert!(ev.iter().all(|l| l.im.abs() < 1e-9), "{ev:?}");
}

#[test]
fn linearization_agrees_with_central_differences_of_the_nonlinear_model() {
    // Away from any equilibrium, with damping: A and B against central differences of
    // the derivatives at consistent points, C and D against differences of the outputs.
    let d = 0.1;
    let ssys = structural_simplify(&pendulum(d)).unwrap();
    let (lin, point) = linearized(&ssys, 0.3, 0.7);
    let names = ssys.unknowns();
    let index: Vec<usize> = lin
        .states
        .iter()
        .map(|s| names.iter().position(|n| n == s).unwrap())
        .collect();
    let x0: Vec<f64> = index.iter().map(|&k| point.u[k]).collect();
    // The derivatives and outputs at a consistent point with states x and input k.
    let at = |x: &[f64], k: f64| {
        let mut builder = DaeProblem::builder(&ssys, (0.0, 1e-9)).value("tau.k", k);
        for (name, &v) in lin.states.iter().zip(x) {
            builder = builder.value(name.as_str(), v);
        }
        let problem = builder.build().unwrap();
        let p = problem.operating_point();
        let sol = problem.solve(&SolverOptions::default()).unwrap();
        let y = [
            sol.at("rev.phi", 0.0).unwrap(),
            sol.at("damper.tau", 0.0).unwrap(),
        ];
        let dx: Vec<f64> = index.iter().map(|&k| p.up[k]).collect();
        (dx, y)
    };
    let h = 1e-6;
    let n = lin.states.len();
    for col in 0..=n {
        let (plus, minus) = if col < n {
            let (mut a, mut b) = (x0.clone(), x0.clone());
            a[col] += h;
            b[col] -= h;
            (at(&a, 0.0), at(&b, 0.0))
        } else {
            (at(&x0, h), at(&x0, -h))
        };
        for row in 0..n {
            let fd = (plus.0[row] - minus.0[row]) / (2.0 * h);
            let exact = if col < n {
                lin.a[(row, col)]
            } else {
                lin.b[(row, 0)]
            };
            let what = &lin.states[row];
            assert!(
                (fd - exact).abs() < 1e-6,
                "d{what}'/d[{col}]: {exact}, differences {fd}"
            );
        }
        for out in 0..2 {
            let fd = (plus.1[out] - minus.1[out]) / (2.0 * h);
            let exact = if col < n {
                lin.c[(out, col)]
            } else {
                lin.d[(out, 0)]
            };
            let what = &lin.outputs[out];
            assert!(
                (fd - exact).abs() < 1e-6,
                "d{what}/d[{col}]: {exact}, differences {fd}"
            );
        }
    }
    // The torque input accelerates the axis by 1 / I: in the transfer to the speed.
    let w = lin.c.row(1).transpose() / d;
    let gain = (w.transpose() * &lin.b)[(0, 0)];
    assert!((gain.abs() - 1.0 / INERTIA).abs() < 1e-9, "{gain}");
    assert_eq!(point.t, 0.0);
}

#[test]
fn a_chain_of_masses_and_springs_has_the_closed_form_eigenfrequencies() {
    // Three masses of 1 kg between two walls, four springs of 1 N/m: 2 sin(j pi / 8).
    let model = system! {
        name: "chain";
        left = Fixed::default();
        s1 = Spring { c: 1.0 };
        m1 = Mass { m: 1.0 };
        s2 = Spring { c: 1.0 };
        m2 = Mass { m: 1.0 };
        s3 = Spring { c: 1.0 };
        m3 = Mass { m: 1.0 };
        s4 = Spring { c: 1.0 };
        right = Fixed::default();
        connect(left.flange, s1.flange_a);
        connect(s1.flange_b, m1.flange_a);
        connect(m1.flange_b, s2.flange_a);
        connect(s2.flange_b, m2.flange_a);
        connect(m2.flange_b, s3.flange_a);
        connect(s3.flange_b, m3.flange_a);
        connect(m3.flange_b, s4.flange_a);
        connect(s4.flange_b, right.flange);
    };
    let ssys = structural_simplify(&model).unwrap();
    let problem = DaeProblem::new(&ssys, &[], (0.0, 1.0)).unwrap();
    let lin = linearize(&ssys, &problem.operating_point(), &[], &[]).unwrap();
    assert_eq!(lin.states.len(), 6, "{:?}", lin.states);
    let mut freqs: Vec<f64> = lin.poles().iter().map(|p| p.frequency).collect();
    freqs.sort_by(f64::total_cmp);
    for j in 1..=3 {
        let exact = 2.0 * (j as f64 * PI / 8.0).sin();
        for f in &freqs[2 * (j - 1)..2 * j] {
            assert!((f - exact).abs() < 1e-9, "{freqs:?}, exact {exact}");
        }
    }
}

#[test]
fn unknown_inputs_and_outputs_are_errors_naming_them() {
    let ssys = structural_simplify(&pendulum(0.0)).unwrap();
    let point = DaeProblem::new(&ssys, &[], (0.0, 1.0))
        .unwrap()
        .operating_point();
    let err = linearize(&ssys, &point, &["tau.kk"], &[])
        .unwrap_err()
        .to_string();
    assert!(err.contains("`tau.kk` is not a parameter"), "{err}");
    let err = linearize(&ssys, &point, &[], &["rev.phii"])
        .unwrap_err()
        .to_string();
    assert!(err.contains("`rev.phii` is not a variable"), "{err}");
}
