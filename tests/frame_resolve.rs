//! Signal forces and relative sensors resolved in the frame connected to
//! `frame_resolve` (MSL `resolveInFrame = frame_resolve`), `ForceAndTorque`,
//! `WorldForceAndTorque`, the vector sources `Constant3` and `RealExpression3`, and
//! MSL's `Examples.Elementary.ForceAndTorque`, each against a closed form, an invariant,
//! or the same mechanism with the signals resolved by hand.
//!
//! Conventions (MSL's): a frame's `R.T` maps world-resolved vectors into the frame. The
//! references use active rotations `R = T'` built by Rodrigues' formula here.

#![allow(missing_docs)]

#[path = "support/mechanics.rs"]
mod mechanics;

use mechanics::{rotation, vector};
use multibody::blocks::{Constant3, RealExpression3};
use multibody::forces::{
    Force, ForceAndTorque, ResolveIn, ResolveInB, Torque, WorldForce, WorldForceAndTorque,
};
use multibody::joints::Revolute;
use multibody::parts::{Body, BodyCylinder, Fixed, FixedRotation, OrientationStates};
use multibody::prelude::*;
use multibody::sensors::{
    AbsolutePosition, AbsoluteVelocity, RelativePosition, RelativeVelocity, ResolveInA,
};
use multibody::world::World;

type V3 = [f64; 3];
type M3 = [[f64; 3]; 3];

const EX: V3 = [1.0, 0.0, 0.0];
const EY: V3 = [0.0, 1.0, 0.0];
const EZ: V3 = [0.0, 0.0, 1.0];

fn add(a: V3, b: V3) -> V3 {
    std::array::from_fn(|i| a[i] + b[i])
}

fn scale(a: V3, s: f64) -> V3 {
    a.map(|x| x * s)
}

fn norm(a: V3) -> f64 {
    mechanics::dot(a, a).sqrt()
}

