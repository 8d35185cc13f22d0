//! State and time events from relations, `when` clauses and `sample` (Modelica's
//! semantics): located by the integrator's root finding, each recorded with its left
//! and right limits, against closed-form solutions.

#![allow(missing_docs)]

mod common;
#[path = "support/small_models.rs"]
mod small_models;

use common::tight_options as options;
use small_models::BouncingBall;

use std::f64::consts::PI;

use multibody::Error;
use multibody::blocks::{
    Constant, Feedback, Gain, Hysteresis, Pulse, Ramp, Sampler, SawTooth, Sine, Step, TimeTable,
    Trapezoid, UnitDelay, ZeroOrderHold,
};
use multibody::prelude::*;
use multibody::rotational::{Damper, Fixed, Inertia, SpeedSensor, Torque};
use multibody::translational::{ElastoGap, Mass};

component! {
    /// A mass on a spring that is stiffer when stretched (`x > 0`) than when
    /// compressed: `m der(v) = -k x`, `k = k_pos` where `x > 0` and `k_neg` elsewhere.
    pub struct BilinearOscillator {
        /// Mass \[kg\].
        parameter m: f64 = 1.0;
        /// Stiffness where `x > 0` \[N/m\].
        parameter k_pos: f64 = 4.0;
        /// Stiffness where `x <= 0` \[N/m\].
        parameter k_neg: f64 = 1.0;
        /// Whether the switch is integrated through without events (`noEvent`).
        structural without_events: bool = false;
        /// Position \[m\].
        variable x(start = 1.0, fixed = true): Real;
        /// Velocity \[m/s\].
        variable v(start = 0.0, fixed = true): Real;
        equation {
            der(x) = v;
            let stretched = if without_events { no_event(gt(x, 0.0)) } else { gt(x, 0.0) };
            m * der(v) = -if_else(stretched, k_pos, k_neg) * x;
        }
    }
}

/// Closed form of the bilinear oscillator from x = a, v = 0: a quarter period at
/// w1 = sqrt(k_pos / m) to the first zero, then alternately half periods at
/// w2 = sqrt(k_neg / m) (x < 0, amplitude a w1 / w2) and w1 (x > 0).
fn bilinear(t: f64, a: f64, w1: f64, w2: f64) -> f64 {
    let t1 = PI / (2.0 * w1);
    if t <= t1 {
        return a * (w1 * t).cos();
    }
    let cycle = PI / w2 + PI / w1;
    let s = (t - t1) % cycle;
    if s <= PI / w2 {
        -a * w1 / w2 * (w2 * s).sin()
    } else {
        a * (w1 * (s - PI / w2)).sin()
    }
}

#[test]
fn bilinear_oscillator_switches_its_stiffness_at_the_closed_form_times() {
    let (a, w1, w2) = (1.0, 2.0, 1.0);
    let mut model = System::new("bilinear");
    model.add("osc", &BilinearOscillator::default());
    let ssys = structural_simplify(&model).unwrap();
    assert_eq!(ssys.event_relations().len(), 1);
    assert_eq!(ssys.event_relations()[0].text, "osc.x > 0");
    let t_end = 10.0;
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
        .unwrap()
        .solve(&options(t_end, 200))
        .unwrap();
    // Zeros of x: pi/4, then alternately pi/w2 and pi/w1 later.
    let mut expected = vec![PI / (2.0 * w1)];
    while expected.len() < 4 {
        let last = *expected.last().unwrap();
        let half = if expected.len() % 2 == 1 {
            PI / w2
        } else {
            PI / w1
        };
        expected.push(last + half);
    }
    let events = sol.events();
    assert_eq!(events.len(), expected.len(), "{events:?}");
    for (k, (e, &t)) in events.iter().zip(&expected).enumerate() {
        assert!((e.t - t).abs() < 1e-8, "event {k} at {}, expected {t}", e.t);
        assert_eq!(e.condition, "osc.x > 0");
        // Falling through zero first (x > 0 becomes false), then rising.
        assert_eq!(e.value, k % 2 == 1, "{e:?}");
        assert_eq!(e.rising, k % 2 == 1, "{e:?}");
    }
    // The trajectory, the left and right limits included.
    let x = sol.get("osc.x").unwrap();
    for (k, &t) in sol.t().iter().enumerate() {
        let want = bilinear(t, a, w1, w2);
        assert!(
            (x[k] - want).abs() < 1e-7,
            "x({t}) = {}, exact {want}",
            x[k]
        );
    }
    // Each event time holds two points: the left limit (ending a segment) and the
    // right one (starting the next); the acceleration jumps between them (by -k x,
    // zero here as x = 0, so it is the velocity's derivative that keeps its value).
    for e in events {
        let at: Vec<usize> = (0..sol.t().len()).filter(|&k| sol.t()[k] == e.t).collect();
        assert_eq!(at.len(), 2, "points at the event {e:?}");
    }
    assert_eq!(sol.segments().len(), events.len() + 1);
}

