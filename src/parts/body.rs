//! Rigid bodies with mass and inertia (MSL `Parts.Body`).

use super::start_orientation::{StartOrientation, given};
use crate::frames::{
    Mat3, Vec3, axes_rotations, invalid_sequence, quaternion_to_t, resolve1, resolve2,
    usable_sequence, valid_sequence,
};
use crate::interfaces::Frame;
use crate::prelude::*;
use crate::world::gravity_acceleration;

/// How a free body (the root of its mechanism) describes its orientation: MSL's
/// `useQuaternions` (true, the default: [`Quaternion`](Self::Quaternion); false:
/// [`Cardan`](Self::Cardan)).
///
/// Quaternions are never singular, so a body may tumble through every orientation.
/// Ours are not quite MSL's: MSL keeps a unit quaternion with its constraint and
/// chooses 3 of its 4 components as states dynamically (6 orientation states with
/// `w_a`); here the quaternion is not normalized by a constraint but its norm is driven
/// back to 1 by its kinematics (7 states, as Multibody.jl), which keeps the model free
/// of nonlinear systems and state switching and integrates more accurately at the same
/// tolerance. Either way the start orientation and angular velocity are best given as
/// MSL does, by `angles_start` (with `sequence_start`) and `w_0_start`, which set the
/// start values of whichever states are used. Cardan angles (`phi`, `phi_d`, 6 states)
/// are singular where the middle angle is +-90 degrees (gimbal lock); choose them when
/// the angles themselves are wanted and the motion stays away from that.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum OrientationStates {
    /// Three angles about the axes of a sequence and their derivatives: 6 states,
    /// singular where the middle rotation is +-90 degrees (gimbal lock).
    Cardan,
    /// A non-unit quaternion (4 states, no constraint: its norm is driven back to 1) and
    /// the angular velocity: 7 states, never singular (as Multibody.jl). The default,
    /// as MSL's.
    #[default]
    Quaternion,
}

/// The condition that an inertia tensor is positive semi-definite (no negative
/// principal moment): every principal minor is non-negative, with a tolerance of 1e-12
/// relative to the trace.
fn inertia_is_physical(i11: Expr, i22: Expr, i33: Expr, i21: Expr, i31: Expr, i32: Expr) -> Expr {
    let tol = (i11 + i22 + i33).abs() * 1e-12;
    let minor2 = |x: Expr, y: Expr, xy: Expr| (x * y - xy * xy).ge(-tol * tol);
    let det = i11 * (i22 * i33 - i32 * i32) - i21 * (i21 * i33 - i32 * i31)
        + i31 * (i21 * i32 - i22 * i31);
    i11.ge(-tol)
        * i22.ge(-tol)
        * i33.ge(-tol)
        * minor2(i11, i22, i21)
        * minor2(i11, i33, i31)
        * minor2(i22, i33, i32)
        * det.ge(-tol * tol * tol)
}

