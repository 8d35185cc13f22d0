//! Every integration method against closed forms: the period of a large-amplitude
//! pendulum, bounces at their closed-form times (events), output times, parameters
//! changed without recompiling; the automatic choice on a non-stiff and a stiff model;
//! the error of an ODE method asked of a model with algebraic unknowns.

#[path = "support/analytic.rs"]
mod analytic;
#[path = "support/small_models.rs"]
mod small_models;
use analytic::elliptic_k;
#[path = "../examples/bench_pendulum_chain/stiff_chain.rs"]
mod stiff;

use multibody::prelude::*;
use multibody::{Error, Method, Solution};
use small_models::{BouncingBall, point_pendulum};
use stiff::stiff_chain;

const ALL: [Method; 10] = [
    Method::Auto,
    Method::Ida,
    Method::CvodeBdf,
    Method::CvodeAdams,
    Method::DormandPrince5,
    Method::Verner6,
    Method::Verner7,
    Method::Verner8,
    Method::Verner9,
    Method::Kvaerno5,
];

fn options(method: Method, rtol: f64) -> SolverOptions {
    SolverOptions {
        method,
        rtol,
        atol: rtol * 1e-2,
        ..SolverOptions::default()
    }
}

#[test]
fn every_method_gives_the_period_of_a_large_amplitude_point_pendulum() {
    // Released at rest from phi0 below the horizontal (the link along x, gravity -y):
    // the period of the swing is 4 sqrt(L/g) K(sin(amplitude / 2)), where the amplitude
    // is measured from the lowest point (phi = -pi/2).
    let ssys = structural_simplify(&point_pendulum()).unwrap();
    let g = 9.80665;
    let mut steps_by_method = Vec::new();
    for length in [1.0f64, 0.5] {
        let phi0 = 0.3;
        let amplitude = phi0 + std::f64::consts::FRAC_PI_2;
        let period = 4.0 * (length / g).sqrt() * elliptic_k((amplitude / 2.0).sin());
        for method in ALL {
            let sol = DaeProblem::new(
                &ssys,
                &[("link.r[1]", length), ("joint.phi", phi0), ("joint.w", 0.0)],
                (0.0, period),
            )
            .unwrap()
            .solve(&SolverOptions {
                output_times: Some(vec![0.25 * period, 0.5 * period, period]),
                ..options(method, 1e-9)
            })
            .unwrap();
            // Each method is itself: the explicit ones evaluate no Jacobian, the
            // implicit ones do.
            let stats = sol.statistics();
            let explicit = matches!(
                method,
                Method::CvodeAdams
                    | Method::DormandPrince5
                    | Method::Verner6
                    | Method::Verner7
                    | Method::Verner8
                    | Method::Verner9
                    | Method::Auto
            );
            assert_eq!(stats.jacobian_evals == 0, explicit, "{method:?}: {stats:?}");
            if length == 1.0 {
                steps_by_method.push(stats.steps);
            }
            let phi = sol.get("joint.phi").unwrap();
            let w = sol.get("joint.w").unwrap();
            // t0, a quarter (the lowest point), half (the other side), the period.
            assert_eq!(sol.t().len(), 4, "{method:?}");
            let bottom = -std::f64::consts::FRAC_PI_2;
            let other = bottom - amplitude;
            let tol = 2e-6;
            assert!(
                (phi[1] - bottom).abs() < tol,
                "{method:?}: {}",
                phi[1] - bottom
            );
            assert!(
                (phi[2] - other).abs() < tol,
                "{method:?}: {}",
                phi[2] - other
            );
            assert!((phi[3] - phi0).abs() < tol, "{method:?}: {}", phi[3] - phi0);
            assert!(w[3].abs() < 10.0 * tol, "{method:?}: w = {}", w[3]);
            // The speed at the bottom from energy: w^2 L^2 = 2 g L sin(amplitude)...
            let w_bottom = (2.0 * g * (1.0 - amplitude.cos()) / length).sqrt();
            assert!(
                (w[1].abs() - w_bottom).abs() < 10.0 * tol,
                "{method:?}: {} vs {w_bottom}",
                w[1]
            );
        }
    }
    // Auto is Verner 8(7) here; every other method takes its own number of steps.
    let mut distinct = steps_by_method.clone();
    distinct.sort_unstable();
    distinct.dedup();
    assert_eq!(distinct.len(), ALL.len() - 1, "{steps_by_method:?}");
}

