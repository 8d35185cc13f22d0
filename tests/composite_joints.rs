//! The joints with several degrees of freedom (MSL `Joints.Cylindrical`, `Planar`,
//! `Universal`, `FreeMotion`) simulated against independent results: free motion along
//! and about their axes in closed form (uniform acceleration by the gravity component,
//! constant spin), the universal joint against the same pendulum built from two
//! revolute joints and against energy conservation, and the free motion joint against
//! the parabola of a free body, and (asymmetric body, no gravity) against conservation of
//! energy and world-resolved angular momentum, with both of its orientation choices
//! (Cardan angles, quaternion) agreeing.

#![allow(missing_docs)]

#[path = "support/mechanics.rs"]
mod mechanics;

use mechanics::{MassProps, body_energy, dot, rotation, to_world, vector};
use multibody::joints::{Cylindrical, FreeMotion, Planar, Revolute, Universal};
use multibody::parts::{Body, OrientationStates};
use multibody::prelude::*;
use multibody::world::World;

const G: f64 = 9.80665;

fn options(t_end: f64, n: usize) -> SolverOptions {
    SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        output_times: Some((0..=n).map(|k| k as f64 * t_end / n as f64).collect()),
        ..SolverOptions::default()
    }
}

fn simulate(model: &System, values: &[(&str, f64)], t_end: f64) -> Solution {
    let ssys = structural_simplify(model).unwrap_or_else(|e| panic!("{e}"));
    DaeProblem::new(&ssys, values, (0.0, t_end))
        .and_then(|p| p.solve(&options(t_end, 200)))
        .unwrap_or_else(|e| panic!("{e}"))
}

fn close(what: &str, t: f64, got: f64, want: f64, tol: f64) {
    assert!(
        (got - want).abs() <= tol,
        "{what} at {t}: {got}, expected {want} (tolerance {tol})"
    );
}

/// A cylindrical joint on the world with its axis along (1, 1, 0) (45 degrees up from
/// x) and a body centred on the axis with isotropic inertia: the body slides along the
/// axis with the gravity component a = -g / sqrt 2, s = s0 + v0 t + a t^2 / 2, and
/// spins at its constant start speed, phi = phi0 + w0 t.
#[test]
fn cylindrical_slides_under_the_gravity_component_and_spins_freely() {
    let model = system! {
        name: "cylindrical";
        world = World::default();
        cyl = Cylindrical { n: [1.0, 1.0, 0.0] };
        body = Body { m: 2.0, I_11: 0.1, I_22: 0.1, I_33: 0.1 };
        connect(world.frame_b, cyl.frame_a);
        connect(cyl.frame_b, body.frame_a);
    }
    .into_system();
    let (s0, v0, phi0, w0) = (0.2, 1.5, 0.1, 3.0);
    let sol = simulate(
        &model,
        &[
            ("cyl.s", s0),
            ("cyl.v", v0),
            ("cyl.phi", phi0),
            ("cyl.w", w0),
        ],
        2.0,
    );
    let a = -G / 2f64.sqrt();
    let get = |n: &str| sol.get(n).unwrap();
    let (s, v, phi, w, acc, wd) = (
        get("cyl.s"),
        get("cyl.v"),
        get("cyl.phi"),
        get("cyl.w"),
        get("cyl.a"),
        get("cyl.wd"),
    );
    let r = vector(&sol, "body.r_0");
    for (k, &t) in sol.t().iter().enumerate() {
        close("s", t, s[k], s0 + v0 * t + 0.5 * a * t * t, 1e-8);
        close("v", t, v[k], v0 + a * t, 1e-8);
        close("a", t, acc[k], a, 1e-8);
        close("phi", t, phi[k], phi0 + w0 * t, 1e-8);
        close("w", t, w[k], w0, 1e-8);
        close("wd", t, wd[k], 0.0, 1e-8);
        // The body's origin on the axis at distance s.
        let e = s[k] / 2f64.sqrt();
        close("body.r_0[1]", t, r[k][0], e, 1e-12);
        close("body.r_0[2]", t, r[k][1], e, 1e-12);
        close("body.r_0[3]", t, r[k][2], 0.0, 1e-12);
    }
}

