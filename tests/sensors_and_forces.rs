//! Sensors, line forces, signal forces, point gravity and `FixedRotation`, each simulated
//! and checked against an independent result: a closed form, an invariant, or another
//! formulation of the same mechanism.
//!
//! Conventions (MSL's): a frame's `R.T` maps world-resolved vectors into the frame
//! (`v_frame = T v_world`). The references below use active rotation matrices `R = T'`
//! (frame-resolved vectors into the world), built by Rodrigues' formula in this file, so
//! they share no code with the library.

#![allow(missing_docs)]

#[path = "support/mechanics.rs"]
mod mechanics;

use mechanics::{MassProps, body_energy, rotation, vector};
use multibody::blocks::Constant3;
use multibody::forces::{
    Damper, Force, ResolveInB, Spring, SpringDamperParallel, Torque, WorldForce, WorldTorque,
};
use multibody::joints::Revolute;
use multibody::parts::{
    Body, Fixed, FixedRotation, FixedTranslation, OrientationStates, RotationType,
};
use multibody::prelude::*;
use multibody::sensors::{
    AbsolutePosition, AbsoluteVelocity, CutForce, CutTorque, Power, RelativeAngles,
    RelativePosition, RelativeVelocity, ResolveIn, ResolveInA,
};
use multibody::world::World;

const G: f64 = 9.80665;

// ---------------------------------------------------------------------------------------
// Small linear algebra for the references.

type V3 = [f64; 3];
type M3 = [[f64; 3]; 3];

const EX: V3 = [1.0, 0.0, 0.0];
const EY: V3 = [0.0, 1.0, 0.0];
const EZ: V3 = [0.0, 0.0, 1.0];

fn add(a: V3, b: V3) -> V3 {
    std::array::from_fn(|i| a[i] + b[i])
}

fn sub(a: V3, b: V3) -> V3 {
    std::array::from_fn(|i| a[i] - b[i])
}

fn scale(a: V3, s: f64) -> V3 {
    a.map(|x| x * s)
}

fn cross(a: V3, b: V3) -> V3 {
    mechanics::cross(a, b)
}

fn dot(a: V3, b: V3) -> f64 {
    mechanics::dot(a, b)
}

fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

/// `a b`.
fn mul(a: &M3, b: &M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

/// `a v`.
fn mv(a: &M3, v: V3) -> V3 {
    std::array::from_fn(|i| dot(a[i], v))
}

/// `a'`.
fn tr(a: &M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

/// The active rotation by `angle` about `axis` (normalized here), by Rodrigues' formula
/// `R v = v cos + (e x v) sin + e (e . v)(1 - cos)`: the columns of `R` are the rotated
/// frame's axes resolved in the original frame.
fn rot(axis: V3, angle: f64) -> M3 {
    let e = scale(axis, 1.0 / norm(axis));
    let (c, s) = (angle.cos(), angle.sin());
    let skew = [[0.0, -e[2], e[1]], [e[2], 0.0, -e[0]], [-e[1], e[0], 0.0]];
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let id = if i == j { 1.0 } else { 0.0 };
            c * id + s * skew[i][j] + (1.0 - c) * e[i] * e[j]
        })
    })
}

fn assert_vec(what: &str, t: f64, got: V3, want: V3, tol: f64) {
    for i in 0..3 {
        assert!(
            (got[i] - want[i]).abs() <= tol,
            "{what} at t = {t}: {got:?}, expected {want:?} (tolerance {tol:e})"
        );
    }
}

fn assert_mat(what: &str, t: f64, got: &M3, want: &M3, tol: f64) {
    for i in 0..3 {
        for j in 0..3 {
            assert!(
                (got[i][j] - want[i][j]).abs() <= tol,
                "{what} at t = {t}: {got:?}, expected {want:?} (tolerance {tol:e})"
            );
        }
    }
}

/// Tolerances far below every comparison of a simulated trajectory with a closed form.
fn tight() -> SolverOptions {
    SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        ..SolverOptions::default()
    }
}

fn tight_on(t_end: f64, n: usize) -> SolverOptions {
    SolverOptions {
        output_times: Some((0..=n).map(|k| k as f64 * t_end / n as f64).collect()),
        ..tight()
    }
}

/// Compiles and solves `model` from `values` over `[0, t_end]`, reporting at `n + 1`
/// equally spaced times (a failure panics with the library's message).
fn simulate(
    model: &(impl AsRef<System> + ?Sized),
    values: &[(&str, f64)],
    t_end: f64,
    n: usize,
) -> Solution {
    let ssys = structural_simplify(model).unwrap_or_else(|e| panic!("{e}"));
    DaeProblem::new(&ssys, values, (0.0, t_end))
        .and_then(|p| p.solve(&tight_on(t_end, n)))
        .unwrap_or_else(|e| panic!("{e}"))
}

// ---------------------------------------------------------------------------------------
// Kinematic sensors.