#[test]
fn without_events_the_switch_is_integrated_through_less_accurately() {
    let (a, w1, w2) = (1.0, 2.0, 1.0);
    let t_end = 10.0;
    let run = |without_events: bool| {
        let mut model = System::new("bilinear");
        model.add(
            "osc",
            &BilinearOscillator {
                without_events,
                ..Default::default()
            },
        );
        let ssys = structural_simplify(&model).unwrap();
        let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
            .unwrap()
            .solve(&options(t_end, 200))
            .unwrap();
        let x = sol.get("osc.x").unwrap();
        let error = sol
            .t()
            .iter()
            .zip(&x)
            .map(|(&t, &x)| (x - bilinear(t, a, w1, w2)).abs())
            .fold(0.0, f64::max);
        let failures = sol.statistics().error_test_failures;
        (
            ssys.event_relations().len(),
            sol.events().len(),
            error,
            failures,
        )
    };
    let (relations, events, with, failures_with) = run(false);
    assert_eq!((relations, events), (1, 4));
    let (relations, events, without, failures_without) = run(true);
    assert_eq!((relations, events), (0, 0));
    // Both are solutions; stepping across the kinks costs accuracy and failed steps.
    assert!(with < 1e-7 && without < 1e-4, "{with:e} {without:e}");
    assert!(with < without, "with events {with:e}, without {without:e}");
    assert!(
        failures_with < failures_without,
        "error test failures with events {failures_with}, without {failures_without}"
    );
}

