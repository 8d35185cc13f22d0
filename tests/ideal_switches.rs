//! Ideal diode and switches (MSL `Electrical.Analog.Ideal`): switching at events,
//! against the closed-form currents of each state.

#![allow(missing_docs)]

use std::f64::consts::PI;

use multibody::blocks::{Sine, Step};
use multibody::electrical::{
    ConstantVoltage, Ground, IdealDiode, IdealOpeningSwitch, Resistor, SignalVoltage,
};
use multibody::prelude::*;

fn tight(times: Vec<f64>) -> SolverOptions {
    SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        output_times: Some(times),
        ..SolverOptions::default()
    }
}

#[test]
fn half_wave_rectifier_switches_at_the_zero_crossings() {
    // A 50 Hz sine of 10 V through the diode into R: i = v / (R + Ron) while it
    // conducts, v Goff / (1 + R Goff) while it blocks; it switches at each zero.
    let (amplitude, f, r, ron, goff) = (10.0, 50.0, 100.0, 1e-5, 1e-5);
    let model = system! {
        name: "rectifier";
        sine = Sine { amplitude, f };
        source = SignalVoltage::default();
        diode = IdealDiode::default();
        load = Resistor { R: r };
        ground = Ground::default();
        connect(sine.y, source.v_ref);
        connect(source.p, diode.p);
        connect(diode.n, load.p);
        connect(load.n, ground.p);
        connect(source.n, ground.p);
    };
    let ssys = structural_simplify(&model).unwrap();
    assert_eq!(
        ssys.event_relations().len(),
        2,
        "{:?}",
        ssys.event_relations()
    );
    let times: Vec<f64> = (1..45).map(|k| k as f64 * 1e-3 + 2.5e-4).collect();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 0.045))
        .unwrap()
        .solve(&tight(times.clone()))
        .unwrap();
    for &t in &times {
        let v = amplitude * (2.0 * PI * f * t).sin();
        let i = if v >= 0.0 {
            v / (r + ron)
        } else {
            v * goff / (1.0 + r * goff)
        };
        let got = sol.at("load.i", t).unwrap();
        assert!((got - i).abs() < 1e-9, "i({t}) = {got}, exact {i}");
    }
    let switches: Vec<f64> = sol
        .events()
        .iter()
        .filter(|e| e.condition == "diode.s < 0")
        .map(|e| e.t)
        .collect();
    assert_eq!(switches.len(), 4, "{:?}", sol.events());
    for (k, t) in switches.iter().enumerate() {
        assert!(
            (t - (k + 1) as f64 / (2.0 * f)).abs() < 1e-12,
            "switch {k} at {t}"
        );
    }
}

#[test]
fn opening_switch_interrupts_the_current_at_its_control_step() {
    let (v0, r, ron, goff) = (12.0, 6.0, 1e-5, 1e-5);
    let model = system! {
        name: "switch";
        control = Step { start_time: 0.5 };
        source = ConstantVoltage { V: v0 };
        switch = IdealOpeningSwitch::default();
        load = Resistor { R: r };
        ground = Ground::default();
        connect(control.y, switch.control);
        connect(source.p, switch.p);
        connect(switch.n, load.p);
        connect(load.n, ground.p);
        connect(source.n, ground.p);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 1.0))
        .unwrap()
        .solve(&tight(vec![0.25, 0.75]))
        .unwrap();
    let closed = v0 / (r + ron);
    let open = v0 * goff / (1.0 + r * goff);
    for (t, i) in [(0.25, closed), (0.75, open)] {
        let got = sol.at("load.i", t).unwrap();
        assert!((got - i).abs() < 1e-12, "i({t}) = {got}, exact {i}");
    }
    // The step and the switch change at the same event.
    let at: Vec<&str> = sol.events().iter().map(|e| e.condition.as_str()).collect();
    assert!(
        sol.events().iter().all(|e| (e.t - 0.5).abs() < 1e-12),
        "{:?}",
        sol.events()
    );
    assert!(at.contains(&"switch.control > 0.5"), "{at:?}");
}
