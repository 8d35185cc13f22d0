//! The ideal rolling wheel (MSL `Joints.RollingWheel`): a wheel rolling without slip on
//! the ground plane z = 0.

use crate::frames::{Vec3, angular_velocity1, axes_rotations, resolve1, resolve2};
use crate::interfaces::Frame;
use crate::prelude::*;

/// The priority of the wheel's coordinates as states (MSL `StateSelect.always`).
const WHEEL_STATE_PRIORITY: f64 = 1000.0;

component! {
    /// A massless joint for a wheel of `radius` rolling without slip on the ground plane
    /// z = 0 (MSL `Joints.RollingWheel`; the world's gravity must be along -z, `n =
    /// [0, 0, -1]`). `frame_a` is fixed in the wheel's centre and turns with it; the
    /// wheel's axle is its y axis. The joint is a root of the orientation graph: its
    /// coordinates are the centre's `x` and `y` and the `angles` (yaw about z, lean
    /// about the turned x axis, spin about the axle: sequence {3, 1, 2}, singular only
    /// for a wheel lying flat, where MSL's {3, 2, 1} is singular every half turn of an
    /// upright wheel). One holonomic constraint keeps the wheel on the ground (the
    /// centre's height `z`), two non-holonomic ones keep the contact point at rest; the
    /// contact force has normal, lateral and longitudinal parts.
    #[type_name = "MultiBody.Joints.RollingWheel"]
    pub struct RollingWheel {
        /// Radius of the wheel \[m\], default 0.3.
        parameter radius(min = 0.0): f64 = 0.3;
        /// Start value of `x` \[m\], default 0.
        structural x_start: f64 = 0.0;
        /// Start value of `y` \[m\], default 0.
        structural y_start: f64 = 0.0;
        /// Start values of the angles \[rad\], default 0.
        structural angles_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Start values of the angles' rates \[rad/s\], default 0.
        structural der_angles_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Whether the start values are fixed (default false; `parts::RollingWheel`
        /// fixes them, as MSL's).
        structural fixed_start: bool = false;
        /// Priority of the coordinates as states (default: always states).
        structural state_priority: f64 = WHEEL_STATE_PRIORITY;
        /// The wheel's centre (y axis: the axle).
        connector frame_a: Frame;
        /// x coordinate of the centre \[m\].
        variable x(start = x_start, fixed = fixed_start, state_priority = state_priority): Real;
        /// y coordinate of the centre \[m\].
        variable y(start = y_start, fixed = fixed_start, state_priority = state_priority): Real;
        /// Height of the centre \[m\].
        variable z: Real;
        /// Heading: rotation about z \[rad\].
        variable yaw(start = angles_start[0], fixed = fixed_start, state_priority = state_priority): Real;
        /// Lean: rotation about the turned x axis \[rad\].
        variable lean(start = angles_start[1], fixed = fixed_start, state_priority = state_priority): Real;
        /// Spin: rotation about the axle \[rad\].
        variable spin(start = angles_start[2], fixed = fixed_start, state_priority = state_priority): Real;
        /// The heading's rate \[rad/s\] (a lower priority as a state than the other
        /// rates: on a vehicle the other wheels determine it).
        variable der_yaw(start = der_angles_start[0], fixed = fixed_start, state_priority = state_priority - 1.0): Real;
        /// The lean's rate \[rad/s\].
        variable der_lean(start = der_angles_start[1], fixed = fixed_start, state_priority = state_priority): Real;
        /// The spin's rate \[rad/s\].
        variable der_spin(start = der_angles_start[2], fixed = fixed_start, state_priority = state_priority): Real;
        /// Yaw, lean and spin \[rad\].
        variable angles: Vec3;
        /// Their rates \[rad/s\].
        variable der_angles: Vec3;
        /// The contact point on the ground, resolved in world \[m\].
        variable r_road_0: Vec3;
        /// The contact force on the wheel, resolved in world \[N\].
        variable f_wheel_0: Vec3;
        /// Normal contact force \[N\].
        variable f_n: Real;
        /// Lateral contact force \[N\].
        variable f_lat: Real;
        /// Longitudinal contact force (along the wheel's plane on the ground, backwards
        /// for a wheel rolling forwards about +y) \[N\].
        variable f_long: Real;
        /// From the centre to the contact point, resolved in world \[m\].
        variable delta_0: Vec3;
        /// Velocity of the centre, resolved in world \[m/s\].
        variable v_0: Vec3;
        equation {
            root(frame_a.R);
            frame_a.r_0 = Vec3::new(x, y, z);
            angles = Vec3::new(yaw, lean, spin);
            der_angles = Vec3::new(der_yaw, der_lean, der_spin);
            der_yaw = der(yaw);
            der_lean = der(lean);
            der_spin = der(spin);
            frame_a.R = axes_rotations([3, 1, 2], angles.0, der_angles.0);
            // The axle is (-sin(yaw) cos(lean), cos(yaw) cos(lean), sin(lean)); the contact
            // point lies below the centre in the wheel's plane, at `radius` along the
            // plane's steepest descent; the wheel's plane meets the ground along e_long.
            delta_0 = Vec3::new(sin(lean) * sin(yaw), -sin(lean) * cos(yaw), cos(lean)).scale(-radius);
            let e_long_0 = Vec3::new(-cos(yaw), -sin(yaw), 0.0);
            let e_lat_0 = Vec3::new(-sin(yaw), cos(yaw), 0.0);
            // One holonomic constraint: the wheel touches the ground.
            z = radius * cos(lean);
            r_road_0 = frame_a.r_0 + delta_0;
            // Two non-holonomic ones: the contact point does not slip.
            v_0 = der(frame_a.r_0);
            let w_0 = angular_velocity1(&frame_a.R);
            let v_contact = v_0 + w_0.cross(delta_0);
            // (Along world x and y, which span the same plane as e_long and e_lat: the
            // centre's velocity has a constant coefficient in each.)
            0.0 = v_contact[0];
            0.0 = v_contact[1];
            f_n = f_wheel_0[2];
            f_lat = f_wheel_0.dot(e_lat_0);
            f_long = f_wheel_0.dot(e_long_0);
            Vec3::zero() = frame_a.f + resolve2(&frame_a.R, f_wheel_0);
            Vec3::zero() = frame_a.t + resolve2(&frame_a.R, delta_0.cross(f_wheel_0));
        }
    }
}

component! {
    /// The rolling contact of a wheel whose orientation comes from elsewhere (a wheel
    /// on a vehicle, closing a kinematic loop through the ground): `frame_a` is fixed in
    /// the wheel's centre with the axle along its y axis; the wheel of `radius` touches
    /// the ground plane z = 0 (one holonomic constraint) and its contact point does not
    /// slip (two non-holonomic ones). The world's gravity must be along -z. Where the
    /// wheel is the root of its mechanism, use [`RollingWheel`] instead.
    #[type_name = "MultiBody.Joints.RollingContact"]
    pub struct RollingContact {
        /// Radius of the wheel \[m\], default 0.3.
        parameter radius(min = 0.0): f64 = 0.3;
        /// The wheel's centre (y axis: the axle).
        connector frame_a: Frame;
        /// From the centre to the contact point, resolved in world \[m\].
        variable delta_0: Vec3;
        /// The contact force on the wheel, resolved in world \[N\].
        variable f_wheel_0: Vec3;
        equation {
            let e_n_0 = Vec3::constant([0.0, 0.0, 1.0]);
            let e_axis_0 = resolve1(&frame_a.R, Vec3::constant([0.0, 1.0, 0.0]));
            // The plane's steepest descent from the centre reaches the ground `radius`
            // below it: the wheel touches the ground.
            let upright = sqrt(1.0 - e_axis_0[2] * e_axis_0[2]);
            delta_0 = (e_n_0 - e_axis_0.scale(e_axis_0[2])).scale(-radius / upright);
            frame_a.r_0[2] = radius * upright;
            // The contact point does not slip.
            let v_contact = der(frame_a.r_0) + angular_velocity1(&frame_a.R).cross(delta_0);
            0.0 = v_contact[0];
            0.0 = v_contact[1];
            Vec3::zero() = frame_a.f + resolve2(&frame_a.R, f_wheel_0);
            Vec3::zero() = frame_a.t + resolve2(&frame_a.R, delta_0.cross(f_wheel_0));
        }
    }
}
