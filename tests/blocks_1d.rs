//! Control blocks, sources and 1-D sensors against responses derived by hand.
//!
//! Every expected value below is a closed-form solution of the block equations as MSL
//! defines them (the block sources in `src/blocks`, `src/rotational`,
//! `src/translational`), never a number read back from a run.

#[path = "support/analytic.rs"]
mod analytic;

use std::f64::consts::PI;

use analytic::tight;

use multibody::blocks::{
    Add, Constant, ControllerType, Feedback, FirstOrder, Gain, Init, Integrator, LimPID, Limiter,
    PI as PIBlock, PID, Ramp, Sine, Step,
};
use multibody::prelude::*;
use multibody::rotational::{
    AngleSensor, ConstantTorque, Inertia, Speed, SpeedSensor, Torque, TorqueSensor,
};
use multibody::translational::{Force, Mass, PositionSensor};

fn solve(model: &(impl AsRef<System> + ?Sized), t1: f64) -> Solution {
    let ssys = structural_simplify(model).unwrap();
    DaeProblem::new(&ssys, &[], (0.0, t1))
        .unwrap()
        .solve(&tight())
        .unwrap()
}

/// Asserts `sol.at(name, t)` against `exact(t)` at each time, to `rel` relative to
/// `max(|exact|, floor)`.
fn check(
    sol: &Solution,
    name: &str,
    times: &[f64],
    rel: f64,
    floor: f64,
    exact: impl Fn(f64) -> f64,
) {
    for &t in times {
        let want = exact(t);
        let got = sol.at(name, t).unwrap();
        assert!(
            (got - want).abs() <= rel * want.abs().max(floor),
            "{name}({t}) = {got}, exact {want} (error {:e})",
            got - want
        );
    }
}

const TIMES: [f64; 6] = [0.1, 0.35, 0.8, 1.3, 2.0, 3.0];

#[test]
fn integrator_of_a_constant_is_a_line() {
    // der(y) = k u, y(0) = y_start (InitialState, the MSL default): y = y_start + k c t.
    let (c, k, y0) = (1.5, 2.0, -0.5);
    let model = system! {
        name: "integrate_constant";
        source = Constant { k: c };
        integrator = Integrator { k, y_start: y0 };
        connect(source.y, integrator.u);
    };
    let ssys = structural_simplify(&model).unwrap();
    let prob = DaeProblem::new(&ssys, &[], (0.0, 3.0)).unwrap();
    // The initial equation y = y_start fixes the only state: nothing is assumed.
    assert!(
        prob.init_report().assumed.is_empty(),
        "{:?}",
        prob.init_report()
    );
    let sol = prob.solve(&tight()).unwrap();
    check(&sol, "integrator.y", &TIMES, 1e-9, 1.0, |t| y0 + k * c * t);
    check(&sol, "integrator.u", &TIMES, 0.0, 1.0, |_| c);
}

#[test]
fn ramp_through_a_gain_integrates_piecewise() {
    // u = offset, then offset + height (t - t0)/duration, then offset + height.
    let (h, d, off, t0, k) = (2.0, 1.0, 0.5, 0.2, 3.0);
    let model = system! {
        name: "ramp_gain";
        ramp = Ramp { height: h, duration: d, offset: off, start_time: t0 };
        gain = Gain { k };
        integrator = Integrator::default();
        connect(ramp.y, gain.u);
        connect(gain.y, integrator.u);
    };
    let sol = solve(&model, 3.0);
    let u = |t: f64| {
        if t < t0 {
            off
        } else if t < t0 + d {
            off + h * (t - t0) / d
        } else {
            off + h
        }
    };
    // Integral of u from 0: 0.5 t; 0.1 + 0.5 (t - 0.2) + (t - 0.2)^2; 1.6 + 2.5 (t - 1.2).
    let integral = |t: f64| {
        if t < t0 {
            off * t
        } else if t < t0 + d {
            off * t + h * (t - t0).powi(2) / (2.0 * d)
        } else {
            off * t + h * d / 2.0 + h * (t - t0 - d)
        }
    };
    let times = [0.1, 0.2, 0.5, 1.0, 1.2, 1.7, 3.0];
    check(&sol, "ramp.y", &times, 1e-12, 1.0, u);
    check(&sol, "gain.y", &times, 1e-12, 1.0, |t| k * u(t));
    // The kinks of the ramp (t = 0.2, 1.2) are stepped over without events: the error
    // they leave is that of the integrator's tolerance.
    check(&sol, "integrator.y", &times, 1e-7, 1.0, |t| k * integral(t));
}