#[test]
fn every_method_finds_the_bounces_at_their_closed_form_times() {
    let (g, e, h0): (f64, f64, f64) = (9.81, 0.8, 1.0);
    let mut model = System::new("bouncing");
    model.add("ball", &BouncingBall::default());
    let ssys = structural_simplify(&model).unwrap();
    let t1 = (2.0 * h0 / g).sqrt();
    let mut impacts = vec![t1];
    for k in 1..5 {
        impacts.push(impacts[k - 1] + 2.0 * e.powi(k as i32) * t1);
    }
    let t_end = impacts[4] + 0.05;
    for method in ALL {
        let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))
            .unwrap()
            .solve(&options(method, 1e-8))
            .unwrap();
        let hits: Vec<f64> = sol.events().iter().map(|ev| ev.t).collect();
        assert!(hits.len() >= 5, "{method:?}: {:?}", sol.events());
        for (k, want) in impacts.iter().enumerate() {
            assert!(
                hits.iter().any(|t| (t - want).abs() < 1e-7),
                "{method:?}: impact {k} at {want} not among {hits:?}"
            );
        }
        let v_end = sol.final_value("ball.v").unwrap();
        let exact = e.powi(5) * g * t1 - g * (t_end - impacts[4]);
        assert!(
            (v_end - exact).abs() < 1e-6,
            "{method:?}: v = {v_end}, exact {exact}"
        );
    }
}

component! {
    /// `x'' = -x` from `x = -1` at rest, counting the instants where its acceleration
    /// turns negative (`cos t < 0`: t = pi/2 + 2 pi k).
    pub struct AccelerationWatch {
        /// Position.
        variable x(start = -1.0, fixed = true): Real;
        /// Velocity.
        variable v(start = 0.0, fixed = true): Real;
        /// Acceleration.
        variable a: Real;
        /// Instants where `a` turned negative.
        variable turns(start = 0.0): Real;
        equation {
            der(x) = v;
            der(v) = -x;
            a = der(v);
            when lt(a, 0.0) {
                turns = pre(turns) + 1.0;
            }
        }
    }
}

#[test]
fn a_crossing_of_an_acceleration_is_found_by_every_method() {
    // ARKODE locates crossings on its interpolant between steps (degree 5 at most):
    // Verner 9(8) put two of these 7e-7 off at rtol 1e-9, Verner 6(5) and Kvaerno 5(4)
    // one 1e-9 and two 8.7e-7 off. Its methods now locate them on the integrated
    // solution (2e-11 or better here).
    let mut model = System::new("watch");
    model.add("w", &AccelerationWatch::default());
    let ssys = structural_simplify(&model).unwrap();
    let pi = std::f64::consts::PI;
    for method in ALL {
        let sol = DaeProblem::new(&ssys, &[], (0.0, 8.0))
            .unwrap()
            .solve(&options(method, 1e-9))
            .unwrap();
        let hits: Vec<f64> = sol.events().iter().map(|ev| ev.t).collect();
        let tol_t = match method {
            Method::Ida | Method::CvodeBdf | Method::CvodeAdams => 2e-8,
            _ => 1e-10,
        };
        for want in [pi / 2.0, 3.0 * pi / 2.0, 5.0 * pi / 2.0] {
            assert!(
                hits.iter().any(|t| (t - want).abs() < tol_t),
                "{method:?}: a crossing at {want} not among {hits:?}"
            );
        }
        assert_eq!(sol.final_value("w.turns").unwrap(), 2.0, "{method:?}");
        // ARKODE's methods restart at each crossing from the state integrated to it,
        // not the interpolated one (1.9e-6 off by Verner 8(7), 8.6e-7 by Kvaerno 5(4)
        // when they did; 1e-10 at most now).
        let x = sol.final_value("w.x").unwrap();
        assert!((x + 8.0f64.cos()).abs() < 1e-8, "{method:?}: x(8) = {x}");
    }
}

