//! Friction elements with stuck and sliding modes (MSL `PartialFriction`): lock and
//! unlock times, speeds and holding torques against closed forms.

#![allow(missing_docs)]

mod common;

use common::tight_options as options;

use std::f64::consts::PI;

use multibody::blocks::{Add, Constant, Pulse, Ramp, Sine, Step};
use multibody::prelude::*;
use multibody::rotational::{
    BearingFriction, Brake, Clutch, ElastoBacklash, Fixed, Inertia, OneWayClutch, Speed, Spring,
    Torque, friction_mode,
};
use multibody::translational::{self, MassWithStopAndFriction};

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
    // From 6 s, 9 N.m on the second: locked, the clutch would carry 3 N.m, more than
    // peak cgeo fn mu = 2.2, so it slips forward at once with 2 N.m.
    let (j1, j2, w0) = (1.0, 2.0, 10.0);
    let model = system! {
        name: "clutch";
        a = Inertia { J: j1, w_start: w0, state_priority: 20.0 };
        b = Inertia { J: j2, w_start: 0.0, state_priority: 20.0 };
        clutch = Clutch { fn_max: 4.0, mu_pos: vec![[0.0, 0.5]], peak: 1.1 };
        press = Step { height: 1.0, start_time: 0.5 };
        load = Step { height: 9.0, start_time: 6.0 };
        torque = Torque::default();
        connect(a.flange_b, clutch.flange_a);
        connect(clutch.flange_b, b.flange_a);
        connect(press.y, clutch.f_normalized);
        connect(load.y, torque.tau);
        connect(torque.flange, b.flange_b);
    };
    let ssys = structural_simplify(&model).unwrap();
    let t_end = 7.0;
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
        .unwrap()
        .solve(&options(t_end, 700))
        .unwrap();
    let t_lock = 0.5 + w0 / (2.0 / j1 + 2.0 / j2);
    let w_lock = j1 * w0 / (j1 + j2);
    for k in 0..=700 {
        let t = k as f64 * t_end / 700.0;
        let s = (t.min(t_lock) - 0.5).max(0.0);
        let slip = (t - 6.0).max(0.0);
        let (w1, w2) = (
            w0 - 2.0 / j1 * s + 2.0 / j1 * slip,
            2.0 / j2 * s + (9.0 - 2.0) / j2 * slip,
        );
        let (g1, g2) = (sol.at("a.w", t).unwrap(), sol.at("b.w", t).unwrap());
        assert!(
            (g1 - w1).abs() < 1e-7 && (g2 - w2).abs() < 1e-7,
            "at {t}: {g1}, {g2} vs {w1}, {w2}"
        );
        // Momentum changes only by the external torque's impulse.
        assert!(
            (j1 * g1 + j2 * g2 - j1 * w0 - 9.0 * slip).abs() < 1e-7,
            "momentum at {t}"
        );
    }
    assert!((sol.at("b.w", 5.9).unwrap() - w_lock).abs() < 1e-9);
    assert_eq!(sol.at("clutch.mode", 0.25).unwrap(), friction_mode::FREE);
    assert_eq!(sol.at("clutch.mode", 2.0).unwrap(), friction_mode::BACKWARD);
    assert_eq!(sol.at("clutch.mode", 5.0).unwrap(), friction_mode::STUCK);
    assert_eq!(sol.at("clutch.locked", 5.0).unwrap(), 1.0);
    assert_eq!(sol.at("clutch.locked", 6.5).unwrap(), 0.0);
    assert_eq!(sol.at("clutch.mode", 6.5).unwrap(), friction_mode::FORWARD);
    let locks = event_times(&sol, "clutch.w_relfric < 0", false);
    assert!(
        (locks[0] - t_lock).abs() < 1e-8,
        "locks at {locks:?}, exact {t_lock}"
    );
}