/// RelativePosition, RelativeVelocity, AbsolutePosition, AbsoluteVelocity and
/// RelativeAngles on a spatial chain of three revolute joints (axes z, y, x), every
/// output compared with the chain's geometry in closed form from the joint angles and
/// speeds of the same solution.
///
/// Geometry: `base` puts joint 1 at D; frame F1 = j1.frame_b is at D turned by
/// R1 = Rz(q1); F2 = j2.frame_b is at D + R1 (L1, 0, 0) turned by R2 = R1 Ry(q2);
/// F3 = j3.frame_b is at o3 = D + R1 pA turned by R3 = R2 Rx(q3), with
/// pA = (L1, 0, 0) + Ry(q2) (L2, 0, 0), the position of F3 relative to F1 resolved in F1.
///
/// - r_rel (F1 to F3): pA in F1, R1 pA in the world, R3' R1 pA in F3;
/// - v_rel = der(pA) (MSL: the derivative of the F1-resolved relative position):
///   vA = w2 ey x Ry(q2) (L2, 0, 0), then R1 vA in the world and R3' R1 vA in F3;
/// - AbsolutePosition of F3: o3 in the world, R3' o3 in F3;
/// - AbsoluteVelocity of F3: v3 = w1 ez x (R1 pA) + R1 vA in the world, R3' v3 in F3;
/// - RelativeAngles world to F3 with sequence {3, 2, 1}: (q1, q2, q3); F1 to F3 with
///   {2, 1, 3}: (q2, q3, 0); F2 to F3 with the default {1, 2, 3}: (q3, 0, 0). These are
///   the angles the sensor returns while each first angle is within pi/2 of its guess 0
///   (the other solution, angle1 +- pi, is then farther), which the test checks.
///
/// Gravity acts along +x, along the arms at q = 0, so the chain swings about q = 0 and
/// the angles stay in that range (the body's inertia, 0.05, keeps j3 from spinning).
///
/// A vector resolved in the wrong frame, a transposed rotation (the sign of every sin q
/// term), or a velocity taken as the world derivative instead of the frame_a one (it
/// differs by w1 ez x R1 pA) fails by far more than the tolerance.
#[test]
fn position_velocity_and_angle_sensors_on_a_three_joint_chain() {
    const D: V3 = [0.1, 0.2, 0.3];
    const L1: f64 = 0.5;
    const L2: f64 = 0.4;
    let model = system! {
        name: "chain_sensors";
        world = World { n: [1.0, 0.0, 0.0] };
        base = FixedTranslation { r: D };
        j1 = Revolute { n: EZ };
        bar1 = FixedTranslation { r: [L1, 0.0, 0.0] };
        j2 = Revolute { n: EY };
        bar2 = FixedTranslation { r: [L2, 0.0, 0.0] };
        j3 = Revolute { n: EX };
        body = Body { m: 1.0, r_CM: [0.2, 0.1, 0.05], I_11: 0.05, I_22: 0.05, I_33: 0.05 };
        connect(world.frame_b, base.frame_a);
        connect(base.frame_b, j1.frame_a);
        connect(j1.frame_b, bar1.frame_a);
        connect(bar1.frame_b, j2.frame_a);
        connect(j2.frame_b, bar2.frame_a);
        connect(bar2.frame_b, j3.frame_a);
        connect(j3.frame_b, body.frame_a);
        relpos_a = RelativePosition::default();
        relpos_w = RelativePosition { resolve_in: ResolveIn::World };
        relpos_b = RelativePosition { resolve_in: ResolveIn::FrameB };
        relvel_a = RelativeVelocity::default();
        relvel_w = RelativeVelocity { resolve_in: ResolveIn::World };
        relvel_b = RelativeVelocity { resolve_in: ResolveIn::FrameB };
        connect(j1.frame_b, relpos_a.frame_a);
        connect(j3.frame_b, relpos_a.frame_b);
        connect(j1.frame_b, relpos_w.frame_a);
        connect(j3.frame_b, relpos_w.frame_b);
        connect(j1.frame_b, relpos_b.frame_a);
        connect(j3.frame_b, relpos_b.frame_b);
        connect(j1.frame_b, relvel_a.frame_a);
        connect(j3.frame_b, relvel_a.frame_b);
        connect(j1.frame_b, relvel_w.frame_a);
        connect(j3.frame_b, relvel_w.frame_b);
        connect(j1.frame_b, relvel_b.frame_a);
        connect(j3.frame_b, relvel_b.frame_b);
        abspos = AbsolutePosition::default();
        abspos_w = AbsolutePosition { resolve_in: ResolveInA::World };
        absvel = AbsoluteVelocity::default();
        absvel_w = AbsoluteVelocity { resolve_in: ResolveInA::World };
        connect(j3.frame_b, abspos.frame_a);
        connect(j3.frame_b, abspos_w.frame_a);
        connect(j3.frame_b, absvel.frame_a);
        connect(j3.frame_b, absvel_w.frame_a);
        ang_321 = RelativeAngles { sequence: [3, 2, 1] };
        ang_213 = RelativeAngles { sequence: [2, 1, 3] };
        ang_123 = RelativeAngles::default();
        connect(world.frame_b, ang_321.frame_a);
        connect(j3.frame_b, ang_321.frame_b);
        connect(j1.frame_b, ang_213.frame_a);
        connect(j3.frame_b, ang_213.frame_b);
        connect(j2.frame_b, ang_123.frame_a);
        connect(j3.frame_b, ang_123.frame_b);
    };
    let start = [
        ("j1.phi", 0.3),
        ("j1.w", 0.4),
        ("j2.phi", -0.4),
        ("j2.w", 0.6),
        ("j3.phi", 0.5),
        ("j3.w", -0.8),
    ];
    let sol = simulate(&model, &start, 1.0, 200);
    let q: Vec<Vec<f64>> = ["j1.phi", "j2.phi", "j3.phi"]
        .iter()
        .map(|n| sol.get(n).unwrap())
        .collect();
    let w: Vec<Vec<f64>> = ["j1.w", "j2.w", "j3.w"]
        .iter()
        .map(|n| sol.get(n).unwrap())
        .collect();
    let out = |name: &str| vector(&sol, name);
    let (relpos_a, relpos_w, relpos_b) = (
        out("relpos_a.r_rel"),
        out("relpos_w.r_rel"),
        out("relpos_b.r_rel"),
    );
    let (relvel_a, relvel_w, relvel_b) = (
        out("relvel_a.v_rel"),
        out("relvel_w.v_rel"),
        out("relvel_b.v_rel"),
    );
    let (abspos, abspos_w) = (out("abspos.r"), out("abspos_w.r"));
    let (absvel, absvel_w) = (out("absvel.v"), out("absvel_w.v"));
    let (ang_321, ang_213, ang_123) = (
        out("ang_321.angles"),
        out("ang_213.angles"),
        out("ang_123.angles"),
    );
    let t3 = rotation(&sol, "j3.frame_b");
    // Everything compared is an algebraic function of the same state at the same time
    // (the velocities through the derivatives index reduction takes symbolically), so
    // the only differences are rounding and the solver's Newton tolerance on algebraic
    // unknowns, far below 1e-9 at rtol 1e-10; the planted errors named above are of
    // order 0.1.
    let tol = 1e-9;
    let mut swing = [0.0f64; 3];
    for (k, &t) in sol.t().iter().enumerate() {
        let (q1, q2, q3) = (q[0][k], q[1][k], q[2][k]);
        for i in 0..3 {
            swing[i] = swing[i].max((q[i][k] - q[i][0]).abs());
        }
        // The angles stay where the sensor's choice of solution is (q1, q2, q3).
        assert!(
            q1.abs() < 1.2 && q2.abs() < 1.2 && q3.abs() < 1.2,
            "q at {t}: {q1} {q2} {q3}"
        );
        let r1 = rot(EZ, q1);
        let ry = rot(EY, q2);
        let r3 = mul(&mul(&r1, &ry), &rot(EX, q3));
        // The reference's convention is the joints': F3's T is R3'.
        assert_mat("j3.frame_b.R.T", t, &t3[k], &tr(&r3), tol);
        let arm2 = mv(&ry, [L2, 0.0, 0.0]);
        let p_a = add([L1, 0.0, 0.0], arm2);
        let o3 = add(D, mv(&r1, p_a));
        let v_a = scale(cross(EY, arm2), w[1][k]);
        let v3 = add(scale(cross(EZ, mv(&r1, p_a)), w[0][k]), mv(&r1, v_a));
        let to3 = tr(&r3);
        assert_vec("relpos_a.r_rel", t, relpos_a[k], p_a, tol);
        assert_vec("relpos_w.r_rel", t, relpos_w[k], mv(&r1, p_a), tol);
        assert_vec(
            "relpos_b.r_rel",
            t,
            relpos_b[k],
            mv(&to3, mv(&r1, p_a)),
            tol,
        );
        assert_vec("relvel_a.v_rel", t, relvel_a[k], v_a, tol);
        assert_vec("relvel_w.v_rel", t, relvel_w[k], mv(&r1, v_a), tol);
        assert_vec(
            "relvel_b.v_rel",
            t,
            relvel_b[k],
            mv(&to3, mv(&r1, v_a)),
            tol,
        );
        assert_vec("abspos.r", t, abspos[k], mv(&to3, o3), tol);
        assert_vec("abspos_w.r", t, abspos_w[k], o3, tol);
        assert_vec("absvel.v", t, absvel[k], mv(&to3, v3), tol);
        assert_vec("absvel_w.v", t, absvel_w[k], v3, tol);
        assert_vec("ang_321.angles", t, ang_321[k], [q1, q2, q3], tol);
        assert_vec("ang_213.angles", t, ang_213[k], [q2, q3, 0.0], tol);
        assert_vec("ang_123.angles", t, ang_123[k], [q3, 0.0, 0.0], tol);
    }
    // The motion is large enough for the references to discriminate.
    assert!(swing.iter().all(|&s| s > 0.2), "joint swings {swing:?}");
}

// ---------------------------------------------------------------------------------------
// Cut sensors and power.

