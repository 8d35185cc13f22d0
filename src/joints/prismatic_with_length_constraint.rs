//! The prismatic joint of joint assemblies whose distance follows from a length
//! constraint in closed form (MSL `Joints.Internal.PrismaticWithLengthConstraint`).

use crate::blocks::RealInput3;
use crate::frames::{Vec3, resolve1};
use crate::interfaces::Frame;
use crate::prelude::*;
use crate::translational;

/// The coefficients `(B, C)` of the length constraint `d^2 + B d + C = 0` of a
/// translation by `d` along the unit axis `e` (parallel frames): the point `r_a`
/// (from `frame_a`) and the point `r_b` (from `frame_b`) are `length` apart.
fn length_constraint_coefficients(e: Vec3, r_a: Vec3, r_b: Vec3, length: Expr) -> [Expr; 2] {
    let rbra = r_b - r_a;
    [e.dot(rbra) * 2.0, rbra.dot(rbra) - length * length]
}

component! {
    /// A prismatic joint whose distance is not a coordinate of its own but follows
    /// analytically from one length constraint of the loop it belongs to (MSL
    /// `Joints.Internal.PrismaticWithLengthConstraint`): the point `position_a` (from
    /// `frame_a`, resolved in `frame_a`) and the point `position_b` (from `frame_b`,
    /// resolved in `frame_b`) are `length` apart, which for the translation by
    /// `distance` along `n` reads `distance^2 + B distance + C = 0`, solved in closed
    /// form. Of its two solutions, the branch nearest `s_offset + s_guess` at the
    /// initial time is kept (`positiveBranch`, computed at initialization). The loop
    /// cannot close where `B^2/4 < C` (MSL asserts `B^2/4 - C > 1e-10`; here the square
    /// root of the difference is bounded below by 1e-12).
    ///
    /// For joint assemblies only (`JointSSP`): the axis force `f` is not related to
    /// `frame_b.f` here; the assembly supplies that equation (MSL leaves it to the
    /// assembly's `constraintResidue`). `bearing` is fixed at position 0; with nothing
    /// connected to `axis`, `f` is 0.
    #[type_name = "MultiBody.Joints.Internal.PrismaticWithLengthConstraint"]
    pub struct PrismaticWithLengthConstraint {
        /// Length of the constraint \[m\]: a number, or inside an assembly the
        /// expression it is bound to (MSL `length`, bound to `JointSSP`'s rod length).
        structural length: Expr = Expr::constant(1.0);
        /// Axis of translation, resolved in `frame_a` (and `frame_b`); normalized here.
        structural n: Vec3 = Vec3::constant([1.0, 0.0, 0.0]);
        /// Offset of the distance: `distance = s_offset + s` \[m\].
        structural s_offset: f64 = 0.0;
        /// The branch of the constraint's solution is the one whose `distance` is
        /// nearest `s_offset + s_guess` at the initial time \[m\].
        structural s_guess: f64 = 0.0;
        /// Width of the box when rendered \[m\].
        structural width: f64 = 0.05;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame, translated by `distance` along `n`.
        connector frame_b: Frame;
        /// Driving flange: its position is `s`, its force `f`.
        connector axis: translational::Flange;
        /// Housing flange, fixed at position 0.
        connector bearing: translational::Flange;
        /// Vector from `frame_a` to the point of the length constraint on its side,
        /// resolved in `frame_a` \[m\].
        connector position_a: RealInput3;
        /// Vector from `frame_b` to the point of the length constraint on its side,
        /// resolved in `frame_b` \[m\].
        connector position_b: RealInput3;
        /// 1 when the positive solution of the constraint is used, 0 for the negative
        /// one; computed at initialization from `s_guess` (MSL's Boolean
        /// `positiveBranch`).
        parameter positiveBranch(fixed = false): f64 = 1.0;
        /// Distance from `frame_a` to `frame_b` along `n` without the offset \[m\]
        /// (computed from the constraint).
        variable s(state_priority = StateSelect::Avoid.priority()): Real;
        /// Distance from `frame_a` to `frame_b` along `n`, `s_offset + s` \[m\].
        variable distance(state_priority = StateSelect::Avoid.priority()): Real;
        /// Force in the axis flange \[N\].
        variable f: Real;
        initial_equation {
            let e = n.scale(1.0 / n.norm());
            let [b, c] = length_constraint_coefficients(e, position_a.into(), position_b.into(), length);
            let k2 = max(b * b * 0.25 - c, 1e-12).sqrt();
            let guess = s_offset + s_guess;
            let positive = -(b * 0.5) + k2;
            let negative = -(b * 0.5) - k2;
            positiveBranch = if_else(le(abs(positive - guess), abs(negative - guess)), 1.0, 0.0);
        }
        equation {
            let e = n.scale(1.0 / n.norm());
            let [b, c] = length_constraint_coefficients(e, position_a.into(), position_b.into(), length);
            let k2 = max(b * b * 0.25 - c, 1e-12).sqrt();
            distance = -(b * 0.5) + if_else(gt(positiveBranch, 0.5), k2, -k2);
            distance = s_offset + s;
            axis.f = f;
            axis.s = s;
            bearing.s = 0.0;
            let r_rel_a = e.scale(distance);
            frame_b.r_0 = frame_a.r_0 + resolve1(&frame_a.R, r_rel_a);
            branch(frame_a.R, frame_b.R);
            frame_b.R = frame_a.R;
            Vec3::zero() = frame_a.f + frame_b.f;
            Vec3::zero() = frame_a.t + frame_b.t + r_rel_a.cross(frame_b.f);
        }
    }
}