#[test]
fn brake_stops_a_spinning_inertia_and_holds_it() {
    // Braking torque cgeo fn mu = 0.8 * 10 * 0.3 = 2.4 N.m from 1 s on an inertia of
    // 3 kg.m2 at 6 rad/s: it stops at 1 + 6 * 3 / 2.4 s and stays stopped, holding the
    // 2 N.m that act on it from 10 s, until they grow to 3 N.m at 12 s and turn it
    // backwards against 2.4 N.m.
    let model = system! {
        name: "brake";
        inertia = Inertia { J: 3.0, w_start: 6.0, state_priority: 20.0 };
        brake = Brake { fn_max: 10.0, mu_pos: vec![[0.0, 0.3]], cgeo: 0.8 };
        press = Step { height: 1.0, start_time: 1.0 };
        push = Step { height: -2.0, start_time: 10.0 };
        more = Step { height: -1.0, start_time: 12.0 };
        sum = Add::default();
        torque = Torque::default();
        connect(inertia.flange_b, brake.flange_a);
        connect(press.y, brake.f_normalized);
        connect(push.y, sum.u1);
        connect(more.y, sum.u2);
        connect(sum.y, torque.tau);
        connect(torque.flange, inertia.flange_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    let t_end = 14.0;
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
        .unwrap()
        .solve(&options(t_end, 280))
        .unwrap();
    let t_stop = 1.0 + 6.0 * 3.0 / 2.4;
    for k in 0..=280 {
        let t = k as f64 * t_end / 280.0;
        let w = 6.0 - 2.4 / 3.0 * (t.clamp(1.0, t_stop) - 1.0) - 0.6 / 3.0 * (t - 12.0).max(0.0);
        let got = sol.at("inertia.w", t).unwrap();
        assert!((got - w).abs() < 1e-7, "w({t}) = {got}, exact {w}");
    }
    assert_eq!(sol.at("brake.mode", 0.5).unwrap(), friction_mode::FREE);
    assert_eq!(sol.at("brake.mode", 5.0).unwrap(), friction_mode::FORWARD);
    assert_eq!(sol.at("brake.mode", 10.0).unwrap(), friction_mode::STUCK);
    assert!((sol.at("brake.tau", 11.0).unwrap() + 2.0).abs() < 1e-9);
    assert_eq!(sol.at("brake.mode", 13.0).unwrap(), friction_mode::BACKWARD);
}

#[test]
fn a_mass_pushed_into_its_stop_stays_there_until_pulled_back() {
    // Without friction, 2 N push the 1 kg mass (length 0.2) from 0 to its stop at
    // smax - L/2 = 0.9 (t = sqrt(0.9) s); it stops dead and holds the push; from t = 2 s
    // the force pulls with 2 N and it slides back.
    let (m, force, s_stop) = (1.0, 2.0, 0.9);
    let model = system! {
        name: "stop";
        push = Step { height: -2.0 * force, offset: force, start_time: 2.0 };
        source = translational::Force::default();
        mass = MassWithStopAndFriction {
            m, L: 0.2, smax: 1.0, smin: -1.0, F_prop: 0.0, F_Coulomb: 0.0, F_Stribeck: 0.0,
        };
        connect(push.y, source.f);
        connect(source.flange, mass.flange_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    let t_end = 3.0;
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
        .unwrap()
        .solve(&options(t_end, 300))
        .unwrap();
    let t_hit = (2.0 * m * s_stop / force).sqrt();
    for k in 0..=300 {
        let t = k as f64 * t_end / 300.0;
        let s = if t < t_hit {
            force * t * t / (2.0 * m)
        } else if t < 2.0 {
            s_stop
        } else {
            s_stop - force * (t - 2.0).powi(2) / (2.0 * m)
        };
        let got = sol.at("mass.s", t).unwrap();
        assert!((got - s).abs() < 1e-7, "s({t}) = {got}, exact {s}");
    }
    // At the stop it is locked and its friction force (the stop's reaction) holds the push.
    assert_eq!(sol.at("mass.locked", 1.5).unwrap(), 1.0);
    assert!((sol.at("mass.f", 1.5).unwrap() - force).abs() < 1e-9);
    assert!(sol.at("mass.v", 1.5).unwrap().abs() < 1e-12);
    let hits: Vec<f64> = sol
        .events()
        .iter()
        .filter(|e| e.condition.starts_with("mass.s >= ") && e.value)
        .map(|e| e.t)
        .collect();
    assert!(
        (hits[0] - t_hit).abs() < 1e-8,
        "hits the stop at {hits:?}, exact {t_hit}"
    );
}

#[test]
fn stribeck_friction_holds_a_mass_until_the_force_exceeds_its_peak() {
    // MSL Translational.Examples.Friction, stop1: 25 sin(pi t / 2) N on the resting mass;
    // it breaks away where the force exceeds 1.001 (F_Coulomb + F_Stribeck) = 15.015 N.
    let model = system! {
        name: "stribeck";
        sine = Sine { amplitude: 25.0, f: 0.25 };
        source = translational::Force::default();
        mass = MassWithStopAndFriction {
            L: 1.0, smax: 25.0, smin: -25.0, m: 1.0, F_prop: 1.0, F_Coulomb: 5.0,
            F_Stribeck: 10.0, fexp: 2.0,
        };
        connect(sine.y, source.f);
        connect(source.flange, mass.flange_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 1.0))
        .unwrap()
        .solve(&options(1.0, 100))
        .unwrap();
    let t_break = (15.015f64 / 25.0).asin() / (PI / 2.0);
    for k in 0..=40 {
        let t = k as f64 * 0.01;
        assert!(sol.at("mass.s", t).unwrap().abs() < 1e-12, "moves at {t}");
        let held = 25.0 * (PI / 2.0 * t).sin();
        assert!(
            (sol.at("mass.f", t).unwrap() - held).abs() < 1e-8,
            "holds at {t}"
        );
    }
    assert!(sol.at("mass.v", 0.5).unwrap() > 0.0);
    assert_eq!(sol.at("mass.mode", 0.5).unwrap(), friction_mode::FORWARD);
    let breaks: Vec<f64> = sol
        .events()
        .iter()
        .filter(|e| e.condition.contains("mass.sa > 1.001") && e.value)
        .map(|e| e.t)
        .collect();
    assert!(
        (breaks[0] - t_break).abs() < 1e-8,
        "breaks at {breaks:?}, exact {t_break}"
    );
}

#[test]
fn one_way_clutch_locks_the_freewheel_and_opens_it_again() {
    // MSL Rotational.Examples.OneWayClutch until the clutch engages at 0.3 s: 10
    // sin(6 pi t) N.m drive the input inertia from -0.5 rad/s; the output (at rest)
    // overruns until the input catches up at t1 (cos 6 pi t1 = 1 - 0.3 pi); locked, both
    // turn together and the freewheel carries -5 sin(6 pi t) until that exceeds the
    // disengaged break-away torque 1e-4 mu cgeo fn_max = 1.5e-4 N.m just after 1/6 s.
    let model = system! {
        name: "freewheel";
        sine = Sine { amplitude: 10.0, f: 3.0 };
        torque = Torque::default();
        input = Inertia { J: 1.0, w_start: -0.5, state_priority: 20.0 };
        clutch = OneWayClutch { peak: 25.0, fn_max: 3.0 };
        output = Inertia { J: 1.0, w_start: 0.0, state_priority: 20.0 };
        press = Pulse { amplitude: 1.0, width: 50.0, period: 1.3, start_time: 0.3 };
        connect(sine.y, torque.tau);
        connect(torque.flange, input.flange_a);
        connect(input.flange_b, clutch.flange_a);
        connect(clutch.flange_b, output.flange_a);
        connect(press.y, clutch.f_normalized);
    };
    let ssys = structural_simplify(&model).unwrap();
    let t_end = 0.29;
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
        .unwrap()
        .solve(&options(t_end, 290))
        .unwrap();
    let omega = 6.0 * PI;
    let t1 = (1.0 - 0.3 * PI).acos() / omega;
    let t2 = (PI + 3e-5f64.asin()) / omega;
    let locked_w = |t: f64| 5.0 / omega * ((omega * t1).cos() - (omega * t).cos());
    for k in 0..=290 {
        let t = k as f64 * t_end / 290.0;
        let (w_in, w_out) = (
            sol.at("input.w", t).unwrap(),
            sol.at("output.w", t).unwrap(),
        );
        let (e_in, e_out) = if t < t1 {
            (-0.5 + 10.0 / omega * (1.0 - (omega * t).cos()), 0.0)
        } else if t < t2 {
            (locked_w(t), locked_w(t))
        } else {
            let w2 = locked_w(t2);
            (
                w2 + 10.0 / omega * ((omega * t2).cos() - (omega * t).cos()),
                w2,
            )
        };
        assert!(
            (w_in - e_in).abs() < 1e-6 && (w_out - e_out).abs() < 1e-6,
            "at {t}: {w_in}, {w_out}, exact {e_in}, {e_out}"
        );
    }
    assert_eq!(sol.at("clutch.locked", 0.12).unwrap(), 1.0);
    assert!((sol.at("clutch.tau", 0.12).unwrap() + 5.0 * (omega * 0.12).sin()).abs() < 1e-7);
    assert_eq!(sol.at("clutch.locked", 0.2).unwrap(), 0.0);
    // The output overruns at the speed it had when the freewheel opened: MSL's 0.280516.
    assert!((sol.at("output.w", 0.25).unwrap() - 0.280516).abs() < 1e-6);
}

#[test]
fn backlash_oscillates_with_the_closed_form_period() {
    // MSL Rotational.Examples.Backlash without damping: an inertia of 5 kg.m2 on a
    // spring of 2e4 N.m/rad with a backlash of pi/4, released at pi/2: contact half
    // periods of pi/w about +-pi/8 and flights across the gap at (3 pi/8) w.
    let (j, c, b) = (5.0, 2.0e4, PI / 4.0);
    let model = system! {
        name: "backlash";
        fixed = Fixed::default();
        backlash = ElastoBacklash { c, d: 0.0, b };
        inertia = Inertia { J: j, phi_start: PI / 2.0, w_start: 0.0, state_priority: 20.0 };
        connect(fixed.flange, backlash.flange_a);
        connect(backlash.flange_b, inertia.flange_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    let t_end = 0.5;
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
        .unwrap()
        .solve(&options(t_end, 1000))
        .unwrap();
    let w = (c / j).sqrt();
    let (amp, half) = (3.0 * PI / 8.0, b / 2.0);
    let v0 = amp * w;
    let flight = b / v0;
    let quarter = PI / (2.0 * w);
    let period = 2.0 * PI / w + 2.0 * flight;
    let exact = |t: f64| {
        if t < quarter {
            return half + amp * (w * t).cos();
        }
        let s = (t - quarter) % period;
        let contact = PI / w;
        if s < flight {
            half - v0 * s
        } else if s < flight + contact {
            -half - amp * (w * (s - flight)).sin()
        } else if s < 2.0 * flight + contact {
            -half + v0 * (s - flight - contact)
        } else {
            half + amp * (w * (s - 2.0 * flight - contact)).sin()
        }
    };
    for k in 0..=1000 {
        let t = k as f64 * t_end / 1000.0;
        let got = sol.at("inertia.phi", t).unwrap();
        assert!(
            (got - exact(t)).abs() < 1e-6,
            "phi({t}) = {got}, exact {}",
            exact(t)
        );
    }
    // In the gap the element transmits nothing.
    let t_gap = quarter + flight / 2.0;
    assert_eq!(sol.at("backlash.tau", t_gap).unwrap(), 0.0);
}