#[test]
fn feedback_around_an_integrator_is_a_first_order_lag() {
    // y' = k (r - y), y(0) = 0  =>  y = r (1 - exp(-k t)); the error is r exp(-k t).
    let (r, k) = (2.0, 4.0);
    let model = system! {
        name: "feedback_lag";
        reference = Constant { k: r };
        feedback = Feedback::default();
        gain = Gain { k };
        integrator = Integrator::default();
        connect(reference.y, feedback.u1);
        connect(integrator.y, feedback.u2);
        connect(feedback.y, gain.u);
        connect(gain.y, integrator.u);
    };
    let sol = solve(&model, 3.0);
    check(&sol, "integrator.y", &TIMES, 1e-8, 1.0, |t| {
        r * (1.0 - (-k * t).exp())
    });
    check(&sol, "feedback.y", &TIMES, 1e-8, r, |t| r * (-k * t).exp());
}

#[test]
fn sum_of_a_sine_and_a_constant_integrates_analytically() {
    // y' = k1 (o + A sin(w t + p)) + k2 c  =>
    // y = (k1 o + k2 c) t + k1 A (cos p - cos(w t + p)) / w.
    let (amp, f, p, o) = (1.5, 0.5, 0.3, 0.2);
    let (c, k1, k2) = (-1.0, 2.0, 0.5);
    let w = 2.0 * PI * f;
    let model = system! {
        name: "sine_sum";
        sine = Sine { amplitude: amp, f, phase: p, offset: o };
        delayed = Sine { amplitude: amp, f, phase: p, offset: o, start_time: 0.5 };
        constant = Constant { k: c };
        add = Add { k1, k2 };
        integrator = Integrator::default();
        connect(sine.y, add.u1);
        connect(constant.y, add.u2);
        connect(add.y, integrator.u);
    };
    let sol = solve(&model, 3.0);
    check(&sol, "sine.y", &TIMES, 1e-12, 1.0, |t| {
        o + amp * (w * t + p).sin()
    });
    check(&sol, "add.y", &TIMES, 1e-12, 1.0, |t| {
        k1 * (o + amp * (w * t + p).sin()) + k2 * c
    });
    // The integrator's global error (about 100 rtol here) is what remains.
    check(&sol, "integrator.y", &TIMES, 1e-7, 1.0, |t| {
        (k1 * o + k2 * c) * t + k1 * amp * (p.cos() - (w * t + p).cos()) / w
    });
    // With a start time the sine is only the offset before it, and starts at its
    // phase then.
    check(
        &sol,
        "delayed.y",
        &[0.1, 0.45, 0.5, 0.8, 2.0],
        1e-12,
        1.0,
        |t| {
            if t < 0.5 {
                o
            } else {
                o + amp * (w * (t - 0.5) + p).sin()
            }
        },
    );
}

#[test]
fn step_into_a_first_order_block_rises_with_its_time_constant() {
    // T y' + y = k u with u = offset + height = 2.5 from t = 0, y(0) = y_start:
    // y = k u + (y_start - k u) exp(-t / T).
    let (h, off, k, tc, y0) = (2.0, 0.5, 1.5, 0.4, 0.25);
    let model = system! {
        name: "first_order_step";
        step = Step { height: h, offset: off };
        lag = FirstOrder { k, T: tc, y_start: y0, init: Init::InitialState };
        connect(step.y, lag.u);
    };
    let sol = solve(&model, 3.0);
    let ku = k * (h + off);
    check(&sol, "lag.y", &TIMES, 1e-8, 1.0, |t| {
        ku + (y0 - ku) * (-t / tc).exp()
    });
    // After one time constant 63.2 % of the way from y_start to k u.
    let y_t = sol.at("lag.y", tc).unwrap();
    let expected = y0 + (ku - y0) * (1.0 - (-1.0f64).exp());
    assert!((y_t - expected).abs() < 1e-8, "y(T) = {y_t}");
}

