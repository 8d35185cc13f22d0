//! The cut joint of planar loops.

use super::{invalid_axis, plane_basis, unit_axis, valid_axis};
use crate::frames::{Vec3, relative_rotation, resolve2};
use crate::interfaces::Frame;
use crate::prelude::*;

component! {
    /// A revolute joint that only constrains the two in-plane position coordinates of a
    /// planar loop (MSL `Joints.RevolutePlanarLoopConstraint`): no angle, no states, no
    /// orientation relation, no torques and no force along the axis. Replace one
    /// revolute joint of a planar loop (parallel axes) by it: the others determine the
    /// rest, and the cut forces along the axes, which cannot be computed in a planar
    /// loop, are zero.
    #[type_name = "MultiBody.Joints.RevolutePlanarLoopConstraint"]
    pub struct RevolutePlanarLoopConstraint {
        /// Axis, resolved in `frame_a` (and `frame_b`).
        structural n: [f64; 3] = [0.0, 0.0, 1.0];
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
        /// Constraint forces in the plane, along `ex_a` and `ey_a` \[N\].
        variable f_c: Vec3;
        equation {
            assert(valid_axis(n), invalid_axis("n", n));
            let e = unit_axis(n);
            let (ex_a, ey_a) = plane_basis(e);
            let r_rel = relative_rotation(&frame_a.R, &frame_b.R);
            let r_rel_a = resolve2(&frame_a.R, frame_b.r_0 - frame_a.r_0);
            0.0 = ex_a.dot(r_rel_a);
            0.0 = ey_a.dot(r_rel_a);
            frame_a.t = Vec3::zero();
            frame_b.t = Vec3::zero();
            f_c[2] = 0.0;
            frame_a.f = ex_a.scale(f_c[0]) + ey_a.scale(f_c[1]);
            frame_b.f = -resolve2(&r_rel, frame_a.f);
        }
    }
}
