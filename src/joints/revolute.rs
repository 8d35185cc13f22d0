//! The revolute joint.

use super::{JOINT_STATE_PRIORITY, invalid_axis, plane_basis, unit_axis, valid_axis};
use crate::frames::{
    Vec3, absolute_rotation, equality_constraint, planar_rotation, resolve1, resolve2,
};
use crate::interfaces::Frame;
use crate::prelude::*;
use crate::rotational;

component! {
    /// A joint rotating `frame_b` relative to `frame_a` about the axis `n` by the angle
    /// `phi` (MSL `Joints.Revolute`). The `axis` flange carries the driving torque `tau`
    /// (0 when nothing is connected to it) and the `support` flange is fixed at angle 0,
    /// so 1-D components (dampers, motors) act on the joint through them. With `iscut`
    /// the joint closes a kinematic loop with three orientation residues instead of
    /// relating the orientations of its frames.
    #[type_name = "MultiBody.Joints.Revolute"]
    pub struct Revolute {
        /// Rotation axis, resolved in `frame_a` (and `frame_b`).
        structural n: [f64; 3] = [0.0, 0.0, 1.0];
        /// Offset of the rotation angle: the joint turns by `phi_offset + phi`, its axis
        /// flange by `phi` [rad], default 0.
        parameter phi_offset: f64 = 0.0;
        /// Start value of the angle \[rad\].
        structural phi_start: f64 = 0.0;
        /// Start value of the angular velocity \[rad/s\].
        structural w_start: f64 = 0.0;
        /// Priority of `phi` and `w` as states.
        structural state_priority: f64 = JOINT_STATE_PRIORITY;
        /// The joint is a cut of a kinematic loop.
        structural iscut: bool = false;
        /// With `iscut`: the joint closes a *planar* loop, so only the position in the
        /// plane normal to `n` and the rotation about `n` are constrained; the force along
        /// `n` and the torques across it are zero (what `PlanarLoops::RemoveRedundant`
        /// sets on one joint of a planar loop).
        structural planar_cut: bool = false;
        /// Whether the 1-D flanges are meant to be connected (they always exist).
        structural axisflange: bool = false;
        /// Radius when rendered \[m\].
        structural radius: f64 = 0.05;
        /// Length when rendered \[m\].
        structural length: f64 = 0.1;
        /// Colour when rendered, RGB in 0..1 (MSL's joint colour, red).
        structural color: [f64; 3] = crate::render::JOINT_COLOR;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        /// Driving flange: its angle is `phi`, its torque `tau`.
        connector axis: rotational::Flange;
        /// Housing flange, fixed at angle 0.
        connector support: rotational::Flange;
        /// Rotation angle from `frame_a` to `frame_b` about `n` \[rad\].
        variable phi(start = phi_start, state_priority = state_priority): Real;
        /// Angular velocity `der(phi)` \[rad/s\].
        variable w(start = w_start, state_priority = state_priority): Real;
        /// Angular acceleration `der(w)` \[rad/s2\].
        variable a: Real;
        /// Driving torque in the direction of the axis \[N.m\].
        variable tau: Real;
        equation {
            assert(valid_axis(n), invalid_axis("n", n));
            let e = unit_axis(n);
            w = der(phi);
            a = der(w);
            if iscut && planar_cut {
                let (ex, ey) = plane_basis(e);
                let r_rel = planar_rotation(e, phi + phi_offset, w);
                let r_rel_a = resolve2(&frame_a.R, frame_b.r_0 - frame_a.r_0);
                0.0 = ex.dot(r_rel_a);
                0.0 = ey.dot(r_rel_a);
                0.0 = e.dot(frame_b.f);
                0.0 = e.dot(equality_constraint(&absolute_rotation(&frame_a.R, &r_rel), &frame_b.R));
                0.0 = ex.dot(frame_b.t);
                0.0 = ey.dot(frame_b.t);
                frame_a.f = -resolve1(&r_rel, frame_b.f);
                frame_a.t = -resolve1(&r_rel, frame_b.t);
            } else if iscut {
                frame_b.r_0 = frame_a.r_0;
                let r_rel = planar_rotation(e, phi + phi_offset, w);
                Vec3::zero() = equality_constraint(&absolute_rotation(&frame_a.R, &r_rel), &frame_b.R);
                frame_a.f = -resolve1(&r_rel, frame_b.f);
                frame_a.t = -resolve1(&r_rel, frame_b.t);
            } else {
                frame_b.r_0 = frame_a.r_0;
                branch(frame_a.R, frame_b.R);
                if rooted(frame_a.R) {
                    let r_rel = planar_rotation(e, phi + phi_offset, w);
                    frame_b.R = absolute_rotation(&frame_a.R, &r_rel);
                    frame_a.f = -resolve1(&r_rel, frame_b.f);
                    frame_a.t = -resolve1(&r_rel, frame_b.t);
                } else {
                    let r_rel = planar_rotation(-e, phi + phi_offset, w);
                    frame_a.R = absolute_rotation(&frame_b.R, &r_rel);
                    frame_b.f = -resolve1(&r_rel, frame_a.f);
                    frame_b.t = -resolve1(&r_rel, frame_a.t);
                }
            }
            tau = -e.dot(frame_b.t);
            axis.phi = phi;
            axis.tau = tau;
            support.phi = 0.0;
        }
    }
}