component! {
    /// A rigid body with mass and inertia (MSL `Parts.Body`): Newton and Euler equations
    /// at `frame_a`. When nothing else determines its orientation (a free body), it is
    /// the root of its mechanism and carries orientation states (Cardan angles or a
    /// quaternion).
    #[type_name = "MultiBody.Parts.Body"]
    pub struct Body {
        /// Mass \[kg\] (at least 0).
        parameter m(min = 0.0): f64 = 1.0;
        /// Vector from `frame_a` to the centre of mass, resolved in `frame_a` \[m\].
        parameter r_CM: [f64; 3] = [0.0, 0.0, 0.0];
        /// Inertia about the centre of mass, element (1,1), axes parallel to `frame_a` \[kg.m2\].
        parameter I_11: f64 = 0.001;
        /// Element (2,2) of the inertia \[kg.m2\].
        parameter I_22: f64 = 0.001;
        /// Element (3,3) of the inertia \[kg.m2\].
        parameter I_33: f64 = 0.001;
        /// Element (2,1) of the inertia \[kg.m2\].
        parameter I_21: f64 = 0.0;
        /// Element (3,1) of the inertia \[kg.m2\].
        parameter I_31: f64 = 0.0;
        /// Element (3,2) of the inertia \[kg.m2\].
        parameter I_32: f64 = 0.0;
        /// Orientation states when the body is a root (MSL `useQuaternions`; default
        /// a quaternion, see [`OrientationStates`]).
        structural orientation_states: OrientationStates = OrientationStates::Quaternion;
        /// Axis sequence of the Cardan angles (MSL `sequence_angleStates`), default
        /// {1, 2, 3}.
        structural sequence_angle_states: [usize; 3] = [1, 2, 3];
        /// Start orientation: angles about the axes of `sequence_start` that rotate the
        /// world frame into `frame_a` \[rad\], default {0, 0, 0} (MSL `angles_start`).
        /// The start values of the orientation states (angles or quaternion) follow
        /// from it.
        structural angles_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Axis sequence of `angles_start`, default {1, 2, 3} (MSL `sequence_start`).
        structural sequence_start: [usize; 3] = [1, 2, 3];
        /// Whether the start orientation is fixed at initialization, default false (MSL
        /// `angles_fixed`; for a body that is the root of its orientation, a free body).
        structural angles_fixed: bool = false;
        /// Start angular velocity of `frame_a`, resolved in world \[rad/s\], default
        /// {0, 0, 0} (MSL `w_0_start`).
        structural w_0_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Whether `w_0_start` is fixed at initialization, default false (MSL `w_0_fixed`).
        structural w_0_fixed: bool = false;
        /// Start angular acceleration of `frame_a`, resolved in world \[rad/s2\], default
        /// {0, 0, 0} (MSL `z_0_start`).
        structural z_0_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Whether `z_0_start` is fixed at initialization, default false (MSL `z_0_fixed`).
        structural z_0_fixed: bool = false;
        /// Priority of `r_0` and `v_0` as states (MSL: avoid).
        structural position_state_priority: f64 = StateSelect::Avoid.priority();
        /// Priority of the orientation states (angles or quaternion) when the body is a
        /// root, default 1000 (always: MSL's `enforceStates`). Lower it for a body that
        /// no joint orients but kinematic loops hold (the platform of a parallel
        /// mechanism), whose orientation the loops determine.
        structural orientation_state_priority: f64 = StateSelect::Always.priority();
        /// Radius of the sphere drawn at the centre of mass \[m\] (0 hides it).
        structural radius: f64 = 0.05;
        /// Colour of the sphere when rendered, RGB in 0..1 (MSL's body colour).
        structural color: [f64; 3] = crate::render::BODY_COLOR;
        /// The frame the body is fixed to.
        connector frame_a: Frame;
        /// Position of `frame_a`, resolved in world \[m\].
        variable r_0(state_priority = position_state_priority): Vec3;
        /// Velocity of `frame_a`, resolved in world \[m/s\].
        variable v_0(state_priority = position_state_priority): Vec3;
        /// Acceleration of `frame_a`, resolved in world \[m/s2\].
        variable a_0: Vec3;
        /// Angular velocity, resolved in `frame_a` \[rad/s\].
        variable w_a(start = given(StartOrientation::new(sequence_start, angles_start, sequence_angle_states, w_0_start, z_0_start).w), fixed = w_0_fixed, state_priority = StateSelect::Avoid.priority()): Vec3;
        /// Angular acceleration, resolved in `frame_a` \[rad/s2\].
        variable z_a(start = given(StartOrientation::new(sequence_start, angles_start, sequence_angle_states, w_0_start, z_0_start).z), fixed = z_0_fixed): Vec3;
        /// Gravity acceleration at the centre of mass, resolved in world \[m/s2\].
        variable g_0: Vec3;
        /// Orientation angles when the body is a root (0 otherwise) \[rad\].
        variable phi(start = given(StartOrientation::new(sequence_start, angles_start, sequence_angle_states, w_0_start, z_0_start).phi), fixed = angles_fixed && orientation_states == OrientationStates::Cardan, state_priority = orientation_state_priority): Vec3;
        /// Derivatives of the angles \[rad/s\].
        variable phi_d(start = given(StartOrientation::new(sequence_start, angles_start, sequence_angle_states, w_0_start, z_0_start).phi_d), state_priority = orientation_state_priority): Vec3;
        /// Second derivatives of the angles \[rad/s2\].
        variable phi_dd: Vec3;
        /// Vector part of the quaternion when the body is a root (0 otherwise).
        variable q_v(start = given(StartOrientation::new(sequence_start, angles_start, sequence_angle_states, w_0_start, z_0_start).q_v()), fixed = angles_fixed && orientation_states == OrientationStates::Quaternion, state_priority = orientation_state_priority): Vec3;
        /// Scalar part of the quaternion when the body is a root (1 otherwise).
        variable q_4(start = StartOrientation::new(sequence_start, angles_start, sequence_angle_states, w_0_start, z_0_start).q[3], fixed = angles_fixed && orientation_states == OrientationStates::Quaternion, state_priority = orientation_state_priority): Real;
        equation {
            assert(
                valid_sequence(sequence_start),
                invalid_sequence("sequence_start", sequence_start)
            );
            assert(
                valid_sequence(sequence_angle_states),
                invalid_sequence("sequence_angle_states", sequence_angle_states)
            );
            assert(
                inertia_is_physical(I_11, I_22, I_33, I_21, I_31, I_32),
                "the inertia (I_11, I_22, I_33, I_21, I_31, I_32) must be positive semi-definite"
            );
            let inertia = Mat3([[I_11, I_21, I_31], [I_21, I_22, I_32], [I_31, I_32, I_33]]);
            r_0 = frame_a.r_0;
            potential_root(frame_a.R);
            if is_root(frame_a.R) {
                match orientation_states {
                    OrientationStates::Cardan => {
                        phi_d = der(phi);
                        phi_dd = der(phi_d);
                        frame_a.R = axes_rotations(usable_sequence(sequence_angle_states), phi.0, phi_d.0);
                        q_v = Vec3::zero();
                        q_4 = 1.0;
                    }
                    OrientationStates::Quaternion => {
                        phi = Vec3::zero();
                        phi_d = Vec3::zero();
                        phi_dd = Vec3::zero();
                        let n2 = q_v.dot(q_v) + q_4 * q_4;
                        let n = n2.sqrt();
                        frame_a.R.T = quaternion_to_t([q_v[0] / n, q_v[1] / n, q_v[2] / n, q_4 / n]);
                        // Kinematics of a non-unit quaternion, with a term that drives its
                        // norm back to 1 (it is orthogonal to the rotation part).
                        der(q_v) = (q_v.cross(w_a) + q_4 * w_a).scale(0.5) + q_v.scale(1.0 - n2);
                        der(q_4) = -0.5 * q_v.dot(w_a) + q_4 * (1.0 - n2);
                    }
                }
            } else {
                phi = Vec3::zero();
                phi_d = Vec3::zero();
                phi_dd = Vec3::zero();
                q_v = Vec3::zero();
                q_4 = 1.0;
            }
            g_0 = gravity_acceleration(frame_a.r_0 + resolve1(&frame_a.R, r_CM));
            v_0 = der(r_0);
            a_0 = der(v_0);
            w_a = frame_a.R.w;
            z_a = der(w_a);
            frame_a.f = (resolve2(&frame_a.R, a_0 - g_0) + z_a.cross(r_CM) + w_a.cross(w_a.cross(r_CM))).scale(m);
            frame_a.t = inertia * z_a + w_a.cross(inertia * w_a) + r_CM.cross(frame_a.f);
        }
    }
}