#[test]
fn a_step_source_switches_at_its_start_time() {
    // A torque step of height h at t_s on an inertia J at rest: w = h (t - t_s) / J
    // after it, phi = h (t - t_s)^2 / (2 J).
    let (h, t_s, j) = (2.0, 0.5, 4.0);
    let model = system! {
        name: "step_torque";
        step = Step { height: h, start_time: t_s };
        torque = Torque::default();
        inertia = Inertia { J: j };
        connect(step.y, torque.tau);
        connect(torque.flange, inertia.flange_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(
        &ssys,
        &[("inertia.phi", 0.0), ("inertia.w", 0.0)],
        (0.0, 2.0),
    )
    .unwrap()
    .solve(&options(2.0, 40))
    .unwrap();
    let events = sol.events();
    assert_eq!(events.len(), 1, "{events:?}");
    // A time event: the integration stops on it exactly, without root finding.
    assert_eq!(events[0].t, t_s, "{events:?}");
    assert_eq!(events[0].condition, "time < step.start_time");
    assert!(!events[0].value);
    let (w, a) = (sol.get("inertia.w").unwrap(), sol.get("inertia.a").unwrap());
    let phi = sol.get("inertia.phi").unwrap();
    let at: Vec<usize> = (0..sol.t().len())
        .filter(|&k| sol.t()[k] == events[0].t)
        .collect();
    assert_eq!(at.len(), 2);
    // Left limit: at rest, no acceleration; right limit: h / J.
    assert!(a[at[0]].abs() < 1e-12 && (a[at[1]] - h / j).abs() < 1e-12);
    for (k, &t) in sol.t().iter().enumerate() {
        let s = (t - t_s).max(0.0);
        assert!((w[k] - h * s / j).abs() < 1e-9, "w({t}) = {}", w[k]);
        assert!(
            (phi[k] - h * s * s / (2.0 * j)).abs() < 1e-9,
            "phi({t}) = {}",
            phi[k]
        );
    }
    // The integrator never steps across the step: no error test fails.
    assert_eq!(
        sol.statistics().error_test_failures,
        0,
        "{:?}",
        sol.statistics()
    );
}

#[test]
fn bouncing_ball_impacts_at_the_closed_form_times() {
    // From h0 at rest: the first impact at t1 = sqrt(2 h0 / g) with speed g t1; each
    // bounce leaves with e times the speed it arrived with, and flies 2 e^k g t1 / g.
    let (g, e, h0): (f64, f64, f64) = (9.81, 0.8, 1.0);
    let mut model = System::new("bouncing");
    model.add("ball", &BouncingBall::default());
    let ssys = structural_simplify(&model).unwrap();
    let t1 = (2.0 * h0 / g).sqrt();
    let mut impacts = vec![t1];
    for k in 1..10 {
        let last = impacts[k - 1];
        impacts.push(last + 2.0 * e.powi(k as i32) * t1);
    }
    let t_end = impacts[9] + 0.05;
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
        .unwrap()
        .solve(&options(t_end, 100))
        .unwrap();
    let hits: Vec<f64> = sol
        .events()
        .iter()
        .filter(|ev| ev.value)
        .map(|ev| ev.t)
        .collect();
    assert_eq!(hits.len(), 10, "{:?}", sol.events());
    for (k, (&got, &want)) in hits.iter().zip(&impacts).enumerate() {
        assert!(
            (got - want).abs() < 1e-6,
            "impact {k} at {got}, exact {want}"
        );
    }
    // The discrete counter changed only at the impacts; the speed after the last one.
    assert_eq!(sol.final_value("ball.bounces").unwrap(), 10.0);
    let v_end = sol.final_value("ball.v").unwrap();
    let exact = e.powi(10) * g * t1 - g * (t_end - impacts[9]);
    assert!((v_end - exact).abs() < 1e-6, "v = {v_end}, exact {exact}");
}

#[test]
fn accumulating_bounces_end_with_an_error_at_the_accumulation_point() {
    // The flights shrink by e each bounce: they accumulate at
    // t1 (1 + 2 e / (1 - e)) = 9 t1 for e = 0.8, where no integration can pass.
    let (g, h0): (f64, f64) = (9.81, 1.0);
    let t_inf = 9.0 * (2.0 * h0 / g).sqrt();
    let mut model = System::new("bouncing");
    model.add("ball", &BouncingBall::default());
    let ssys = structural_simplify(&model).unwrap();
    let err = DaeProblem::new(&ssys, &[], (0.0, 5.0))
        .unwrap()
        .solve(&options(5.0, 100))
        .unwrap_err();
    let Error::Solve(e) = &err else {
        panic!("{err}");
    };
    assert_eq!(e.flag, "EVENT_ACCUMULATION", "{err}");
    assert!((e.t - t_inf).abs() < 1e-6, "{err}");
    assert!(err.to_string().contains("`ball.h < 0`"), "{err}");
}

#[test]
fn sampled_speed_control_matches_the_discrete_time_closed_form() {
    // An inertia J with viscous damping d, driven by tau_k = K (w_ref - w(t_k)) held
    // over each sample period T (sampler, then a gain): between samples w relaxes
    // toward tau_k / d, so w_{k+1} = a w_k + (1 - a) tau_k / d with a = exp(-d T / J).
    let (j, d, k, w_ref, period): (f64, f64, f64, f64, f64) = (0.5, 0.2, 2.0, 10.0, 0.1);
    let model = system! {
        name: "sampled_control";
        reference = Constant { k: w_ref };
        sensor = SpeedSensor::default();
        sampler = Sampler { sample_period: period };
        error = Feedback::default();
        gain = Gain { k };
        torque = Torque::default();
        inertia = Inertia { J: j };
        damper = Damper { d };
        ground = Fixed::default();
        connect(inertia.flange_b, sensor.flange);
        connect(sensor.w, sampler.u);
        connect(reference.y, error.u1);
        connect(sampler.y, error.u2);
        connect(error.y, gain.u);
        connect(gain.y, torque.tau);
        connect(torque.flange, inertia.flange_a);
        connect(ground.flange, damper.flange_a);
        connect(damper.flange_b, inertia.flange_b);
    };
    let ssys = structural_simplify(&model).unwrap();
    let t_end = 2.0;
    // Output times between the sample instants.
    let times: Vec<f64> = (0..20).map(|m| 0.05 + period * m as f64).collect();
    let a = (-d * period / j).exp();
    let mut w_k = 0.0;
    let mut held = Vec::new();
    for _ in 0..20 {
        let tau = k * (w_ref - w_k);
        held.push((w_k, tau));
        w_k = a * w_k + (1.0 - a) * tau / d;
    }
    // The same with every kind of method: sample instants are time events.
    for method in [
        multibody::Method::Ida,
        multibody::Method::Verner8,
        multibody::Method::CvodeBdf,
        multibody::Method::Kvaerno5,
    ] {
        let sol = DaeProblem::new(
            &ssys,
            &[("inertia.phi", 0.0), ("inertia.w", 0.0)],
            (0.0, t_end),
        )
        .unwrap()
        .solve(&SolverOptions {
            rtol: 1e-10,
            atol: 1e-12,
            output_times: Some(times.clone()),
            method,
            ..SolverOptions::default()
        })
        .unwrap();
        let (w, tau) = (sol.get("inertia.w").unwrap(), sol.get("gain.y").unwrap());
        for &t in &times {
            let m = (t / period).floor() as usize;
            let (w_m, tau_m) = held[m];
            let exact = tau_m / d + (w_m - tau_m / d) * (-d * (t - m as f64 * period) / j).exp();
            let i = sol.t().iter().position(|&s| s == t).unwrap();
            assert!(
                (w[i] - exact).abs() < 1e-7,
                "{method:?}: w({t}) = {}, exact {exact}",
                w[i]
            );
            // The control signal changes only at the sample instants.
            assert!(
                (tau[i] - tau_m).abs() < 1e-7,
                "{method:?}: tau({t}) = {}, held {tau_m}",
                tau[i]
            );
        }
        // A sample at t = 0 and every period after it up to t_end, which has its own (the
        // instants are multiples of the period, not sums of it).
        let samples: Vec<f64> = sol
            .events()
            .iter()
            .filter(|e| e.value)
            .map(|e| e.t)
            .collect();
        assert_eq!(samples.len(), 21, "{method:?}: {:?}", sol.events());
        for (m, &t) in samples.iter().enumerate() {
            assert_eq!(t, m as f64 * period, "{method:?}: sample {m}");
        }
    }
}

#[test]
fn sampler_hold_and_unit_delay_of_a_ramp() {
    // u = t: the sampler and the hold give T floor(t / T); the unit delay, fed by the
    // sampler at the same instants, gives its value one period late (0 before).
    let period = 0.25;
    let model = system! {
        name: "discrete_blocks";
        ramp = Ramp { height: 10.0, duration: 10.0 };
        sampler = Sampler { sample_period: period };
        hold = ZeroOrderHold { sample_period: period };
        delay = UnitDelay { sample_period: period };
        connect(ramp.y, sampler.u);
        connect(ramp.y, hold.u);
        connect(sampler.y, delay.u);
    };
    let ssys = structural_simplify(&model).unwrap();
    let times: Vec<f64> = (0..12).map(|m| 0.1 + 0.2 * m as f64).collect();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 2.5))
        .unwrap()
        .solve(&SolverOptions {
            output_times: Some(times.clone()),
            ..SolverOptions::default()
        })
        .unwrap();
    for &t in &times {
        let m = (t / period).floor();
        for (name, exact) in [
            ("sampler.y", period * m),
            ("hold.y", period * m),
            ("delay.y", period * (m - 1.0).max(0.0)),
        ] {
            let got = sol.at(name, t).unwrap();
            assert!(
                (got - exact).abs() < 1e-9,
                "{name}({t}) = {got}, exact {exact}"
            );
        }
    }
}

