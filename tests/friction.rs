//! Friction elements with stuck and sliding modes (MSL `PartialFriction`): lock and
//! unlock times, speeds and holding torques against closed forms.

#![allow(missing_docs)]

use multibody::blocks::{Constant, Ramp, Step};
use multibody::prelude::*;
use multibody::rotational::{
    BearingFriction, Brake, Clutch, Fixed, Inertia, Speed, Spring, Torque, friction_mode,
};

fn options(t_end: f64, n: usize) -> SolverOptions {
    SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        output_times: Some((0..=n).map(|k| k as f64 * t_end / n as f64).collect()),
        ..SolverOptions::default()
    }
}

/// The times of the events where `condition` took `value`.
fn event_times(sol: &Solution, condition: &str, value: bool) -> Vec<f64> {
    sol.events()
        .iter()
        .filter(|e| e.condition == condition && e.value == value)
        .map(|e| e.t)
        .collect()
}

#[test]
fn bearing_friction_stops_sticks_and_breaks_away_at_the_closed_form_times() {
    // J w' = 0.25 t - 1.5 while sliding forward from w = 1: stops at t1 = 6 - sqrt(20);
    // stuck (holding 0.25 t) until 0.25 t exceeds peak * 1.5 = 1.8 at t2 = 7.2; then
    // slides forward again.
    let (j, tau_c, peak, slope) = (2.0, 1.5, 1.2, 0.25);
    let model = system! {
        name: "bearing";
        ramp = Ramp { height: slope * 20.0, duration: 20.0 };
        torque = Torque::default();
        inertia = Inertia { J: j, w_start: 1.0, state_priority: 20.0 };
        friction = BearingFriction { tau_pos: vec![[0.0, tau_c]], peak };
        connect(ramp.y, torque.tau);
        connect(torque.flange, inertia.flange_a);
        connect(inertia.flange_b, friction.flange_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    let t_end = 10.0;
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
        .unwrap()
        .solve(&options(t_end, 400))
        .unwrap();
    let t1 = 6.0 - 20f64.sqrt();
    let t2 = peak * tau_c / slope;
    let w = |t: f64| {
        if t < t1 {
            1.0 + (0.5 * slope * t * t - tau_c * t) / j
        } else if t < t2 {
            0.0
        } else {
            (0.5 * slope * (t * t - t2 * t2) - tau_c * (t - t2)) / j
        }
    };
    for k in 0..=400 {
        let t = k as f64 * t_end / 400.0;
        let got = sol.at("inertia.w", t).unwrap();
        assert!((got - w(t)).abs() < 1e-7, "w({t}) = {got}, exact {}", w(t));
    }
    // Stuck between the two, the friction torque holds the drive.
    for t in [2.0, 4.0, 7.0] {
        let mode = sol.at("friction.mode", t).unwrap();
        assert_eq!(mode, friction_mode::STUCK, "mode at {t}");
        let tau = sol.at("friction.tau", t).unwrap();
        assert!(
            (tau - slope * t).abs() < 1e-8,
            "holding torque at {t}: {tau}"
        );
    }
    for t in [1.0, 8.0, 10.0] {
        assert_eq!(
            sol.at("friction.mode", t).unwrap(),
            friction_mode::FORWARD,
            "at {t}"
        );
    }
    let stops = event_times(&sol, "friction.w_relfric > 0", false);
    assert!(
        (stops[0] - t1).abs() < 1e-8,
        "stops at {stops:?}, exact {t1}"
    );
    let breaks = event_times(&sol, "friction.sa > friction.tau0_max", true);
    assert!(!breaks.is_empty(), "{:?}", sol.events());
    assert!(
        (breaks[0] - t2).abs() < 1e-8,
        "breaks away at {breaks:?}, exact {t2}"
    );
}

#[test]
fn stick_slip_on_a_moving_belt_follows_the_closed_form_cycle() {
    // An inertia on a spring to the ground, its bearing on a drum turning at v (the
    // rotational form of a mass on a moving belt): it sticks to the drum until the
    // spring pulls c x = peak * F, slips with friction F on a half ellipse about
    // x = F / c back to drum speed at x = 2 F / c - x_s, and sticks again.
    let (c, f, peak, v) = (1.0, 1.0, 1.5, 1.0);
    let model = system! {
        name: "belt";
        wall = Fixed::default();
        spring = Spring { c };
        inertia = Inertia { J: 1.0, w_start: v, state_priority: 20.0 };
        friction = BearingFriction { tau_pos: vec![[0.0, f]], peak, use_support: true };
        speed = Constant { k: v };
        drum = Speed { exact: true };
        connect(wall.flange, spring.flange_a);
        connect(spring.flange_b, inertia.flange_a);
        connect(inertia.flange_b, friction.flange_a);
        connect(friction.support, drum.flange);
        connect(speed.y, drum.w_ref);
    };
    let ssys = structural_simplify(&model).unwrap();
    let t_end = 16.0;
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
        .unwrap()
        .solve(&options(t_end, 800))
        .unwrap();
    let x_s = peak * f / c;
    let omega: f64 = 1.0;
    let a = (x_s - f / c) * omega;
    let phi = a.atan2(v);
    let slip = (2.0 * std::f64::consts::PI - 2.0 * phi) / omega;
    let x_end = 2.0 * f / c - x_s;
    let stick = (x_s - x_end) / v;
    // The first stick lasts x_s / v; then slip and stick alternate.
    let x = |t: f64| {
        let t0 = x_s / v;
        if t < t0 {
            return v * t;
        }
        let s = (t - t0) % (slip + stick);
        if s < slip {
            f / c + (x_s - f / c) * (omega * s).cos() + v / omega * (omega * s).sin()
        } else {
            x_end + v * (s - slip)
        }
    };
    for k in 0..=800 {
        let t = k as f64 * t_end / 800.0;
        let got = sol.at("inertia.phi", t).unwrap();
        assert!((got - x(t)).abs() < 1e-6, "x({t}) = {got}, exact {}", x(t));
    }
    let slips = event_times(&sol, "friction.sa < -friction.tau0_max", true);
    let expected: Vec<f64> = (0..3)
        .map(|k| x_s / v + k as f64 * (slip + stick))
        .collect();
    assert!(slips.len() >= 3, "{:?}", sol.events());
    for (got, want) in slips.iter().zip(&expected) {
        assert!(
            (got - want).abs() < 1e-7,
            "slips at {slips:?}, exact {expected:?}"
        );
    }
}

#[test]
fn clutch_locks_two_inertias_at_the_momentum_conserving_speed() {
    // Engaged at 0.5 s with a sliding torque of cgeo fn mu = 2 N.m: w1 = 10 - 2 (t -
    // 0.5), w2 = (t - 0.5); they lock at 0.5 + 10/3 s at (J1 w1 + J2 w2) / (J1 + J2).
    let (j1, j2, w0) = (1.0, 2.0, 10.0);
    let model = system! {
        name: "clutch";
        a = Inertia { J: j1, w_start: w0, state_priority: 20.0 };
        b = Inertia { J: j2, w_start: 0.0, state_priority: 20.0 };
        clutch = Clutch { fn_max: 4.0, mu_pos: vec![[0.0, 0.5]], peak: 1.1 };
        press = Step { height: 1.0, start_time: 0.5 };
        connect(a.flange_b, clutch.flange_a);
        connect(clutch.flange_b, b.flange_a);
        connect(press.y, clutch.f_normalized);
    };
    let ssys = structural_simplify(&model).unwrap();
    let t_end = 6.0;
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
        .unwrap()
        .solve(&options(t_end, 600))
        .unwrap();
    let t_lock = 0.5 + w0 / (2.0 / j1 + 2.0 / j2);
    let w_lock = j1 * w0 / (j1 + j2);
    for k in 0..=600 {
        let t = k as f64 * t_end / 600.0;
        let s = (t.min(t_lock) - 0.5).max(0.0);
        let (w1, w2) = (w0 - 2.0 / j1 * s, 2.0 / j2 * s);
        let (g1, g2) = (sol.at("a.w", t).unwrap(), sol.at("b.w", t).unwrap());
        assert!(
            (g1 - w1).abs() < 1e-7 && (g2 - w2).abs() < 1e-7,
            "at {t}: {g1}, {g2} vs {w1}, {w2}"
        );
        // Momentum is conserved throughout.
        assert!(
            (j1 * g1 + j2 * g2 - j1 * w0).abs() < 1e-7,
            "momentum at {t}"
        );
    }
    assert!((sol.at("b.w", t_end).unwrap() - w_lock).abs() < 1e-9);
    assert_eq!(sol.at("clutch.mode", 0.25).unwrap(), friction_mode::FREE);
    assert_eq!(sol.at("clutch.mode", 2.0).unwrap(), friction_mode::BACKWARD);
    assert_eq!(sol.at("clutch.mode", 5.0).unwrap(), friction_mode::STUCK);
    assert_eq!(sol.at("clutch.locked", 5.0).unwrap(), 1.0);
    let locks = event_times(&sol, "clutch.w_relfric < 0", false);
    assert!(
        (locks[0] - t_lock).abs() < 1e-8,
        "locks at {locks:?}, exact {t_lock}"
    );
}

#[test]
fn brake_stops_a_spinning_inertia_and_holds_it() {
    // Braking torque cgeo fn mu = 0.8 * 10 * 0.3 = 2.4 N.m from 1 s on an inertia of
    // 3 kg.m2 at 6 rad/s: it stops at 1 + 6 * 3 / 2.4 s and stays stopped.
    let model = system! {
        name: "brake";
        inertia = Inertia { J: 3.0, w_start: 6.0, state_priority: 20.0 };
        brake = Brake { fn_max: 10.0, mu_pos: vec![[0.0, 0.3]], cgeo: 0.8 };
        press = Step { height: 1.0, start_time: 1.0 };
        connect(inertia.flange_b, brake.flange_a);
        connect(press.y, brake.f_normalized);
    };
    let ssys = structural_simplify(&model).unwrap();
    let t_end = 12.0;
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
        .unwrap()
        .solve(&options(t_end, 240))
        .unwrap();
    let t_stop = 1.0 + 6.0 * 3.0 / 2.4;
    for k in 0..=240 {
        let t = k as f64 * t_end / 240.0;
        let w = 6.0 - 2.4 / 3.0 * (t.clamp(1.0, t_stop) - 1.0);
        let got = sol.at("inertia.w", t).unwrap();
        assert!((got - w).abs() < 1e-7, "w({t}) = {got}, exact {w}");
    }
    assert_eq!(sol.at("brake.mode", 0.5).unwrap(), friction_mode::FREE);
    assert_eq!(sol.at("brake.mode", 5.0).unwrap(), friction_mode::FORWARD);
    assert_eq!(sol.at("brake.mode", 10.0).unwrap(), friction_mode::STUCK);
}
