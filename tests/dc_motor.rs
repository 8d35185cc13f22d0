//! The seed's DC motor: speed control to the reference, and the electrical time
//! constant of its armature.

#[path = "../examples/dc_motor.rs"]
#[allow(dead_code)]
mod example;

#[path = "support/analytic.rs"]
mod analytic;

use analytic::tight;
use multibody::electrical::{ConstantVoltage, EMF, Ground, Inductor, Resistor};
use multibody::prelude::*;
use multibody::rotational::Fixed;

#[test]
fn speed_controller_follows_the_reference() {
    let ssys = structural_simplify(&example::dc_motor()).unwrap();
    // Motor angle, armature current, integrator state and motor speed.
    assert_eq!(
        ssys.states(),
        [
            "motor_inertia.phi",
            "resistor.i",
            "controller.xi",
            "motor_inertia.w"
        ]
    );
    let sol = DaeProblem::new(&ssys, &[], (0.0, 3.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    // At rest before the reference steps at 0.5 s.
    assert!(sol.at("load_inertia.w", 0.45).unwrap().abs() < 1e-9);
    // Steady state: the load follows 1 rad/s, the motor turns 100 times faster, and
    // with no load torque the voltage balances the back-EMF (k w = 100 V, no current).
    let w = sol.final_value("load_inertia.w").unwrap();
    assert!((w - 1.0).abs() < 1e-4, "load speed {w}");
    assert!((sol.final_value("motor_inertia.w").unwrap() - 100.0).abs() < 1e-2);
    assert!((sol.final_value("controller.y").unwrap() - 100.0).abs() < 1e-2);
    assert!(sol.final_value("inductor.i").unwrap().abs() < 1e-4);
    // The controller output stays inside its limits.
    let y = sol.get("controller.y").unwrap();
    assert!(y.iter().all(|v| (-200.0 - 1e-9..=200.0 + 1e-9).contains(v)));
}

#[test]
fn blocked_rotor_current_rises_with_time_constant_l_over_r() {
    let (v, r, l) = (10.0, 10.0, 0.05);
    let model = system! {
        name: "blocked_rotor";
        source = ConstantVoltage { V: v };
        resistor = Resistor { R: r };
        inductor = Inductor { L: l };
        emf = EMF { k: 1.0 };
        rotor_lock = Fixed::default();
        ground = Ground::default();
        connect(source.p, resistor.p);
        connect(resistor.n, inductor.p);
        connect(inductor.n, emf.p);
        connect(emf.n, source.n);
        connect(source.n, ground.p);
        connect(emf.flange, rotor_lock.flange);
    };
    let ssys = structural_simplify(&model).unwrap();
    assert_eq!(ssys.unknowns().len(), 1);
    let sol = DaeProblem::new(&ssys, &[("inductor.i", 0.0)], (0.0, 0.05))
        .unwrap()
        .solve(&SolverOptions {
            rtol: 1e-9,
            atol: 1e-12,
            ..SolverOptions::default()
        })
        .unwrap();
    let tau = l / r;
    // i(tau) = (V/R)(1 - 1/e); the 63.2 % point is the time constant.
    let i_tau = sol.at("inductor.i", tau).unwrap();
    assert!(
        (i_tau - v / r * (1.0 - (-1.0f64).exp())).abs() < 1e-7,
        "i(L/R) = {i_tau}"
    );
    let t = sol.t();
    let i = sol.get("inductor.i").unwrap();
    let k = i
        .iter()
        .position(|&x| x >= v / r * (1.0 - (-1.0f64).exp()))
        .unwrap();
    assert!(t[k - 1] <= tau + 1e-12 && t[k] >= tau - 1e-12);
    // The blocked rotor takes the full torque k i.
    assert!(
        (sol.final_value("rotor_lock.flange.tau").unwrap()
            - 1.0 * sol.final_value("inductor.i").unwrap())
        .abs()
            < 1e-9
    );
}

/// `exp(M s)` of a 4x4 matrix: Taylor series after scaling, then squaring.
fn expm4(m: &[[f64; 4]; 4], s: f64) -> [[f64; 4]; 4] {
    let mul = |a: &[[f64; 4]; 4], b: &[[f64; 4]; 4]| {
        let mut c = [[0.0; 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                c[i][j] = (0..4).map(|l| a[i][l] * b[l][j]).sum();
            }
        }
        c
    };
    let norm = m
        .iter()
        .map(|r| r.iter().map(|x| x.abs()).sum::<f64>())
        .fold(0.0, f64::max)
        * s;
    let mut q = 0;
    while norm / f64::powi(2.0, q) > 0.5 {
        q += 1;
    }
    let scale = s / f64::powi(2.0, q);
    let a = m.map(|r| r.map(|x| x * scale));
    let mut e = [[0.0; 4]; 4];
    let mut term = [[0.0; 4]; 4];
    for i in 0..4 {
        e[i][i] = 1.0;
        term[i][i] = 1.0;
    }
    for p in 1..20 {
        term = mul(&term, &a).map(|r| r.map(|x| x / p as f64));
        for i in 0..4 {
            for j in 0..4 {
                e[i][j] += term[i][j];
            }
        }
    }
    for _ in 0..q {
        e = mul(&e, &e);
    }
    e
}

#[test]
fn motor_current_first_rises_with_l_over_r_then_the_motor_answers() {
    // The example itself: at rest until the reference steps to 1 rad/s at t = 0.5 s.
    // From then on (s = t - 0.5), while the controller is not limited (|y| < 200 V):
    //   V = Kp (1 - w_m / N + xi),   xi' = (1 - w_m / N) / Ti,
    //   L i' + R i = V - k w_m,      J w_m' = k i,   J = J_m + J_load / N^2,
    // with Kp = 100, Ti = 0.1, R = 10, L = 0.05, k = 1, N = 100, J = 1.5e-3.
    let (r, l, k, n, kp, ti) = (10.0, 0.05, 1.0, 100.0, 100.0, 0.1);
    let j = 1e-3 + 5.0 / (n * n);
    let tau = l / r;
    let t_step = 0.5;
    let ssys = structural_simplify(&example::dc_motor()).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_step + 0.02))
        .unwrap()
        .solve(&tight())
        .unwrap();
    assert_eq!(sol.at("inductor.i", t_step - 1e-3).unwrap(), 0.0);

    // 1. The first millisecond. Without the motor's motion the circuit sees the PI's
    // output Kp (1 + s / Ti): L i_r' + R i_r = Kp (1 + s / Ti), i_r(0) = 0, so
    //   i_r = c1 (1 - exp(-s / tau)) + c2 s,  c1 = Kp / R (1 - tau / Ti),  c2 = Kp / (R Ti).
    // The motion only lowers the voltage, by g = (Kp / N + k) w_m + Kp / (N Ti) int w_m
    // >= 0, so 0 <= i <= i_r, w_m <= (k / J) int i_r, and
    //   i_r - i = (1/L) int exp(-(s - u) / tau) g(u) du <= B(s)
    //   = k / (J L) ((Kp / N + k) I2(s) + Kp / (N Ti) I3(s)),
    // with I2, I3 the second and third integrals of i_r (closed forms below).
    let (c1, c2) = (kp / r * (1.0 - tau / ti), kp / (r * ti));
    let ex = |s: f64| 1.0 - (-s / tau).exp();
    let i_r = |s: f64| c1 * ex(s) + c2 * s;
    let i2 = |s: f64| c1 * (s * s / 2.0 - tau * s + tau * tau * ex(s)) + c2 * s.powi(3) / 6.0;
    let i3 = |s: f64| {
        c1 * (s.powi(3) / 6.0 - tau * s * s / 2.0 + tau * tau * s - tau.powi(3) * ex(s))
            + c2 * s.powi(4) / 24.0
    };
    let bound = |s: f64| k / (j * l) * ((kp / n + k) * i2(s) + kp / (n * ti) * i3(s));
    for s in [1e-4, 2e-4, 5e-4, 1e-3] {
        let i = sol.at("inductor.i", t_step + s).unwrap();
        let (ir, b) = (i_r(s), bound(s));
        // The back-EMF and the speed feedback are negligible here: under 0.5 %.
        assert!(b <= 5e-3 * ir, "bound {b} at s = {s} vs {ir}");
        assert!(
            i <= ir + 1e-9 && i >= ir - b - 1e-9,
            "i({s}) = {i} outside [{}, {ir}]",
            ir - b
        );
    }
    // That band resolves the time constant: with R 25 % larger or smaller (tau 4 ms or
    // 6.25 ms) the rise at 1 ms would fall outside it.
    let s = 1e-3;
    let i = sol.at("inductor.i", t_step + s).unwrap();
    for r2 in [12.5, 8.0] {
        let tau2 = l / r2;
        let other = kp / r2 * ((1.0 - tau2 / ti) * (1.0 - (-s / tau2).exp()) + s / ti);
        assert!(
            (other - i).abs() > 3.0 * bound(s),
            "R = {r2}: {other} vs {i}"
        );
    }

    // 2. Later the motor is not still: the exact solution of the linear system above
    // (x = [i, w_m, xi, 1], x' = M x, from rest) over the first 20 ms.
    let m = [
        [-r / l, -(kp / n + k) / l, kp / l, kp / l],
        [k / j, 0.0, 0.0, 0.0],
        [0.0, -1.0 / (n * ti), 0.0, 1.0 / ti],
        [0.0; 4],
    ];
    for s in [1e-3, 2e-3, tau, 1e-2, 2e-2] {
        let e = expm4(&m, s);
        let (i_exact, w_exact) = (e[0][3], e[1][3]);
        let t = t_step + s;
        let i = sol.at("inductor.i", t).unwrap();
        let w = sol.at("motor_inertia.w", t).unwrap();
        assert!(
            (i - i_exact).abs() < 1e-7 * i_exact.abs(),
            "i({s}) = {i}, exact {i_exact}"
        );
        assert!(
            (w - w_exact).abs() < 1e-7 * w_exact.abs(),
            "w({s}) = {w}, exact {w_exact}"
        );
        // Unlimited throughout: the linear model holds.
        let y = sol.at("controller.y", t).unwrap();
        assert_eq!(y, sol.at("controller.y_unlimited", t).unwrap());
    }
    // At s = L/R the motor turns at about 12 rad/s already; its back-EMF and the
    // controller's speed feedback have taken about 8 % off the blocked-rotor value
    // (V/R)(1 - 1/e): on the running motor the 63.2 % point is not at L/R (the
    // blocked-rotor test above measures that).
    let i_tau = sol.at("inductor.i", t_step + tau).unwrap();
    let blocked = kp / r * (1.0 - (-1.0f64).exp());
    assert!(
        (i_tau - blocked) / blocked < -0.07 && (i_tau - blocked) / blocked > -0.09,
        "i(L/R) = {i_tau} vs {blocked}"
    );
}