#[test]
fn delayed_step_moves_a_first_order_block_from_its_steady_state() {
    // SteadyState: y' = 0 at t = 0, so y(0) = k offset; from t0 on u = offset + height:
    // y = k (offset + height) + (k offset - k (offset + height)) exp(-(t - t0) / T).
    let (h, off, t0, k, tc) = (2.0, 0.5, 0.3, 1.5, 0.4);
    let model = system! {
        name: "first_order_delayed_step";
        step = Step { height: h, offset: off, start_time: t0 };
        lag = FirstOrder { k, T: tc, init: Init::SteadyState };
        connect(step.y, lag.u);
    };
    let sol = solve(&model, 3.0);
    let exact = |t: f64| {
        if t < t0 {
            k * off
        } else {
            k * (off + h) - k * h * (-(t - t0) / tc).exp()
        }
    };
    check(&sol, "step.y", &[0.0, 0.29, 0.3, 1.0], 0.0, 1.0, |t| {
        if t < t0 { off } else { off + h }
    });
    check(&sol, "lag.y", &[0.0, 0.1, 0.25], 1e-10, 1.0, exact);
    // The jump of the input is stepped over without an event: IDA's error test
    // places it to within a step that is a small multiple of its tolerance, which
    // shows as a time shift of the exponential; 1e-6 of the step height bounds it.
    check(&sol, "lag.y", &[0.5, 0.8, 1.5, 3.0], 1e-6, 1.0, exact);
}

#[test]
fn pi_on_a_step_ramps_with_slope_k_over_t() {
    // y = k (x + u), x' = u / T. Step e from t = 0:
    //   InitialState (x(0) = x_start): y = k (x_start + e + e t / T);
    //   InitialOutput (y(0) = y_start): x(0) = y_start / k - e, y = y_start + k e t / T.
    let (e, k, tc, x0, y0) = (0.8, 2.5, 0.5, 0.1, 1.0);
    let model = system! {
        name: "pi_step";
        step = Step { height: e };
        pi_state = PIBlock { k, T: tc, x_start: x0, init: Init::InitialState };
        pi_output = PIBlock { k, T: tc, y_start: y0, init: Init::InitialOutput };
        connect(step.y, pi_state.u);
        connect(step.y, pi_output.u);
    };
    let sol = solve(&model, 3.0);
    check(&sol, "pi_state.y", &TIMES, 1e-9, 1.0, |t| {
        k * (x0 + e + e * t / tc)
    });
    check(&sol, "pi_output.y", &TIMES, 1e-9, 1.0, |t| {
        y0 + k * e * t / tc
    });
    check(&sol, "pi_output.x", &TIMES, 1e-9, 1.0, |t| {
        y0 / k - e + e * t / tc
    });
}

#[test]
fn pi_controls_an_integrator_plant_to_the_reference() {
    // Plant y' = v, controller v = k (e + x), x' = e / T, e = r - y:
    //   y'' + k y' + (k / T) y = (k / T) r.
    // k = 3, T = 1.5: s^2 + 3 s + 2 = (s + 1)(s + 2); y(0) = 0, y'(0) = k r:
    //   y = r (1 + exp(-t) - 2 exp(-2 t)),  v = y' = r (-exp(-t) + 4 exp(-2 t)).
    let (r, k, tc) = (1.0, 3.0, 1.5);
    let model = system! {
        name: "pi_loop";
        reference = Constant { k: r };
        feedback = Feedback::default();
        controller = PIBlock { k, T: tc, init: Init::InitialState };
        plant = Integrator::default();
        connect(reference.y, feedback.u1);
        connect(plant.y, feedback.u2);
        connect(feedback.y, controller.u);
        connect(controller.y, plant.u);
    };
    let sol = solve(&model, 6.0);
    let times = [0.1, 0.5, 1.0, 2.0, 4.0, 6.0];
    check(&sol, "plant.y", &times, 1e-8, 1.0, |t| {
        r * (1.0 + (-t).exp() - 2.0 * (-2.0 * t).exp())
    });
    check(&sol, "controller.y", &times, 1e-7, 1.0, |t| {
        r * (-(-t).exp() + 4.0 * (-2.0 * t).exp())
    });
}