#[test]
fn periodic_sources_against_their_definitions() {
    // Pulse: 1 + 2 for the first 30 % of each 0.5 s period from 0.2 s, three periods.
    // SawTooth: t mod 0.5 / 0.5. Trapezoid: up over 0.1 s, 0.2 s at 1, down over 0.1 s.
    let model = system! {
        name: "periodic";
        pulse = Pulse { amplitude: 2.0, width: 30.0, period: 0.5, nperiod: 3.0,
                        offset: 1.0, start_time: 0.2 };
        saw = SawTooth { period: 0.5 };
        trapezoid = Trapezoid { rising: 0.1, width: 0.2, falling: 0.1, period: 0.5 };
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 2.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    let pulse = |t: f64| {
        let s = t - 0.2;
        if !(0.0..1.5).contains(&s) || s % 0.5 >= 0.15 {
            1.0
        } else {
            3.0
        }
    };
    let trapezoid = |t: f64| {
        let s = t % 0.5;
        if s < 0.1 {
            s / 0.1
        } else if s < 0.3 {
            1.0
        } else if s < 0.4 {
            (0.4 - s) / 0.1
        } else {
            0.0
        }
    };
    for t in [
        0.05, 0.1, 0.25, 0.33, 0.4, 0.62, 0.75, 0.9, 1.3, 1.5, 1.75, 1.95,
    ] {
        for (name, exact) in [
            ("pulse.y", pulse(t)),
            ("saw.y", (t % 0.5) / 0.5),
            ("trapezoid.y", trapezoid(t)),
        ] {
            let got = sol.at(name, t).unwrap();
            assert!(
                (got - exact).abs() < 1e-9,
                "{name}({t}) = {got}, exact {exact}"
            );
        }
    }
    // The pulse's edges are events at their exact times.
    for edge in [0.2, 0.35, 0.7, 0.85, 1.2, 1.35] {
        assert!(
            sol.events().iter().any(|e| (e.t - edge).abs() < 1e-12),
            "no event at {edge}: {:?}",
            sol.events()
        );
    }
}

#[test]
fn a_mass_rebounds_from_an_elasto_gap_after_half_a_period() {
    // A unit mass at s = 1 moving at -1 m/s towards a gap (c = 100 N/m, no damping)
    // whose contact begins at s = 0.5: it touches at t = 0.5, stays in contact for
    // pi / w (w = 10 rad/s) and leaves at +1 m/s.
    let (c, w) = (100.0, 10.0);
    let model = system! {
        name: "gap";
        ground = multibody::translational::Fixed::default();
        gap = ElastoGap { c, d: 0.0, s_rel0: 0.5 };
        mass = Mass { m: 1.0 };
        connect(ground.flange, gap.flange_a);
        connect(gap.flange_b, mass.flange_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[("mass.s", 1.0), ("mass.v", -1.0)], (0.0, 1.5))
        .unwrap()
        .solve(&options(1.5, 60))
        .unwrap();
    let t_out = 0.5 + PI / w;
    let contact: Vec<(f64, bool)> = sol
        .events()
        .iter()
        .filter(|e| e.condition == "gap.s_rel < gap.s_rel0")
        .map(|e| (e.t, e.value))
        .collect();
    assert_eq!(contact.len(), 2, "{:?}", sol.events());
    assert!(
        (contact[0].0 - 0.5).abs() < 1e-9 && contact[0].1,
        "{contact:?}"
    );
    assert!(
        (contact[1].0 - t_out).abs() < 1e-8 && !contact[1].1,
        "{contact:?}"
    );
    let s = sol.get("mass.s").unwrap();
    for (k, &t) in sol.t().iter().enumerate() {
        let exact = if t <= 0.5 {
            1.0 - t
        } else if t <= t_out {
            0.5 - (w * (t - 0.5)).sin() / w
        } else {
            0.5 + (t - t_out)
        };
        assert!(
            (s[k] - exact).abs() < 1e-7,
            "s({t}) = {}, exact {exact}",
            s[k]
        );
    }
}

component! {
    /// The bouncing ball, ended by `terminate` at its third impact.
    pub struct ThreeBounces {
        /// Height \[m\].
        variable h(start = 1.0, fixed = true): Real;
        /// Velocity \[m/s\].
        variable v(start = 0.0, fixed = true): Real;
        /// Bounces so far.
        variable bounces(start = 0.0): Real;
        equation {
            der(h) = v;
            der(v) = -9.81;
            when lt(h, 0.0) {
                reinit(v, -0.8 * pre(v));
                bounces = pre(bounces) + 1.0;
            }
            when ge(bounces, 3.0) {
                terminate("three bounces");
            }
        }
    }
}

#[test]
fn terminate_ends_the_simulation_at_its_event() {
    let t1 = (2.0f64 / 9.81).sqrt();
    let t3 = t1 * (1.0 + 2.0 * 0.8 + 2.0 * 0.64);
    let mut model = System::new("terminating");
    model.add("ball", &ThreeBounces::default());
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 10.0))
        .unwrap()
        .solve(&options(10.0, 100))
        .unwrap();
    let end = sol.terminated().expect("terminated");
    assert!((end.t - t3).abs() < 1e-8, "{end:?}, exact {t3}");
    assert_eq!(end.message, "ball: three bounces");
    // The solution ends there, after the impact.
    assert_eq!(*sol.t().last().unwrap(), end.t);
    assert_eq!(sol.final_value("ball.bounces").unwrap(), 3.0);
    assert!(sol.final_value("ball.v").unwrap() > 0.0);
}