/// A planar joint on the world, plane normal z, x direction along (1, 1, 0): the x axis
/// of the plane is (1, 1, 0) / sqrt 2 and its y axis n x n_x = (-1, 1, 0) / sqrt 2, so
/// gravity (0, -g, 0) has the components -g / sqrt 2 along both. A body with its centre
/// of mass on frame_b moves on a parabola in the plane and spins at constant speed.
#[test]
fn planar_joint_moves_on_a_parabola_and_spins_freely() {
    let model = system! {
        name: "planar";
        world = World::default();
        pl = Planar { n: [0.0, 0.0, 1.0], n_x: [1.0, 1.0, 0.0] };
        body = Body { m: 0.7, I_11: 0.01, I_22: 0.02, I_33: 0.03 };
        connect(world.frame_b, pl.frame_a);
        connect(pl.frame_b, body.frame_a);
    }
    .into_system();
    let (x0, y0, vx0, vy0, phi0, w0) = (0.1, -0.3, 2.0, 4.0, 0.5, -2.0);
    let sol = simulate(
        &model,
        &[
            ("pl.s_x", x0),
            ("pl.s_y", y0),
            ("pl.v_x", vx0),
            ("pl.v_y", vy0),
            ("pl.phi", phi0),
            ("pl.w", w0),
        ],
        1.5,
    );
    let a = -G / 2f64.sqrt();
    let get = |n: &str| sol.get(n).unwrap();
    let (sx, sy, phi) = (get("pl.s_x"), get("pl.s_y"), get("pl.phi"));
    let (ax, ay, wd, w) = (get("pl.a_x"), get("pl.a_y"), get("pl.wd"), get("pl.w"));
    let r = vector(&sol, "body.r_0");
    let h = 1.0 / 2f64.sqrt();
    for (k, &t) in sol.t().iter().enumerate() {
        let x = x0 + vx0 * t + 0.5 * a * t * t;
        let y = y0 + vy0 * t + 0.5 * a * t * t;
        close("s_x", t, sx[k], x, 1e-8);
        close("s_y", t, sy[k], y, 1e-8);
        close("a_x", t, ax[k], a, 1e-8);
        close("a_y", t, ay[k], a, 1e-8);
        close("phi", t, phi[k], phi0 + w0 * t, 1e-8);
        close("w", t, w[k], w0, 1e-8);
        close("wd", t, wd[k], 0.0, 1e-8);
        // World position: x (1, 1, 0) / sqrt 2 + y (-1, 1, 0) / sqrt 2.
        close("body.r_0[1]", t, r[k][0], h * (sx[k] - sy[k]), 1e-12);
        close("body.r_0[2]", t, r[k][1], h * (sx[k] + sy[k]), 1e-12);
        close("body.r_0[3]", t, r[k][2], 0.0, 1e-12);
    }
}

const PEND: MassProps = MassProps {
    m: 1.2,
    r_cm: [0.3, -0.6, 0.2],
    inertia: [[0.02, 0.0, 0.0], [0.0, 0.03, 0.0], [0.0, 0.0, 0.04]],
};

