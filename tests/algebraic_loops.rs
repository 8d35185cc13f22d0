//! Algebraic loops: a linear resistor network that tearing solves inside the compiled
//! functions, and a nonlinear loop whose tearing variable is left to the solver.

#![allow(missing_docs)]

#[path = "support/models_1d.rs"]
mod models_1d;

#[path = "support/analytic.rs"]
mod analytic;

use analytic::tight;
use multibody::electrical::Pin;
use multibody::prelude::*;

/// Node voltages (a, b) of the bridge for a capacitor voltage `vc = va - vb`: nodal
/// analysis with the capacitor current `ic` as unknown, solved by hand.
fn bridge_nodes(vc: f64) -> (f64, f64, f64) {
    // KCL at a: (10 - va)/100 = va/300 + (va - vb)/500 + ic
    // KCL at b: (10 - vb)/200 + (va - vb)/500 + ic = vb/400
    // va - vb = vc.  Substitute va = vb + vc and add the two KCLs (ic cancels):
    // (10 - vb - vc)/100 - (vb + vc)/300 + (10 - vb)/200 - vb/400 = 0
    let (g1, g2, g3, g4) = (1.0 / 100.0, 1.0 / 200.0, 1.0 / 300.0, 1.0 / 400.0);
    let vb = (10.0 * g1 - vc * g1 - vc * g3 + 10.0 * g2) / (g1 + g3 + g2 + g4);
    let va = vb + vc;
    let ic = (10.0 - va) * g1 - va * g3 - (va - vb) / 500.0;
    (va, vb, ic)
}

#[test]
fn resistor_bridge_is_a_linear_block_solved_inside() {
    let ssys = structural_simplify(&models_1d::bridge()).unwrap();
    // One state (the capacitor voltage); the network's currents form one linear block
    // that tearing reduces and the compiled residual solves: no algebraic unknowns.
    assert_eq!(ssys.states(), ["c.v"]);
    assert_eq!(ssys.mass_matrix_diagonal(), &[1.0]);
    let st = ssys.statistics();
    assert_eq!(st.algebraic, 0, "{st}");
    assert_eq!(st.linear_inline.len(), 1, "{st}");
    let (size, torn) = st.linear_inline[0];
    assert!(size >= 4 && torn >= 1 && torn < size, "{st}");
    assert!(st.nonlinear.is_empty(), "{st}");

    let sol = DaeProblem::new(&ssys, &[("c.v", 0.0)], (0.0, 2.0))
        .unwrap()
        .solve(&tight())
        .unwrap();
    for &t in &[0.0, 0.05, 0.3, 2.0] {
        let vc = sol.at("c.v", t).unwrap();
        let (va, vb, ic) = bridge_nodes(vc);
        assert!((sol.at("r3.v", t).unwrap() - va).abs() < 1e-9, "va at {t}");
        assert!((sol.at("r4.v", t).unwrap() - vb).abs() < 1e-9, "vb at {t}");
        assert!((sol.at("c.i", t).unwrap() - ic).abs() < 1e-11, "ic at {t}");
    }
    // At steady state the capacitor carries no current: vc = va - vb of the bridge
    // without it.
    let vc_end = sol.final_value("c.v").unwrap();
    let (_, _, ic_end) = bridge_nodes(vc_end);
    assert!(ic_end.abs() < 1e-6, "capacitor current at the end {ic_end}");
}

#[test]
fn nonlinear_loop_keeps_one_iteration_variable() {
    let model = models_1d::cubic_loop();
    let ssys = structural_simplify(&model).unwrap();
    // The current through the cubic resistor cannot be solved explicitly: it is the
    // tearing variable of a nonlinear block and an algebraic unknown of the DAE.
    assert_eq!(
        ssys.statistics().nonlinear,
        vec![(1, 1)],
        "{}",
        ssys.statistics()
    );
    assert_eq!(ssys.unknowns().len(), 2);
    assert_eq!(ssys.mass_matrix_diagonal(), &[0.0, 1.0]);
    let sol = DaeProblem::new(&ssys, &[("c.v", 0.0)], (0.0, 3.0))
        .unwrap()
        .solve(&SolverOptions {
            rtol: 1e-8,
            atol: 1e-10,
            ..SolverOptions::default()
        })
        .unwrap();
    // The dynamics in closed form. With i the current through the cubic resistor,
    // 5 - vc = i + 2 i^3 and i = vc / 2 + C vc' (C = 0.1). Writing vc = 5 - i - 2 i^3:
    //   (1 + 6 i^2) i' = -10 (i^3 + 1.5 i - 2.5) = -10 (i - 1) (i^2 + i + 2.5),
    // separable; partial fractions give
    //   F(i) = 14/9 ln(i - 1) + 20/9 ln(i^2 + i + 2.5) + 4/9 atan((2 i + 1) / 3)
    //        = F(i0) - 10 t,
    // with i0 the real root of 2 i^3 + i - 5 = 0 (vc(0) = 0), by Cardano. F increases
    // on (1, i0]: bisection inverts it. (Checked against RK4 of the ODE: 1e-15.)
    let f = |i: f64| {
        14.0 / 9.0 * (i - 1.0).ln()
            + 20.0 / 9.0 * (i * i + i + 2.5).ln()
            + 4.0 / 9.0 * ((2.0 * i + 1.0) / 3.0).atan()
    };
    // i^3 + p i + q = 0 with p = 1/2, q = -5/2.
    let (p, q) = (0.5f64, -2.5f64);
    let d = (q * q / 4.0 + p * p * p / 27.0).sqrt();
    let i0 = (-q / 2.0 + d).cbrt() + (-q / 2.0 - d).cbrt();
    assert!((2.0 * i0.powi(3) + i0 - 5.0).abs() < 1e-12, "{i0}");
    let i_exact = |t: f64| {
        let target = f(i0) - 10.0 * t;
        let (mut lo, mut hi) = (1.0f64, i0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if f(mid) < target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    };
    let vc = sol.get("c.v").unwrap();
    let i = sol.get("nonlinear.i").unwrap();
    let load = sol.get("load.i").unwrap();
    assert!(vc.len() > 20);
    for (k, &t) in sol.t().iter().enumerate() {
        let ie = i_exact(t);
        let vce = 5.0 - ie - 2.0 * ie.powi(3);
        // rtol 1e-8 on values of order 1 over 3 s of a stable decay: errors near
        // 1e-8; 1e-6 leaves margin. A wrong C or R (rate -10 (i - 1) ... scales with
        // 1/C) changes vc by 0.1-1 at t = 0.1-0.5.
        assert!(
            (vc[k] - vce).abs() < 1e-6,
            "vc({t}) = {}, exact {vce}",
            vc[k]
        );
        assert!((i[k] - ie).abs() < 1e-6, "i({t}) = {}, exact {ie}", i[k]);
        assert!(
            (load[k] - vce / 2.0).abs() < 1e-6,
            "load.i({t}) = {}, exact {}",
            load[k],
            vce / 2.0
        );
    }
    // Steady state: 2 i^3 + 3 i - 5 = 0 -> i = 1, reached to 1e-9 by t = 3.
    assert!((sol.final_value("load.i").unwrap() - 1.0).abs() < 1e-6);
    let _ = Pin;
}
