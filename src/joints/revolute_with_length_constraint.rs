//! The revolute joint of joint assemblies whose angle follows from a length constraint
//! in closed form (MSL `Joints.Internal.RevoluteWithLengthConstraint`).

use crate::blocks::RealInput3;
use crate::frames::{Vec3, absolute_rotation, planar_rotation, resolve1};
use crate::interfaces::Frame;
use crate::prelude::*;
use crate::rotational;

/// The coefficients `(A, B, C)` of the length constraint `A cos(angle) + B sin(angle) + C
/// = 0` of a rotation by `angle` about the unit axis `e` (frames with a common origin):
/// the point `r_a` (resolved in `frame_a`) and the point `r_b` (resolved in `frame_b`)
/// are `length` apart.
fn length_constraint_coefficients(e: Vec3, r_a: Vec3, r_b: Vec3, length: Expr) -> [Expr; 3] {
    let (ea, eb) = (e.dot(r_a), e.dot(r_b));
    let a = (r_b.dot(r_a) - eb * ea) * -2.0;
    let b = r_b.dot(e.cross(r_a)) * 2.0;
    let c = r_a.dot(r_a) + r_b.dot(r_b) - length * length - eb * ea * 2.0;
    [a, b, c]
}

/// The two solutions `(positive, negative)` of `A cos(angle) + B sin(angle) + C = 0`, in
/// (-pi, pi]. Where there is no real solution (`A^2 + B^2 < C^2`, the loop cannot close)
/// the square root is taken of 1e-12 instead (MSL `maxWithoutEvent`).
fn length_constraint_angles(a: Expr, b: Expr, c: Expr) -> (Expr, Expr) {
    let k2 = max(a * a + b * b - c * c, 1e-12).sqrt();
    let positive = atan2(-(b * c) - a * k2, -(a * c) + b * k2);
    let negative = atan2(-(b * c) + a * k2, -(a * c) - b * k2);
    (positive, negative)
}

component! {
    /// A revolute joint whose angle is not a coordinate of its own but follows
    /// analytically from one length constraint of the loop it belongs to (MSL
    /// `Joints.Internal.RevoluteWithLengthConstraint`): the point `position_a` (from
    /// `frame_a`, resolved in `frame_a`) and the point `position_b` (from `frame_b`,
    /// resolved in `frame_b`) are `lengthConstraint` apart, which for the rotation by
    /// `angle` about `n` reads `A cos(angle) + B sin(angle) + C = 0`, solved in closed
    /// form. Of its two solutions, the branch nearest `phi_offset + phi_guess` at the
    /// initial time is kept (`positiveBranch`, computed at initialization). The loop
    /// cannot close where `A^2 + B^2 < C^2` (MSL asserts `A^2 + B^2 - C^2 > 1e-10`;
    /// here the square root of the difference is bounded below by 1e-12).
    ///
    /// For joint assemblies only (`JointUSR`, `JointRRR`): the orientation is propagated
    /// from `frame_a` to `frame_b` only (`frame_a` must be on the side of the root), and
    /// the axis torque `tau` is not related to `frame_b.t` here: the assembly supplies
    /// that equation (MSL leaves it to the assembly's `constraintResidue`, to keep this
    /// model balanced). `bearing` is fixed at angle 0; with nothing connected to `axis`,
    /// `tau` is 0.
    #[type_name = "MultiBody.Joints.Internal.RevoluteWithLengthConstraint"]
    pub struct RevoluteWithLengthConstraint {
        /// Length of the constraint \[m\]: a number, or inside an assembly the
        /// expression it is bound to (MSL `lengthConstraint`, bound to the rod length
        /// parameter of `JointUSR`'s `rod1`).
        structural lengthConstraint: Expr = Expr::constant(1.0);
        /// Axis of rotation, resolved in `frame_a` (and `frame_b`); normalized here. A
        /// vector of numbers or, inside an assembly, of the parameters it is bound to
        /// (`JointUSR.n_b`).
        structural n: Vec3 = Vec3::constant([0.0, 0.0, 1.0]);
        /// Offset of the angle: `angle = phi_offset + phi` \[deg\].
        structural phi_offset: f64 = 0.0;
        /// The branch of the constraint's solution is the one whose `angle` is nearest
        /// `phi_offset + phi_guess` at the initial time \[deg\].
        structural phi_guess: f64 = 0.0;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame, rotated by `angle` about `n`.
        connector frame_b: Frame;
        /// Driving flange: its angle is `phi`, its torque `tau`.
        connector axis: rotational::Flange;
        /// Housing flange, fixed at angle 0.
        connector bearing: rotational::Flange;
        /// Vector from `frame_a` to the point of the length constraint on its side,
        /// resolved in `frame_a` \[m\].
        connector position_a: RealInput3;
        /// Vector from `frame_b` to the point of the length constraint on its side,
        /// resolved in `frame_b` \[m\].
        connector position_b: RealInput3;
        /// 1 when the positive solution of the constraint is used, 0 for the negative
        /// one; computed at initialization from `phi_guess` (MSL's Boolean
        /// `positiveBranch`).
        parameter positiveBranch(fixed = false): f64 = 1.0;
        /// Rotation angle from `frame_a` to `frame_b` without the offset \[rad\]
        /// (computed from the constraint; jumps by 2 pi where `angle` passes pi, so it
        /// is a state only if nothing else can be).
        variable phi(state_priority = StateSelect::Avoid.priority()): Real;
        /// Rotation angle from `frame_a` to `frame_b` about `n`, `phi_offset + phi`, in
        /// (-pi, pi] \[rad\].
        variable angle(state_priority = StateSelect::Avoid.priority()): Real;
        /// Torque in the axis flange \[N.m\].
        variable tau: Real;
        initial_equation {
            let e = n.scale(1.0 / n.norm());
            let [a, b, c] = length_constraint_coefficients(e, position_a.into(), position_b.into(), lengthConstraint);
            let (positive, negative) = length_constraint_angles(a, b, c);
            let guess = (phi_offset + phi_guess).to_radians();
            positiveBranch = if_else(le(abs(positive - guess), abs(negative - guess)), 1.0, 0.0);
        }
        equation {
            let e = n.scale(1.0 / n.norm());
            let [a, b, c] = length_constraint_coefficients(e, position_a.into(), position_b.into(), lengthConstraint);
            let k2 = max(a * a + b * b - c * c, 1e-12).sqrt();
            let positive = gt(positiveBranch, 0.5);
            let k_cos = -(a * c) + if_else(positive, b, -b) * k2;
            let k_sin = -(b * c) + if_else(positive, -a, a) * k2;
            angle = atan2(k_sin, k_cos);
            angle = phi_offset.to_radians() + phi;
            axis.tau = tau;
            axis.phi = phi;
            bearing.phi = 0.0;
            frame_b.r_0 = frame_a.r_0;
            branch(frame_a.R, frame_b.R);
            let r_rel = planar_rotation(e, angle, der(angle));
            frame_b.R = absolute_rotation(&frame_a.R, &r_rel);
            Vec3::zero() = frame_a.f + resolve1(&r_rel, frame_b.f);
            Vec3::zero() = frame_a.t + resolve1(&r_rel, frame_b.t);
        }
    }
}