/// CutForce and CutTorque (resolved in frame_a and in the world) between a revolute
/// joint (axis z, at the world origin) and a pendulum body whose centre of mass is off
/// the joint's plane: r_CM = (l, 0, c) in the body frame, inertia diag(I1, I2, I3)
/// about the centre of mass, gravity -y.
///
/// Reference (Newton-Euler for the body, in the body frame, which turns by phi about
/// z): the equation of motion J phi'' = -m g l cos(phi), J = I3 + m l^2, gives
/// alpha = phi'' from phi alone; the body-frame acceleration of the centre of mass is
/// (-l w^2, l alpha, 0) and gravity is (-g sin(phi), -g cos(phi), 0), so the force the
/// joint side exerts on the body is
///   F = m (-l w^2 + g sin(phi), l alpha + g cos(phi), 0)
/// (at the bottom, phi = -pi/2: F_x = -m (g + l w^2), the rod pulling the body towards
/// the pivot), and the torque about the joint is
///   M = I z + w x I w + r_CM x F = (-c F_y, c F_x, I3 alpha + l F_y),
/// whose z component vanishes by the equation of motion (a revolute joint transmits no
/// torque about its axis). World-resolved: Rz(phi) F and Rz(phi) M.
#[test]
fn cut_force_and_cut_torque_in_a_pendulum_match_newton_euler() {
    let (m, l, c) = (2.0, 0.6, 0.25);
    let (i1, i2, i3) = (0.01, 0.02, 0.03);
    let model = system! {
        name: "cut_sensors";
        world = World::default();
        rev = Revolute { n: EZ };
        cut_f = CutForce::default();
        cut_f_w = CutForce { resolve_in_world: true };
        cut_t = CutTorque::default();
        cut_t_w = CutTorque { resolve_in_world: true };
        body = Body { m, r_CM: [l, 0.0, c], I_11: i1, I_22: i2, I_33: i3 };
        connect(world.frame_b, rev.frame_a);
        connect(rev.frame_b, cut_f.frame_a);
        connect(cut_f.frame_b, cut_f_w.frame_a);
        connect(cut_f_w.frame_b, cut_t.frame_a);
        connect(cut_t.frame_b, cut_t_w.frame_a);
        connect(cut_t_w.frame_b, body.frame_a);
    };
    // Released level: the body swings through the bottom at sqrt(2 m g l / J) = 5.6 rad/s.
    let sol = simulate(&model, &[("rev.phi", 0.0), ("rev.w", 0.0)], 3.0, 300);
    let phi = sol.get("rev.phi").unwrap();
    let w = sol.get("rev.w").unwrap();
    let f_a = vector(&sol, "cut_f.force");
    let f_w = vector(&sol, "cut_f_w.force");
    let t_a = vector(&sol, "cut_t.torque");
    let t_w = vector(&sol, "cut_t_w.torque");
    let j = i3 + m * l * l;
    // Algebraic functions of the same state (see the kinematic sensors' test): the
    // differences are rounding, near 1e-14, on forces up to 57 N. A sign error, a
    // missing term (l w^2, the lever arm c) or the other frame is off by newtons.
    let tol = 1e-8;
    let mut max_speed = 0.0f64;
    for (k, &t) in sol.t().iter().enumerate() {
        let (p, w) = (phi[k], w[k]);
        max_speed = max_speed.max(w.abs());
        let alpha = -m * G * l * p.cos() / j;
        let f = [
            m * (-l * w * w + G * p.sin()),
            m * (l * alpha + G * p.cos()),
            0.0,
        ];
        let torque = [-c * f[1], c * f[0], i3 * alpha + l * f[1]];
        let rz = rot(EZ, p);
        assert_vec("cut_f.force", t, f_a[k], f, tol);
        assert_vec("cut_f_w.force", t, f_w[k], mv(&rz, f), tol);
        assert_vec("cut_t.torque", t, t_a[k], torque, tol);
        assert_vec("cut_t_w.torque", t, t_w[k], mv(&rz, torque), tol);
    }
    assert!(
        max_speed > 4.0,
        "the pendulum swung at most {max_speed} rad/s"
    );
}

/// Power, WorldForce and WorldTorque on a pendulum (revolute about z at the origin,
/// gravity -y): a constant world force F and a constant world torque tau act at the
/// point P = R (a, 0, 0) of the link (through a FixedTranslation), and a Power sensor
/// sits between them and the link (the power flows from frame_a, the forces' side, to
/// frame_b, the link's side).
///
/// References:
/// - the power of the forces: P = F . v_P + tau . w_world with v_P = w a
///   (-sin(phi), cos(phi), 0) and w_world = (0, 0, w), i.e.
///   P = a w (F_y cos(phi) - F_x sin(phi)) + tau_z w;
/// - their work: constant forces are conservative, so the body's energy (kinetic plus
///   potential in gravity) minus F . r_P minus tau_z phi is constant.
#[test]
fn power_of_world_force_and_torque_on_a_pendulum() {
    let (m, l_cm, a, i_c) = (1.5, 0.4, 0.7, 0.02);
    let f = [2.0, 5.0, -1.0];
    let tau = [0.3, -0.4, 1.2];
    let model = system! {
        name: "power";
        world = World::default();
        rev = Revolute { n: EZ };
        body = Body { m, r_CM: [l_cm, 0.0, 0.0], I_11: i_c, I_22: i_c, I_33: i_c };
        arm = FixedTranslation { r: [a, 0.0, 0.0] };
        power = Power::default();
        force = WorldForce::default();
        torque = WorldTorque::default();
        force_value = Constant3 { k: f };
        torque_value = Constant3 { k: tau };
        connect(world.frame_b, rev.frame_a);
        connect(rev.frame_b, body.frame_a);
        connect(rev.frame_b, arm.frame_a);
        connect(arm.frame_b, power.frame_b);
        connect(force.frame_b, power.frame_a);
        connect(torque.frame_b, power.frame_a);
        connect(force_value.y, force.force);
        connect(torque_value.y, torque.torque);
    };
    let sol = simulate(&model, &[("rev.phi", 0.0), ("rev.w", 0.0)], 4.0, 400);
    let phi = sol.get("rev.phi").unwrap();
    let w = sol.get("rev.w").unwrap();
    let power = sol.get("power.power").unwrap();
    let props = MassProps {
        m,
        r_cm: [l_cm, 0.0, 0.0],
        inertia: [[i_c, 0.0, 0.0], [0.0, i_c, 0.0], [0.0, 0.0, i_c]],
    };
    let energy = body_energy(&sol, "body", props, G, [0.0, -1.0, 0.0]);
    let conserved: Vec<f64> = (0..sol.t().len())
        .map(|k| {
            let r_p = [a * phi[k].cos(), a * phi[k].sin(), 0.0];
            energy[k] - dot(f, r_p) - tau[2] * phi[k]
        })
        .collect();
    let mut max_power = 0.0f64;
    for (k, &t) in sol.t().iter().enumerate() {
        let (p, w) = (phi[k], w[k]);
        let expected = a * w * (f[1] * p.cos() - f[0] * p.sin()) + tau[2] * w;
        max_power = max_power.max(expected.abs());
        // Algebraic in the state: rounding only (powers up to 8 W).
        assert!(
            (power[k] - expected).abs() < 1e-8,
            "power at {t}: {}, expected F.v + tau.w = {expected}",
            power[k]
        );
        // The invariant drifts only by the integration error: about 1e-8 J at rtol
        // 1e-10 over 4 s of swinging through energies of 5 J; leaving out the force or
        // the torque, or doubling one, changes it by joules.
        assert!(
            (conserved[k] - conserved[0]).abs() < 1e-6,
            "energy minus work at {t}: {} vs {}",
            conserved[k],
            conserved[0]
        );
    }
    assert!(
        max_power > 5.0,
        "the forces delivered at most {max_power} W"
    );
}

// ---------------------------------------------------------------------------------------
// Signal forces.