/// A pendulum on a universal joint (axes x, then z of the intermediate frame) and the
/// same pendulum on two revolute joints in series: the same angles, and the energy of
/// each conserved.
#[test]
fn universal_joint_pendulum_matches_two_revolutes_and_keeps_its_energy() {
    let body = || Body {
        m: PEND.m,
        r_CM: PEND.r_cm,
        I_11: PEND.inertia[0][0],
        I_22: PEND.inertia[1][1],
        I_33: PEND.inertia[2][2],
        ..Default::default()
    };
    let mut universal = system! {
        name: "universal";
        world = World::default();
        u = Universal { n_a: [1.0, 0.0, 0.0], n_b: [0.0, 0.0, 1.0] };
        connect(world.frame_b, u.frame_a);
    }
    .into_system();
    universal.add("body", &body());
    universal.connect("u.frame_b", "body.frame_a");
    let mut revolutes = system! {
        name: "revolutes";
        world = World::default();
        r1 = Revolute { n: [1.0, 0.0, 0.0] };
        r2 = Revolute { n: [0.0, 0.0, 1.0] };
        connect(world.frame_b, r1.frame_a);
        connect(r1.frame_b, r2.frame_a);
    }
    .into_system();
    revolutes.add("body", &body());
    revolutes.connect("r2.frame_b", "body.frame_a");
    let t_end = 4.0;
    let a = simulate(
        &universal,
        &[
            ("u.phi_a", 0.7),
            ("u.phi_b", -0.4),
            ("u.w_a", 0.0),
            ("u.w_b", 1.0),
        ],
        t_end,
    );
    let b = simulate(
        &revolutes,
        &[
            ("r1.phi", 0.7),
            ("r2.phi", -0.4),
            ("r1.w", 0.0),
            ("r2.w", 1.0),
        ],
        t_end,
    );
    let get = |s: &Solution, n: &str| s.get(n).unwrap();
    let (pa, pb, wa, wb) = (
        get(&a, "u.phi_a"),
        get(&a, "u.phi_b"),
        get(&a, "u.w_a"),
        get(&a, "u.w_b"),
    );
    let (aa, ab) = (get(&a, "u.a_a"), get(&a, "u.a_b"));
    let (q1, q2, v1, v2) = (
        get(&b, "r1.phi"),
        get(&b, "r2.phi"),
        get(&b, "r1.w"),
        get(&b, "r2.w"),
    );
    let (d1, d2) = (get(&b, "r1.a"), get(&b, "r2.a"));
    let e_u = body_energy(&a, "body", PEND, G, [0.0, -1.0, 0.0]);
    let e_r = body_energy(&b, "body", PEND, G, [0.0, -1.0, 0.0]);
    let mut swing = 0.0f64;
    for (k, &t) in a.t().iter().enumerate() {
        swing = swing.max((pa[k] - 0.7).abs());
        // Two integrations at rtol 1e-10 of the same equations of motion.
        close("phi_a", t, pa[k], q1[k], 1e-7);
        close("phi_b", t, pb[k], q2[k], 1e-7);
        close("w_a", t, wa[k], v1[k], 1e-6);
        close("w_b", t, wb[k], v2[k], 1e-6);
        close("a_a", t, aa[k], d1[k], 1e-5);
        close("a_b", t, ab[k], d2[k], 1e-5);
        // Energy: no dissipation. About 10 J of motion.
        close("energy (universal)", t, e_u[k], e_u[0], 1e-7);
        close("energy (revolutes)", t, e_r[k], e_r[0], 1e-7);
    }
    assert!(swing > 0.5, "the pendulum swung only {swing} rad");
}

