//! 1-D models against analytic solutions, with their exact structure after
//! simplification.

#[path = "support/analytic.rs"]
mod analytic;
#[path = "support/models_1d.rs"]
mod models_1d;

use analytic::{damped, tight};
use multibody::prelude::*;

#[test]
fn damped_mass_spring_matches_the_analytic_solution() {
    let (m, c, d) = (2.0, 50.0, 1.5);
    let model = models_1d::mass_spring_damper(m, c, d);
    let ssys = structural_simplify(&model).unwrap();
    assert_eq!(ssys.states(), ["damper.s_rel", "damper.v_rel"]);
    assert_eq!(ssys.mass_matrix_diagonal(), &[1.0, 1.0]);
    let prob = DaeProblem::new(&ssys, &[("mass.s", 0.1), ("mass.v", 0.0)], (0.0, 5.0)).unwrap();
    let sol = prob.solve(&tight()).unwrap();
    for &t in &[0.1, 0.5, 1.0, 2.0, 3.5, 5.0] {
        let exact = damped(m, d, c, 0.1, 0.0, t);
        let got = sol.at("mass.s", t).unwrap();
        assert!(
            (got - exact).abs() <= 1e-6 * exact.abs().max(1e-4),
            "s({t}) = {got}, exact {exact}"
        );
    }
}

#[test]
fn rc_circuit_charges_with_time_constant_rc() {
    let model = models_1d::rc_circuit();
    let ssys = structural_simplify(&model).unwrap();
    assert_eq!(ssys.states(), ["capacitor.v"]);
    assert_eq!(ssys.unknowns().len(), 1);
    let sol = DaeProblem::new(&ssys, &[], (0.0, 5.0))
        .unwrap()
        .solve(&tight())
        .unwrap();
    for &t in &[0.2, 1.0, 2.0, 5.0] {
        let exact = 10.0 * (1.0 - (-t / 1.0f64).exp());
        let got = sol.at("capacitor.v", t).unwrap();
        assert!(
            (got - exact).abs() < 1e-6 * exact,
            "v({t}) = {got}, exact {exact}"
        );
        let i = sol.at("resistor.i", t).unwrap();
        assert!((i - (10.0 - exact) / 1000.0).abs() < 1e-9, "i({t}) = {i}");
    }
}

#[test]
fn two_inertias_with_a_spring_damper_conserve_momentum() {
    let (j1, j2, c, d) = (1.0, 3.0, 20.0, 0.5);
    let model = models_1d::two_inertias(j1, j2, c, d);
    let ssys = structural_simplify(&model).unwrap();
    // Free chain: the absolute angle of one inertia and the relative states.
    assert_eq!(ssys.states().len(), 4);
    let prob = DaeProblem::new(
        &ssys,
        &[
            ("inertia1.phi", 0.0),
            ("inertia1.w", 2.0),
            ("inertia2.w", 0.0),
            ("coupling.phi_rel", 0.0),
        ],
        (0.0, 4.0),
    )
    .unwrap();
    let sol = prob.solve(&tight()).unwrap();
    let w1 = sol.get("inertia1.w").unwrap();
    let w2 = sol.get("inertia2.w").unwrap();
    for k in 0..w1.len() {
        assert!(
            (j1 * w1[k] + j2 * w2[k] - 2.0).abs() < 1e-8,
            "momentum at {}",
            sol.t()[k]
        );
    }
    // Relative motion: J_red phi'' + d phi' + c phi = 0, phi(0) = 0, phi'(0) = -2.
    let jr = j1 * j2 / (j1 + j2);
    for &t in &[0.3, 1.0, 2.5, 4.0] {
        let exact = damped(jr, d, c, 0.0, -2.0, t);
        let got = sol.at("coupling.phi_rel", t).unwrap();
        assert!(
            (got - exact).abs() < 1e-6 * exact.abs().max(1e-3),
            "phi_rel({t}) = {got}, exact {exact}"
        );
    }
}

#[test]
fn undamped_oscillator_keeps_its_energy_for_100_periods() {
    let c = 4.0 * std::f64::consts::PI * std::f64::consts::PI; // period 1 s with J = 1
    let model = models_1d::undamped_oscillator(c);
    let ssys = structural_simplify(&model).unwrap();
    assert_eq!(ssys.states(), ["inertia.phi", "inertia.w"]);
    // The energy error is the integrator's: it shrinks with the tolerance (BDF damps a
    // little each period, so over 100 periods it is about a thousand times rtol).
    let drift = |rtol: f64| -> (f64, Solution) {
        let opts = SolverOptions {
            rtol,
            atol: rtol * 1e-2,
            ..SolverOptions::default()
        };
        let sol = DaeProblem::new(&ssys, &[], (0.0, 100.0))
            .unwrap()
            .solve(&opts)
            .unwrap();
        let s = sol.get_many(&["inertia.phi", "inertia.w"]).unwrap();
        let e0 = 0.5 * c;
        let mut worst = 0.0f64;
        for k in 0..s[0].len() {
            let e = 0.5 * s[1][k] * s[1][k] + 0.5 * c * s[0][k] * s[0][k];
            worst = worst.max(((e - e0) / e0).abs());
        }
        (worst, sol)
    };
    let (coarse, _) = drift(1e-6);
    let (fine, sol) = drift(1e-8);
    assert!(fine < 1e-4, "relative energy drift {fine:e} at rtol 1e-8");
    assert!(
        fine < coarse / 20.0,
        "drift {fine:e} at rtol 1e-8 vs {coarse:e} at 1e-6"
    );
    // The phase stays right too: phi(100) = cos(2 pi 100) = 1.
    assert!((sol.final_value("inertia.phi").unwrap() - 1.0).abs() < 1e-4);
}
