//! Linearization against closed forms (a pendulum at its equilibria, a chain of masses
//! and springs) and against central differences of the nonlinear model.

#![allow(missing_docs)]

use std::f64::consts::PI;

use multibody::blocks::Constant;
use multibody::joints::{Revolute, RevolutePlanarLoopConstraint};
use multibody::nalgebra::Complex;
use multibody::parts::{Body, BodyShape, FixedTranslation};
use multibody::prelude::*;
use multibody::rotational::{Damper, Torque};
use multibody::translational::{Fixed, Mass, Spring};
use multibody::world::World;
use multibody::{LinearModel, OperatingPoint, linearize};

#[path = "../examples/fourbar.rs"]
#[allow(dead_code)]
mod fourbar_example;

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

/// Asserts that `lin` (of `ssys` at `point`) agrees with central differences of the
/// nonlinear model: A and B with the derivatives at consistent points with perturbed
/// states and inputs, C and D with the outputs there (to `tol`).
fn check_differences(ssys: &SimplifiedSystem, lin: &LinearModel, point: &OperatingPoint, tol: f64) {
    let names = ssys.unknowns();
    let index: Vec<usize> = lin
        .states
        .iter()
        .map(|s| names.iter().position(|n| n == s).unwrap())
        .collect();
    let x0: Vec<f64> = index.iter().map(|&k| point.u[k]).collect();
    let p0: Vec<f64> = lin
        .inputs
        .iter()
        .map(|name| {
            let problem = DaeProblem::new(ssys, &[], (0.0, 1e-9)).unwrap();
            problem
                .solve(&SolverOptions::default())
                .unwrap()
                .parameter(name.as_str())
                .unwrap()
        })
        .collect();
    let at = |x: &[f64], p: &[f64]| {
        let mut builder = DaeProblem::builder(ssys, (0.0, 1e-9));
        for (name, &v) in lin.states.iter().zip(x).chain(lin.inputs.iter().zip(p)) {
            builder = builder.value(name.as_str(), v);
        }
        let problem = builder.build().unwrap();
        let q = problem.operating_point();
        let sol = problem.solve(&SolverOptions::default()).unwrap();
        let y: Vec<f64> = lin
            .outputs
            .iter()
            .map(|o| sol.at(o.as_str(), 0.0).unwrap())
            .collect();
        let dx: Vec<f64> = index.iter().map(|&k| q.up[k]).collect();
        (dx, y)
    };
    let h = 1e-6;
    let (n, m) = (lin.states.len(), lin.inputs.len());
    for col in 0..n + m {
        let (mut xa, mut xb, mut pa, mut pb) = (x0.clone(), x0.clone(), p0.clone(), p0.clone());
        if col < n {
            xa[col] += h;
            xb[col] -= h;
        } else {
            pa[col - n] += h;
            pb[col - n] -= h;
        }
        let (plus, minus) = (at(&xa, &pa), at(&xb, &pb));
        for row in 0..n {
            let fd = (plus.0[row] - minus.0[row]) / (2.0 * h);
            let exact = if col < n {
                lin.a[(row, col)]
            } else {
                lin.b[(row, col - n)]
            };
            let what = &lin.states[row];
            assert!(
                (fd - exact).abs() < tol,
                "d{what}'/d[{col}]: {exact}, differences {fd}"
            );
        }
        for out in 0..lin.outputs.len() {
            let fd = (plus.1[out] - minus.1[out]) / (2.0 * h);
            let exact = if col < n {
                lin.c[(out, col)]
            } else {
                lin.d[(out, col - n)]
            };
            let what = &lin.outputs[out];
            assert!(
                (fd - exact).abs() < tol,
                "d{what}/d[{col}]: {exact}, differences {fd}"
            );
        }
    }
}

#[test]
fn linearization_agrees_with_central_differences_of_the_nonlinear_model() {
    // Away from any equilibrium, with damping and a torque input.
    let d = 0.1;
    let ssys = structural_simplify(&pendulum(d)).unwrap();
    let (lin, point) = linearized(&ssys, 0.3, 0.7);
    check_differences(&ssys, &lin, &point, 1e-6);
    // The torque input accelerates the axis by 1 / I: in the transfer to the speed.
    let w = lin.c.row(1).transpose() / d;
    let gain = (w.transpose() * &lin.b)[(0, 0)];
    assert!((gain.abs() - 1.0 / INERTIA).abs() < 1e-9, "{gain}");
}