#[test]
fn time_table_interpolates_jumps_and_extrapolates_as_msl_documents() {
    // MSL's own example: table [0, 0; 1, 0; 1, 1; 2, 4; 3, 9; 4, 16] gives 0 before
    // and 1 after the jump at t = 1, 2.5 at 1.5, 4 at 2 and 23 at 5 (extrapolated).
    let model = system! {
        name: "table";
        table = TimeTable { table: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [2.0, 4.0], [3.0, 9.0], [4.0, 16.0]] };
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 5.0))
        .unwrap()
        .solve(&SolverOptions {
            output_times: Some(vec![0.5, 1.5, 2.0, 2.5, 5.0]),
            ..SolverOptions::default()
        })
        .unwrap();
    for (t, exact) in [(0.5, 0.0), (1.5, 2.5), (2.0, 4.0), (2.5, 6.5), (5.0, 23.0)] {
        let got = sol.at("table.y", t).unwrap();
        assert!((got - exact).abs() < 1e-12, "y({t}) = {got}, exact {exact}");
    }
    // The jump: both limits at t = 1.
    let y = sol.get("table.y").unwrap();
    let at: Vec<usize> = (0..sol.t().len()).filter(|&k| sol.t()[k] == 1.0).collect();
    assert!(at.len() >= 2, "{:?}", sol.t());
    assert_eq!((y[at[0]], y[*at.last().unwrap()]), (0.0, 1.0));
}

#[test]
fn a_time_table_that_does_not_start_at_zero_is_rejected_by_name() {
    let model = system! {
        name: "bad_table";
        source = TimeTable { table: vec![[1.0, 0.0], [2.0, 1.0]] };
    };
    let err = structural_simplify(&model).unwrap_err().to_string();
    assert!(
        err.contains("source") && err.contains("the first time of the table must be 0, not 1"),
        "{err}"
    );
}

