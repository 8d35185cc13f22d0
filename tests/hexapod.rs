//! The seed's hexapod: the actuator forces at rest equal an independent static balance
//! of the platform; driven by the inverse kinematics of a heaving and rolling motion,
//! the platform follows that motion (the model's forward kinematics) and the actuator
//! forces equal the platform's Newton-Euler equations for it.

#[path = "../examples/hexapod.rs"]
#[allow(dead_code)]
mod hexapod_example;
#[path = "support/mechanics.rs"]
mod mechanics;
use hexapod_example::{
    CM, Drive, G, I_ROLL, M_PLATFORM, Motion, guesses, hexapod, hexapod_driven, leg_forces,
    static_leg_forces,
};
use mechanics::cross;
use multibody::prelude::*;

/// `ssys` (a hexapod moving as `motion`) solved from the start of `motion` to `t_end`,
/// output every `dt`.
fn solve_system(
    ssys: &multibody::SimplifiedSystem,
    motion: Motion,
    t_end: f64,
    dt: f64,
) -> Solution {
    let guesses = guesses(motion);
    let named: Vec<(&str, f64)> = guesses.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    DaeProblem::new_with_guesses(ssys, &[], &named, (0.0, t_end))
        .unwrap()
        .solve(&SolverOptions {
            rtol: 1e-8,
            atol: 1e-10,
            ..SolverOptions::default().with_output_interval(0.0, t_end, dt)
        })
        .unwrap()
}

fn solve(motion: Motion, t_end: f64) -> Solution {
    let ssys = structural_simplify(&hexapod(motion)).unwrap();
    solve_system(&ssys, motion, t_end, 0.1)
}

#[test]
fn the_actuators_hold_the_platform_as_the_static_balance_says() {
    let sol = solve(Motion::REST, 1.0);
    let balance = static_leg_forces();
    for (i, want) in balance.iter().enumerate() {
        let f = sol
            .get(format!("leg{}.actuator.f", i + 1).as_str())
            .unwrap();
        for got in [f[0], *f.last().unwrap()] {
            assert!(
                (got - want).abs() < 1e-6 * want.abs(),
                "leg{}: {got} vs {want}",
                i + 1
            );
        }
    }
    // Off-centre mass: the legs carry unequal loads.
    let spread = balance.iter().fold(0.0f64, |m, f| m.max(*f))
        - balance.iter().fold(f64::MAX, |m, f| m.min(*f));
    assert!(spread > 10.0, "{balance:?}");
}

#[test]
fn the_platform_follows_the_motion_and_the_forces_are_its_newton_euler_equations() {
    let motion = Motion {
        heave: 0.2,
        roll: 0.1,
        f: 0.5,
    };
    let sol = solve(motion, 2.0);
    let w = 2.0 * PI * motion.f;
    let get = |name: String| sol.get(name.as_str()).unwrap();
    let r0: Vec<Vec<f64>> = (1..=3).map(|j| get(format!("platform.r_0[{j}]"))).collect();
    let t22 = get("platform.frame_a.R.T[2,2]".into());
    let t23 = get("platform.frame_a.R.T[2,3]".into());
    let forces: Vec<Vec<f64>> = (1..=6).map(|i| get(format!("leg{i}.actuator.f"))).collect();
    for (k, &t) in sol.t().iter().enumerate() {
        // Forward kinematics against the prescribed pose.
        let (c, roll) = motion.pose(t);
        for j in 0..3 {
            assert!(
                (r0[j][k] - c[j]).abs() < 1e-7,
                "t = {t}: r_0[{}] = {} vs {}",
                j + 1,
                r0[j][k],
                c[j]
            );
        }
        assert!((t22[k] - roll.cos()).abs() < 1e-7, "t = {t}: T[2,2]");
        assert!(
            (t23[k] - roll.sin()).abs() < 1e-7,
            "t = {t}: T[2,3] = {} vs {}",
            t23[k],
            roll.sin()
        );
        // Newton-Euler of the platform (massless legs): the legs' forces along their
        // lines give m (a_cm - g) and, about the centre of mass, I_11 alpha about x.
        let (s, co) = (w * t).sin_cos();
        let (omega, alpha) = (motion.roll * w * co, -motion.roll * w * w * s);
        let (rs, rc) = roll.sin_cos();
        let r = [CM[0], CM[1] * rc - CM[2] * rs, CM[1] * rs + CM[2] * rc];
        let (om, al) = ([omega, 0.0, 0.0], [alpha, 0.0, 0.0]);
        let a_c = [0.0, -motion.heave * w * w * s, 0.0];
        let a_cm: Vec<f64> = (0..3)
            .map(|j| a_c[j] + cross(al, r)[j] + cross(om, cross(om, r))[j])
            .collect();
        let cm = [c[0] + r[0], c[1] + r[1], c[2] + r[2]];
        let want = leg_forces(
            motion,
            t,
            cm,
            [
                M_PLATFORM * a_cm[0],
                M_PLATFORM * (a_cm[1] + G),
                M_PLATFORM * a_cm[2],
                I_ROLL * alpha,
                0.0,
                0.0,
            ],
        );
        for i in 0..6 {
            let got = forces[i][k];
            assert!(
                (got - want[i]).abs() < 1e-5 * want[i].abs().max(1.0),
                "t = {t}: leg{} force {got} vs {}",
                i + 1,
                want[i]
            );
        }
    }
}

#[test]
fn force_controlled_legs_give_the_seed_s_18_states_and_track_the_motion() {
    // Legs force-controlled to the inverse kinematics (PID per leg): the states are the
    // six actuators' lengths and speeds and the six integrals, 18 as in the seed's
    // translation log.
    let solve_controlled = |motion: Motion, t_end: f64| {
        let ssys = structural_simplify(&hexapod_driven(motion, Drive::Controlled)).unwrap();
        let states = ssys.states();
        assert_eq!(states.len(), 18, "{states:?}");
        for i in 1..=6 {
            for name in ["actuator.s", "actuator.v", "held"] {
                let name = format!("leg{i}.{name}");
                assert!(states.contains(&name), "{name} not in {states:?}");
            }
        }
        solve_system(&ssys, motion, t_end, 0.05)
    };
    // At rest the controllers settle on the forces of the independent static balance.
    let sol = solve_controlled(Motion::REST, 1.0);
    for (i, want) in static_leg_forces().iter().enumerate() {
        let got = sol
            .final_value(format!("leg{}.actuator.f", i + 1).as_str())
            .unwrap();
        assert!(
            (got - want).abs() < 1e-6 * want.abs(),
            "leg{}: {got} vs {want}",
            i + 1
        );
    }
    // Heaving and rolling: the closed loop (about 200 rad/s) lags the 0.5 Hz motion by
    // about m w^2 A / kp = 17 kg (pi rad/s)^2 0.2 m / 1e6 N/m = 3e-5 m.
    let motion = Motion {
        heave: 0.2,
        roll: 0.1,
        f: 0.5,
    };
    let sol = solve_controlled(motion, 2.0);
    for &t in sol.t() {
        let (c, _) = motion.pose(t);
        let y = sol.at("platform.r_0[2]", t).unwrap();
        assert!((y - c[1]).abs() < 1e-4, "t = {t}: {y} vs {}", c[1]);
    }
}