#[test]
fn output_times_carry_the_methods_accuracy_and_none_is_lost_at_a_crossing() {
    // ARKODE's interpolant (degree 5) gave Verner 8(7)'s output times 2.8e-6 off at
    // rtol 1e-9 (its steps 1e-12); the methods of order above 5 now integrate to them
    // from the step's start. Those in a step where a crossing was found are integrated
    // to by every ARKODE method, and those between the interpolant's crossing time and
    // the located one are reported once.
    let mut model = System::new("watch");
    model.add("w", &AccelerationWatch::default());
    let ssys = structural_simplify(&model).unwrap();
    // Every 0.01 s, and every 1e-8 s within 2e-6 of the first crossing, where the
    // interpolant's crossing time and the located one lie apart.
    let pi = std::f64::consts::PI;
    let mut times: Vec<f64> = (1..=800).map(|k| k as f64 * 0.01).collect();
    times.extend((-200..=200).map(|k| pi / 2.0 + k as f64 * 1e-8));
    times.sort_by(f64::total_cmp);
    for method in ALL {
        let sol = DaeProblem::new(&ssys, &[], (0.0, 8.0))
            .unwrap()
            .solve(&SolverOptions {
                output_times: Some(times.clone()),
                ..options(method, 1e-9)
            })
            .unwrap();
        let tol = match method {
            Method::Ida | Method::CvodeBdf | Method::CvodeAdams => 1e-7,
            Method::DormandPrince5 | Method::Kvaerno5 => 2e-9,
            _ => 1e-10,
        };
        let x = sol.get("w.x").unwrap();
        for want in &times {
            let at: Vec<usize> = (0..sol.t().len())
                .filter(|&k| sol.t()[k] == *want)
                .collect();
            // Once, or twice where the crossing's time is an output time (the values
            // before and after the event).
            assert!(
                at.len() == 1 || (at.len() == 2 && sol.events().iter().any(|e| e.t == *want)),
                "{method:?}: output at {want} {} times",
                at.len()
            );
            let k = at[0];
            assert!(
                (x[k] + want.cos()).abs() < tol,
                "{method:?}: x({want}) = {}",
                x[k]
            );
        }
    }
}

component! {
    /// `x'' = -x` from `x = -1` at rest (`a = cos t`), with two thresholds of its
    /// acceleration crossed 4e-7 s apart, closer than ARKODE's interpolant locates them.
    pub struct TwoThresholds {
        /// Position.
        variable x(start = -1.0, fixed = true): Real;
        /// Velocity.
        variable v(start = 0.0, fixed = true): Real;
        /// Acceleration.
        variable a: Real;
        /// Crossings of `a = 2e-7` downwards.
        variable early(start = 0.0): Real;
        /// Crossings of `a = -2e-7` downwards.
        variable late(start = 0.0): Real;
        equation {
            der(x) = v;
            der(v) = -x;
            a = der(v);
            when lt(a, -2e-7) {
                late = pre(late) + 1.0;
            }
            when lt(a, 2e-7) {
                early = pre(early) + 1.0;
            }
        }
    }
}

#[test]
fn crossings_close_together_are_each_located_in_their_order() {
    // The two crossings near pi/2 lie 4e-7 s apart; on the interpolant Verner 9(8)
    // put crossings there 7e-7 off. Each is located on the integrated solution, the
    // earlier first (the choice among several functions is tested on plain data in
    // `solve/ode/earliest_crossing.rs`).
    let mut model = System::new("two");
    model.add("w", &TwoThresholds::default());
    let ssys = structural_simplify(&model).unwrap();
    let (t_early, t_late) = (2e-7f64.acos(), (-2e-7f64).acos());
    for method in ALL {
        let sol = DaeProblem::new(&ssys, &[], (0.0, 2.0))
            .unwrap()
            .solve(&options(method, 1e-9))
            .unwrap();
        let tol = match method {
            Method::Ida | Method::CvodeBdf | Method::CvodeAdams => 2e-8,
            _ => 1e-10,
        };
        let when = |condition: &str| -> Vec<f64> {
            sol.events()
                .iter()
                .filter(|e| e.condition == condition && e.value)
                .map(|e| e.t)
                .collect()
        };
        let (early, late) = (when("w.a < 2e-7"), when("w.a < -2e-7"));
        assert!(
            early.len() == 1 && (early[0] - t_early).abs() < tol,
            "{method:?}: early crossing at {early:?}, exact {t_early}; {:?}",
            sol.events()
        );
        assert!(
            late.len() == 1 && (late[0] - t_late).abs() < tol,
            "{method:?}: late crossing at {late:?}, exact {t_late}"
        );
        assert_eq!(sol.final_value("w.early").unwrap(), 1.0, "{method:?}");
        assert_eq!(sol.final_value("w.late").unwrap(), 1.0, "{method:?}");
    }
}

fn steps(sol: &Solution) -> u64 {
    sol.statistics().steps
}

