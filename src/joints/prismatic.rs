//! The prismatic joint.

use super::{JOINT_STATE_PRIORITY, invalid_axis, unit_axis, valid_axis};
use crate::frames::{Vec3, equality_constraint, resolve1};
use crate::interfaces::Frame;
use crate::prelude::*;
use crate::translational;

component! {
    /// A joint translating `frame_b` relative to `frame_a` along the axis `n` by the
    /// distance `s` (MSL `Joints.Prismatic`); both frames keep the same orientation. The
    /// `axis` flange carries the driving force `f` (0 when nothing is connected to it)
    /// and the `support` flange is fixed at position 0. With `iscut` the joint closes a
    /// kinematic loop.
    #[type_name = "MultiBody.Joints.Prismatic"]
    pub struct Prismatic {
        /// Translation axis, resolved in `frame_a` (and `frame_b`).
        structural n: [f64; 3] = [1.0, 0.0, 0.0];
        /// Start value of the distance \[m\].
        structural s_start: f64 = 0.0;
        /// Start value of the velocity \[m/s\].
        structural v_start: f64 = 0.0;
        /// Priority of `s` and `v` as states.
        structural state_priority: f64 = JOINT_STATE_PRIORITY;
        /// The joint is a cut of a kinematic loop.
        structural iscut: bool = false;
        /// Whether the 1-D flanges are meant to be connected (they always exist).
        structural axisflange: bool = false;
        /// Width of the box when rendered \[m\].
        structural width: f64 = 0.05;
        /// Colour when rendered, RGB in 0..1 (MSL's joint colour, red).
        structural color: [f64; 3] = crate::render::JOINT_COLOR;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        /// Driving flange: its position is `s`, its force `f`.
        connector axis: translational::Flange;
        /// Housing flange, fixed at position 0.
        connector support: translational::Flange;
        /// Distance from `frame_a` to `frame_b` along `n` \[m\].
        variable s(start = s_start, state_priority = state_priority): Real;
        /// Velocity `der(s)` \[m/s\].
        variable v(start = v_start, state_priority = state_priority): Real;
        /// Acceleration `der(v)` \[m/s2\].
        variable a: Real;
        /// Driving force in the direction of the axis \[N\].
        variable f: Real;
        equation {
            assert(valid_axis(n), invalid_axis("n", n));
            let e = unit_axis(n);
            v = der(s);
            a = der(v);
            frame_b.r_0 = frame_a.r_0 + resolve1(&frame_a.R, e.scale(s));
            if iscut {
                Vec3::zero() = equality_constraint(&frame_a.R, &frame_b.R);
            } else {
                branch(frame_a.R, frame_b.R);
                frame_b.R = frame_a.R;
            }
            Vec3::zero() = frame_a.f + frame_b.f;
            Vec3::zero() = frame_a.t + frame_b.t + e.scale(s).cross(frame_b.f);
            f = -e.dot(frame_b.f);
            axis.s = s;
            axis.f = f;
            support.s = 0.0;
        }
    }
}
