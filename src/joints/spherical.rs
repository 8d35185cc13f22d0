//! The spherical joint and the free motion joint: 3 and 6 degrees of freedom with
//! orientation states of their own when asked for.

use crate::frames::{
    Orientation, Vec3, absolute_rotation, axes_rotations, inverse_rotation, quaternion_to_t,
    resolve_relative, resolve1, resolve2,
};
use crate::frames::{invalid_sequence, valid_sequence};
use crate::interfaces::Frame;
use crate::parts::OrientationStates;
use crate::parts::{StartOrientation, given};
use crate::prelude::*;

/// Priority of joint orientation states when they are enforced.
const ENFORCED: f64 = 1000.0;

/// The relative rotation described by Cardan angles or a (non-unit) quaternion.
pub(crate) fn relative_orientation(
    states: OrientationStates,
    sequence: [usize; 3],
    phi: Vec3,
    phi_d: Vec3,
    q_v: Vec3,
    q_4: Expr,
    w_rel: Vec3,
) -> Orientation {
    match states {
        OrientationStates::Cardan => axes_rotations(sequence, phi.0, phi_d.0),
        OrientationStates::Quaternion => {
            let n = (q_v.dot(q_v) + q_4 * q_4).sqrt();
            Orientation::new(
                quaternion_to_t([q_v[0] / n, q_v[1] / n, q_v[2] / n, q_4 / n]),
                w_rel,
            )
        }
    }
}

component! {
    /// A ball joint (MSL `Joints.Spherical`): frames at the same point, free relative
    /// rotation. By default it does not relate the orientations of its frames (it is no
    /// branch): the body beyond it carries the orientation states. With `state` it is a
    /// branch with its own orientation states (Cardan angles of `sequence`, or a
    /// quaternion).
    #[type_name = "MultiBody.Joints.Spherical"]
    pub struct Spherical {
        /// Use the joint's relative rotation as states (MSL `enforceStates`).
        structural state: bool = false;
        /// Orientation states with `state` (MSL `useQuaternions`; default a quaternion).
        structural orientation_states: OrientationStates = OrientationStates::Quaternion;
        /// Axis sequence of the angles.
        structural sequence: [usize; 3] = [1, 2, 3];
        /// Radius when rendered \[m\].
        structural radius: f64 = 0.05;
        /// Colour when rendered, RGB in 0..1 (MSL's joint colour, red).
        structural color: [f64; 3] = crate::render::JOINT_COLOR;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        /// Angles rotating `frame_a` into `frame_b` (with `state` and Cardan angles) \[rad\].
        variable phi(state_priority = if state { ENFORCED } else { -100.0 }): Vec3;
        /// Derivatives of the angles \[rad/s\].
        variable phi_d(state_priority = if state { ENFORCED } else { -100.0 }): Vec3;
        /// Second derivatives of the angles \[rad/s2\].
        variable phi_dd: Vec3;
        /// Angular velocity of `frame_b` relative to `frame_a`, resolved in `frame_b`
        /// (a state with quaternions) \[rad/s\].
        variable w_rel(state_priority = if state { ENFORCED } else { -100.0 }): Vec3;
        /// Vector part of the relative quaternion (with `state` and quaternions).
        variable q_v(state_priority = if state { ENFORCED } else { -100.0 }): Vec3;
        /// Scalar part of the relative quaternion.
        variable q_4(start = 1.0, state_priority = if state { ENFORCED } else { -100.0 }): Real;
        equation {
            frame_b.r_0 = frame_a.r_0;
            frame_a.t = Vec3::zero();
            frame_b.t = Vec3::zero();
            if state {
                let n2 = q_v.dot(q_v) + q_4 * q_4;
                let r_rel = relative_orientation(orientation_states, sequence, phi, phi_d, q_v, q_4, w_rel);
                match orientation_states {
                    OrientationStates::Cardan => {
                        phi_d = der(phi);
                        phi_dd = der(phi_d);
                        q_v = Vec3::zero();
                        q_4 = 1.0;
                        w_rel = r_rel.w;
                    }
                    OrientationStates::Quaternion => {
                        phi = Vec3::zero();
                        phi_d = Vec3::zero();
                        phi_dd = Vec3::zero();
                        der(q_v) = (q_v.cross(w_rel) + q_4 * w_rel).scale(0.5) + q_v.scale(1.0 - n2);
                        der(q_4) = -0.5 * q_v.dot(w_rel) + q_4 * (1.0 - n2);
                    }
                }
                branch(frame_a.R, frame_b.R);
                if rooted(frame_a.R) {
                    frame_b.R = absolute_rotation(&frame_a.R, &r_rel);
                    Vec3::zero() = frame_a.f + resolve1(&r_rel, frame_b.f);
                } else {
                    frame_a.R = absolute_rotation(&frame_b.R, &inverse_rotation(&r_rel));
                    Vec3::zero() = frame_b.f + resolve2(&r_rel, frame_a.f);
                }
            } else {
                Vec3::zero() = frame_a.f + resolve_relative(frame_b.f, &frame_b.R, &frame_a.R);
                phi = Vec3::zero();
                phi_d = Vec3::zero();
                phi_dd = Vec3::zero();
                w_rel = Vec3::zero();
                q_v = Vec3::zero();
                q_4 = 1.0;
            }
        }
    }
}

