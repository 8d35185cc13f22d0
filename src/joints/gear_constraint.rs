//! The ideal gear between two shafts of any directions in a bearing (MSL
//! `Joints.GearConstraint`).

use super::{JOINT_STATE_PRIORITY, Revolute};
use crate::frames::resolve2;
use crate::interfaces::Frame;
use crate::parts::FixedTranslation;
use crate::prelude::*;
use crate::rotational::IdealGear;

/// The revolute joints inside do not compete for states: the gear's own variables do.
const NEVER: f64 = -100.0;

component! {
    /// An ideal gearbox between two shafts of any directions (MSL
    /// `Joints.GearConstraint`): `frame_a` turns about `n_a` by `phi_a` relative to the
    /// `bearing` (at `r_a` from it), `frame_b` about `n_b` by `phi_b` (at `r_b`), with
    /// `phi_a = ratio * phi_b`; massless, every reaction on the bearing. With
    /// `check_total_power`, `totalPower` is the power flowing into the gear (zero).
    #[type_name = "MultiBody.Joints.GearConstraint"]
    pub struct GearConstraint {
        /// Speed ratio `w_a / w_b` \[1\], default 2.
        parameter ratio: f64 = 2.0;
        /// Axis of shaft a (the same in `frame_a`, `frame_b` and `bearing`), default
        /// {1, 0, 0}.
        structural n_a: [f64; 3] = [1.0, 0.0, 0.0];
        /// Axis of shaft b, default {1, 0, 0}.
        structural n_b: [f64; 3] = [1.0, 0.0, 0.0];
        /// Position of `frame_a` from the bearing, resolved in it \[m\], default 0.
        parameter r_a: [f64; 3] = [0.0, 0.0, 0.0];
        /// Position of `frame_b` from the bearing, resolved in it \[m\], default 0.
        parameter r_b: [f64; 3] = [0.0, 0.0, 0.0];
        /// Priority of `phi_b` and `w_b` as states.
        structural state_priority: f64 = JOINT_STATE_PRIORITY;
        /// Start value of `phi_b` \[rad\], default 0.
        structural phi_b_start: f64 = 0.0;
        /// Start value of `w_b` \[rad/s\], default 0.
        structural w_b_start: f64 = 0.0;
        /// Whether `totalPower` is computed (default false: it is 0).
        structural check_total_power: bool = false;
        /// Shaft a.
        connector frame_a: Frame;
        /// Shaft b.
        connector frame_b: Frame;
        /// The bearing.
        connector bearing: Frame;
        /// The rotation of shaft a.
        component actuatedRevolute_a: Revolute = Revolute {
            n: self.n_a, axisflange: true, state_priority: NEVER, ..Revolute::default()
        };
        /// The rotation of shaft b.
        component actuatedRevolute_b: Revolute = Revolute {
            n: self.n_b, axisflange: true, state_priority: NEVER, ..Revolute::default()
        };
        /// The gear between the two rotations.
        component idealGear: IdealGear = IdealGear { ratio: self.ratio, ..IdealGear::default() };
        /// From the bearing to shaft b.
        component fixedTranslation1: FixedTranslation = FixedTranslation { r: self.r_b, radius: 0.0, ..FixedTranslation::default() };
        /// From the bearing to shaft a.
        component fixedTranslation2: FixedTranslation = FixedTranslation { r: self.r_a, radius: 0.0, ..FixedTranslation::default() };
        /// Angle of shaft b relative to the bearing \[rad\].
        variable phi_b(start = phi_b_start, state_priority = state_priority): Real;
        /// `der(phi_b)` \[rad/s\].
        variable w_b(start = w_b_start, state_priority = state_priority): Real;
        /// `der(w_b)` \[rad/s2\].
        variable a_b: Real;
        /// The power flowing into the gear (with `check_total_power`; else 0) \[W\].
        variable totalPower: Real;
        equation {
            phi_b = actuatedRevolute_b.phi;
            w_b = der(phi_b);
            a_b = der(w_b);
            if check_total_power {
                totalPower = frame_a.f.dot(resolve2(&frame_a.R, der(frame_a.r_0)))
                    + frame_b.f.dot(resolve2(&frame_b.R, der(frame_b.r_0)))
                    + bearing.f.dot(resolve2(&bearing.R, der(bearing.r_0)))
                    + frame_a.t.dot(frame_a.R.w)
                    + frame_b.t.dot(frame_b.R.w)
                    + bearing.t.dot(bearing.R.w);
            } else {
                totalPower = 0.0;
            }
            connect(actuatedRevolute_a.axis, idealGear.flange_a);
            connect(idealGear.flange_b, actuatedRevolute_b.axis);
            connect(actuatedRevolute_a.frame_a, fixedTranslation2.frame_b);
            connect(fixedTranslation2.frame_a, bearing);
            connect(fixedTranslation1.frame_a, bearing);
            connect(fixedTranslation1.frame_b, actuatedRevolute_b.frame_a);
            connect(frame_a, actuatedRevolute_a.frame_b);
            connect(actuatedRevolute_b.frame_b, frame_b);
        }
    }
}