#[test]
fn the_automatic_choice_stays_explicit_on_a_smooth_model_and_takes_bdf_on_a_stiff_one() {
    // Smooth: the pendulum. Auto takes Verner 8(7) throughout: the same steps.
    let ssys = structural_simplify(&point_pendulum()).unwrap();
    let solve = |method| {
        DaeProblem::new(&ssys, &[("joint.phi", 0.3)], (0.0, 10.0))
            .unwrap()
            .solve(&options(method, 1e-6))
            .unwrap()
    };
    let (auto, vern8, ida) = (
        solve(Method::Auto),
        solve(Method::Verner8),
        solve(Method::Ida),
    );
    assert_eq!(steps(&auto), steps(&vern8));
    // Nor does it switch at a loose tolerance, where its steps are long.
    let loose = |method| {
        DaeProblem::new(&ssys, &[("joint.phi", 0.3)], (0.0, 10.0))
            .unwrap()
            .solve(&options(method, 1e-4))
            .unwrap()
    };
    assert_eq!(steps(&loose(Method::Auto)), steps(&loose(Method::Verner8)));
    assert!(
        5 * steps(&auto) < steps(&ida),
        "Verner 8(7) {} steps, IDA {}",
        steps(&auto),
        steps(&ida)
    );

    // Stiff: spring-dampers of 1e4 N/m and 300 N s/m between masses of 1 kg (modes from
    // about -1100 /s to a slow one decaying at 12 /s). The static stretch of every spring
    // is force / c, so mass k rests at k force / c.
    let (n, c, d, force) = (5, 1e4, 300.0, 50.0);
    let ssys = structural_simplify(&stiff_chain(n, c, d, force)).unwrap();
    let solve = |method| {
        DaeProblem::new(&ssys, &[], (0.0, 10.0))
            .unwrap()
            .solve(&options(method, 1e-6))
            .unwrap()
    };
    let (auto, vern7, bdf) = (
        solve(Method::Auto),
        solve(Method::Verner7),
        solve(Method::CvodeBdf),
    );
    for sol in [&auto, &vern7, &bdf] {
        for k in 1..=n {
            let s = sol.final_value(format!("mass{k}.s").as_str()).unwrap();
            let exact = k as f64 * force / c;
            assert!((s - exact).abs() < 1e-7, "mass{k}.s = {s}, exact {exact}");
        }
    }
    assert!(
        5 * steps(&bdf) < steps(&vern7),
        "BDF {} steps, Verner 7(6) {}",
        steps(&bdf),
        steps(&vern7)
    );
    assert!(
        3 * steps(&auto) < steps(&vern7),
        "Auto {} steps, Verner 7(6) {}",
        steps(&auto),
        steps(&vern7)
    );

    // 15 masses, 30 states: the implicit methods factor with the sparse LU.
    let (n, c) = (15, 1e4);
    let ssys = structural_simplify(&stiff_chain(n, c, d, force)).unwrap();
    assert_eq!(ssys.states().len(), 2 * n);
    for method in [Method::CvodeBdf, Method::Kvaerno5] {
        let sol = DaeProblem::new(&ssys, &[], (0.0, 20.0))
            .unwrap()
            .solve(&options(method, 1e-8))
            .unwrap();
        for k in 1..=n {
            let s = sol.final_value(format!("mass{k}.s").as_str()).unwrap();
            let exact = k as f64 * force / c;
            assert!(
                (s - exact).abs() < 1e-7,
                "{method:?}: mass{k}.s = {s}, exact {exact}"
            );
        }
    }
}

component! {
    /// `x' = -y` with `y` the root of `y^3 + y = x`: a nonlinear equation the
    /// integrator solves (an algebraic unknown).
    pub struct Implicit {
        /// The state.
        variable x(start = 2.0, fixed = true): Real;
        /// The algebraic unknown.
        variable y(start = 1.0): Real;
        equation {
            der(x) = -y;
            y * y * y + y = x;
        }
    }
}

#[test]
fn an_ode_method_on_a_model_with_algebraic_unknowns_is_an_error_naming_them() {
    let mut model = System::new("implicit");
    model.add("m", &Implicit::default());
    let ssys = structural_simplify(&model).unwrap();
    assert!(
        ssys.mass_matrix_diagonal().contains(&0.0),
        "{:?}",
        ssys.unknowns()
    );
    let problem = DaeProblem::new(&ssys, &[], (0.0, 1.0)).unwrap();
    let ida = problem.solve(&options(Method::Ida, 1e-6)).unwrap();
    let auto = problem.solve(&options(Method::Auto, 1e-6)).unwrap();
    assert_eq!(auto.t(), ida.t(), "Auto takes IDA for a DAE");
    for method in [Method::Verner7, Method::CvodeBdf, Method::Kvaerno5] {
        let err = problem.solve(&options(method, 1e-6)).unwrap_err();
        let Error::Solve(e) = &err else {
            panic!("{err}");
        };
        assert_eq!(e.flag, "BAD_METHOD", "{err}");
        assert!(
            err.to_string().contains("algebraic unknowns (m.y)"),
            "{err}"
        );
    }
}

