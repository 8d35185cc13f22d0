//! The seed's DC motor: speed control to the reference, and the electrical time
//! constant of its armature.

#[path = "../examples/dc_motor.rs"]
#[allow(dead_code)]
mod example;

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