/// WorldForce on two free bodies (forces at their centres of mass, so their rotation
/// does not matter to their paths), gravity -y:
/// - `world_body` (quaternion states, tumbling at w0): a world-resolved force F, so
///   r(t) = r0 + v0 t + (F / m + g) t^2 / 2 whatever its rotation;
/// - `spin_body` (Cardan states), turning about z at w0 (torque free, so the turn
///   stays: phi_3 = w0 t), with a force Fb fixed in the body (`resolve_in =
///   FrameB`): in the world F(t) = Rz(w0 t) Fb, and integrating twice
///   x = x0 + vx t + (Fb_x (1 - cos) / w0^2 - Fb_y (t / w0 - sin / w0^2)) / m,
///   y = y0 + vy t + (Fb_x (t / w0 - sin / w0^2) + Fb_y (1 - cos) / w0^2) / m - g t^2 / 2,
///   z = z0 + vz t + Fb_z t^2 / (2 m), with cos, sin of w0 t.
///   A force resolved in the world instead, or turned the other way (a transposed
///   rotation), drifts off by far more than the tolerance.
#[test]
fn world_force_accelerates_free_bodies_in_closed_form() {
    let (m1, m2) = (2.0, 0.5);
    let f1 = [1.0, 3.0, -2.0];
    let fb = [0.8, -0.4, 0.3];
    let model = system! {
        name: "world_force";
        world = World::default();
        world_body = Body { m: m1, I_11: 0.01, I_22: 0.02, I_33: 0.03,
                            orientation_states: OrientationStates::Quaternion };
        f_world = WorldForce::default();
        f_world_value = Constant3 { k: f1 };
        connect(f_world.frame_b, world_body.frame_a);
        connect(f_world_value.y, f_world.force);
        spin_body = Body { m: m2, orientation_states: OrientationStates::Cardan };
        f_body = WorldForce { resolve_in: ResolveInB::FrameB };
        f_body_value = Constant3 { k: fb };
        connect(f_body.frame_b, spin_body.frame_a);
        connect(f_body_value.y, f_body.force);
    };
    let (r1, v1) = ([0.1, 0.2, 0.3], [0.5, -0.2, 0.1]);
    let (r2, v2) = ([-0.3, 0.0, 0.4], [0.2, 0.0, 0.1]);
    let w0 = 3.0;
    let start = [
        ("world_body.r_0[1]", r1[0]),
        ("world_body.r_0[2]", r1[1]),
        ("world_body.r_0[3]", r1[2]),
        ("world_body.v_0[1]", v1[0]),
        ("world_body.v_0[2]", v1[1]),
        ("world_body.v_0[3]", v1[2]),
        ("world_body.w_a[1]", 0.5),
        ("world_body.w_a[2]", 1.0),
        ("world_body.w_a[3]", -0.3),
        ("spin_body.r_0[1]", r2[0]),
        ("spin_body.r_0[2]", r2[1]),
        ("spin_body.r_0[3]", r2[2]),
        ("spin_body.v_0[1]", v2[0]),
        ("spin_body.v_0[2]", v2[1]),
        ("spin_body.v_0[3]", v2[2]),
        ("spin_body.phi_d[3]", w0),
    ];
    let sol = simulate(&model, &start, 2.0, 200);
    let p1 = vector(&sol, "world_body.r_0");
    let p2 = vector(&sol, "spin_body.r_0");
    let phi3 = sol.get("spin_body.phi[3]").unwrap();
    let t_world_body = rotation(&sol, "world_body.frame_a");
    // rtol 1e-10 on positions of order 1 to 20 m over 2 s: errors near 2e-9.
    let tol = 1e-7;
    for (k, &t) in sol.t().iter().enumerate() {
        let expected1: V3 = std::array::from_fn(|i| {
            let g = if i == 1 { -G } else { 0.0 };
            r1[i] + v1[i] * t + (f1[i] / m1 + g) * t * t / 2.0
        });
        assert_vec("world_body.r_0", t, p1[k], expected1, tol);
        let (c, s) = ((w0 * t).cos(), (w0 * t).sin());
        let i_cos = (1.0 - c) / (w0 * w0);
        let i_sin = t / w0 - s / (w0 * w0);
        let expected2 = [
            r2[0] + v2[0] * t + (fb[0] * i_cos - fb[1] * i_sin) / m2,
            r2[1] + v2[1] * t + (fb[0] * i_sin + fb[1] * i_cos) / m2 - G * t * t / 2.0,
            r2[2] + v2[2] * t + fb[2] * t * t / (2.0 * m2),
        ];
        assert_vec("spin_body.r_0", t, p2[k], expected2, tol);
        assert!((phi3[k] - w0 * t).abs() < tol, "spin angle at {t}");
    }
    // The tumbling body did turn (so a body-resolved force would have shown).
    let last = t_world_body.last().unwrap();
    assert!(last[0][0] < 0.9, "world_body barely turned: {last:?}");
}

/// WorldTorque on two free bodies with isotropic inertia J (quaternion states), no
/// gravity. For an isotropic body the Euler equations reduce to J der(w) = tau in any
/// frame where tau is constant:
/// - `world_body`, torque tau fixed in the world: the world-resolved angular velocity is
///   w0 + tau t / J;
/// - `body_body`, torque tau_b fixed in the body (`resolve_in = FrameB`): the
///   body-resolved angular velocity w_a is w0 + tau_b t / J.
///
/// Both spin at 2 rad/s about z from the start, so a torque resolved in the wrong frame
/// turns with the body and misses by about |tau| t / J.
#[test]
fn world_torque_spins_up_isotropic_bodies_in_closed_form() {
    let (j1, j2) = (0.2, 0.1);
    let tau = [0.4, -0.2, 0.0];
    let tau_b = [0.3, 0.0, 0.1];
    let (w1, w2) = ([0.0, 0.0, 2.0], [0.0, 0.5, 2.0]);
    let model = system! {
        name: "world_torque";
        world = World { g: 0.0 };
        world_body = Body { I_11: j1, I_22: j1, I_33: j1,
                            orientation_states: OrientationStates::Quaternion };
        t_world = WorldTorque::default();
        t_world_value = Constant3 { k: tau };
        connect(t_world.frame_b, world_body.frame_a);
        connect(t_world_value.y, t_world.torque);
        body_body = Body { I_11: j2, I_22: j2, I_33: j2,
                           orientation_states: OrientationStates::Quaternion };
        t_body = WorldTorque { resolve_in: ResolveInB::FrameB };
        t_body_value = Constant3 { k: tau_b };
        connect(t_body.frame_b, body_body.frame_a);
        connect(t_body_value.y, t_body.torque);
    };
    // Both start aligned with the world, so body- and world-resolved w0 agree.
    let start = [
        ("world_body.w_a[1]", w1[0]),
        ("world_body.w_a[2]", w1[1]),
        ("world_body.w_a[3]", w1[2]),
        ("body_body.w_a[1]", w2[0]),
        ("body_body.w_a[2]", w2[1]),
        ("body_body.w_a[3]", w2[2]),
    ];
    let sol = simulate(&model, &start, 3.0, 300);
    let wa1 = vector(&sol, "world_body.w_a");
    let t1 = rotation(&sol, "world_body.frame_a");
    let wa2 = vector(&sol, "body_body.w_a");
    // rtol 1e-10 on rates of order 5 rad/s over 3 s.
    let tol = 1e-7;
    for (k, &t) in sol.t().iter().enumerate() {
        let w_world = mechanics::to_world(&t1[k], wa1[k]);
        assert_vec(
            "world_body w (world)",
            t,
            w_world,
            add(w1, scale(tau, t / j1)),
            tol,
        );
        assert_vec(
            "body_body.w_a",
            t,
            wa2[k],
            add(w2, scale(tau_b, t / j2)),
            tol,
        );
    }
}

/// The two free bodies of the Force and Torque tests: `a` (mass 1, isotropic inertia
/// 0.1) at the origin and `b` (mass 2, isotropic inertia 0.2) at D, no gravity.
const D_AB: V3 = [1.0, 0.5, -0.2];