fn mul(a: &M3, b: &M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn mv(a: &M3, v: V3) -> V3 {
    std::array::from_fn(|i| mechanics::dot(a[i], v))
}

fn tr(a: &M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

/// The active rotation by `angle` about `axis` (Rodrigues).
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

#[track_caller]
fn assert_vec(what: &str, t: f64, got: V3, want: V3, tol: f64) {
    for i in 0..3 {
        assert!(
            (got[i] - want[i]).abs() <= tol,
            "{what} at t = {t}: {got:?}, expected {want:?} (tolerance {tol:e})"
        );
    }
}

#[track_caller]
fn assert_mat(what: &str, t: f64, got: &M3, want: &M3, tol: f64) {
    for i in 0..3 {
        assert_vec(what, t, got[i], want[i], tol);
    }
}

fn simulate(model: &System, values: &[(&str, f64)], t_end: f64, n: usize) -> Solution {
    let ssys = structural_simplify(model).unwrap_or_else(|e| panic!("{e}"));
    let options = SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        output_times: Some((0..=n).map(|k| k as f64 * t_end / n as f64).collect()),
        ..SolverOptions::default()
    };
    DaeProblem::new(&ssys, values, (0.0, t_end))
        .and_then(|p| p.solve(&options))
        .unwrap_or_else(|e| panic!("{e}"))
}

/// An isotropic free body (quaternion states, no rotation unless driven).
fn free_body(m: f64, j: f64) -> Body {
    Body {
        m,
        I_11: j,
        I_22: j,
        I_33: j,
        orientation_states: OrientationStates::Quaternion,
        ..Default::default()
    }
}

// ---------------------------------------------------------------------------------------
// Forces and torques resolved in frame_resolve.

/// The Cardan angles of the reference frame and its active rotation: MSL's
/// `axesRotations({1, 2, 3}, phi)` is T = T3 T2 T1 with T_i = axisRotation(i, phi_i), the
/// transpose of the active rotation about axis i, so R = T' = Rx(phi1) Ry(phi2) Rz(phi3).
const PHI_REF: V3 = [0.3, -0.5, 0.8];

fn r_ref() -> M3 {
    mul(
        &mul(&rot(EX, PHI_REF[0]), &rot(EY, PHI_REF[1])),
        &rot(EZ, PHI_REF[2]),
    )
}

/// Five free bodies without gravity, each driven by one element whose signals are
/// resolved in `reference.frame_a`, a free body turned by Cardan angles PHI_REF and at
/// rest. A frame_resolve takes no force and no torque, so the reference stays where and
/// as it is; a signal v then acts in the world as R v, R the reference's rotation, and
/// each body (force at its frame, centre of mass there, isotropic inertia J, starting
/// at rest) follows r = r0 + (R F / m) t^2 / 2 and w = (R tau / J) t (world-resolved):
///
/// - `WorldForce`, `WorldForceAndTorque` on bodies 1 and 2;
/// - `Force`, `Torque`, `ForceAndTorque` from a fixed point to bodies 3, 4 and 5.
///
/// A signal resolved in the world, or rotated by R' instead of R, misses by about
/// |F| t^2 / m.
#[test]
fn forces_and_torques_resolved_in_a_rotated_frame_act_along_the_rotated_vectors() {
    let f: [V3; 5] = [
        [1.0, -2.0, 0.5],
        [0.4, 0.3, -1.0],
        [-0.7, 0.2, 0.9],
        [0.0; 3],
        [0.5, 0.5, -0.3],
    ];
    let tau: [V3; 5] = [
        [0.0; 3],
        [0.2, -0.1, 0.3],
        [0.0; 3],
        [-0.3, 0.2, 0.1],
        [0.1, 0.25, -0.2],
    ];
    let (m, j) = ([2.0, 0.5, 1.5, 1.0, 0.8], [0.1, 0.05, 0.2, 0.15, 0.12]);
    let r0: [V3; 5] = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [-1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
    ];
    let fr = ResolveIn::FrameResolve;
    let frb = ResolveInB::FrameResolve;
    let model = system! {
        name: "resolved_forces";
        world = World { g: 0.0 };
        reference = Body { m: 1.0, I_11: 0.1, I_22: 0.1, I_33: 0.1, angles_start: PHI_REF };
        anchor = Fixed { r: [0.0, 0.0, -2.0] };
        b1 = free_body(m[0], j[0]);
        b2 = free_body(m[1], j[1]);
        b3 = free_body(m[2], j[2]);
        b4 = free_body(m[3], j[3]);
        b5 = free_body(m[4], j[4]);
        e1 = WorldForce { resolve_in: frb };
        e2 = WorldForceAndTorque { resolve_in: frb };
        e3 = Force { resolve_in: fr };
        e4 = Torque { resolve_in: fr };
        e5 = ForceAndTorque { resolve_in: fr };
        f1 = Constant3 { k: f[0] };
        f2 = Constant3 { k: f[1] };
        t2 = Constant3 { k: tau[1] };
        f3 = Constant3 { k: f[2] };
        t4 = Constant3 { k: tau[3] };
        f5 = Constant3 { k: f[4] };
        t5 = Constant3 { k: tau[4] };
        connect(f1.y, e1.force);
        connect(f2.y, e2.force);
        connect(t2.y, e2.torque);
        connect(f3.y, e3.force);
        connect(t4.y, e4.torque);
        connect(f5.y, e5.force);
        connect(t5.y, e5.torque);
        connect(e1.frame_b, b1.frame_a);
        connect(e2.frame_b, b2.frame_a);
        connect(anchor.frame_b, e3.frame_a);
        connect(e3.frame_b, b3.frame_a);
        connect(anchor.frame_b, e4.frame_a);
        connect(e4.frame_b, b4.frame_a);
        connect(anchor.frame_b, e5.frame_a);
        connect(e5.frame_b, b5.frame_a);
        connect(e1.frame_resolve, reference.frame_a);
        connect(e2.frame_resolve, reference.frame_a);
        connect(e3.frame_resolve, reference.frame_a);
        connect(e4.frame_resolve, reference.frame_a);
        connect(e5.frame_resolve, reference.frame_a);
    }
    .into_system();
    let mut start: Vec<(String, f64)> = Vec::new();
    for (k, r) in r0.iter().enumerate() {
        for i in 0..3 {
            start.push((format!("b{}.r_0[{}]", k + 1, i + 1), r[i]));
        }
    }
    let start: Vec<(&str, f64)> = start.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    let sol = simulate(&model, &start, 2.0, 100);
    let r = r_ref();
    let t_ref = rotation(&sol, "reference.frame_a");
    let p_ref = vector(&sol, "reference.r_0");
    // rtol 1e-10 over 2 s on positions up to 10 m and rates up to 10 rad/s.
    let tol = 1e-7;
    for (k, &t) in sol.t().iter().enumerate() {
        assert_mat("reference.frame_a.R.T", t, &t_ref[k], &tr(&r), 1e-12);
        assert_vec("reference.r_0", t, p_ref[k], [0.0; 3], 1e-12);
    }
    for b in 0..5 {
        let name = format!("b{}", b + 1);
        let p = vector(&sol, &format!("{name}.r_0"));
        let tb = rotation(&sol, &format!("{name}.frame_a"));
        let w = vector(&sol, &format!("{name}.w_a"));
        let (acc, spin) = (
            scale(mv(&r, f[b]), 1.0 / m[b]),
            scale(mv(&r, tau[b]), 1.0 / j[b]),
        );
        for (k, &t) in sol.t().iter().enumerate() {
            assert_vec(
                &format!("{name}.r_0"),
                t,
                p[k],
                add(r0[b], scale(acc, t * t / 2.0)),
                tol,
            );
            let w_world = mechanics::to_world(&tb[k], w[k]);
            assert_vec(
                &format!("{name}'s w (world)"),
                t,
                w_world,
                scale(spin, t),
                tol,
            );
        }
    }
}

/// Torques resolved in `frame_b` of a spinning isotropic body: `ForceAndTorque` (zero
/// force) between two free bodies, and `WorldForceAndTorque` on a third. An isotropic
/// body obeys J der(w) = torque in any frame in which the torque is constant, so the
/// body-resolved w_b is w_b0 + tau t / J_b; for the pair, a receives the reaction and
/// the total angular momentum J_a w_a + J_b w_b (world) is conserved. Each body spins
/// from the start (about x), so a torque resolved in the world instead turns with it
/// and misses.
#[test]
fn torques_resolved_in_frame_b_of_spinning_bodies() {
    let (j_a, j_b, j_c) = (0.5, 0.25, 0.4);
    let (tau, tau_c): (V3, V3) = ([0.2, -0.1, 0.3], [-0.3, 0.4, 0.1]);
    let w0: V3 = [2.0, 0.0, 0.0];
    let model = system! {
        name: "frame_b_torques";
        world = World { g: 0.0 };
        a = free_body(1.0, j_a);
        b = free_body(1.0, j_b);
        c = free_body(1.0, j_c);
        pair = ForceAndTorque { resolve_in: ResolveIn::FrameB };
        single = WorldForceAndTorque { resolve_in: ResolveInB::FrameB };
        zero = Constant3 { k: [0.0; 3] };
        torque = Constant3 { k: tau };
        torque_c = Constant3 { k: tau_c };
        connect(pair.frame_a, a.frame_a);
        connect(pair.frame_b, b.frame_a);
        connect(single.frame_b, c.frame_a);
        connect(zero.y, pair.force);
        connect(torque.y, pair.torque);
        connect(zero.y, single.force);
        connect(torque_c.y, single.torque);
    }
    .into_system();
    let mut start = vec![("b.r_0[1]", 1.0), ("c.r_0[2]", 1.0)];
    start.extend([("a.w_a[1]", 0.0), ("b.w_a[1]", w0[0]), ("c.w_a[1]", w0[0])]);
    let sol = simulate(&model, &start, 3.0, 150);
    let (ta, wa) = (rotation(&sol, "a.frame_a"), vector(&sol, "a.w_a"));
    let (tb, wb) = (rotation(&sol, "b.frame_a"), vector(&sol, "b.w_a"));
    let wc = vector(&sol, "c.w_a");
    let (pb, pc) = (vector(&sol, "b.r_0"), vector(&sol, "c.r_0"));
    let momentum0 = scale(w0, j_b);
    let tol = 1e-7;
    for (k, &t) in sol.t().iter().enumerate() {
        assert_vec("b.w_a", t, wb[k], add(w0, scale(tau, t / j_b)), tol);
        assert_vec("c.w_a", t, wc[k], add(w0, scale(tau_c, t / j_c)), tol);
        let momentum = add(
            scale(mechanics::to_world(&ta[k], wa[k]), j_a),
            scale(mechanics::to_world(&tb[k], wb[k]), j_b),
        );
        assert_vec("angular momentum", t, momentum, momentum0, tol);
        assert_vec("b.r_0", t, pb[k], EX, tol);
        assert_vec("c.r_0", t, pc[k], EY, tol);
    }
    assert!(tb.last().unwrap()[1][1] < 0.5, "b barely turned");
}

// ---------------------------------------------------------------------------------------
// Relative sensors resolved in frame_resolve.

/// RelativePosition and RelativeVelocity from body p to body q, resolved in the world
/// and in `observer.frame_a`, and AbsolutePosition and AbsoluteVelocity of q resolved
/// in `observer.frame_a` (R_o(t)' q(t), R_o(t)' v_q), an isotropic free body spinning at w_o from the world's
/// orientation (torque free, so about a fixed axis: R_o(t) = rot(w_o, |w_o| t)). No
/// gravity and no forces: p (not turning) and q move uniformly, so
/// d = q0 - p0 + (v_q - v_p) t and, p not turning, v_rel = v_q - v_p. The sensors give
/// d and v_rel in the world and R_o(t)' d and R_o(t)' v_rel in the observer; a rotation
/// the wrong way round (or frozen at t = 0) misses by |d| |w_o| t.
#[test]
fn sensors_resolved_in_a_spinning_frame() {
    let w_o: V3 = [0.4, -0.8, 1.2];
    let (p0, q0): (V3, V3) = ([0.1, 0.2, 0.3], [1.0, -0.5, 0.4]);
    let (vp, vq): (V3, V3) = ([0.3, 0.0, -0.2], [-0.1, 0.6, 0.2]);
    let model = system! {
        name: "resolved_sensors";
        world = World { g: 0.0 };
        p = free_body(1.0, 0.1);
        q = free_body(1.0, 0.1);
        observer = free_body(1.0, 0.1);
        pos_w = RelativePosition { resolve_in: ResolveIn::World };
        pos_o = RelativePosition { resolve_in: ResolveIn::FrameResolve };
        vel_w = RelativeVelocity { resolve_in: ResolveIn::World };
        vel_o = RelativeVelocity { resolve_in: ResolveIn::FrameResolve };
        connect(pos_w.frame_a, p.frame_a);
        connect(pos_w.frame_b, q.frame_a);
        connect(pos_o.frame_a, p.frame_a);
        connect(pos_o.frame_b, q.frame_a);
        connect(vel_w.frame_a, p.frame_a);
        connect(vel_w.frame_b, q.frame_a);
        connect(vel_o.frame_a, p.frame_a);
        connect(vel_o.frame_b, q.frame_a);
        connect(pos_o.frame_resolve, observer.frame_a);
        connect(vel_o.frame_resolve, observer.frame_a);
        abs_pos_o = AbsolutePosition { resolve_in: ResolveInA::FrameResolve };
        abs_vel_o = AbsoluteVelocity { resolve_in: ResolveInA::FrameResolve };
        connect(abs_pos_o.frame_a, q.frame_a);
        connect(abs_vel_o.frame_a, q.frame_a);
        connect(abs_pos_o.frame_resolve, observer.frame_a);
        connect(abs_vel_o.frame_resolve, observer.frame_a);
    }
    .into_system();
    let mut start: Vec<(String, f64)> = Vec::new();
    for i in 0..3 {
        let n = i + 1;
        start.push((format!("p.r_0[{n}]"), p0[i]));
        start.push((format!("q.r_0[{n}]"), q0[i]));
        start.push((format!("p.v_0[{n}]"), vp[i]));
        start.push((format!("q.v_0[{n}]"), vq[i]));
        start.push((format!("observer.w_a[{n}]"), w_o[i]));
    }
    let start: Vec<(&str, f64)> = start.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    let sol = simulate(&model, &start, 3.0, 150);
    let t_o = rotation(&sol, "observer.frame_a");
    let (rw, ro) = (vector(&sol, "pos_w.r_rel"), vector(&sol, "pos_o.r_rel"));
    let (vw, vo) = (vector(&sol, "vel_w.v_rel"), vector(&sol, "vel_o.v_rel"));
    let (aro, avo) = (vector(&sol, "abs_pos_o.r"), vector(&sol, "abs_vel_o.v"));
    let v_rel: V3 = std::array::from_fn(|i| vq[i] - vp[i]);
    let tol = 1e-7;
    for (k, &t) in sol.t().iter().enumerate() {
        let r_o = rot(w_o, norm(w_o) * t);
        assert_mat("observer.frame_a.R.T", t, &t_o[k], &tr(&r_o), tol);
        let d: V3 = std::array::from_fn(|i| q0[i] - p0[i] + v_rel[i] * t);
        assert_vec("pos_w.r_rel", t, rw[k], d, tol);
        assert_vec("pos_o.r_rel", t, ro[k], mv(&tr(&r_o), d), tol);
        assert_vec("vel_w.v_rel", t, vw[k], v_rel, tol);
        assert_vec("vel_o.v_rel", t, vo[k], mv(&tr(&r_o), v_rel), tol);
        let q_t: V3 = std::array::from_fn(|i| q0[i] + vq[i] * t);
        assert_vec("abs_pos_o.r", t, aro[k], mv(&tr(&r_o), q_t), tol);
        assert_vec("abs_vel_o.v", t, avo[k], mv(&tr(&r_o), vq), tol);
    }
    // The observer turned far (about 4.5 rad), so a frozen rotation would show.
    assert!(norm(w_o) * 3.0 > 4.0);
}

// ---------------------------------------------------------------------------------------
// Vector sources.

/// `RealExpression3` drives a force with an expression of time: a free body (no
/// gravity) pushed by the world-resolved F(t) = (F0 cos(w t), F0 sin(w t), k t) moves as
/// the twice-integrated F / m: x = F0 (1 - cos(w t)) / (m w^2), y = F0 (t / w -
/// sin(w t) / w^2) / m, z = k t^3 / (6 m).
#[test]
fn real_expression3_drives_a_force_with_time() {
    let (f0, w, kz, m) = (2.0, 3.0, 0.6, 0.5);
    let model = system! {
        name: "expression_force";
        world = World { g: 0.0 };
        body = free_body(m, 0.1);
        push = WorldForce::default();
        signal = RealExpression3 {
            expression: |t| Vec3::new(2.0 * cos(3.0 * t), 2.0 * sin(3.0 * t), 0.6 * t),
        };
        connect(signal.y, push.force);
        connect(push.frame_b, body.frame_a);
    }
    .into_system();
    let sol = simulate(&model, &[], 2.0, 100);
    let p = vector(&sol, "body.r_0");
    for (k, &t) in sol.t().iter().enumerate() {
        let want = [
            f0 * (1.0 - (w * t).cos()) / (m * w * w),
            f0 * (t / w - (w * t).sin() / (w * w)) / m,
            kz * t * t * t / (6.0 * m),
        ];
        assert_vec("body.r_0", t, p[k], want, 1e-8);
    }
}

// ---------------------------------------------------------------------------------------
// MSL Examples.Elementary.ForceAndTorque.

/// MSL `Examples.Elementary.ForceAndTorque`: a BodyCylinder r = (1, 0, 0) on revolute1
/// (axis z, at fixed1 = (0, -0.5, 0)) and revolute2 (axis y); a ForceAndTorque from
/// fixed2 = (1.5, 0.25, 0) to the cylinder's end with force (0, 1000, 0) and torque
/// (-100, 100, 0) resolved in `frame_resolve`, connected to `resolve_frame`; gravity.
/// `resolve_frame` is `FixedRotation(n = z, angle = 30)` on fixed1 in MSL; `None` here
/// resolves the signals in the world after rotating them by hand.
fn msl_force_and_torque(resolve_frame: Option<&dyn Component>) -> System {
    let rz30 = rot(EZ, 30f64.to_radians());
    let (force, torque): (V3, V3) = ([0.0, 1000.0, 0.0], [-100.0, 100.0, 0.0]);
    let resolve_in = if resolve_frame.is_some() {
        ResolveIn::FrameResolve
    } else {
        ResolveIn::World
    };
    let (force, torque) = if resolve_frame.is_some() {
        (force, torque)
    } else {
        (mv(&rz30, force), mv(&rz30, torque))
    };
    let mut model = system! {
        name: "msl_force_and_torque";
        world = World::default();
        body = BodyCylinder { r: [1.0, 0.0, 0.0] };
        fixed1 = Fixed { r: [0.0, -0.5, 0.0] };
        force_and_torque = ForceAndTorque { resolve_in };
        revolute2 = Revolute { n: [0.0, 1.0, 0.0] };
        torque = Constant3 { k: torque };
        revolute1 = Revolute::default();
        fixed2 = Fixed { r: [1.5, 0.25, 0.0] };
        force = Constant3 { k: force };
        connect(revolute2.frame_b, body.frame_a);
        connect(force_and_torque.frame_b, body.frame_b);
        connect(fixed1.frame_b, revolute1.frame_a);
        connect(revolute1.frame_b, revolute2.frame_a);
        connect(fixed2.frame_b, force_and_torque.frame_a);
        connect(force.y, force_and_torque.force);
        connect(torque.y, force_and_torque.torque);
    }
    .into_system();
    if let Some(frame) = resolve_frame {
        model.add("resolve_frame", frame);
        model.connect("force_and_torque.frame_resolve", "resolve_frame.frame_b");
        if frame.type_name().ends_with("FixedRotation") {
            model.connect("fixed1.frame_b", "resolve_frame.frame_a");
        }
    }
    model
}

/// The joint angles of a model built by [`msl_force_and_torque`] over MSL's 1 s.
fn msl_angles(model: &System, extra: &[(&str, f64)]) -> (Vec<f64>, Vec<f64>, Solution) {
    let sol = simulate(model, extra, 1.0, 100);
    let phi1 = sol.get("revolute1.phi").unwrap();
    let phi2 = sol.get("revolute2.phi").unwrap();
    (phi1, phi2, sol)
}

/// Compares two runs of the MSL model: the cylinder whirls round (the angles reach
/// several radians in 1 s), so a force or torque resolved in a frame turned otherwise
/// separates the runs by far more than the tolerance.
fn assert_same_motion(a: &(Vec<f64>, Vec<f64>, Solution), b: &(Vec<f64>, Vec<f64>, Solution)) {
    for k in 0..a.0.len() {
        let t = a.2.t()[k];
        assert!(
            (a.0[k] - b.0[k]).abs() < 1e-6,
            "revolute1.phi at {t}: {} vs {}",
            a.0[k],
            b.0[k]
        );
        assert!(
            (a.1[k] - b.1[k]).abs() < 1e-6,
            "revolute2.phi at {t}: {} vs {}",
            a.1[k],
            b.1[k]
        );
    }
    let swing = a.0.iter().chain(&a.1).fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(swing > 1.0, "the cylinder barely moved: {swing}");
}

/// MSL's model as written, with `FixedRotation(n = z, angle = 30)` on `Parts.Fixed`,
/// against the same model with the signals rotated by 30 degrees about z by hand and
/// resolved in the world.
#[test]
fn msl_force_and_torque_example() {
    let fixed_rotation = FixedRotation {
        n: EZ,
        angle: 30.0,
        ..Default::default()
    };
    let exact = msl_angles(&msl_force_and_torque(Some(&fixed_rotation)), &[]);
    let by_hand = msl_angles(&msl_force_and_torque(None), &[]);
    assert_same_motion(&exact, &by_hand);
}

/// MSL's model with the FixedRotation replaced by a moving frame: a free body turned
/// 30 degrees about z (Cardan angles (0, 0, 30 deg)), which falls under gravity without
/// turning (gravity acts at its centre of mass, and frame_resolve takes no torque), so
/// its frame has MSL's orientation at every instant. Against the same
/// model with the signals rotated by hand and resolved in the world.
#[test]
fn msl_force_and_torque_example_resolved_in_a_falling_rotated_frame() {
    let frame = multibody::parts::BodyShape {
        r: [0.0; 3],
        angles_start: [0.0, 0.0, 30f64.to_radians()],
        ..Default::default()
    };
    let model = msl_force_and_torque(Some(&frame));
    let resolved = msl_angles(&model, &[]);
    let t_frame = rotation(&resolved.2, "resolve_frame.frame_b");
    let rz30 = rot(EZ, 30f64.to_radians());
    for (k, &t) in resolved.2.t().iter().enumerate() {
        assert_mat(
            "resolve_frame's orientation",
            t,
            &t_frame[k],
            &tr(&rz30),
            1e-9,
        );
    }
    let by_hand = msl_angles(&msl_force_and_torque(None), &[]);
    assert_same_motion(&resolved, &by_hand);
}

// ---------------------------------------------------------------------------------------
// Misuse.

/// With `FrameResolve`, an unconnected `frame_resolve` leaves its orientation
/// undetermined: an error naming it (MSL: the cardinality assert).
#[test]
fn an_unconnected_frame_resolve_is_an_error_naming_it() {
    let model = system! {
        name: "unresolved";
        world = World::default();
        body = Body::default();
        push = WorldForce { resolve_in: ResolveInB::FrameResolve };
        value = Constant3 { k: [1.0, 0.0, 0.0] };
        connect(value.y, push.force);
        connect(push.frame_b, body.frame_a);
    }
    .into_system();
    let e = structural_simplify(&model)
        .map(|_| ())
        .expect_err("an error");
    let text = e.to_string();
    assert!(
        matches!(e, multibody::Error::Model(_)),
        "wrong phase: {text}"
    );
    assert!(
        text.contains("push.frame_resolve") && text.contains("not determined"),
        "{text}"
    );
}

/// Without `FrameResolve`, `frame_resolve` is fixed parallel to the world (MSL's
/// ZeroPosition); connecting it to a mechanism fixed elsewhere is an error naming both
/// roots.
#[test]
fn a_frame_resolve_connected_without_frame_resolve_mode_is_an_error() {
    let model = system! {
        name: "overresolved";
        world = World::default();
        body = Body::default();
        push = Force { resolve_in: ResolveIn::World };
        value = Constant3 { k: [1.0, 0.0, 0.0] };
        connect(value.y, push.force);
        connect(world.frame_b, push.frame_a);
        connect(push.frame_b, body.frame_a);
        connect(push.frame_resolve, world.frame_b);
    }
    .into_system();
    let e = structural_simplify(&model)
        .map(|_| ())
        .expect_err("an error");
    let text = e.to_string();
    assert!(
        text.contains("push.frame_resolve") && text.contains("two roots"),
        "{text}"
    );
}
