//! A free body's start orientation and angular velocity given as MSL does
//! (`angles_start` about the axes of `sequence_start`, `w_0_start` resolved in the
//! world), with Cardan angles and with quaternions as orientation states, against the
//! same body started from a quaternion and angular velocity computed by hand; and the
//! torque-free rotation of the asymmetric body keeping its energy and world-resolved
//! angular momentum.

#![allow(missing_docs)]

#[path = "support/mechanics.rs"]
mod mechanics;

use mechanics::{dot, rotation, to_world, vector};
use multibody::parts::{Body, OrientationStates};
use multibody::prelude::*;
use multibody::world::World;

type V3 = [f64; 3];
type Q = [f64; 4];

const INERTIA: V3 = [0.1, 0.2, 0.3];
/// About z, then the new x, then the newer y (sequence {3, 1, 2}) [rad].
const ANGLES: V3 = [0.4, 0.3, -0.2];
const SEQUENCE: [usize; 3] = [3, 1, 2];

/// The quaternion (vector part first) of the rotation about coordinate axis `i`
/// (1..3) by `a`.
fn q_axis(i: usize, a: f64) -> Q {
    let mut q = [0.0, 0.0, 0.0, (a / 2.0).cos()];
    q[i - 1] = (a / 2.0).sin();
    q
}

/// Hamilton product `p q` (scalar last): the rotation p followed by q about the axes
/// q's rotation carried along (R(p q) = R(p) R(q)).
fn qmul(p: Q, q: Q) -> Q {
    [
        p[3] * q[0] + q[3] * p[0] + p[1] * q[2] - p[2] * q[1],
        p[3] * q[1] + q[3] * p[1] + p[2] * q[0] - p[0] * q[2],
        p[3] * q[2] + q[3] * p[2] + p[0] * q[1] - p[1] * q[0],
        p[3] * q[3] - p[0] * q[0] - p[1] * q[1] - p[2] * q[2],
    ]
}

/// `v` rotated by the unit quaternion `q` (active): v + 2 s (u x v) + 2 u x (u x v).
fn qrot(q: Q, v: V3) -> V3 {
    let u = [q[0], q[1], q[2]];
    let c = |a: V3, b: V3| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let uv = c(u, v);
    let uuv = c(u, uv);
    std::array::from_fn(|i| v[i] + 2.0 * q[3] * uv[i] + 2.0 * uuv[i])
}

fn body(states: OrientationStates, from_angles: bool, w_0: V3) -> System {
    let mut model = system! {
        name: "start_orientation";
        world = World { g: 0.0 };
    }
    .into_system();
    let mut b = Body {
        m: 1.0,
        I_11: INERTIA[0],
        I_22: INERTIA[1],
        I_33: INERTIA[2],
        orientation_states: states,
        ..Default::default()
    };
    if from_angles {
        b.angles_start = ANGLES;
        b.sequence_start = SEQUENCE;
        b.w_0_start = w_0;
    }
    model.add("body", &b);
    model
}