/// Force between two free bodies (`frame_a` on body a, `frame_b` on body b): b receives
/// f0 (world-resolved), a receives -f0 and the torque of the lever arm,
/// -(r_b - r_a) x f0, so that the element is in equilibrium. Both forces act at the
/// centres of mass, so
///   r_a = -f0 t^2 / (2 m_a), r_b = D + f0 t^2 / (2 m_b),
/// r_b - r_a = D + (...) f0, whose cross product with f0 is D x f0 for all t: a spins up
/// at the constant rate -(D x f0) / J_a (isotropic), b does not turn.
///
/// Each resolution of the signal: World (f0 is the signal); FrameB, with b turned by
/// theta about z at the start (f0 = Rz(theta) f_b); FrameA, with a turned by alpha about
/// z and f0 along D (no lever torque, so a keeps its orientation;
/// f_a = Rz(alpha)' f0). A transposed rotation, the wrong frame or a lever torque of
/// the wrong sign moves or turns the bodies by far more than the tolerance.
#[test]
fn force_between_two_free_bodies_in_closed_form() {
    let (m_a, m_b, j_a, j_b) = (1.0, 2.0, 0.1, 0.2);
    let (theta, alpha) = (0.8f64, -0.6f64);
    let f_w: V3 = [0.3, -0.2, 0.4];
    let f_along_d = scale(D_AB, 0.5 / norm(D_AB));
    // (resolve_in, signal, f0 in the world, a's states, a's angle about z, b's angle).
    let cases = [
        (
            ResolveIn::World,
            f_w,
            f_w,
            OrientationStates::Quaternion,
            0.0,
            0.0,
        ),
        (
            ResolveIn::FrameB,
            f_w,
            mv(&rot(EZ, theta), f_w),
            OrientationStates::Quaternion,
            0.0,
            theta,
        ),
        (
            ResolveIn::FrameA,
            mv(&tr(&rot(EZ, alpha)), f_along_d),
            f_along_d,
            OrientationStates::Cardan,
            alpha,
            0.0,
        ),
    ];
    for (resolve_in, signal, f0, a_states, a_angle, b_angle) in cases {
        let model = system! {
            name: "force_pair";
            world = World { g: 0.0 };
            a = Body { m: m_a, I_11: j_a, I_22: j_a, I_33: j_a, orientation_states: a_states,
                       angles_start: [0.0, 0.0, a_angle] };
            b = Body { m: m_b, I_11: j_b, I_22: j_b, I_33: j_b, angles_start: [0.0, 0.0, b_angle] };
            force = Force { resolve_in };
            value = Constant3 { k: signal };
            connect(force.frame_a, a.frame_a);
            connect(force.frame_b, b.frame_a);
            connect(value.y, force.force);
        };
        let start = [
            ("b.r_0[1]", D_AB[0]),
            ("b.r_0[2]", D_AB[1]),
            ("b.r_0[3]", D_AB[2]),
        ];
        let sol = simulate(&model, &start, 2.0, 200);
        let (ra, rb) = (vector(&sol, "a.r_0"), vector(&sol, "b.r_0"));
        let (ta, wa) = (rotation(&sol, "a.frame_a"), vector(&sol, "a.w_a"));
        let (tb, wb) = (rotation(&sol, "b.frame_a"), vector(&sol, "b.w_a"));
        let spin = scale(cross(D_AB, f0), -1.0 / j_a);
        let (ta0, tb0) = (tr(&rot(EZ, a_angle)), tr(&rot(EZ, b_angle)));
        // rtol 1e-10 over 2 s on positions and rates of order 1.
        let tol = 1e-7;
        let what = |s: &str| format!("{resolve_in:?}: {s}");
        for (k, &t) in sol.t().iter().enumerate() {
            let h = t * t / 2.0;
            assert_vec(&what("a.r_0"), t, ra[k], scale(f0, -h / m_a), tol);
            assert_vec(&what("b.r_0"), t, rb[k], add(D_AB, scale(f0, h / m_b)), tol);
            let w_a_world = mechanics::to_world(&ta[k], wa[k]);
            assert_vec(&what("a's w (world)"), t, w_a_world, scale(spin, t), tol);
            assert_vec(&what("b.w_a"), t, wb[k], [0.0; 3], tol);
            assert_mat(&what("b.frame_a.R.T"), t, &tb[k], &tb0, tol);
            if resolve_in == ResolveIn::FrameA {
                assert_mat(&what("a.frame_a.R.T"), t, &ta[k], &ta0, tol);
            }
        }
    }
}

/// Torque between two free bodies with isotropic inertia (quaternion states, no
/// gravity, no forces, so they stay where they are): b receives tau, a receives -tau.
/// An isotropic body obeys J der(w) = torque in any frame where the torque is constant,
/// and the total angular momentum J_a w_a + J_b w_b (world-resolved) is conserved.
///
/// - World: w_b = w_b0 + tau t / J_b and w_a = w_a0 - tau t / J_a, world-resolved;
/// - FrameB: b's body-resolved w is w_b0 + tau_b t / J_b; a's world-resolved w is
///   (L0 - J_b w_b) / J_a;
/// - FrameA: a's body-resolved w is w_a0 - tau_a t / J_a; b's from the momentum.
///
/// Each body spins from the start (a about z, b about x), so a torque resolved in the
/// wrong frame turns with it and misses.
#[test]
fn torque_between_two_free_bodies_in_closed_form() {
    let (j_a, j_b) = (0.5, 0.25);
    let tau: V3 = [0.2, -0.1, 0.3];
    let (w_a0, w_b0): (V3, V3) = ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    let momentum0 = add(scale(w_a0, j_a), scale(w_b0, j_b));
    for resolve_in in [ResolveIn::World, ResolveIn::FrameB, ResolveIn::FrameA] {
        let model = system! {
            name: "torque_pair";
            world = World { g: 0.0 };
            a = Body { I_11: j_a, I_22: j_a, I_33: j_a,
                       orientation_states: OrientationStates::Quaternion };
            b = Body { I_11: j_b, I_22: j_b, I_33: j_b,
                       orientation_states: OrientationStates::Quaternion };
            torque = Torque { resolve_in };
            value = Constant3 { k: tau };
            connect(torque.frame_a, a.frame_a);
            connect(torque.frame_b, b.frame_a);
            connect(value.y, torque.torque);
        };
        // Both start aligned with the world: body- and world-resolved w0 agree.
        let start = [
            ("b.r_0[1]", D_AB[0]),
            ("b.r_0[2]", D_AB[1]),
            ("b.r_0[3]", D_AB[2]),
            ("a.w_a[1]", w_a0[0]),
            ("a.w_a[2]", w_a0[1]),
            ("a.w_a[3]", w_a0[2]),
            ("b.w_a[1]", w_b0[0]),
            ("b.w_a[2]", w_b0[1]),
            ("b.w_a[3]", w_b0[2]),
        ];
        let sol = simulate(&model, &start, 3.0, 300);
        let (ta, wa) = (rotation(&sol, "a.frame_a"), vector(&sol, "a.w_a"));
        let (tb, wb) = (rotation(&sol, "b.frame_a"), vector(&sol, "b.w_a"));
        let (ra, rb) = (vector(&sol, "a.r_0"), vector(&sol, "b.r_0"));
        // rtol 1e-10 on rates of order 3 rad/s over 3 s.
        let tol = 1e-7;
        let what = |s: &str| format!("{resolve_in:?}: {s}");
        for (k, &t) in sol.t().iter().enumerate() {
            let wa_world = mechanics::to_world(&ta[k], wa[k]);
            let wb_world = mechanics::to_world(&tb[k], wb[k]);
            match resolve_in {
                ResolveIn::World => {
                    assert_vec(
                        &what("b's w"),
                        t,
                        wb_world,
                        add(w_b0, scale(tau, t / j_b)),
                        tol,
                    );
                    assert_vec(
                        &what("a's w"),
                        t,
                        wa_world,
                        sub(w_a0, scale(tau, t / j_a)),
                        tol,
                    );
                }
                ResolveIn::FrameB => {
                    assert_vec(
                        &what("b.w_a"),
                        t,
                        wb[k],
                        add(w_b0, scale(tau, t / j_b)),
                        tol,
                    );
                }
                ResolveIn::FrameA => {
                    assert_vec(
                        &what("a.w_a"),
                        t,
                        wa[k],
                        sub(w_a0, scale(tau, t / j_a)),
                        tol,
                    );
                }
                ResolveIn::FrameResolve => unreachable!("not among the cases"),
            }
            let momentum = add(scale(wa_world, j_a), scale(wb_world, j_b));
            assert_vec(&what("angular momentum"), t, momentum, momentum0, tol);
            assert_vec(&what("a.r_0"), t, ra[k], [0.0; 3], tol);
            assert_vec(&what("b.r_0"), t, rb[k], D_AB, tol);
        }
        // b turned far from its start, so the frames differ.
        let last = tb.last().unwrap();
        assert!(
            last[1][1] < 0.5,
            "{resolve_in:?}: b barely turned: {last:?}"
        );
    }
}

// ---------------------------------------------------------------------------------------
// Line forces.

/// A free body of mass `m` (quaternion states, small isotropic inertia, so it tumbles
/// freely) with no gravity, on the line force `element` (named `line`) between a fixed
/// point `anchor` and the body's frame.
fn body_on_line_force(element: &dyn Component, anchor: V3, m: f64) -> System {
    let mut model = system! {
        name: "line_force";
        world = World { g: 0.0 };
        fixed = Fixed { r: anchor };
        body = Body { m, I_11: 0.01, I_22: 0.01, I_33: 0.01,
                      orientation_states: OrientationStates::Quaternion };
    }
    .into_system();
    model.add("line", element);
    model.connect("fixed.frame_b", "line.frame_a");
    model.connect("line.frame_b", "body.frame_a");
    model
}