#[test]
fn hysteresis_switches_at_its_thresholds() {
    // u = sin(2 pi t): on where u rises through 0.5 (t = 1/12 + k), off where it falls
    // through -0.5 (t = 7/12 + k).
    let model = system! {
        name: "hysteresis";
        sine = Sine { amplitude: 1.0, f: 1.0 };
        switch = Hysteresis { u_low: -0.5, u_high: 0.5 };
        connect(sine.y, switch.u);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 2.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    let on = |t: f64| {
        let s = t % 1.0;
        if (1.0 / 12.0..7.0 / 12.0).contains(&s) {
            1.0
        } else {
            0.0
        }
    };
    for t in [0.05, 0.1, 0.5, 0.6, 0.9, 1.05, 1.1, 1.55, 1.6, 1.95] {
        let got = sol.at("switch.y", t).unwrap();
        assert_eq!(got, on(t), "y({t})");
    }
    let switches: Vec<f64> = sol
        .events()
        .iter()
        .filter(|e| e.value && e.condition.contains("switch"))
        .map(|e| e.t)
        .collect();
    let exact = [1.0 / 12.0, 7.0 / 12.0, 13.0 / 12.0, 19.0 / 12.0];
    assert_eq!(switches.len(), 4, "{:?}", sol.events());
    for (t, e) in switches.iter().zip(exact) {
        assert!((t - e).abs() < 1e-6, "switch at {t}, exact {e}");
    }
}

component! {
    /// `reinit` of a variable that is no state.
    pub struct ReinitAlgebraic {
        /// A state.
        variable x(start = 1.0, fixed = true): Real;
        /// Follows from `x`.
        variable y: Real;
        equation {
            der(x) = -1.0;
            y = 2.0 * x;
            when lt(x, 0.0) {
                reinit(y, 1.0);
            }
        }
    }
}

#[test]
fn reinit_of_a_variable_that_is_no_state_is_an_error_naming_it() {
    let mut model = System::new("bad_reinit");
    model.add("c", &ReinitAlgebraic::default());
    let err = structural_simplify(&model).unwrap_err().to_string();
    assert!(
        err.contains("reinit(c.y, ..)")
            && err.contains("`c.y` is not a state")
            && err.contains("c.x < 0"),
        "{err}"
    );
}

component! {
    /// Counts the rising edges of a hysteresis's output and its changes.
    pub struct EdgeCounter {
        /// The hysteresis output (1 or 0).
        connector u: multibody::blocks::RealInput;
        /// Rising edges so far.
        variable rises(start = 0.0): Real;
        /// Changes so far.
        variable changes(start = 0.0): Real;
        equation {
            when edge(u) {
                rises = pre(rises) + 1.0;
            }
            when change(u) {
                changes = pre(changes) + 1.0;
            }
        }
    }
}

#[test]
fn edge_and_change_count_the_switches_of_a_signal() {
    // The hysteresis of sin(2 pi t) switches on at 1/12 + k and off at 7/12 + k: in
    // 2.5 s three rises and five changes.
    let model = system! {
        name: "edges";
        sine = Sine { amplitude: 1.0, f: 1.0 };
        switch = Hysteresis { u_low: -0.5, u_high: 0.5 };
        counter = EdgeCounter::default();
        connect(sine.y, switch.u);
        connect(switch.y, counter.u);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 2.5))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    assert_eq!(sol.final_value("counter.rises").unwrap(), 3.0);
    assert_eq!(sol.final_value("counter.changes").unwrap(), 5.0);
    assert_eq!(sol.at("counter.rises", 1.0).unwrap(), 1.0);
}

component! {
    /// Two conditions that become true at the same instant, chained or not.
    pub struct Chained {
        /// The second condition's instant \[s\].
        parameter t2: f64 = 1.0;
        /// Whether the second clause is an `elsewhen` of the first.
        structural chained: bool = true;
        /// Which clause set it last.
        variable a(start = 0.0): Real;
        equation {
            if chained {
                when ge(time, 1.0) {
                    a = 1.0;
                } elsewhen ge(time, t2) {
                    a = 2.0;
                }
            } else {
                when ge(time, 1.0) {
                    a = 1.0;
                }
                when ge(time, t2) {
                    a = 2.0;
                }
            }
        }
    }
}

#[test]
fn elsewhen_is_skipped_where_its_when_fires() {
    let run = |chained: bool, t2: f64| {
        let mut model = System::new("chain");
        model.add("c", &Chained { chained, t2 });
        let ssys = structural_simplify(&model).unwrap();
        let sol = DaeProblem::new(&ssys, &[], (0.0, 2.0))
            .unwrap()
            .solve(&SolverOptions::default())
            .unwrap();
        (
            sol.at("c.a", 0.75).unwrap(),
            sol.final_value("c.a").unwrap(),
        )
    };
    // Both at t = 1: the when wins over its elsewhen; two plain whens both act (the
    // second last).
    assert_eq!(run(true, 1.0), (0.0, 1.0));
    assert_eq!(run(false, 1.0), (0.0, 2.0));
    // The elsewhen alone at t = 0.5, the when at 1.
    assert_eq!(run(true, 0.5), (2.0, 1.0));
}