/// A free body on a FreeMotion joint from the world, with a spherical inertia: its
/// origin follows the parabola r0 + v0 t + g t^2 / 2, and its angular velocity stays
/// at the start value (resolved in the body, it is constant for a spherical inertia),
/// for both orientation choices.
#[test]
fn free_motion_in_gravity_is_a_parabola_with_constant_spin() {
    for states in [OrientationStates::Cardan, OrientationStates::Quaternion] {
        let model = system! {
            name: "free_parabola";
            world = World::default();
            fm = FreeMotion { orientation_states: states };
            body = Body { m: 3.0, I_11: 0.5, I_22: 0.5, I_33: 0.5 };
            connect(world.frame_b, fm.frame_a);
            connect(fm.frame_b, body.frame_a);
        }
        .into_system();
        let r0 = [0.5, 2.0, -1.0];
        let v0 = [1.0, 3.0, 0.5];
        let w0 = [0.4, -0.2, 0.3];
        let mut values = vec![
            ("fm.r_rel_a[1]", r0[0]),
            ("fm.r_rel_a[2]", r0[1]),
            ("fm.r_rel_a[3]", r0[2]),
            ("fm.v_rel_a[1]", v0[0]),
            ("fm.v_rel_a[2]", v0[1]),
            ("fm.v_rel_a[3]", v0[2]),
        ];
        // At zero angles of the sequence {1, 2, 3} the angle rates are the angular
        // velocity.
        let w_names = match states {
            OrientationStates::Cardan => ["fm.phi_d[1]", "fm.phi_d[2]", "fm.phi_d[3]"],
            OrientationStates::Quaternion => ["fm.w_rel_b[1]", "fm.w_rel_b[2]", "fm.w_rel_b[3]"],
        };
        for i in 0..3 {
            values.push((w_names[i], w0[i]));
        }
        let sol = simulate(&model, &values, 2.0);
        let r = vector(&sol, "body.r_0");
        let w = vector(&sol, "fm.w_rel_b");
        for (k, &t) in sol.t().iter().enumerate() {
            for i in 0..3 {
                let g = if i == 1 { -G } else { 0.0 };
                let want = r0[i] + v0[i] * t + 0.5 * g * t * t;
                close(
                    &format!("{states:?}: r_0[{}]", i + 1),
                    t,
                    r[k][i],
                    want,
                    1e-8,
                );
                close(
                    &format!("{states:?}: w_rel_b[{}]", i + 1),
                    t,
                    w[k][i],
                    w0[i],
                    1e-8,
                );
            }
        }
    }
}

/// Torque-free rotation of an asymmetric body (inertia diag(0.1, 0.2, 0.3), no
/// gravity) on a FreeMotion joint, spinning mostly about its axis of least inertia:
/// the kinetic energy w.I.w / 2 and the world-resolved angular momentum R (I w) stay
/// at their start values, and the Cardan and quaternion runs give the same angular
/// velocity and orientation.
#[test]
fn free_motion_torque_free_rotation_conserves_energy_and_momentum() {
    let inertia = [0.1, 0.2, 0.3];
    let w0 = [3.0, 0.3, 0.4];
    let mut runs = Vec::new();
    for states in [OrientationStates::Cardan, OrientationStates::Quaternion] {
        let model = system! {
            name: "torque_free";
            world = World { g: 0.0 };
            fm = FreeMotion { orientation_states: states };
            body = Body { m: 1.0, I_11: 0.1, I_22: 0.2, I_33: 0.3 };
            connect(world.frame_b, fm.frame_a);
            connect(fm.frame_b, body.frame_a);
        }
        .into_system();
        let w_names = match states {
            OrientationStates::Cardan => ["fm.phi_d[1]", "fm.phi_d[2]", "fm.phi_d[3]"],
            OrientationStates::Quaternion => ["fm.w_rel_b[1]", "fm.w_rel_b[2]", "fm.w_rel_b[3]"],
        };
        let values: Vec<(&str, f64)> = (0..3).map(|i| (w_names[i], w0[i])).collect();
        let sol = simulate(&model, &values, 10.0);
        let w = vector(&sol, "fm.w_rel_b");
        let t = rotation(&sol, "body.frame_a");
        let l_of = |w: [f64; 3]| [inertia[0] * w[0], inertia[1] * w[1], inertia[2] * w[2]];
        let e0 = 0.5 * dot(w0, l_of(w0));
        let l0 = l_of(w0);
        for k in 0..sol.t().len() {
            let time = sol.t()[k];
            let e = 0.5 * dot(w[k], l_of(w[k]));
            close(&format!("{states:?}: energy"), time, e, e0, 1e-8);
            let l = to_world(&t[k], l_of(w[k]));
            for i in 0..3 {
                close(
                    &format!("{states:?}: L_world[{}]", i + 1),
                    time,
                    l[i],
                    l0[i],
                    1e-8,
                );
            }
        }
        // The body really tumbles: its angular velocity in the body moves.
        let spread = w.iter().map(|v| (v[1] - w0[1]).abs()).fold(0.0, f64::max);
        assert!(spread > 0.1, "{states:?}: w_rel_b[2] moved only {spread}");
        runs.push((w, t));
    }
    let (w_c, t_c) = &runs[0];
    let (w_q, t_q) = &runs[1];
    for k in 0..w_c.len() {
        for i in 0..3 {
            assert!(
                (w_c[k][i] - w_q[k][i]).abs() < 1e-7,
                "w_rel_b[{}] at step {k}: Cardan {} quaternion {}",
                i + 1,
                w_c[k][i],
                w_q[k][i]
            );
            for j in 0..3 {
                assert!((t_c[k][i][j] - t_q[k][i][j]).abs() < 1e-7);
            }
        }
    }
}