/// Start values: the body at `r0` with velocity `v0`, tumbling (so its frame, in which
/// the line force resolves its force, turns).
fn line_start(r0: V3, v0: V3) -> Vec<(&'static str, f64)> {
    vec![
        ("body.r_0[1]", r0[0]),
        ("body.r_0[2]", r0[1]),
        ("body.r_0[3]", r0[2]),
        ("body.v_0[1]", v0[0]),
        ("body.v_0[2]", v0[1]),
        ("body.v_0[3]", v0[2]),
        ("body.w_a[1]", 0.7),
        ("body.w_a[2]", -1.1),
        ("body.w_a[3]", 1.6),
    ]
}

/// Spring with zero unstretched length from the origin: the force is -c r, an
/// isotropic oscillator, r(t) = r0 cos(wt) + v0 / w sin(wt), w = sqrt(c / m), an
/// ellipse through 3-D space (it never passes the origin, where the line has no
/// direction). Two periods.
#[test]
fn spring_from_a_fixed_point_is_an_isotropic_oscillator() {
    let (c, m): (f64, f64) = (8.0, 2.0);
    let w = (c / m).sqrt();
    let model = body_on_line_force(
        &Spring {
            c,
            s_unstretched: 0.0,
            ..Default::default()
        },
        [0.0; 3],
        m,
    );
    let (r0, v0) = ([1.0, 0.2, -0.3], [0.1, 1.5, 0.4]);
    let t_end = 2.0 * 2.0 * std::f64::consts::PI / w;
    let sol = simulate(&model, &line_start(r0, v0), t_end, 300);
    let r = vector(&sol, "body.r_0");
    let length = sol.get("line.length").unwrap();
    // rtol 1e-10 over two periods: phase errors near 1e-9. A force of the wrong sign
    // or length (a missing factor) changes the frequency and fails within a period.
    let tol = 1e-7;
    for (k, &t) in sol.t().iter().enumerate() {
        let expected = add(scale(r0, (w * t).cos()), scale(v0, (w * t).sin() / w));
        assert_vec("body.r_0", t, r[k], expected, tol);
        assert!((length[k] - norm(expected)).abs() < tol, "length at {t}");
    }
}

/// Damper alone, motion along the line: the body starts at s0 e from the anchor p with
/// velocity u0 e, e = (2, -1, 2) / 3, so it stays on the line and m s'' = -d s':
///   s(t) = s0 + m u0 / d (1 - exp(-d t / m)).
#[test]
fn damper_along_the_line_decays_exponentially() {
    let (d, m) = (3.0, 2.0);
    let p = [0.2, -0.1, 0.3];
    let e = [2.0 / 3.0, -1.0 / 3.0, 2.0 / 3.0];
    let (s0, u0) = (0.5, 1.5);
    let model = body_on_line_force(
        &Damper {
            d,
            ..Default::default()
        },
        p,
        m,
    );
    let sol = simulate(
        &model,
        &line_start(add(p, scale(e, s0)), scale(e, u0)),
        3.0,
        300,
    );
    let r = vector(&sol, "body.r_0");
    let f = sol.get("line.f").unwrap();
    // At rtol 1e-10 the error is near 2e-10 m; a damping 1 % off moves the body's end
    // point by 1.5 cm, a damper of the wrong sign runs away.
    let tol = 1e-8;
    for (k, &t) in sol.t().iter().enumerate() {
        let decay = (-d * t / m).exp();
        let s = s0 + m * u0 / d * (1.0 - decay);
        assert_vec("body.r_0", t, r[k], add(p, scale(e, s)), tol);
        // Tension d s' = d u0 exp(-d t / m): a damper resisting the opening.
        assert!((f[k] - d * u0 * decay).abs() < tol, "damper tension at {t}");
    }
}

/// SpringDamperParallel, motion along the line (as for the damper): with
/// x = s - s_unstretched, m x'' = -c x - d x', underdamped:
///   x(t) = exp(-delta t) (x0 cos(wd t) + (u0 + delta x0) / wd sin(wd t)),
///   delta = d / (2 m), wd = sqrt(c / m - delta^2).
#[test]
fn spring_damper_parallel_along_the_line_is_a_damped_oscillator() {
    let (c, d, m, s_un) = (18.0, 1.2, 2.0, 1.0);
    let p = [0.2, -0.1, 0.3];
    let e = [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0];
    let (x0, u0) = (0.4, -0.5);
    let element = SpringDamperParallel {
        c,
        d,
        s_unstretched: s_un,
        ..Default::default()
    };
    let model = body_on_line_force(&element, p, m);
    let sol = simulate(
        &model,
        &line_start(add(p, scale(e, s_un + x0)), scale(e, u0)),
        4.0,
        400,
    );
    let r = vector(&sol, "body.r_0");
    let delta = d / (2.0 * m);
    let wd = (c / m - delta * delta).sqrt();
    // rtol 1e-10 over 2 periods of a motion of amplitude 0.4 m: errors near 4e-10. A
    // damping of the wrong sign grows the amplitude instead, a stiffness or damping
    // 1 % off shifts the motion by millimetres.
    let tol = 1e-8;
    for (k, &t) in sol.t().iter().enumerate() {
        let x =
            (-delta * t).exp() * (x0 * (wd * t).cos() + (u0 + delta * x0) / wd * (wd * t).sin());
        assert_vec("body.r_0", t, r[k], add(p, scale(e, s_un + x)), tol);
    }
}

/// SpringDamperParallel against a Spring and a Damper side by side (another formulation
/// of the same force): a body in gravity, off the line and swinging in 3-D, on either.
#[test]
fn spring_damper_parallel_matches_a_spring_and_a_damper_side_by_side() {
    let (c, d, s_un) = (30.0, 0.8, 0.6);
    let start = [
        ("body.r_0[1]", 0.8),
        ("body.r_0[2]", -0.3),
        ("body.r_0[3]", 0.5),
        ("body.v_0[1]", 0.0),
        ("body.v_0[2]", 0.4),
        ("body.v_0[3]", 1.0),
    ];
    let parallel = system! {
        name: "parallel";
        world = World::default();
        line = SpringDamperParallel { c, d, s_unstretched: s_un };
        body = Body::default();
        connect(world.frame_b, line.frame_a);
        connect(line.frame_b, body.frame_a);
    };
    let separate = system! {
        name: "separate";
        world = World::default();
        spring = Spring { c, s_unstretched: s_un };
        damper = Damper { d };
        body = Body::default();
        connect(world.frame_b, spring.frame_a);
        connect(spring.frame_b, body.frame_a);
        connect(world.frame_b, damper.frame_a);
        connect(damper.frame_b, body.frame_a);
    };
    let a = simulate(&parallel, &start, 3.0, 300);
    let b = simulate(&separate, &start, 3.0, 300);
    let (ra, rb) = (vector(&a, "body.r_0"), vector(&b, "body.r_0"));
    let mut travel = 0.0f64;
    for (k, &t) in a.t().iter().enumerate() {
        travel = travel.max(norm(sub(ra[k], ra[0])));
        // Two integrations at rtol 1e-10 of the same smooth motion.
        assert_vec("body.r_0", t, ra[k], rb[k], 1e-7);
    }
    assert!(travel > 0.5, "the body moved at most {travel} m");
}

// ---------------------------------------------------------------------------------------
// Point gravity.

