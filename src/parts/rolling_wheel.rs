//! The ideal rolling wheel with its mass (MSL `Parts.RollingWheel`).

use crate::interfaces::Frame;
use crate::joints;
use crate::parts::Body;
use crate::prelude::*;

component! {
    /// A wheel of `radius`, mass `m` and inertia `I_axis` about its axle (`I_long`
    /// across it) rolling without slip on the ground plane z = 0 (MSL
    /// `Parts.RollingWheel`: a [`joints::RollingWheel`] and a body at its centre; the
    /// world's gravity must be along -z). Its coordinates start at the given values,
    /// fixed (as MSL's): the centre's velocity follows from the rolling.
    #[type_name = "MultiBody.Parts.RollingWheel"]
    pub struct RollingWheel {
        /// Radius \[m\], default 0.3.
        parameter radius(min = 0.0): f64 = 0.3;
        /// Mass \[kg\], default 2.
        parameter m(min = 0.0): f64 = 2.0;
        /// Inertia about the axle \[kg.m2\], default 0.06.
        parameter I_axis(min = 0.0): f64 = 0.06;
        /// Inertia about a diameter \[kg.m2\], default 0.12.
        parameter I_long(min = 0.0): f64 = 0.12;
        /// Start value of the centre's x \[m\], default 0.
        structural x_start: f64 = 0.0;
        /// Start value of the centre's y \[m\], default 0.
        structural y_start: f64 = 0.0;
        /// Start values of yaw, lean and spin \[rad\] (see [`joints::RollingWheel`]),
        /// default 0.
        structural angles_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Start values of their rates \[rad/s\], default 0.
        structural der_angles_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// The wheel's centre (y axis: the axle; it turns with the wheel, so connect a
        /// carrier through a revolute joint about y).
        connector frame_a: Frame;
        /// The rolling contact.
        component rollingWheel: joints::RollingWheel = joints::RollingWheel {
            radius: self.radius,
            x_start: self.x_start,
            y_start: self.y_start,
            angles_start: self.angles_start,
            der_angles_start: self.der_angles_start,
            fixed_start: true,
            ..joints::RollingWheel::default()
        };
        /// The wheel's mass.
        component body: Body = Body {
            m: self.m, I_11: self.I_long, I_22: self.I_axis, I_33: self.I_long,
            radius: 0.0, ..Body::default()
        };
        equation {
            connect(rollingWheel.frame_a, frame_a);
            connect(body.frame_a, frame_a);
        }
    }
}
