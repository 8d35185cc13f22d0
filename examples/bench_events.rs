//! Benchmark: the cost of events.
//!
//! - `end_stops`: N masses, each oscillating on a soft spring between two stiff end
//!   stops, 10 s: events per simulated second, and the cost of one event against one
//!   step (the step's cost taken from the same model with the stops' switches stepped
//!   across, `no_event`, solved in the same process).
//! - `slider_crank`: a one-cylinder slider crank whose gas force acts while the crank
//!   angle is in its expansion half-turn, 20 s, solved with events and with `no_event`
//!   (the switch stepped across): steps, error-test failures and time of both.
//!
//! `cargo run --release --example bench_events` prints one JSON object per line.
//! Every run is repeated and the median time taken (rtol 1e-6, atol 1e-8).

use std::time::Instant;

use multibody::prelude::*;

const REPEAT: usize = 5;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn options() -> SolverOptions {
    SolverOptions {
        rtol: 1e-6,
        atol: 1e-8,
        ..SolverOptions::default()
    }
}

/// Solves `model` from `start` over `0..t_end` `REPEAT` times: the last solution and
/// the median time.
fn solve(
    model: &System,
    start: &[(&str, f64)],
    t_end: f64,
) -> Result<(Solution, f64), multibody::Error> {
    let ssys = structural_simplify(model)?;
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..REPEAT {
        let t0 = Instant::now();
        let sol = DaeProblem::new(&ssys, start, (0.0, t_end))?.solve(&options())?;
        times.push(t0.elapsed().as_secs_f64());
        last = Some(sol);
    }
    Ok((last.expect("solved"), median(times)))
}

component! {
    /// A unit mass on a soft spring (`c = 10 N/m`) between two stiff end stops
    /// (`c_stop = 1e4 N/m`) at `s = -0.1` and `s = 0.1` m.
    pub struct StoppedMass {
        /// Whether the stops' switches are stepped across (`no_event`).
        structural without_events: bool = false;
        /// Start velocity [m/s].
        structural v_start: f64 = 1.0;
        /// Position [m].
        variable s(start = 0.0, fixed = true): Real;
        /// Velocity [m/s].
        variable v(start = v_start, fixed = true): Real;
        /// Force of the stops [N].
        variable f_stop: Real;
        equation {
            let (below, above) = if without_events {
                (no_event(lt(s, -0.1)), no_event(gt(s, 0.1)))
            } else {
                (lt(s, -0.1), gt(s, 0.1))
            };
            f_stop = if_else(below, -1e4 * (s + 0.1), if_else(above, -1e4 * (s - 0.1), 0.0));
            der(s) = v;
            der(v) = -10.0 * s + f_stop;
        }
    }
}

/// `n` stopped masses started at different speeds.
fn end_stops(n: usize, without_events: bool) -> System {
    let mut model = System::new("end_stops");
    for k in 0..n {
        model.add(
            &format!("mass{k}"),
            &StoppedMass {
                without_events,
                v_start: 1.0 + 0.01 * k as f64,
            },
        );
    }
    model
}

component! {
    /// A one-cylinder slider crank reduced to its crank angle: crank radius `r`, rod
    /// length `l`, the piston at `x = r cos(phi) + sqrt(l^2 - r^2 sin(phi)^2)`; the
    /// gas force `f_gas` pushes the piston during the expansion half-turn
    /// (`sin(phi) > 0`), a viscous load `d` brakes the crank.
    pub struct SliderCrank {
        /// Crank radius [m].
        parameter r: f64 = 0.05;
        /// Rod length [m].
        parameter l: f64 = 0.15;
        /// Inertia of crank and flywheel [kg.m2].
        parameter j: f64 = 0.05;
        /// Gas force on the piston [N].
        parameter f_gas: f64 = 500.0;
        /// Viscous load on the crank [N.m.s/rad].
        parameter d: f64 = 0.02;
        /// Whether the switch of the gas force is stepped across (`no_event`).
        structural without_events: bool = false;
        /// Crank angle [rad].
        variable phi(start = 0.1, fixed = true): Real;
        /// Crank speed [rad/s].
        variable w(start = 20.0, fixed = true): Real;
        /// Piston force on the crank [N].
        variable f: Real;
        equation {
            der(phi) = w;
            let s = sin(phi);
            let root = sqrt(l * l - r * r * s * s);
            // dx/dphi of the piston position.
            let dx = -r * s - r * r * s * cos(phi) / root;
            let expansion = if without_events { no_event(gt(s, 0.0)) } else { gt(s, 0.0) };
            f = if_else(expansion, f_gas, 0.0);
            j * der(w) = -f * dx - d * w;
        }
    }
}

fn main() -> Result<(), multibody::Error> {
    // End stops, with events and stepped across: the second gives the cost of a step.
    for n in [10, 100] {
        let t_end = 10.0;
        let (plain, plain_s) = solve(&end_stops(n, true), &[], t_end)?;
        let step_s = plain_s / plain.statistics().steps as f64;
        let (sol, solve_s) = solve(&end_stops(n, false), &[], t_end)?;
        let (steps, events) = (sol.statistics().steps, sol.events().len());
        let event_s = (solve_s - steps as f64 * step_s) / events.max(1) as f64;
        println!(
            "{{\"model\": \"end_stops\", \"n\": {n}, \"t_end\": {t_end}, \"events\": {events}, \
             \"events_per_simulated_s\": {:.1}, \"steps\": {steps}, \"solve_s\": {solve_s:.6}, \
             \"no_event_steps\": {}, \"no_event_error_test_failures\": {}, \
             \"no_event_solve_s\": {plain_s:.6}, \"step_s\": {step_s:.3e}, \
             \"event_s\": {event_s:.3e}, \"event_in_steps\": {:.1}}}",
            events as f64 / t_end,
            plain.statistics().steps,
            plain.statistics().error_test_failures,
            event_s / step_s
        );
    }
    // The slider crank with and without events.
    let mut times = Vec::new();
    for without_events in [false, true] {
        let mut model = System::new("slider_crank");
        model.add(
            "crank",
            &SliderCrank {
                without_events,
                ..Default::default()
            },
        );
        let (sol, solve_s) = solve(&model, &[], 20.0)?;
        let st = sol.statistics();
        println!(
            "{{\"model\": \"slider_crank\", \"variant\": \"{}\", \"steps\": {}, \
             \"error_test_failures\": {}, \"events\": {}, \"solve_s\": {solve_s:.6}, \
             \"w_end\": {:.6}}}",
            if without_events { "no_event" } else { "events" },
            st.steps,
            st.error_test_failures,
            sol.events().len(),
            sol.final_value("crank.w")?
        );
        times.push(solve_s);
    }
    println!(
        "{{\"model\": \"slider_crank\", \"solve_ratio\": {:.3}}}",
        times[0] / times[1]
    );
    Ok(())
}