/// A body in the central field -mu r / |r|^3 of the world's point gravity, on a
/// circular orbit of radius R in a plane tilted by beta about x: speed sqrt(mu / R),
/// r(t) = R (cos(W t), sin(W t) cos(beta), sin(W t) sin(beta)), W = sqrt(mu / R^3).
/// Two periods (2 pi / W = 8.9 s). A field of the wrong power of r, a wrong mu or a
/// field evaluated elsewhere changes the radius or the period.
#[test]
fn point_gravity_circular_orbit() {
    let (mu, r, beta) = (4.0f64, 2.0f64, 0.4f64);
    let model = system! {
        name: "orbit";
        world = World { point_gravity: 1.0, mu };
        body = Body { m: 3.0 };
    };
    let v = (mu / r).sqrt();
    let big_w = (mu / r.powi(3)).sqrt();
    let t_end = 2.0 * 2.0 * std::f64::consts::PI / big_w;
    let start = [
        ("body.r_0[1]", r),
        ("body.r_0[2]", 0.0),
        ("body.r_0[3]", 0.0),
        ("body.v_0[1]", 0.0),
        ("body.v_0[2]", v * beta.cos()),
        ("body.v_0[3]", v * beta.sin()),
    ];
    let sol = simulate(&model, &start, t_end, 400);
    let pos = vector(&sol, "body.r_0");
    let g0 = vector(&sol, "body.g_0");
    // At rtol 1e-10 the integration error grows along the orbit to about 7e-7 m after
    // two revolutions (a phase error); 1e-5 leaves margin, while a mu 1 % off shifts
    // the phase by 0.06 rad (0.1 m) and a field of the wrong power of r leaves the
    // circle altogether.
    let tol = 1e-5;
    for (k, &t) in sol.t().iter().enumerate() {
        let (c, s) = ((big_w * t).cos(), (big_w * t).sin());
        let expected = [r * c, r * s * beta.cos(), r * s * beta.sin()];
        assert_vec("body.r_0", t, pos[k], expected, tol);
        // The field itself: mu / R^2 towards the origin.
        assert_vec("body.g_0", t, g0[k], scale(expected, -mu / r.powi(3)), tol);
    }
}

/// An eccentric Kepler orbit (mu = 1, released at perihelion r0 = (1, 0, 0) with
/// v0 = (0, 1.2, 0.3)): the energy E = v^2 / 2 - mu / r, the angular momentum
/// h = r x v and the Laplace-Runge-Lenz vector A = v x h - mu r / |r| are constant,
/// and after one period 2 pi sqrt(a^3 / mu), a = -mu / (2 E), the body is back at r0
/// with v0 (eccentricity 0.53, so the speed varies by a factor 3.3).
#[test]
fn point_gravity_kepler_orbit_keeps_its_invariants_and_period() {
    let mu = 1.0f64;
    let model = system! {
        name: "kepler";
        world = World { point_gravity: 1.0, mu };
        body = Body { m: 0.5 };
    };
    let (r0, v0) = ([1.0, 0.0, 0.0], [0.0, 1.2, 0.3]);
    let energy = |r: V3, v: V3| dot(v, v) / 2.0 - mu / norm(r);
    let e0 = energy(r0, v0);
    let a = -mu / (2.0 * e0);
    let period = 2.0 * std::f64::consts::PI * (a.powi(3) / mu).sqrt();
    let start = [
        ("body.r_0[1]", r0[0]),
        ("body.r_0[2]", r0[1]),
        ("body.r_0[3]", r0[2]),
        ("body.v_0[1]", v0[0]),
        ("body.v_0[2]", v0[1]),
        ("body.v_0[3]", v0[2]),
    ];
    let sol = simulate(&model, &start, period, 500);
    let (pos, vel) = (vector(&sol, "body.r_0"), vector(&sol, "body.v_0"));
    let h0 = cross(r0, v0);
    let lrl = |r: V3, v: V3| sub(cross(v, cross(r, v)), scale(r, mu / norm(r)));
    let a0 = lrl(r0, v0);
    // The invariants drift only by the integration error (at rtol 1e-10 over one orbit,
    // about 2e-8 for the Runge-Lenz vector, less for the others); a force 1 % off
    // changes the energy by 1e-2.
    let tol = 1e-7;
    for (k, &t) in sol.t().iter().enumerate() {
        let (r, v) = (pos[k], vel[k]);
        assert!((energy(r, v) - e0).abs() < tol, "energy at {t}");
        assert_vec("angular momentum", t, cross(r, v), h0, tol);
        assert_vec("Runge-Lenz vector", t, lrl(r, v), a0, tol);
    }
    // Half a period after the perihelion (sample 250 of 500) the body is at the
    // aphelion, a (1 + e) = 2 a - 1 from the origin (the perihelion a (1 - e) is 1).
    let aphelion = norm(pos[250]);
    assert!(
        (aphelion - (2.0 * a - 1.0)).abs() < 1e-6,
        "aphelion {aphelion}, expected {}",
        2.0 * a - 1.0
    );
    // Back at the start after one period: the integration error of one orbit, about
    // 2e-7 at rtol 1e-10.
    let k = sol.t().len() - 1;
    assert_vec("r after one period", period, pos[k], r0, 1e-6);
    assert_vec("v after one period", period, vel[k], v0, 1e-6);
}

// ---------------------------------------------------------------------------------------
// FixedRotation.

const FR_R: V3 = [0.5, 0.1, -0.2];
const FR_P: V3 = [0.3, -0.2, 0.4];
const FR_I: f64 = 0.01;

/// The three ways to give a FixedRotation, each with its rotation matrix R (frame_b's
/// axes resolved in frame_a, the columns) derived independently:
/// - RotationAxis about (1, 1, 1) by 50 degrees: Rodrigues' formula;
/// - TwoAxesVectors n_x = (1, 1, 0), n_y = (0, 1, 1): e_x = n_x / |n_x|,
///   e_z = n_x x n_y / |.| = (1, -1, 1) / sqrt 3, e_y = e_z x e_x = (-1, 1, 2) / sqrt 6;
/// - PlanarRotationSequence {3, 1, 2} by (30, 45, 60) degrees: about z, then the new x,
///   then the newer y: R = Rz(30) Rx(45) Ry(60).
fn fixed_rotations() -> Vec<(&'static str, FixedRotation, M3)> {
    let s2 = 2f64.sqrt();
    let s3 = 3f64.sqrt();
    let s6 = 6f64.sqrt();
    let e_x = [1.0 / s2, 1.0 / s2, 0.0];
    let e_y = [-1.0 / s6, 1.0 / s6, 2.0 / s6];
    let e_z = [1.0 / s3, -1.0 / s3, 1.0 / s3];
    let deg = f64::to_radians;
    vec![
        (
            "RotationAxis",
            FixedRotation {
                r: FR_R,
                rotation_type: RotationType::RotationAxis,
                n: [1.0, 1.0, 1.0],
                angle: 50.0,
                ..Default::default()
            },
            rot([1.0, 1.0, 1.0], deg(50.0)),
        ),
        (
            "TwoAxesVectors",
            FixedRotation {
                r: FR_R,
                rotation_type: RotationType::TwoAxesVectors,
                n_x: [1.0, 1.0, 0.0],
                n_y: [0.0, 1.0, 1.0],
                ..Default::default()
            },
            std::array::from_fn(|i| [e_x[i], e_y[i], e_z[i]]),
        ),
        (
            "PlanarRotationSequence",
            FixedRotation {
                r: FR_R,
                rotation_type: RotationType::PlanarRotationSequence,
                sequence: [3, 1, 2],
                angles: [30.0, 45.0, 60.0],
                ..Default::default()
            },
            mul(
                &mul(&rot(EZ, deg(30.0)), &rot(EX, deg(45.0))),
                &rot(EY, deg(60.0)),
            ),
        ),
    ]
}

/// A pendulum about z at the origin (gravity -y) whose body (isotropic inertia, so
/// turning it changes nothing) hangs from `link`'s far frame at r_CM = `p`: `link` is
/// either a FixedRotation or nothing (`None`: the body on the joint).
fn pendulum_through(link: Option<&FixedRotation>, reversed: bool, p: V3) -> System {
    let mut model = system! {
        name: "fr_pendulum";
        world = World::default();
        rev = Revolute { n: EZ };
        body = Body { r_CM: p, I_11: FR_I, I_22: FR_I, I_33: FR_I };
        connect(world.frame_b, rev.frame_a);
    }
    .into_system();
    match link {
        None => model.connect("rev.frame_b", "body.frame_a"),
        Some(fr) => {
            model.add("fr", fr);
            let (near, far) = if reversed {
                ("fr.frame_b", "fr.frame_a")
            } else {
                ("fr.frame_a", "fr.frame_b")
            };
            model.connect("rev.frame_b", near);
            model.connect(far, "body.frame_a");
        }
    }
    model
}

