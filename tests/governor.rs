//! The centrifugal governor (`examples/governor.rs`) settles where the balls' weight and
//! centripetal force balance: cos(theta) = g / (w^2 L).

#[path = "../examples/governor.rs"]
#[allow(dead_code)]
mod governor_example;

use governor_example::{L, W, governor};
use multibody::prelude::*;

#[test]
fn the_flyballs_settle_at_the_closed_form_angle() {
    let ssys = structural_simplify(&governor()).unwrap();
    let sol = DaeProblem::builder(&ssys, (0.0, 30.0))
        .value("shaft.phi", 0.0)
        .value("hinge1.w", 0.0)
        .value("hinge2.w", 0.0)
        .build()
        .unwrap()
        .solve(&SolverOptions {
            rtol: 1e-10,
            atol: 1e-12,
            ..SolverOptions::default()
        })
        .unwrap();
    let theta = (9.80665 / (W * W * L)).acos();
    for hinge in ["hinge1", "hinge2"] {
        let phi = sol.final_value(format!("{hinge}.phi").as_str()).unwrap();
        let w = sol.final_value(format!("{hinge}.w").as_str()).unwrap();
        assert!((phi - theta).abs() < 1e-8, "{hinge}: {phi} vs {theta}");
        assert!(w.abs() < 1e-8, "{hinge} still moves: {w}");
    }
    // In the steady turn nothing dissipates: the drive holds the shaft without torque.
    let tau = sol.final_value("shaft.tau").unwrap();
    assert!(tau.abs() < 1e-8, "drive torque {tau}");
}