fn solve(model: &System, values: &[(&str, f64)]) -> Solution {
    let ssys = structural_simplify(model).unwrap_or_else(|e| panic!("{e}"));
    DaeProblem::new(&ssys, values, (0.0, 10.0))
        .and_then(|p| {
            p.solve(&SolverOptions {
                rtol: 1e-10,
                atol: 1e-12,
                output_times: Some((0..=500).map(|k| k as f64 * 0.02).collect()),
                ..SolverOptions::default()
            })
        })
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The body turned by ANGLES about z, x', y'' and spinning at w_0 (world), mostly about
/// its own x axis (least inertia: a stable spin, far from the Cardan angles' gimbal
/// lock), three ways: Cardan angles {1, 2, 3} from `angles_start` (converted from the
/// sequence {3, 1, 2}), a quaternion from `angles_start`, and a quaternion and body
/// angular velocity given as values, computed here: Q = q_z q_x q_y, w_a = R' w_0.
#[test]
fn angles_start_gives_the_hand_computed_start_with_both_state_choices() {
    let q = qmul(
        qmul(
            q_axis(SEQUENCE[0], ANGLES[0]),
            q_axis(SEQUENCE[1], ANGLES[1]),
        ),
        q_axis(SEQUENCE[2], ANGLES[2]),
    );
    let q_inv = [-q[0], -q[1], -q[2], q[3]];
    let body_x = qrot(q, [1.0, 0.0, 0.0]);
    let w_0: V3 = std::array::from_fn(|i| 3.0 * body_x[i] + [0.2, -0.3, 0.25][i]);
    let w_a = qrot(q_inv, w_0);
    let reference = solve(
        &body(OrientationStates::Quaternion, false, w_0),
        &[
            ("body.q_v[1]", q[0]),
            ("body.q_v[2]", q[1]),
            ("body.q_v[3]", q[2]),
            ("body.q_4", q[3]),
            ("body.w_a[1]", w_a[0]),
            ("body.w_a[2]", w_a[1]),
            ("body.w_a[3]", w_a[2]),
        ],
    );
    let t_ref = rotation(&reference, "body.frame_a");
    let w_ref = vector(&reference, "body.w_a");
    // The hand-computed start is what the reference starts from.
    let at0 = to_world(&t_ref[0], [1.0, 0.0, 0.0]);
    for i in 0..3 {
        assert!((at0[i] - body_x[i]).abs() < 1e-12, "{at0:?} {body_x:?}");
    }
    let l_of = |w: V3| [INERTIA[0] * w[0], INERTIA[1] * w[1], INERTIA[2] * w[2]];
    for states in [OrientationStates::Cardan, OrientationStates::Quaternion] {
        let sol = solve(&body(states, true, w_0), &[]);
        let t = rotation(&sol, "body.frame_a");
        let w = vector(&sol, "body.w_a");
        // w_0_start is the world-resolved angular velocity at the start.
        let w_world = to_world(&t[0], w[0]);
        for i in 0..3 {
            assert!(
                (w_world[i] - w_0[i]).abs() < 1e-9,
                "{states:?}: w_0 at the start {w_world:?}, w_0_start {w_0:?}"
            );
        }
        let e0 = 0.5 * dot(w[0], l_of(w[0]));
        let l0 = to_world(&t[0], l_of(w[0]));
        let mut spread = 0.0f64;
        for k in 0..sol.t().len() {
            let time = sol.t()[k];
            for i in 0..3 {
                // Same body, same start, two integrations at rtol 1e-10.
                assert!(
                    (w[k][i] - w_ref[k][i]).abs() < 1e-7,
                    "{states:?}: w_a[{}] at {time}: {} vs {} from the hand-computed start",
                    i + 1,
                    w[k][i],
                    w_ref[k][i]
                );
                for j in 0..3 {
                    assert!(
                        (t[k][i][j] - t_ref[k][i][j]).abs() < 1e-7,
                        "{states:?}: R.T[{},{}] at {time}: {} vs {}",
                        i + 1,
                        j + 1,
                        t[k][i][j],
                        t_ref[k][i][j]
                    );
                }
            }
            // Torque-free: kinetic energy and world angular momentum conserved.
            let e = 0.5 * dot(w[k], l_of(w[k]));
            assert!(
                (e - e0).abs() < 1e-8 * e0,
                "{states:?}: energy {e} at {time}, {e0}"
            );
            let l = to_world(&t[k], l_of(w[k]));
            for i in 0..3 {
                assert!(
                    (l[i] - l0[i]).abs() < 1e-8,
                    "{states:?}: L[{}] {} at {time}, {} at the start",
                    i + 1,
                    l[i],
                    l0[i]
                );
            }
            spread = spread.max((w[k][1] - w[0][1]).abs());
        }
        assert!(
            spread > 0.1,
            "{states:?}: the body does not tumble ({spread})"
        );
    }
}

/// With `angles_fixed` and `w_0_fixed` the start orientation and angular velocity are
/// initial conditions (initial equations, not start values the initialization may
/// assume): the body starts there, with either state choice.
#[test]
fn fixed_start_orientation_and_angular_velocity_are_initial_conditions() {
    for states in [OrientationStates::Cardan, OrientationStates::Quaternion] {
        let mut model = system! {
            name: "fixed_start";
            world = World { g: 0.0 };
        }
        .into_system();
        let w_0 = [0.3, -0.4, 1.1];
        model.add(
            "body",
            &Body {
                I_11: INERTIA[0],
                I_22: INERTIA[1],
                I_33: INERTIA[2],
                orientation_states: states,
                angles_start: [0.2, 0.1, -0.3],
                angles_fixed: true,
                w_0_start: w_0,
                w_0_fixed: true,
                ..Default::default()
            },
        );
        let sol = solve(&model, &[]);
        let t = rotation(&sol, "body.frame_a");
        let w = vector(&sol, "body.w_a");
        let w_world = to_world(&t[0], w[0]);
        // R_start = Rx(0.2) Ry(0.1) Rz(-0.3) (sequence {1, 2, 3}): its quaternion.
        let q = qmul(qmul(q_axis(1, 0.2), q_axis(2, 0.1)), q_axis(3, -0.3));
        let x = qrot(q, [1.0, 0.0, 0.0]);
        let x_sol = to_world(&t[0], [1.0, 0.0, 0.0]);
        for i in 0..3 {
            assert!(
                (w_world[i] - w_0[i]).abs() < 1e-9,
                "{states:?}: {w_world:?}"
            );
            assert!(
                (x_sol[i] - x[i]).abs() < 1e-12,
                "{states:?}: {x_sol:?} vs {x:?}"
            );
        }
    }
}