component! {
    /// `y' = sqrt(1 - t)`: not a number from t = 1 on.
    pub struct RootOfOneMinusTime {
        /// Time.
        variable x(start = 0.0, fixed = true): Real;
        /// The integral.
        variable y(start = 0.0, fixed = true): Real;
        equation {
            der(x) = 1.0;
            der(y) = sqrt(1.0 - x);
        }
    }
}

#[test]
fn every_method_fails_where_the_derivatives_stop_being_numbers() {
    let mut model = System::new("root");
    model.add("r", &RootOfOneMinusTime::default());
    let ssys = structural_simplify(&model).unwrap();
    let problem = DaeProblem::new(&ssys, &[], (0.0, 2.0)).unwrap();
    for method in ALL {
        let err = problem.solve(&options(method, 1e-6)).unwrap_err();
        let Error::Solve(e) = &err else {
            panic!("{method:?}: {err}");
        };
        assert!((e.t - 1.0).abs() < 0.05, "{method:?}: {err}");
        assert!(
            err.to_string().contains("is not finite"),
            "{method:?}: {err}"
        );
    }
}

component! {
    /// `x'' = -x` from `x = -1` at rest: `x = -cos t`.
    pub struct Oscillator {
        /// Position.
        variable x(start = -1.0, fixed = true): Real;
        /// Velocity.
        variable v(start = 0.0, fixed = true): Real;
        equation {
            der(x) = v;
            der(v) = -x;
        }
    }
}

#[test]
fn kvaerno_stays_within_its_tolerance_on_an_oscillator() {
    // ARKODE tested a stage's first Newton correction against the rate of the previous
    // stage; unconverged stages passed the error test: 9e-2, 7e-2 and 1.7e-3 off at
    // rtol 1e-4, 1e-6 and 1e-8 over 8 s (8.1e-5, 5.4e-7 and 5.2e-9 now).
    let mut model = System::new("osc");
    model.add("o", &Oscillator::default());
    let ssys = structural_simplify(&model).unwrap();
    for rtol in [1e-4, 1e-6, 1e-8] {
        let sol = DaeProblem::new(&ssys, &[], (0.0, 8.0))
            .unwrap()
            .solve(&options(Method::Kvaerno5, rtol))
            .unwrap();
        let x = sol.get("o.x").unwrap();
        let worst = sol
            .t()
            .iter()
            .zip(&x)
            .map(|(t, x)| (x + t.cos()).abs())
            .fold(0.0, f64::max);
        assert!(worst < 20.0 * rtol, "rtol {rtol}: {worst:e} off");
    }
}

/// `y' = -y`, whose right-hand side fails recoverably once: at its first call after
/// `fail_after` (a stage within a step, before that step's end is reported).
struct FailsOnce {
    failed: bool,
    fail_after: f64,
}

impl multibody_core::solve::ode::OdeFunctions for FailsOnce {
    fn len(&self) -> usize {
        1
    }
    fn rhs(
        &mut self,
        t: f64,
        y: &[f64],
        ydot: &mut [f64],
    ) -> Result<(), multibody_core::codegen::EvalError> {
        if t > self.fail_after && !self.failed {
            self.failed = true;
            return Err(multibody_core::codegen::EvalError {
                message: "a trial state out of range".into(),
                recoverable: true,
            });
        }
        ydot[0] = -y[0];
        Ok(())
    }
}

#[test]
fn auto_takes_up_a_recoverable_failure_of_the_explicit_method_with_bdf() {
    // ARKODE's explicit stepper cannot retry a step after a recoverable failure;
    // `Auto` goes on with BDF from the start of the failed step.
    use multibody_core::solve::ida::{IdaSettings, OutputMode};
    use multibody_core::solve::ode::{self, OdeMethod};
    let settings = IdaSettings {
        rtol: 1e-8,
        atol: 1e-10,
        ..IdaSettings::default()
    };
    let mut f = FailsOnce {
        failed: false,
        fail_after: 0.5,
    };
    let mut last = (0.0, 0.0);
    let r = ode::integrate_monitored(
        &mut f,
        OdeMethod::Auto,
        0.0,
        &[1.0],
        &settings,
        &OutputMode::EveryStep { t_end: 2.0 },
        &mut |t, y, _| {
            assert!(t >= last.0, "time went back: {t} after {}", last.0);
            last = (t, y[0]);
            true
        },
        None,
    )
    .unwrap();
    assert!(r.switched);
    assert_eq!(last.0, 2.0);
    assert!((last.1 - (-2.0f64).exp()).abs() < 1e-7, "y(2) = {}", last.1);
}