#[test]
fn pid_adds_the_filtered_derivative() {
    // y = k (u + xi + Nd (u - xd)), xi' = u / Ti, xd' = (u - xd) Nd / Td; tau = Td / Nd.
    // Ramp u = a t, xi(0) = xd(0) = 0:
    //   xi = a t^2 / (2 Ti), u - xd = a tau (1 - exp(-t / tau)),
    //   y = k (a t + a t^2 / (2 Ti) + a Td (1 - exp(-t / tau))): the derivative part
    //   tends to Td u'.
    // Step u = e, InitialState: y = k (e + e t / Ti + Nd e exp(-t / tau)) (the kick).
    // Step u = e, InitialOutput: xd(0) = e, xi(0) = y_start / k - e,
    //   y = y_start + k e t / Ti.
    let (k, ti, td, nd) = (2.0, 0.5, 0.2, 4.0);
    let (a, e, y0) = (0.3, 0.4, 0.7);
    let tau = td / nd;
    let model = system! {
        name: "pid";
        ramp = Ramp { height: 10.0 * a, duration: 10.0 };
        step = Step { height: e };
        pid_ramp = PID { k, Ti: ti, Td: td, Nd: nd, init: Init::InitialState };
        pid_step = PID { k, Ti: ti, Td: td, Nd: nd, init: Init::InitialState };
        pid_output = PID { k, Ti: ti, Td: td, Nd: nd, y_start: y0, init: Init::InitialOutput };
        connect(ramp.y, pid_ramp.u);
        connect(step.y, pid_step.u);
        connect(step.y, pid_output.u);
    };
    let sol = solve(&model, 3.0);
    let times = [0.01, 0.05, 0.1, 0.35, 1.0, 3.0];
    check(&sol, "pid_ramp.y", &times, 1e-8, 1.0, |t| {
        k * (a * t + a * t * t / (2.0 * ti) + a * td * (1.0 - (-t / tau).exp()))
    });
    check(&sol, "pid_step.y", &times, 1e-8, 1.0, |t| {
        k * (e + e * t / ti + nd * e * (-t / tau).exp())
    });
    check(&sol, "pid_output.y", &times, 1e-9, 1.0, |t| {
        y0 + k * e * t / ti
    });
    check(&sol, "pid_output.xd", &times, 1e-9, 1.0, |_| e);
}

#[test]
fn limiter_clips_a_ramp_and_the_integral_follows() {
    // u = -2 + t on [0, 4]; the limiter keeps [-1, 1]: y = -1, then t - 2 on [1, 3],
    // then 1. Its integral: -t; -1 + ((t - 2)^2 - 1) / 2; -1 + (t - 3).
    let model = system! {
        name: "limiter";
        ramp = Ramp { height: 4.0, duration: 4.0, offset: -2.0 };
        limiter = Limiter { y_max: 1.0, y_min: -1.0 };
        integrator = Integrator::default();
        connect(ramp.y, limiter.u);
        connect(limiter.y, integrator.u);
    };
    let sol = solve(&model, 4.0);
    let times = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0];
    check(&sol, "limiter.y", &times, 1e-12, 1.0, |t| {
        (t - 2.0).clamp(-1.0, 1.0)
    });
    // The kinks at t = 1 and 3 are stepped over without events.
    check(&sol, "integrator.y", &times, 1e-7, 1.0, |t| {
        if t < 1.0 {
            -t
        } else if t < 3.0 {
            -1.0 + ((t - 2.0).powi(2) - 1.0) / 2.0
        } else {
            -1.0 + (t - 3.0)
        }
    });
}

