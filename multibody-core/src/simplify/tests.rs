//! Tests of structural simplification on small models built with the builder API.

use crate::expr::Expr;
use crate::model::{System, Variable};
use crate::solve::{DaeProblem, SolverOptions};

use super::*;

/// m x'' + d x' + k x = 0 with x(0) = 1, v(0) = 0.
fn oscillator(name: &str, m: f64, d: f64, k: f64) -> System {
    let mut s = System::new(name);
    let x = s.variable(Variable::new("x").start(1.0).fixed(true));
    let v = s.variable(Variable::new("v").start(0.0).fixed(true));
    let pm = s.param("m", m);
    let pd = s.param("d", d);
    let pk = s.param("k", k);
    s.equation(x.der(), v);
    s.equation(pm * v.der(), -pk * x - pd * v);
    s
}

#[test]
fn damped_oscillator_matches_the_analytic_solution() {
    let (m, d, k) = (1.0, 0.4, 4.0);
    let ssys = structural_simplify(&oscillator("osc", m, d, k)).unwrap();
    assert_eq!(ssys.states(), vec!["x", "v"]);
    assert_eq!(ssys.unknowns(), vec!["x", "v"]);
    assert_eq!(ssys.mass_matrix_diagonal(), &[1.0, 1.0]);
    let prob = DaeProblem::new(&ssys, &[], (0.0, 10.0)).unwrap();
    let opts = SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        ..SolverOptions::default()
    };
    let sol = prob.solve(&opts).unwrap();
    // x(t) = e^{-zeta w t} (cos(wd t) + zeta w / wd sin(wd t))
    let w0 = (k / m).sqrt();
    let zeta = d / (2.0 * (k * m).sqrt());
    let wd = w0 * (1.0 - zeta * zeta).sqrt();
    for &t in &[0.5, 1.0, 2.5, 5.0, 10.0] {
        let exact = (-zeta * w0 * t).exp() * ((wd * t).cos() + zeta * w0 / wd * (wd * t).sin());
        let got = sol.at("x", t).unwrap();
        assert!(
            (got - exact).abs() <= 1e-6 * exact.abs().max(1e-3),
            "x({t}) = {got}, exact {exact}"
        );
    }
    // Observed derivative and a new problem with another parameter value.
    let dv = sol.get("der(v)").unwrap();
    let x = sol.get("x").unwrap();
    let v = sol.get("v").unwrap();
    for i in 0..x.len() {
        assert!((dv[i] - (-k * x[i] - d * v[i]) / m).abs() < 1e-9);
    }
    let prob2 = DaeProblem::new(&ssys, &[("k", 9.0), ("x", 2.0)], (0.0, 1.0)).unwrap();
    assert_eq!(prob2.initial_unknowns(), &[2.0, 0.0]);
    let sol2 = prob2.solve(&opts).unwrap();
    let exact = 2.0
        * (-0.2f64).exp()
        * ((9.0f64 - 0.04).sqrt().cos()
            + 0.2 / (9.0f64 - 0.04).sqrt() * (9.0f64 - 0.04).sqrt().sin());
    assert!(
        (sol2.final_value("x").unwrap() - exact).abs() < 1e-6,
        "{}",
        sol2.final_value("x").unwrap()
    );
}

/// The Cartesian pendulum: index 3.
fn pendulum(prefer_y: bool) -> System {
    let mut s = System::new("pendulum");
    let x = s.variable(Variable::new("x").start(1.0));
    let mut yv = Variable::new("y").start(0.0);
    if prefer_y {
        yv = yv.state_priority(10.0);
    }
    let y = s.variable(yv);
    let vx = s.var("vx");
    let vy = s.var("vy");
    let lambda = s.var("lambda");
    let g = s.param("g", 9.81);
    let l = s.param("L", 1.0);
    s.equation(x.der(), vx);
    s.equation(y.der(), vy);
    s.equation(vx.der(), -lambda * x);
    s.equation(vy.der(), -lambda * y - g);
    s.equation(x * x + y * y, l * l);
    s
}

#[test]
fn cartesian_pendulum_reduces_to_two_states() {
    let ssys = structural_simplify(&pendulum(false)).unwrap();
    let st = ssys.statistics();
    assert_eq!(st.differentiated_equations, 2, "{st}");
    assert_eq!(st.derivative_aliases, 2);
    assert_eq!(ssys.states(), vec!["x", "vx"]);
    // y comes from the nonlinear constraint: an algebraic unknown between the states.
    assert_eq!(ssys.unknowns(), vec!["x", "y", "vx"]);
    assert_eq!(ssys.mass_matrix_diagonal(), &[1.0, 0.0, 1.0]);

    let ssys = structural_simplify(&pendulum(true)).unwrap();
    assert_eq!(ssys.states(), vec!["y", "vy"]);
    assert_eq!(ssys.unknowns(), vec!["y", "x", "vy"]);
}

