//! The seed's inverse pendulum (`001`, Exercise 1): the upright eigenvalues against the
//! box's closed form, the designed closed-loop poles, and the controllers holding it.

#![allow(missing_docs)]

#[path = "../examples/inverse_pendulum.rs"]
#[allow(dead_code)]
mod example;

use multibody::nalgebra::{Complex, DVector};
use multibody::prelude::*;

#[test]
fn upright_eigenvalues_are_the_closed_form_of_the_box() {
    // A steel box (7700 kg/m3) of 0.5 x 0.25 x 0.25 m on an axis through the centre of
    // one end face: I = m (L^2 + w^2) / 12 + m (L/2)^2; upright it falls with
    // lambda = +-sqrt(m g L/2 / I).
    let (l, w): (f64, f64) = (0.5, 0.25);
    let m = 7700.0 * l * w * w;
    let inertia = m * (l * l + w * w) / 12.0 + m * (l / 2.0).powi(2);
    let lambda = (m * 9.80665 * l / 2.0 / inertia).sqrt();
    let ssys = structural_simplify(&example::inverse_pendulum()).unwrap();
    let open = example::linearized(&ssys, (0.0, 0.0)).unwrap();
    let ev = open.eigenvalues();
    assert_eq!(ev.len(), 2);
    assert!(
        (ev[0].re + lambda).abs() < 1e-9 * lambda && ev[0].im == 0.0,
        "{ev:?}"
    );
    assert!(
        (ev[1].re - lambda).abs() < 1e-9 * lambda && ev[1].im == 0.0,
        "{ev:?}"
    );
    // The torque input: b = 1 / I in the speed's row.
    let w_row = open.states.iter().position(|s| s == "rev.w").unwrap();
    assert!((open.b[(w_row, 0)] - 1.0 / inertia).abs() < 1e-9 / inertia);
}

#[test]
fn pole_placement_and_the_regulator_hold_the_pendulum_upright() {
    let ssys = structural_simplify(&example::inverse_pendulum()).unwrap();
    let open = example::linearized(&ssys, (0.0, 0.0)).unwrap();
    // PD: the linearized closed loop has the designed poles.
    let pd = example::pd_gains(&open, [-4.0, -6.0]);
    let closed = example::linearized(&ssys, pd).unwrap();
    let ev = closed.eigenvalues();
    assert!(
        (ev[0].re + 6.0).abs() < 1e-6 && (ev[1].re + 4.0).abs() < 1e-6,
        "{ev:?}"
    );
    assert!(ev.iter().all(|l| l.im.abs() < 1e-6), "{ev:?}");
    let sol = example::simulate(&ssys, pd, 3.0).unwrap();
    assert!(sol.final_value("rev.phi").unwrap().abs() < 1e-4);
    // LQR: the closed loop's eigenvalues are those of A - B K of the design, and the
    // pendulum comes upright from 5 deg.
    let state = example::lqr_gains(&open, [1e4, 1e2], 1e-2, pd);
    let k: Vec<f64> = open
        .states
        .iter()
        .map(|s| if s == "rev.phi" { state.0 } else { state.1 })
        .collect();
    let design = &open.a - &open.b * DVector::from_vec(k).transpose();
    let mut expected: Vec<Complex<f64>> = design.complex_eigenvalues().iter().copied().collect();
    expected.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
    let closed = example::linearized(&ssys, state).unwrap();
    for (got, want) in closed.eigenvalues().iter().zip(&expected) {
        assert!((got - want).norm() < 1e-6, "{got} vs {want}");
        assert!(got.re < 0.0);
    }
    let sol = example::simulate(&ssys, state, 3.0).unwrap();
    assert!(sol.final_value("rev.phi").unwrap().abs() < 1e-6);
    // The open loop falls.
    let falling = example::simulate(&ssys, (0.0, 0.0), 0.8).unwrap();
    assert!(falling.final_value("rev.phi").unwrap() > 0.5);
}

#[path = "../examples/cart_pole.rs"]
#[allow(dead_code)]
mod cart_pole;

#[test]
fn the_regulator_brings_the_cart_pole_upright_and_back_to_its_start() {
    let ssys = structural_simplify(&cart_pole::cart_pole()).unwrap();
    let open = cart_pole::linearized(&ssys, &[]).unwrap();
    assert_eq!(open.states.len(), 4, "{:?}", open.states);
    // The cart's position and speed are free: a double eigenvalue at 0; the pendulum
    // a real pair.
    let ev = open.eigenvalues();
    assert!(ev[1].norm() < 1e-9 && ev[2].norm() < 1e-9 && (ev[0] + ev[3]).norm() < 1e-9);
    let gains = cart_pole::design(&open);
    // The cart position does not enter the dynamics (a zero column of A), so the
    // Riccati equation's diagonal entry gives its gain exactly: Q_s = R k_s^2.
    let k_s = gains
        .iter()
        .find(|(n, _)| *n == "controller.k_s")
        .unwrap()
        .1;
    assert!((k_s.abs() - (10.0f64 / 0.1).sqrt()).abs() < 1e-9, "{k_s}");
    // The linearized closed loop has the eigenvalues of A - B K.
    let k: Vec<f64> = gains.iter().map(|&(_, v)| v).collect();
    let design = &open.a - &open.b * DVector::from_vec(k).transpose();
    let mut expected: Vec<Complex<f64>> = design.complex_eigenvalues().iter().copied().collect();
    expected.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
    let closed = cart_pole::linearized(&ssys, &gains).unwrap();
    for (got, want) in closed.eigenvalues().iter().zip(&expected) {
        assert!(
            (got - want).norm() < 1e-6 && got.re < 0.0,
            "{got} vs {want}"
        );
    }
    let sol = DaeProblem::new(&ssys, &gains, (0.0, 8.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    assert!(sol.final_value("hinge.phi").unwrap().abs() < 1e-4);
    assert!(sol.final_value("slider.s").unwrap().abs() < 1e-4);
}
