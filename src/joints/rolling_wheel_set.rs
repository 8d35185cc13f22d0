//! The ideal rolling wheel set (MSL `Joints.RollingWheelSet`): two upright wheels on a
//! common axle rolling without slip on the ground plane z = 0.

use super::{Prismatic, Revolute};
use crate::frames::{Vec3, angular_velocity1, resolve1, resolve2};
use crate::interfaces::Frame;
use crate::parts::{Fixed, FixedTranslation, Mounting1D};
use crate::prelude::*;
use crate::rotational::Flange;

/// The joints inside do not compete for states: the wheel set's coordinates do.
const NEVER: f64 = -100.0;
/// The priority of the wheel set's position and heading as states.
const SET_STATE_PRIORITY: f64 = 100.0;
/// The priority of the wheels' angles and speeds: above the position's, so that the
/// wheels' speeds are the velocity states (the rolling constraints then give the
/// axle's velocity; the other way round, the lateral constraint would be singular).
const WHEEL_STATE_PRIORITY: f64 = 1000.0;

component! {
    /// The rolling constraint of an upright wheel whose centre is `frame_a` (y axis: the
    /// axle) on the ground plane z = 0 (MSL
    /// `Joints.Internal.RollingConstraintVerticalWheel`): the contact point, `radius`
    /// below the centre, does not slip along the wheel, nor across it with
    /// `lateral_sliding_constraint` (else the lateral force is 0, for the second wheel
    /// of an axle). The wheel's height and uprightness come from elsewhere.
    #[type_name = "MultiBody.Joints.Internal.RollingConstraintVerticalWheel"]
    pub struct RollingConstraintVerticalWheel {
        /// Radius of the wheel \[m\], default 0.3.
        parameter radius(min = 0.0): f64 = 0.3;
        /// Whether the wheel does not slide across (default true).
        structural lateral_sliding_constraint: bool = true;
        /// The wheel's centre.
        connector frame_a: Frame;
        /// The contact force on the wheel, resolved in world \[N\].
        variable f_wheel_0: Vec3;
        /// Lateral contact force \[N\].
        variable f_lat: Real;
        /// Longitudinal contact force \[N\].
        variable f_long: Real;
        equation {
            let e_n_0 = Vec3::constant([0.0, 0.0, 1.0]);
            let e_axis_0 = resolve1(&frame_a.R, Vec3::constant([0.0, 1.0, 0.0]));
            let aux = e_n_0.cross(e_axis_0);
            let e_long_0 = aux.scale(1.0 / sqrt(aux.dot(aux)));
            let e_lat_0 = e_long_0.cross(e_n_0);
            let r_contact_0 = Vec3::constant([0.0, 0.0, -1.0]).scale(radius);
            let v_contact_0 = der(frame_a.r_0) + angular_velocity1(&frame_a.R).cross(r_contact_0);
            0.0 = v_contact_0.dot(e_long_0);
            if lateral_sliding_constraint {
                0.0 = v_contact_0.dot(e_lat_0);
                f_wheel_0 = e_lat_0.scale(f_lat) + e_long_0.scale(f_long);
            } else {
                f_lat = 0.0;
                f_wheel_0 = e_long_0.scale(f_long);
            }
            Vec3::zero() = frame_a.f + resolve2(&frame_a.R, f_wheel_0);
            Vec3::zero() = frame_a.t + resolve2(&frame_a.R, r_contact_0.cross(f_wheel_0));
        }
    }
}

