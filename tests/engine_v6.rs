//! MSL's EngineV6: inside the Modelica Association's reference tube at its rows, every
//! loop closed as the slider-crank's closed form says, and the energy of the bodies and
//! the load inertia changed by exactly the work of the gas forces and the load torque.

mod common;
#[path = "support/mechanics.rs"]
mod mechanics;

#[path = "../examples/engine_v6.rs"]
#[allow(dead_code)]
mod engine_example;

use common::assert_in_tube;
use engine_example::{CYLINDERS, cylinder_bodies, engine, piston_travel, run};
use mechanics::{MassProps, body_energy};
use multibody::prelude::*;

const G: f64 = 9.80665;

#[test]
fn engine_v6_runs_in_the_tube_closes_its_loops_and_balances_its_power() {
    let ssys = structural_simplify(&engine()).unwrap();
    // MSL: one degree of freedom; the load's angle and speed and the filter's two
    // states are the states.
    assert_eq!(ssys.states().len(), 4, "{:?}", ssys.states());
    let sol = run(
        &ssys,
        1.01,
        &SolverOptions {
            rtol: 1e-7,
            atol: 1e-9,
            ..SolverOptions::default()
        },
    )
    .unwrap();
    assert_in_tube("EngineV6", &sol, &["load.phi", "load.w"]);

    // Every piston where the crank angle puts it.
    let phi = sol.get("load.phi").unwrap();
    for (k, &(offset, inclination)) in CYLINDERS.iter().enumerate() {
        let s = sol
            .get(format!("cylinder{}.cylinder.s", k + 1).as_str())
            .unwrap();
        for (i, (&s, &phi)) in s.iter().zip(&phi).enumerate() {
            let exact = piston_travel(phi, offset.to_radians(), inclination.to_radians());
            assert!(
                (s - exact).abs() < 1e-9,
                "cylinder{} at t = {}: s = {s}, closed form {exact}",
                k + 1,
                sol.t()[i]
            );
        }
    }

    // Energy: the bodies' kinetic and potential energy and the load's kinetic energy.
    let n = sol.t().len();
    let mut energy = vec![0.0; n];
    for k in 1..=6 {
        for (path, p) in cylinder_bodies() {
            let props = MassProps {
                m: p.m,
                r_cm: p.r_cm,
                inertia: p.inertia,
            };
            let e = body_energy(
                &sol,
                &format!("cylinder{k}.{path}"),
                props,
                G,
                [0.0, -1.0, 0.0],
            );
            energy.iter_mut().zip(&e).for_each(|(a, b)| *a += b);
        }
    }
    let w = sol.get("load.w").unwrap();
    energy
        .iter_mut()
        .zip(&w)
        .for_each(|(a, w)| *a += 0.5 * w * w);
    // Power: the gas forces on the pistons and the load torque.
    let mut power = vec![0.0; n];
    for k in 1..=6 {
        let f = sol
            .get(format!("cylinder{k}.gas_force.f").as_str())
            .unwrap();
        let v = sol
            .get(format!("cylinder{k}.gas_force.v_rel").as_str())
            .unwrap();
        for i in 0..n {
            power[i] -= f[i] * v[i];
        }
    }
    let tau = sol.get("load2.tau").unwrap();
    power
        .iter_mut()
        .zip(tau.iter().zip(&w))
        .for_each(|(p, (t, w))| *p += t * w);
    // The work, by the trapezoidal rule over the reported points (about 30 per cycle of
    // the power at the end; its quadrature error is about 2e-4 of the work done).
    let t = sol.t();
    let (mut work, mut throughput, mut worst) = (0.0, 0.0, 0.0f64);
    for i in 1..n {
        let h = t[i] - t[i - 1];
        work += 0.5 * h * (power[i] + power[i - 1]);
        throughput += 0.5 * h * (power[i].abs() + power[i - 1].abs());
        worst = worst.max((energy[i] - energy[0] - work).abs());
    }
    assert!(
        worst < 1e-3 * throughput,
        "energy balance off by {worst} J of {throughput} J of work"
    );
    // The engine ran up: MSL's reference speed at the end.
    assert!((w[n - 1] - 564.611).abs() < 0.5, "final speed {}", w[n - 1]);
}