component! {
    /// Keeps the value its state had at the start.
    pub struct RemembersTheStart {
        /// Decays from 3.
        variable x(start = 3.0, fixed = true): Real;
        /// `x` at the start.
        variable x0(start = 0.0): Real;
        /// Initial events so far.
        variable count(start = 0.0): Real;
        equation {
            der(x) = -x;
            when initial() {
                x0 = x;
                count = pre(count) + 1.0;
            }
        }
    }
}

#[test]
fn initial_fires_once_at_the_start() {
    let mut model = System::new("start");
    model.add("m", &RemembersTheStart::default());
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 2.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    assert_eq!(sol.final_value("m.x0").unwrap(), 3.0);
    assert_eq!(sol.final_value("m.count").unwrap(), 1.0);
    assert!((sol.final_value("m.x").unwrap() - 3.0 * (-2.0f64).exp()).abs() < 1e-5);
}

component! {
    /// A discrete variable with an equation that never settles: `n = pre(n) + 1`.
    pub struct Runaway {
        /// Counts the rounds of the event iteration.
        variable n(discrete = true, start = 0.0): Real;
        /// Something continuous.
        variable x(start = 1.0, fixed = true): Real;
        equation {
            n = pre(n) + 1.0;
            der(x) = -x;
        }
    }
}

component! {
    /// A discrete variable without an equation.
    pub struct Undefined {
        /// Never given a value.
        variable mode(discrete = true): Real;
        /// Something continuous.
        variable x(start = 1.0, fixed = true): Real;
        equation {
            der(x) = -x * mode;
        }
    }
}

component! {
    /// A discrete variable defined by an equation of relations and `pre`: the number of
    /// times `x` went above 1 and `hot`, whether it is above now.
    pub struct Thermostat {
        /// Heating on below this temperature \[K\].
        parameter low: f64 = 1.0;
        /// Heating off above this temperature \[K\].
        parameter high: f64 = 2.0;
        /// Temperature \[K\].
        variable x(start = 0.0, fixed = true): Real;
        /// 1 while heating (discrete).
        variable on(discrete = true, start = 1.0): Real;
        equation {
            on = or(lt(x, low), and(pre(on), lt(x, high)));
            der(x) = if_else(on, 1.0, -0.5);
        }
    }
}

#[test]
fn a_discrete_equation_with_pre_switches_a_thermostat_at_the_closed_form_times() {
    // Heats at 1 K/s from 0 to 2 (t = 2), cools at 0.5 K/s to 1 (t = 4), heats to 2
    // (t = 5), ...: switching off at 2 + 3k and on at 4 + 3k.
    let mut model = System::new("thermostat");
    model.add("th", &Thermostat::default());
    let ssys = structural_simplify(&model).unwrap();
    let t_end = 12.0;
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
        .unwrap()
        .solve(&options(t_end, 240))
        .unwrap();
    for k in 0..=240 {
        let t = k as f64 * t_end / 240.0;
        let x = if t <= 2.0 {
            t
        } else {
            let s = (t - 2.0) % 3.0;
            if s < 2.0 {
                2.0 - 0.5 * s
            } else {
                1.0 + (s - 2.0)
            }
        };
        let got = sol.at("th.x", t).unwrap();
        assert!((got - x).abs() < 1e-8, "x({t}) = {got}, exact {x}");
    }
    assert_eq!(sol.at("th.on", 3.0).unwrap(), 0.0);
    assert_eq!(sol.at("th.on", 4.5).unwrap(), 1.0);
    let offs: Vec<f64> = sol
        .events()
        .iter()
        .filter(|e| e.condition == "th.x < th.high" && !e.value)
        .map(|e| e.t)
        .collect();
    assert_eq!(offs.len(), 4, "{:?}", sol.events());
    for (k, t) in offs.iter().enumerate() {
        assert!((t - (2.0 + 3.0 * k as f64)).abs() < 1e-9, "off at {offs:?}");
    }
}