component! {
    /// Free motion of `frame_b` relative to `frame_a` (MSL `Joints.FreeMotion`): six
    /// degrees of freedom, with the relative position, its derivative and the relative
    /// orientation (Cardan angles or a quaternion) as states. No forces act.
    #[type_name = "MultiBody.Joints.FreeMotion"]
    pub struct FreeMotion {
        /// Orientation states (MSL `useQuaternions`; default a quaternion).
        structural orientation_states: OrientationStates = OrientationStates::Quaternion;
        /// Axis sequence of the angles (MSL `sequence_angleStates`), default {1, 2, 3}.
        structural sequence: [usize; 3] = [1, 2, 3];
        /// Start orientation: angles about the axes of `sequence_start` that rotate
        /// `frame_a` into `frame_b` \[rad\], default {0, 0, 0} (MSL `angles_start`).
        structural angles_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Axis sequence of `angles_start`, default {1, 2, 3} (MSL `sequence_start`).
        structural sequence_start: [usize; 3] = [1, 2, 3];
        /// Whether the start orientation is fixed at initialization, default false (MSL
        /// `angles_fixed`).
        structural angles_fixed: bool = false;
        /// Start angular velocity of `frame_b` relative to `frame_a`, resolved in
        /// `frame_a` \[rad/s\], default {0, 0, 0} (MSL `w_rel_a_start`). A start value
        /// of `w_rel_b` (and of the angle rates with Cardan angles); with quaternions
        /// the velocity states are usually the body's `w_a`, so set `w_rel_a_fixed` to
        /// impose it.
        structural w_rel_a_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Whether `w_rel_a_start` is fixed at initialization, default false (MSL
        /// `w_rel_a_fixed`).
        structural w_rel_a_fixed: bool = false;
        /// Start angular acceleration of `frame_b` relative to `frame_a`, resolved in
        /// `frame_a` \[rad/s2\], default {0, 0, 0} (MSL `z_rel_a_start`).
        structural z_rel_a_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Whether `z_rel_a_start` is fixed at initialization, default false (MSL
        /// `z_rel_a_fixed`).
        structural z_rel_a_fixed: bool = false;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        /// Position of `frame_b` relative to `frame_a`, resolved in `frame_a` \[m\].
        variable r_rel_a(state_priority = ENFORCED): Vec3;
        /// `der(r_rel_a)` \[m/s\].
        variable v_rel_a(state_priority = ENFORCED): Vec3;
        /// `der(v_rel_a)` \[m/s2\].
        variable a_rel_a: Vec3;
        /// Angles rotating `frame_a` into `frame_b` (Cardan states) \[rad\].
        variable phi(start = given(StartOrientation::new(sequence_start, angles_start, sequence, w_rel_a_start, z_rel_a_start).phi), fixed = angles_fixed && orientation_states == OrientationStates::Cardan, state_priority = ENFORCED): Vec3;
        /// Derivatives of the angles \[rad/s\].
        variable phi_d(start = given(StartOrientation::new(sequence_start, angles_start, sequence, w_rel_a_start, z_rel_a_start).phi_d), state_priority = ENFORCED): Vec3;
        /// Second derivatives of the angles \[rad/s2\].
        variable phi_dd: Vec3;
        /// Angular velocity of `frame_b` relative to `frame_a`, resolved in `frame_b`
        /// \[rad/s\].
        variable w_rel_b(start = given(StartOrientation::new(sequence_start, angles_start, sequence, w_rel_a_start, z_rel_a_start).w), fixed = w_rel_a_fixed, state_priority = ENFORCED): Vec3;
        /// Vector part of the relative quaternion (quaternion states).
        variable q_v(start = given(StartOrientation::new(sequence_start, angles_start, sequence, w_rel_a_start, z_rel_a_start).q_v()), fixed = angles_fixed && orientation_states == OrientationStates::Quaternion, state_priority = ENFORCED): Vec3;
        /// Scalar part of the relative quaternion.
        variable q_4(start = StartOrientation::new(sequence_start, angles_start, sequence, w_rel_a_start, z_rel_a_start).q[3], fixed = angles_fixed && orientation_states == OrientationStates::Quaternion, state_priority = ENFORCED): Real;
        initial_equation {
            if z_rel_a_fixed {
                der(w_rel_b) = Vec3::constant(StartOrientation::new(sequence_start, angles_start, sequence, w_rel_a_start, z_rel_a_start).z);
            }
        }
        equation {
            assert(valid_sequence(sequence), invalid_sequence("sequence", sequence));
            assert(
                valid_sequence(sequence_start),
                invalid_sequence("sequence_start", sequence_start)
            );
            v_rel_a = der(r_rel_a);
            a_rel_a = der(v_rel_a);
            frame_b.r_0 = frame_a.r_0 + resolve1(&frame_a.R, r_rel_a);
            frame_a.f = Vec3::zero();
            frame_a.t = Vec3::zero();
            frame_b.f = Vec3::zero();
            frame_b.t = Vec3::zero();
            let n2 = q_v.dot(q_v) + q_4 * q_4;
            let r_rel = relative_orientation(orientation_states, crate::frames::usable_sequence(sequence), phi, phi_d, q_v, q_4, w_rel_b);
            match orientation_states {
                OrientationStates::Cardan => {
                    phi_d = der(phi);
                    phi_dd = der(phi_d);
                    q_v = Vec3::zero();
                    q_4 = 1.0;
                    w_rel_b = r_rel.w;
                }
                OrientationStates::Quaternion => {
                    phi = Vec3::zero();
                    phi_d = Vec3::zero();
                    phi_dd = Vec3::zero();
                    der(q_v) = (q_v.cross(w_rel_b) + q_4 * w_rel_b).scale(0.5) + q_v.scale(1.0 - n2);
                    der(q_4) = -0.5 * q_v.dot(w_rel_b) + q_4 * (1.0 - n2);
                }
            }
            branch(frame_a.R, frame_b.R);
            if rooted(frame_a.R) {
                frame_b.R = absolute_rotation(&frame_a.R, &r_rel);
            } else {
                frame_a.R = absolute_rotation(&frame_b.R, &inverse_rotation(&r_rel));
            }
        }
    }
}