component! {
    /// A massless joint for two upright wheels of `radius` on an axle of length `track`
    /// rolling without slip on the ground plane z = 0 (MSL `Joints.RollingWheelSet`;
    /// the world's gravity along -z): `frameMiddle` moves in the plane z = `radius`
    /// (coordinates `x`, `y` and the heading `phi`), the wheels turn about the axle (y)
    /// by `theta1` (`frame1`, at +track/2) and `theta2` (`frame2`), driven through
    /// `axis1` and `axis2` with their reactions on `support` (mounted on `frameMiddle`).
    /// Five coordinates, two velocities free.
    #[type_name = "MultiBody.Joints.RollingWheelSet"]
    pub struct RollingWheelSet {
        /// Radius of one wheel \[m\], default 0.3.
        structural radius: f64 = 0.3;
        /// Distance between the wheels \[m\], default 1.
        structural track: f64 = 1.0;
        /// Priority of the position and heading as states (the wheels' angles and
        /// speeds have a higher one).
        structural state_priority: f64 = SET_STATE_PRIORITY;
        /// The middle of the axle (y: along the axle, z: up).
        connector frameMiddle: Frame;
        /// The centre of wheel 1.
        connector frame1: Frame;
        /// The centre of wheel 2.
        connector frame2: Frame;
        /// Drive of wheel 1.
        connector axis1: Flange;
        /// Drive of wheel 2.
        connector axis2: Flange;
        /// Support of the drives.
        connector support: Flange;
        /// The plane the axle's middle moves in.
        component fixed: Fixed = Fixed { r: [0.0, 0.0, self.radius] };
        /// Motion along x.
        component prismatic1: Prismatic = Prismatic { n: [1.0, 0.0, 0.0], state_priority: NEVER, ..Prismatic::default() };
        /// Motion along y.
        component prismatic2: Prismatic = Prismatic { n: [0.0, 1.0, 0.0], state_priority: NEVER, ..Prismatic::default() };
        /// Heading.
        component revolute: Revolute = Revolute { n: [0.0, 0.0, 1.0], state_priority: NEVER, ..Revolute::default() };
        /// From the middle to wheel 1.
        component rod1: FixedTranslation = FixedTranslation { r: [0.0, self.track / 2.0, 0.0], radius: 0.0, ..FixedTranslation::default() };
        /// From the middle to wheel 2.
        component rod2: FixedTranslation = FixedTranslation { r: [0.0, -self.track / 2.0, 0.0], radius: 0.0, ..FixedTranslation::default() };
        /// Wheel 1 on the axle.
        component revolute1: Revolute = Revolute { n: [0.0, 1.0, 0.0], axisflange: true, state_priority: WHEEL_STATE_PRIORITY, ..Revolute::default() };
        /// Wheel 2 on the axle.
        component revolute2: Revolute = Revolute { n: [0.0, 1.0, 0.0], axisflange: true, state_priority: WHEEL_STATE_PRIORITY, ..Revolute::default() };
        /// Rolling of wheel 1.
        component rolling1: RollingConstraintVerticalWheel = RollingConstraintVerticalWheel { radius: self.radius, ..RollingConstraintVerticalWheel::default() };
        /// Rolling of wheel 2 (no lateral constraint: the axle has it from wheel 1).
        component rolling2: RollingConstraintVerticalWheel = RollingConstraintVerticalWheel {
            radius: self.radius, lateral_sliding_constraint: false, ..RollingConstraintVerticalWheel::default()
        };
        /// The drives' housing on the axle.
        component mounting1D: Mounting1D;
        /// x coordinate of the axle's middle \[m\].
        variable x(state_priority = state_priority): Real;
        /// y coordinate of the axle's middle \[m\].
        variable y(state_priority = state_priority): Real;
        /// Heading of the axle about z \[rad\].
        variable phi(state_priority = state_priority): Real;
        /// Angle of wheel 1 \[rad\].
        variable theta1(state_priority = WHEEL_STATE_PRIORITY): Real;
        /// Angle of wheel 2 \[rad\].
        variable theta2(state_priority = WHEEL_STATE_PRIORITY): Real;
        /// Speed of wheel 1 \[rad/s\].
        variable der_theta1(state_priority = WHEEL_STATE_PRIORITY): Real;
        /// Speed of wheel 2 \[rad/s\].
        variable der_theta2(state_priority = WHEEL_STATE_PRIORITY): Real;
        equation {
            prismatic1.s = x;
            prismatic2.s = y;
            revolute.phi = phi;
            revolute1.phi = theta1;
            revolute2.phi = theta2;
            der_theta1 = der(theta1);
            der_theta2 = der(theta2);
            connect(fixed.frame_b, prismatic1.frame_a);
            connect(prismatic1.frame_b, prismatic2.frame_a);
            connect(prismatic2.frame_b, revolute.frame_a);
            connect(revolute.frame_b, frameMiddle);
            connect(rod1.frame_a, frameMiddle);
            connect(rod2.frame_a, frameMiddle);
            connect(rod1.frame_b, revolute1.frame_a);
            connect(revolute1.frame_b, frame1);
            connect(rod2.frame_b, revolute2.frame_a);
            connect(revolute2.frame_b, frame2);
            connect(rolling1.frame_a, revolute1.frame_b);
            connect(rolling2.frame_a, revolute2.frame_b);
            connect(revolute1.axis, axis1);
            connect(revolute2.axis, axis2);
            connect(frameMiddle, mounting1D.frame_a);
            connect(mounting1D.flange_b, support);
        }
    }
}