#[test]
fn a_discrete_equation_that_never_settles_is_an_error_naming_it() {
    let mut model = System::new("runaway");
    model.add("r", &Runaway::default());
    let ssys = structural_simplify(&model).unwrap();
    let err = DaeProblem::new(&ssys, &[], (0.0, 1.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("EVENT_ITERATION") || err.contains("do not settle"),
        "{err}"
    );
    assert!(err.contains("r.n"), "{err}");
}

#[test]
fn a_discrete_variable_without_an_equation_is_an_error_naming_it() {
    let mut model = System::new("undefined");
    model.add("u", &Undefined::default());
    let err = structural_simplify(&model).unwrap_err().to_string();
    assert!(
        err.contains("u") && err.contains("`mode`") && err.contains("needs an equation"),
        "{err}"
    );
}

component! {
    /// Records `x` at the end of the simulation (Modelica's `terminal()`).
    pub struct FinalValue {
        /// Decays from 1.
        variable x(start = 1.0, fixed = true): Real;
        /// `x` at the end; 0 before.
        variable x_end(start = 0.0): Real;
        equation {
            der(x) = -x;
            when terminal() {
                x_end = x;
            }
        }
    }
}

#[test]
fn terminal_acts_once_at_the_stop_time() {
    let mut model = System::new("final");
    model.add("f", &FinalValue::default());
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 2.0))
        .unwrap()
        .solve(&options(2.0, 20))
        .unwrap();
    assert_eq!(sol.at("f.x_end", 1.0).unwrap(), 0.0);
    let exact = (-2.0f64).exp();
    assert!((sol.final_value("f.x_end").unwrap() - exact).abs() < 1e-9);
    assert!((sol.final_value("f.x").unwrap() - exact).abs() < 1e-9);
}

#[test]
fn a_time_event_at_the_stop_time_gives_the_last_point_its_right_limit() {
    // A step at the stop time: the run's last point is after it, as Dymola stores it.
    let model = system! {
        name: "late_step";
        step = Step { height: 2.0, start_time: 1.0 };
        gain = Gain { k: 3.0 };
        connect(step.y, gain.u);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 1.0))
        .unwrap()
        .solve(&options(1.0, 10))
        .unwrap();
    assert_eq!(sol.final_value("gain.y").unwrap(), 6.0);
    assert_eq!(sol.events().len(), 1, "{:?}", sol.events());
    assert_eq!(sol.events()[0].t, 1.0);
    assert_eq!(sol.at("gain.y", 0.9).unwrap(), 0.0);
}

#[test]
fn kinematic_ptp_accelerations_integrate_to_kinematic_ptp2_positions() {
    // Two axes of 2 and -1 rad at 1 rad/s and 2 rad/s2 from 0.2 s: the first sets the
    // time (path speed 0.5/s, path acceleration 1/s2: 0.5 s accelerating, 1.5 s at
    // constant speed, 0.5 s braking); integrated twice the acceleration of axis 1 is
    // KinematicPTP2's position.
    use multibody::blocks::{Integrator, KinematicPTP, KinematicPTP2};
    let model = system! {
        name: "ptp";
        acc = KinematicPTP {
            deltaq: vec![2.0, -1.0], qd_max: vec![1.0], qdd_max: vec![2.0], axis: 1,
            start_time: 0.2,
        };
        speed = Integrator::default();
        position = Integrator::default();
        path = KinematicPTP2 {
            q_begin: vec![0.0], q_end: vec![2.0, -1.0], qd_max: vec![1.0], qdd_max: vec![2.0],
            axis: 1, start_time: 0.2,
        };
        connect(acc.y, speed.u);
        connect(speed.y, position.u);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 3.0))
        .unwrap()
        .solve(&options(3.0, 300))
        .unwrap();
    for k in 0..=300 {
        let t = k as f64 * 0.01;
        let (p, q) = (
            sol.at("position.y", t).unwrap(),
            sol.at("path.q", t).unwrap(),
        );
        let (v, qd) = (sol.at("speed.y", t).unwrap(), sol.at("path.qd", t).unwrap());
        assert!(
            (p - q).abs() < 1e-8 && (v - qd).abs() < 1e-8,
            "at {t}: {p} {q} {v} {qd}"
        );
    }
    // Axis 1 arrives at -1 when axis 0 does: 0.2 + 2.5 = 2.7 s.
    assert!((sol.at("path.q", 2.7).unwrap() + 1.0).abs() < 1e-12);
    assert!((sol.at("path.q", 1.0).unwrap() + 0.275).abs() < 1e-12);
    assert_eq!(sol.at("path.end_time", 1.0).unwrap(), 2.7);
    assert_eq!(sol.at("path.moving", 2.8).unwrap(), 0.0);
}

component! {
    /// A mode that leaves `x` undetermined: `x = 1` until `z > 0.5`, then nothing.
    pub struct LosesAnEquation {
        /// Rises at 1/s.
        variable z(start = 0.0, fixed = true): Real;
        /// Determined only while `z < 0.5`.
        variable x(start = 1.0): Real;
        equation {
            der(z) = 1.0;
            0.0 = if_else(gt(z, 0.5), 0.0, x - 1.0);
        }
    }
}

#[test]
fn a_mode_without_a_consistent_solution_is_an_error_naming_what_switched() {
    let mut model = System::new("modes");
    model.add("m", &LosesAnEquation::default());
    let ssys = structural_simplify(&model).unwrap();
    let err = DaeProblem::new(&ssys, &[], (0.0, 1.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("no consistent solution in the mode")
            && err.contains("`m.z > 0.5` is now true"),
        "{err}"
    );
}