#[test]
fn cartesian_pendulum_keeps_its_length_and_energy() {
    let ssys = structural_simplify(&pendulum(false)).unwrap();
    // Start at 30 degrees from the bottom, at rest: x = sin, y = -cos.
    let a = 30f64.to_radians();
    let prob = DaeProblem::new_with_guesses(
        &ssys,
        &[("x", a.sin()), ("vx", 0.0)],
        &[("y", -1.0)],
        (0.0, 5.0),
    )
    .unwrap();
    let u0 = prob.initial_unknowns();
    assert!((u0[1] + a.cos()).abs() < 1e-10, "y0 = {}", u0[1]);
    let opts = SolverOptions {
        rtol: 1e-9,
        atol: 1e-10,
        ..SolverOptions::default()
    };
    let sol = prob.solve(&opts).unwrap();
    let s = sol.get_many(&["x", "y", "vx", "vy"]).unwrap();
    let e0 = 9.81 * s[1][0];
    for k in 0..sol.t().len() {
        let (x, y, vx, vy) = (s[0][k], s[1][k], s[2][k], s[3][k]);
        assert!(
            (x * x + y * y - 1.0).abs() < 1e-8,
            "length at {}",
            sol.t()[k]
        );
        assert!(
            (x * vx + y * vy).abs() < 1e-7,
            "velocity constraint at {}",
            sol.t()[k]
        );
        let e = 0.5 * (vx * vx + vy * vy) + 9.81 * y;
        assert!(
            (e - e0).abs() < 1e-5,
            "energy drift {} at {}",
            e - e0,
            sol.t()[k]
        );
    }
    // The exact period of the pendulum (L = 1, g = 9.81) swinging from 30 degrees:
    // T = 4 sqrt(L/g) K(k), k = sin(15 deg), with the complete elliptic integral
    // K(k) = pi / (2 AGM(1, sqrt(1 - k^2))) (mpmath: T = 2.0409898895191304 s; the
    // small-angle period 2 pi sqrt(L/g) = 2.006 s is 1.7 % shorter).
    let k = (a / 2.0).sin();
    let (mut p, mut q) = (1.0f64, (1.0 - k * k).sqrt());
    while (p - q).abs() > 1e-15 {
        (p, q) = ((p + q) / 2.0, (p * q).sqrt());
    }
    let period = 4.0 / 9.81f64.sqrt() * std::f64::consts::PI / (2.0 * p);
    assert!((period - 2.040_989_889_519_13).abs() < 1e-12, "{period}");
    // x passes 0 at T/4, 3T/4, ... with speed sqrt(2 g (1 - cos a)) = 1.62 m/s, and
    // turns at x = -sin(a), +sin(a) at T/2, T, ...: 9 checks over 2.4 periods. At rtol
    // 1e-9 the global error stays near 1e-8, so 1e-6 passes with margin while a 0.1 %
    // period error moves the last zero crossing by 4.6 ms, i.e. x by 7e-3.
    for j in 1..=9 {
        let t = j as f64 * period / 4.0;
        let expected = match j % 4 {
            1 | 3 => 0.0,
            2 => -a.sin(),
            _ => a.sin(),
        };
        let x = sol.at("x", t).unwrap();
        assert!(
            (x - expected).abs() < 1e-6,
            "x({t}) = {x}, expected {expected}"
        );
    }
}

#[test]
fn structurally_singular_model_names_its_variables() {
    let mut s = System::new("bad");
    let x = s.var("x");
    let y = s.var("y");
    s.equation(x, Expr::time());
    s.equation(x * 2.0, Expr::time().sin());
    let _ = y;
    let err = structural_simplify(&s).unwrap_err().to_string();
    assert!(
        err.contains("model `bad` is structurally singular"),
        "{err}"
    );
    assert!(err.contains("no equation determines y"), "{err}");
    assert!(err.contains("determined more than once: x"), "{err}");
    assert!(err.contains("model: 2*x = sin(time)"), "{err}");
}