/// Compares a pendulum through a FixedRotation with the same pendulum with the rotation
/// folded into the body's geometry (`p_folded`, in the joint's frame), and the
/// FixedRotation's far frame with the joint frame moved by the rotation in closed form:
/// `far_t(T_joint)` and `far_r(r_joint, T_joint)`.
fn check_against_folded(
    name: &str,
    fr: &FixedRotation,
    reversed: bool,
    p_folded: V3,
    far_t: impl Fn(&M3) -> M3,
    far_r: impl Fn(V3, &M3) -> V3,
) {
    let start = [("rev.phi", 0.2), ("rev.w", 0.0)];
    let t_end = 3.0;
    let a = simulate(
        &pendulum_through(Some(fr), reversed, FR_P),
        &start,
        t_end,
        300,
    );
    let b = simulate(&pendulum_through(None, false, p_folded), &start, t_end, 300);
    let (phi_a, phi_b) = (a.get("rev.phi").unwrap(), b.get("rev.phi").unwrap());
    let far = if reversed { "fr.frame_a" } else { "fr.frame_b" };
    let (t_joint, r_joint) = (rotation(&a, "rev.frame_b"), vector(&a, "rev.frame_b.r_0"));
    let (t_far, r_far) = (rotation(&a, far), vector(&a, &format!("{far}.r_0")));
    let mut swing = 0.0f64;
    for (k, &t) in a.t().iter().enumerate() {
        swing = swing.max((phi_a[k] - phi_a[0]).abs());
        // Two integrations at rtol 1e-10 of the same pendulum (they agree to about
        // 1e-12). A transposed rotation in the transmitted force or torque, or a lever
        // arm resolved in the wrong frame, changes the torque about the joint by a
        // fraction of m g |p| and the angle by far more than this.
        assert!(
            (phi_a[k] - phi_b[k]).abs() < 1e-7,
            "{name}: rev.phi at {t}: {} through the FixedRotation, {} folded",
            phi_a[k],
            phi_b[k]
        );
        // Kinematics: algebraic in the same state.
        assert_mat(
            &format!("{name}: {far}.R.T"),
            t,
            &t_far[k],
            &far_t(&t_joint[k]),
            1e-12,
        );
        assert_vec(
            &format!("{name}: {far}.r_0"),
            t,
            r_far[k],
            far_r(r_joint[k], &t_joint[k]),
            1e-12,
        );
    }
    assert!(swing > 1.0, "{name}: the pendulum swung only {swing} rad");
}

/// FixedRotation behind a joint, all three rotation types, frame_a towards the joint:
/// frame_b's T is R' T_a and frame_b.r_0 = frame_a.r_0 + T_a' r; the body at r_CM = p
/// in frame_b is the body at r + R p in frame_a.
#[test]
fn fixed_rotation_behind_a_joint_matches_the_folded_geometry() {
    for (name, fr, r) in fixed_rotations() {
        let folded = add(FR_R, mv(&r, FR_P));
        check_against_folded(
            name,
            &fr,
            false,
            folded,
            |t_a| mul(&tr(&r), t_a),
            |r_a, t_a| add(r_a, mv(&tr(t_a), FR_R)),
        );
    }
}

/// FixedRotation behind a joint connected the other way round (frame_b towards the
/// joint, so frame_a's orientation is computed from frame_b's): frame_a's T is R T_b,
/// frame_a.r_0 = frame_b.r_0 - T_a' r; the body at r_CM = p in frame_a is at
/// R' (p - r) in frame_b.
#[test]
fn fixed_rotation_connected_backwards_matches_the_folded_geometry() {
    for (name, fr, r) in fixed_rotations() {
        let folded = mv(&tr(&r), sub(FR_P, FR_R));
        check_against_folded(
            name,
            &fr,
            true,
            folded,
            |t_b| mul(&r, t_b),
            |r_b, t_b| sub(r_b, mv(&tr(&mul(&r, t_b)), FR_R)),
        );
    }
}

/// A pendulum hung from a FixedRotation on the world frame: world -> FixedRotation (r,
/// R) -> revolute (axis n in the rotated frame) -> body (r_CM = p). Folded: world ->
/// FixedTranslation (r) -> revolute with axis R n -> body at R p (isotropic inertia).
/// Same motion (R Rot(n, phi) p = Rot(R n, phi) R p), and FixedRotation's frame_b is the
/// constant (r, T = R').
fn pendulum_under_a_fixed_rotation_on_the_world(axis: V3, angle_deg: f64) {
    let n_joint = EX;
    let p = [0.1, 0.0, 0.5];
    let r = [0.2, 0.3, -0.1];
    let rr = rot(axis, angle_deg.to_radians());
    let through = system! {
        name: "fr_on_world";
        world = World::default();
        fr = FixedRotation { r, n: axis, angle: angle_deg };
        rev = Revolute { n: n_joint };
        body = Body { r_CM: p, I_11: FR_I, I_22: FR_I, I_33: FR_I };
        connect(world.frame_b, fr.frame_a);
        connect(fr.frame_b, rev.frame_a);
        connect(rev.frame_b, body.frame_a);
    };
    let folded = system! {
        name: "fr_folded";
        world = World::default();
        shift = FixedTranslation { r };
        rev = Revolute { n: mv(&rr, n_joint) };
        body = Body { r_CM: mv(&rr, p), I_11: FR_I, I_22: FR_I, I_33: FR_I };
        connect(world.frame_b, shift.frame_a);
        connect(shift.frame_b, rev.frame_a);
        connect(rev.frame_b, body.frame_a);
    };
    let start = [("rev.phi", 0.0), ("rev.w", 0.0)];
    let a = simulate(&through, &start, 3.0, 300);
    let b = simulate(&folded, &start, 3.0, 300);
    let (phi_a, phi_b) = (a.get("rev.phi").unwrap(), b.get("rev.phi").unwrap());
    let t_fr = rotation(&a, "fr.frame_b");
    let r_fr = vector(&a, "fr.frame_b.r_0");
    let mut swing = 0.0f64;
    for (k, &t) in a.t().iter().enumerate() {
        swing = swing.max((phi_a[k] - phi_a[0]).abs());
        // Two integrations at rtol 1e-10 of the same pendulum; a joint axis or body
        // turned the wrong way (R' for R) swings differently by tenths of a radian.
        assert!(
            (phi_a[k] - phi_b[k]).abs() < 1e-7,
            "rev.phi at {t}: {} under the FixedRotation, {} folded",
            phi_a[k],
            phi_b[k]
        );
        assert_mat("fr.frame_b.R.T", t, &t_fr[k], &tr(&rr), 1e-12);
        assert_vec("fr.frame_b.r_0", t, r_fr[k], r, 1e-12);
    }
    assert!(swing > 1.0, "the pendulum swung only {swing} rad");
}

/// The rotation about z by 30 degrees on the world frame. This used to fail to compile
/// ("structurally singular ... determined more than once: fr.frame_b.R.T[2,3]"): the
/// FixedRotation's orientation equations, e.g.
/// `fr.frame_b.R.T[2,3] = -0.5 fr.frame_a.R.T[1,3] + 0.866 fr.frame_a.R.T[2,3]` and
/// `fr.frame_b.R.w[1] = 0.866 fr.frame_a.R.w[1] + 0.5 fr.frame_a.R.w[2]`, each reduce to
/// `0 = fr.frame_b...` on the constant world frame, but alias elimination looked at
/// them only as written; the entry's derivative rule then folded to the single
/// variable `fr.frame_b.R.w[1]`, which made the two a derivative chain that both
/// equations determined. Alias elimination now repeats on the substituted equations
/// and finds both constant (more cases in `tests/fixed_rotation.rs`).
#[test]
fn pendulum_under_a_fixed_rotation_about_z_on_the_world() {
    pendulum_under_a_fixed_rotation_on_the_world(EZ, 30.0);
}

/// The rotation about (1, 1, 1) by 30 degrees on the world frame (no zero entry in its
/// matrix).
#[test]
fn pendulum_under_a_fixed_rotation_about_a_skew_axis_on_the_world() {
    pendulum_under_a_fixed_rotation_on_the_world([1.0, 1.0, 1.0], 30.0);
}