#[test]
fn the_seed_four_bar_linearizes_in_its_degrees_of_freedom() {
    // A closed loop (cut automatically): linearized in the states the simplifier chose
    // (the two dampers' relative angles and speeds), against central differences.
    let model = fourbar_example::fourbar();
    let ssys = structural_simplify(&model).unwrap();
    let problem = DaeProblem::new(&ssys, &[], (0.0, 1.0)).unwrap();
    let point = problem.operating_point();
    let lin = linearize(&ssys, &point, &[], &["j2.phi", "j3.phi"]).unwrap();
    assert_eq!(lin.states.len(), 4, "{:?}", lin.states);
    check_differences(&ssys, &lin, &point, 1e-5);
}

#[test]
fn a_double_pendulum_has_the_closed_form_eigenfrequencies() {
    // Point masses m on massless links l, hanging: w^2 = (g / l) (2 -+ sqrt 2).
    let (m, l) = (1.0, 0.8);
    let model = system! {
        name: "double";
        world = World::default();
        rev1 = Revolute { n: [0.0, 0.0, 1.0] };
        link1 = FixedTranslation { r: [l, 0.0, 0.0] };
        mass1 = Body { m, I_11: 0.0, I_22: 0.0, I_33: 0.0 };
        rev2 = Revolute { n: [0.0, 0.0, 1.0] };
        link2 = FixedTranslation { r: [l, 0.0, 0.0] };
        mass2 = Body { m, I_11: 0.0, I_22: 0.0, I_33: 0.0 };
        connect(world.frame_b, rev1.frame_a);
        connect(rev1.frame_b, link1.frame_a);
        connect(link1.frame_b, mass1.frame_a);
        connect(link1.frame_b, rev2.frame_a);
        connect(rev2.frame_b, link2.frame_a);
        connect(link2.frame_b, mass2.frame_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    let start = [
        ("rev1.phi", -PI / 2.0),
        ("rev1.w", 0.0),
        ("rev2.phi", 0.0),
        ("rev2.w", 0.0),
    ];
    let problem = DaeProblem::new(&ssys, &start, (0.0, 1.0)).unwrap();
    let lin = linearize(&ssys, &problem.operating_point(), &[], &[]).unwrap();
    let mut freqs: Vec<f64> = lin.poles().iter().map(|p| p.frequency).collect();
    freqs.sort_by(f64::total_cmp);
    let slow = (G / l * (2.0 - 2f64.sqrt())).sqrt();
    let fast = (G / l * (2.0 + 2f64.sqrt())).sqrt();
    assert_eq!(freqs.len(), 4);
    for (f, exact) in freqs.iter().zip([slow, slow, fast, fast]) {
        assert!(
            (f - exact).abs() < 1e-9,
            "{freqs:?}, exact {slow} and {fast}"
        );
    }
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

#[test]
fn a_dc_motor_has_the_closed_form_poles_and_frequency_response() {
    // L i' = V - R i - k w, J w' = k i - d w: w / V = k / ((L s + R)(J s + d) + k^2).
    use multibody::electrical::{EMF, Ground, Inductor, Resistor, SignalVoltage};
    let (r, l, k, j, d) = (2.0, 0.05, 0.8, 0.1, 0.02);
    let model = system! {
        name: "motor";
        v = Constant { k: 0.0 };
        source = SignalVoltage::default();
        resistor = Resistor { R: r };
        inductor = Inductor { L: l };
        emf = EMF { k };
        ground = Ground::default();
        rotor = multibody::rotational::Inertia { J: j };
        friction = Damper { d };
        housing = multibody::rotational::Fixed::default();
        connect(v.y, source.v_ref);
        connect(source.p, resistor.p);
        connect(resistor.n, inductor.p);
        connect(inductor.n, emf.p);
        connect(emf.n, source.n);
        connect(source.n, ground.p);
        connect(emf.flange, rotor.flange_a);
        connect(rotor.flange_b, friction.flange_b);
        connect(friction.flange_a, housing.flange);
    };
    let ssys = structural_simplify(&model).unwrap();
    let problem = DaeProblem::new(&ssys, &[], (0.0, 1.0)).unwrap();
    let lin = linearize(&ssys, &problem.operating_point(), &["v.k"], &["rotor.w"]).unwrap();
    // Poles: the roots of (L s + R)(J s + d) + k^2, besides the angle's integrator.
    let (a2, a1, a0) = (l * j, l * d + r * j, r * d + k * k);
    let disc = a1 * a1 - 4.0 * a2 * a0;
    let mut expected = if disc >= 0.0 {
        vec![
            Complex::new((-a1 - disc.sqrt()) / (2.0 * a2), 0.0),
            Complex::new((-a1 + disc.sqrt()) / (2.0 * a2), 0.0),
        ]
    } else {
        vec![
            Complex::new(-a1 / (2.0 * a2), -(-disc).sqrt() / (2.0 * a2)),
            Complex::new(-a1 / (2.0 * a2), (-disc).sqrt() / (2.0 * a2)),
        ]
    };
    let got: Vec<Complex<f64>> = lin
        .eigenvalues()
        .into_iter()
        .filter(|p| p.norm() > 1e-9)
        .collect();
    expected.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
    assert_eq!(got.len(), 2, "{:?}", lin.eigenvalues());
    for (g, e) in got.iter().zip(&expected) {
        assert!((g - e).norm() < 1e-9 * e.norm(), "{g} vs {e}");
    }
    // The frequency response against the closed-form transfer function, and the
    // steady-state gain k / (R d + k^2) at low frequency.
    for w in [0.01, 1.0, 10.0, 100.0] {
        let s = Complex::new(0.0, w);
        let exact = k / ((s * l + r) * (s * j + d) + k * k);
        let h = lin.frequency_response(w).unwrap()[(0, 0)];
        assert!(
            (h - exact).norm() < 1e-9 * exact.norm(),
            "at {w}: {h} vs {exact}"
        );
    }
    let dc = lin.frequency_response(1e-9).unwrap()[(0, 0)];
    assert!((dc.re - k / (r * d + k * k)).abs() < 1e-6);
    // The Bode diagram and the poles as PNGs.
    let dir = std::env::temp_dir().join(format!("multibody-bode-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    multibody::plot::plot_bode(&lin, (0, 0), (0.01, 1000.0), 200, dir.join("bode.png")).unwrap();
    multibody::plot::plot_poles(&lin, dir.join("poles.png")).unwrap();
    assert!(std::fs::metadata(dir.join("bode.png")).unwrap().len() > 1000);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn linearization_in_chosen_states() {
    // With a damper, state selection takes its relative angle and speed; asked in the
    // joint's angle and speed, the model has the pendulum's form [[0, 1], [a, b]] and
    // the same eigenvalues.
    let ssys = structural_simplify(&pendulum(0.1)).unwrap();
    let (lin, point) = linearized(&ssys, 0.3, 0.0);
    let chosen = multibody::linearize_in(
        &ssys,
        &point,
        &["tau.k"],
        &["rev.phi"],
        &["rev.phi", "rev.w"],
    )
    .unwrap();
    assert_eq!(chosen.states, vec!["rev.phi", "rev.w"]);
    assert!(chosen.a[(0, 0)].abs() < 1e-12 && (chosen.a[(0, 1)] - 1.0).abs() < 1e-12);
    assert!((chosen.b[(1, 0)] - 1.0 / INERTIA).abs() < 1e-9 && chosen.b[(0, 0)].abs() < 1e-12);
    assert!((chosen.c[(0, 0)] - 1.0).abs() < 1e-12 && chosen.c[(0, 1)].abs() < 1e-12);
    for (x, y) in lin.eigenvalues().iter().zip(chosen.eigenvalues()) {
        assert!((x - y).norm() < 1e-9);
    }
    let err = multibody::linearize_in(&ssys, &point, &[], &[], &["rev.phi", "damper.phi_rel"])
        .unwrap_err()
        .to_string();
    assert!(err.contains("do not determine the state"), "{err}");
}

#[test]
fn a_parallelogram_four_bar_linearizes_in_its_one_degree_of_freedom() {
    // Two cranks of length l hanging from the world at x = 0 and x = l, a coupler
    // between their lower ends, point masses m at the bars' centres: one degree of
    // freedom (the first crank's angle), with kinetic energy (m l^2 / 4 + m l^2 / 4 +
    // m l^2) phi'^2 / 2 and potential energy 2 m g l (1 - cos phi). About the hanging
    // position it oscillates with w^2 = 2 m g l / (1.5 m l^2) = 4 g / (3 l).
    let (m, l) = (0.7, 1.2);
    let model = system! {
        name: "parallelogram";
        world = World::default();
        anchor = FixedTranslation { r: [l, 0.0, 0.0] };
        j1 = Revolute { n: [0.0, 0.0, 1.0] };
        j2 = Revolute { n: [0.0, 0.0, 1.0] };
        j3 = Revolute { n: [0.0, 0.0, 1.0] };
        j4 = RevolutePlanarLoopConstraint { n: [0.0, 0.0, 1.0] };
        crank1 = BodyShape { m, r: [0.0, -l, 0.0], I_diag: [0.0, 0.0, 0.0] };
        coupler = BodyShape { m, r: [l, 0.0, 0.0], I_diag: [0.0, 0.0, 0.0] };
        crank2 = BodyShape { m, r: [0.0, l, 0.0], I_diag: [0.0, 0.0, 0.0] };
        connect(world.frame_b, j1.frame_a);
        connect(j1.frame_b, crank1.frame_a);
        connect(crank1.frame_b, j2.frame_a);
        connect(j2.frame_b, coupler.frame_a);
        connect(coupler.frame_b, j3.frame_a);
        connect(j3.frame_b, crank2.frame_a);
        connect(crank2.frame_b, j4.frame_a);
        connect(world.frame_b, anchor.frame_a);
        connect(anchor.frame_b, j4.frame_b);
    };
    let ssys = structural_simplify(&model).unwrap();
    assert_eq!(ssys.states().len(), 2, "{:?}", ssys.states());
    let problem = DaeProblem::builder(&ssys, (0.0, 1.0))
        .value(model.j1.phi, 0.0)
        .value(model.j1.w, 0.0)
        .build()
        .unwrap();
    let point = problem.operating_point();
    let lin = multibody::linearize_in(
        &ssys,
        &point,
        &[],
        &["j2.phi", "j3.phi"],
        &["j1.phi", "j1.w"],
    )
    .unwrap();
    let w2 = 4.0 * G / (3.0 * l);
    assert!(
        lin.a[(0, 0)].abs() < 1e-12 && (lin.a[(0, 1)] - 1.0).abs() < 1e-12,
        "{}",
        lin.a
    );
    assert!(
        (lin.a[(1, 0)] + w2).abs() < 1e-9 * w2,
        "{} vs {}",
        lin.a[(1, 0)],
        -w2
    );
    assert!(lin.a[(1, 1)].abs() < 1e-12, "{}", lin.a);
    for e in lin.eigenvalues() {
        assert!(
            e.re.abs() < 1e-9 && (e.im.abs() - w2.sqrt()).abs() < 1e-9,
            "{e}"
        );
    }
    // The coupler stays parallel to the ground (j2 = -j1) and the other crank turns with
    // the first (j3 = j1).
    assert!(
        (lin.c[(0, 0)] + 1.0).abs() < 1e-9 && (lin.c[(1, 0)] - 1.0).abs() < 1e-9,
        "{}",
        lin.c
    );
    // Away from the equilibrium too, against central differences of the nonlinear model.
    let moving = DaeProblem::builder(&ssys, (0.0, 1.0))
        .value(model.j1.phi, 0.4)
        .value(model.j1.w, 0.3)
        .build()
        .unwrap();
    let point = moving.operating_point();
    let lin = linearize(&ssys, &point, &[], &["j3.phi"]).unwrap();
    check_differences(&ssys, &lin, &point, 1e-6);
}