#[test]
fn nonlinear_algebraic_loop_becomes_an_iteration_variable() {
    // der(x) = -z, z + z^3 = x  (z from a cubic: not solvable explicitly).
    let mut s = System::new("cubic");
    let x = s.variable(Variable::new("x").start(2.0).fixed(true));
    let z = s.variable(Variable::new("z").start(1.0));
    s.equation(x.der(), -z);
    s.equation(z + z.powi(3), x);
    let ssys = structural_simplify(&s).unwrap();
    assert_eq!(ssys.unknowns(), vec!["z", "x"]);
    assert_eq!(ssys.mass_matrix_diagonal(), &[0.0, 1.0]);
    assert_eq!(ssys.statistics().nonlinear, vec![(1, 1)]);
    let prob = DaeProblem::new(&ssys, &[], (0.0, 1.0)).unwrap();
    assert!((prob.initial_unknowns()[0] - 1.0).abs() < 1e-10);
    let sol = prob
        .solve(&SolverOptions {
            rtol: 1e-9,
            atol: 1e-11,
            ..SolverOptions::default()
        })
        .unwrap();
    // The dynamics in closed form: x = z + z^3 gives (1 + 3 z^2) z' = -z, so
    // ln z + 3/2 z^2 = 3/2 - t (z(0) = 1). G(z) = ln z + 3/2 z^2 increases with z:
    // bisection on (0, 1] gives z(t), and x(t) = z + z^3.
    let z_exact = |t: f64| {
        let (mut lo, mut hi) = (1e-6f64, 1.0f64);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if mid.ln() + 1.5 * mid * mid < 1.5 - t {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    };
    let (xs, zs) = (sol.get("x").unwrap(), sol.get("z").unwrap());
    assert!(xs.len() > 10);
    for (k, &t) in sol.t().iter().enumerate() {
        let z = z_exact(t);
        // rtol 1e-9 over one time unit: errors near 1e-9; 1e-7 leaves margin, while z
        // falls from 1 to 0.7343 over the run, so a wrong sign or factor in either
        // equation misses by orders of magnitude more.
        assert!((zs[k] - z).abs() < 1e-7, "z({t}) = {}, exact {z}", zs[k]);
        assert!(
            (xs[k] - (z + z * z * z)).abs() < 1e-7,
            "x({t}) = {}, exact {}",
            xs[k],
            z + z * z * z
        );
    }
}

#[test]
fn pendulum_translation_report() {
    let ssys = structural_simplify(&pendulum(false)).unwrap();
    let report = ssys.statistics().to_string();
    for line in [
        "flat model: 5 scalar equations, 5 scalar unknowns",
        "alias elimination: 0 unknowns removed, 2 derivative aliases",
        "index reduction: 2 equations differentiated, 2 dummy derivatives",
        "sorted system: 5 equations; 2 continuous states, 1 algebraic unknowns, 2 explicit assignments",
        "linear systems solved inside: sizes {3, 1} before and {1, 1} after tearing",
        "nonlinear systems: sizes {1} before and {1} after tearing",
    ] {
        assert!(report.contains(line), "missing `{line}` in\n{report}");
    }
    let eqs = ssys.equations();
    assert_eq!(eqs[0], "0 = x^2 + y^2 - L^2");
    assert_eq!(eqs[1], "der(x) = vx");
    let observed: Vec<String> = ssys.observed().iter().map(|(n, _)| n.clone()).collect();
    for n in ["vy", "lambda", "der(vx)", "der(vy)"] {
        assert!(observed.contains(&n.to_string()), "{observed:?}");
    }
}

#[test]
fn derivative_names_are_made_when_asked_and_match_the_slots() {
    // x'' = -x written with a second derivative: the slots der(x) and der(der(x)).
    let mut s = System::new("second_order");
    let x = s.variable(Variable::new("x").start(1.0).fixed(true));
    s.equation(x.der().der(), -x);
    let ssys = structural_simplify(&s).unwrap();
    let names = ssys.variable_names();
    let derivative_slots: Vec<String> = ssys
        .reduction
        .slots
        .iter()
        .filter(|s| s.order > 0)
        .map(|s| s.name(&ssys.model.variables))
        .collect();
    assert_eq!(derivative_slots, ["der(x)", "der(der(x))"]);
    for slot in &derivative_slots {
        assert!(names.contains(slot), "{slot} missing from {names:?}");
    }
    let prob = DaeProblem::new(&ssys, &[], (0.0, 1.0)).unwrap();
    let sol = prob.solve(&SolverOptions::default()).unwrap();
    // x = cos t, so der(der(x)) = -cos t.
    let acc = sol.get("der(der(x))").unwrap();
    let last = acc.len() - 1;
    assert!((acc[last] + 1f64.cos()).abs() < 1e-3, "{}", acc[last]);
}

#[test]
fn constants_found_after_substitution_are_eliminated_too() {
    // a = 1 and c = 2 are constants; b = 0.5 a + 0.3 c and then d = 3 b - a c are only
    // once a and c are substituted (as a rotation of a constant frame is), and so is
    // e = b + d in a third pass. Only the state x is left, with der(x) = e.
    let mut s = System::new("chained_constants");
    let x = s.variable(Variable::new("x").start(0.0).fixed(true));
    let [a, b, c, d, e] = ["a", "b", "c", "d", "e"].map(|n| s.var(n));
    s.equation(a, 1.0);
    s.equation(c, 2.0);
    s.equation(b, a * 0.5 + c * 0.3);
    s.equation(d, b * 3.0 - a * c);
    s.equation(e, b + d);
    s.equation(x.der(), e);
    let ssys = structural_simplify(&s).unwrap();
    assert_eq!(ssys.unknowns(), ["x"]);
    assert_eq!(
        ssys.statistics().alias_variables,
        5,
        "{}",
        ssys.statistics()
    );
    let sol = DaeProblem::new(&ssys, &[], (0.0, 2.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    // b = 1.1, d = 3.3 - 2 = 1.3, e = 2.4.
    assert!((sol.at("e", 1.0).unwrap() - 2.4).abs() < 1e-12);
    assert!((sol.at("x", 2.0).unwrap() - 4.8).abs() < 1e-9);
}