#[test]
fn limpid_saturates_and_unwinds_by_tracking() {
    // LimPID as PI with u_s = e, u_m = 0: y_u = k (e + xi), y = min(max(y_u, y_min),
    // y_max), xi' = (e + (y - y_u) / (k Ni)) / Ti, xi(0) = 0.
    // Unsaturated: xi = e t / Ti, y = k e (1 + t / Ti), until y_u = y_max at
    //   t1 = Ti (y_max / (k e) - 1).
    // Saturated: xi' = (xi_inf - xi) / (Ni Ti) with xi_inf = Ni e + y_max / k - e, so
    //   xi = xi_inf - Ni e exp(-(t - t1) / (Ni Ti)) and y_u -> k (Ni e + y_max / k).
    let (e, k, ti, ni, y_max) = (1.0, 2.0, 0.5, 0.9, 3.0);
    let model = system! {
        name: "limpid";
        set_point = Constant { k: e };
        measurement = Constant { k: 0.0 };
        controller = LimPID {
            controller_type: ControllerType::PI,
            k,
            Ti: ti,
            Ni: ni,
            y_max,
            y_min: -y_max,
            init: Init::InitialState,
        };
        connect(set_point.y, controller.u_s);
        connect(measurement.y, controller.u_m);
    };
    let sol = solve(&model, 3.0);
    let t1 = ti * (y_max / (k * e) - 1.0);
    assert!((t1 - 0.25).abs() < 1e-15);
    let xi_inf = ni * e + y_max / k - e;
    let xi = |t: f64| {
        if t < t1 {
            e * t / ti
        } else {
            xi_inf - ni * e * (-(t - t1) / (ni * ti)).exp()
        }
    };
    let times = [0.1, 0.2, 0.3, 0.5, 1.0, 3.0];
    check(&sol, "controller.xi", &times, 1e-7, 1.0, xi);
    check(&sol, "controller.y", &times, 1e-7, 1.0, |t| {
        (k * (e + xi(t))).min(y_max)
    });
    check(&sol, "controller.y_unlimited", &times, 1e-7, 1.0, |t| {
        k * (e + xi(t))
    });
    check(&sol, "controller.control_error", &times, 0.0, 1.0, |_| e);
}

#[test]
fn constant_torque_accelerates_an_inertia() {
    // J phi'' = tau: phi = phi0 + w0 t + tau t^2 / (2 J), w = w0 + tau t / J. The torque
    // sensor between source and inertia carries the source's torque.
    let (tau, j, phi0, w0) = (0.6, 0.3, 0.2, -0.5);
    let model = system! {
        name: "constant_torque";
        source = ConstantTorque { tau_constant: tau };
        torque_sensor = TorqueSensor::default();
        inertia = Inertia { J: j, phi_start: phi0, w_start: w0 };
        angle = AngleSensor::default();
        speed = SpeedSensor::default();
        connect(source.flange, torque_sensor.flange_a);
        connect(torque_sensor.flange_b, inertia.flange_a);
        connect(inertia.flange_b, angle.flange);
        connect(inertia.flange_b, speed.flange);
    };
    let sol = solve(&model, 3.0);
    let phi = |t: f64| phi0 + w0 * t + tau * t * t / (2.0 * j);
    check(&sol, "inertia.phi", &TIMES, 1e-9, 1.0, phi);
    check(&sol, "angle.phi", &TIMES, 1e-9, 1.0, phi);
    check(&sol, "speed.w", &TIMES, 1e-9, 1.0, |t| w0 + tau * t / j);
    check(&sol, "inertia.a", &TIMES, 1e-9, 1.0, |_| tau / j);
    check(&sol, "torque_sensor.tau", &TIMES, 1e-12, 1.0, |_| tau);
}

#[test]
fn torque_sensor_measures_what_the_second_inertia_receives() {
    // tau(t) = A sin(w t) on J1, rigidly coupled through the sensor to J2, from rest:
    // acceleration tau / (J1 + J2); speed A (1 - cos w t) / (w (J1 + J2)); angle
    // A (t - sin(w t) / w) / (w (J1 + J2)); the sensor passes J2 a = tau J2 / (J1 + J2).
    let (amp, f, j1, j2) = (2.0, 0.5, 0.5, 1.5);
    let w = 2.0 * PI * f;
    let jt = j1 + j2;
    let model = system! {
        name: "torque_sensor";
        signal = Sine { amplitude: amp, f };
        torque = Torque::default();
        inertia1 = Inertia { J: j1 };
        sensor = TorqueSensor::default();
        inertia2 = Inertia { J: j2 };
        angle = AngleSensor::default();
        speed = SpeedSensor::default();
        connect(signal.y, torque.tau);
        connect(torque.flange, inertia1.flange_a);
        connect(inertia1.flange_b, sensor.flange_a);
        connect(sensor.flange_b, inertia2.flange_a);
        connect(inertia2.flange_b, angle.flange);
        connect(inertia2.flange_b, speed.flange);
    };
    let sol = solve(&model, 3.0);
    check(&sol, "sensor.tau", &TIMES, 1e-8, 1.0, |t| {
        amp * (w * t).sin() * j2 / jt
    });
    check(&sol, "speed.w", &TIMES, 1e-8, 1.0, |t| {
        amp * (1.0 - (w * t).cos()) / (w * jt)
    });
    check(&sol, "angle.phi", &TIMES, 1e-8, 1.0, |t| {
        amp * (t - (w * t).sin() / w) / (w * jt)
    });
}