/// FreeMotion's start from MSL's parameters: `angles_start` about {3, 1, 2} and
/// `w_rel_a_start` (resolved in frame_a, here the world), with both orientation
/// choices: frame_b's orientation and angular velocity at the start are the ones
/// computed by hand (R = Rz(0.4) Rx(0.3) Ry(-0.2); w in frame_b = R' w), and both
/// runs agree afterwards (torque-free asymmetric body). With Cardan angles the start
/// value suffices (the angle rates, states, start from it); with quaternions the body's
/// `w_a` carries the velocity states, so the start is given as `w_rel_a_fixed`.
#[test]
fn free_motion_starts_from_angles_start_and_w_rel_a_start() {
    let rz = |a: f64| {
        [
            [a.cos(), -a.sin(), 0.0],
            [a.sin(), a.cos(), 0.0],
            [0.0, 0.0, 1.0],
        ]
    };
    let rx = |a: f64| {
        [
            [1.0, 0.0, 0.0],
            [0.0, a.cos(), -a.sin()],
            [0.0, a.sin(), a.cos()],
        ]
    };
    let ry = |a: f64| {
        [
            [a.cos(), 0.0, a.sin()],
            [0.0, 1.0, 0.0],
            [-a.sin(), 0.0, a.cos()],
        ]
    };
    let mul = |a: [[f64; 3]; 3], b: [[f64; 3]; 3]| -> [[f64; 3]; 3] {
        std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
    };
    let r = mul(mul(rz(0.4), rx(0.3)), ry(-0.2));
    let w_a = [2.0, -0.5, 0.7];
    let w_b: [f64; 3] = std::array::from_fn(|i| (0..3).map(|k| r[k][i] * w_a[k]).sum());
    let mut runs = Vec::new();
    for states in [OrientationStates::Cardan, OrientationStates::Quaternion] {
        let model = system! {
            name: "free_start";
            world = World { g: 0.0 };
            fm = FreeMotion {
                orientation_states: states,
                angles_start: [0.4, 0.3, -0.2],
                sequence_start: [3, 1, 2],
                w_rel_a_start: w_a,
                w_rel_a_fixed: states == OrientationStates::Quaternion,
            };
            body = Body { m: 1.0, I_11: 0.1, I_22: 0.2, I_33: 0.3 };
            connect(world.frame_b, fm.frame_a);
            connect(fm.frame_b, body.frame_a);
        }
        .into_system();
        let sol = simulate(&model, &[], 3.0);
        let t = rotation(&sol, "fm.frame_b");
        let w = vector(&sol, "fm.w_rel_b");
        for i in 0..3 {
            close(
                &format!("{states:?}: w_rel_b[{}]", i + 1),
                0.0,
                w[0][i],
                w_b[i],
                1e-9,
            );
            for j in 0..3 {
                // T = R'.
                close(
                    &format!("{states:?}: T[{},{}]", i + 1, j + 1),
                    0.0,
                    t[0][i][j],
                    r[j][i],
                    1e-12,
                );
            }
        }
        runs.push(w);
    }
    for k in 0..runs[0].len() {
        for i in 0..3 {
            close(
                "w_rel_b Cardan vs quaternion",
                k as f64,
                runs[0][k][i],
                runs[1][k][i],
                1e-7,
            );
        }
    }
}