#[test]
fn exact_speed_source_follows_its_reference_and_pays_the_inertia_torque() {
    // w = w_ref = o + A sin(w t) exactly; phi = phi0 + o t + A (1 - cos w t) / w; the
    // torque that the source passes through the sensor is J w' = J A w cos(w t).
    let (amp, f, o, j, phi0) = (1.2, 0.4, 0.1, 0.8, 0.3);
    let w = 2.0 * PI * f;
    let model = system! {
        name: "exact_speed";
        reference = Sine { amplitude: amp, f, offset: o };
        source = Speed { exact: true };
        sensor = TorqueSensor::default();
        inertia = Inertia { J: j, phi_start: phi0 };
        speed = SpeedSensor::default();
        connect(reference.y, source.w_ref);
        connect(source.flange, sensor.flange_a);
        connect(sensor.flange_b, inertia.flange_a);
        connect(inertia.flange_b, speed.flange);
    };
    let sol = solve(&model, 3.0);
    check(&sol, "speed.w", &TIMES, 1e-9, 1.0, |t| {
        o + amp * (w * t).sin()
    });
    check(&sol, "inertia.phi", &TIMES, 1e-8, 1.0, |t| {
        phi0 + o * t + amp * (1.0 - (w * t).cos()) / w
    });
    check(&sol, "sensor.tau", &TIMES, 1e-8, 1.0, |t| {
        j * amp * w * (w * t).cos()
    });
}

#[test]
fn filtered_speed_source_is_a_first_order_lag() {
    // a = (w_ref - w) 2 pi f_crit: from rest w = W (1 - exp(-wc t)),
    // phi = W (t - (1 - exp(-wc t)) / wc), torque through the sensor J W wc exp(-wc t).
    let (big_w, f_crit, j) = (3.0, 1.0, 0.4);
    let wc = 2.0 * PI * f_crit;
    let model = system! {
        name: "filtered_speed";
        reference = Constant { k: big_w };
        source = Speed { f_crit };
        sensor = TorqueSensor::default();
        inertia = Inertia { J: j };
        connect(reference.y, source.w_ref);
        connect(source.flange, sensor.flange_a);
        connect(sensor.flange_b, inertia.flange_a);
    };
    let sol = solve(&model, 3.0);
    check(&sol, "inertia.w", &TIMES, 1e-8, 1.0, |t| {
        big_w * (1.0 - (-wc * t).exp())
    });
    check(&sol, "inertia.phi", &TIMES, 1e-8, 1.0, |t| {
        big_w * (t - (1.0 - (-wc * t).exp()) / wc)
    });
    check(&sol, "sensor.tau", &TIMES, 1e-8, j * big_w * wc, |t| {
        j * big_w * wc * (-wc * t).exp()
    });
}

#[test]
fn constant_force_accelerates_a_mass() {
    // m s'' = F: s = s0 + v0 t + F t^2 / (2 m); the flanges are L/2 either side of s.
    let (force, m, len, s0, v0) = (1.2, 0.6, 0.4, 1.0, 0.5);
    let model = system! {
        name: "constant_force";
        source = Constant { k: force };
        push = Force::default();
        mass = Mass { m, L: len, s_start: s0, v_start: v0 };
        front = PositionSensor::default();
        back = PositionSensor::default();
        connect(source.y, push.f);
        connect(push.flange, mass.flange_a);
        connect(mass.flange_a, back.flange);
        connect(mass.flange_b, front.flange);
    };
    let sol = solve(&model, 3.0);
    let s = |t: f64| s0 + v0 * t + force * t * t / (2.0 * m);
    check(&sol, "mass.s", &TIMES, 1e-9, 1.0, s);
    check(&sol, "mass.v", &TIMES, 1e-9, 1.0, |t| v0 + force * t / m);
    check(&sol, "front.s", &TIMES, 1e-9, 1.0, |t| s(t) + len / 2.0);
    check(&sol, "back.s", &TIMES, 1e-9, 1.0, |t| s(t) - len / 2.0);
}
