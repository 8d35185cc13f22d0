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

component! {
    /// Two wheels (radius `R_wheel`, mass `m_wheel`, inertia `I_wheelAxis` about the
    /// axle, `I_wheelLong` across it) on an axle of length `track`, upright, rolling
    /// without slip on the ground plane z = 0 (MSL `Parts.RollingWheelSet`: a
    /// [`joints::RollingWheelSet`] and a body at each wheel's centre; the world's gravity
    /// along -z). Its coordinates start at the given values, fixed (as MSL's).
    #[type_name = "MultiBody.Parts.RollingWheelSet"]
    pub struct RollingWheelSet {
        /// Radius of one wheel \[m\], default 0.3.
        structural R_wheel: f64 = 0.3;
        /// Mass of one wheel \[kg\], default 2.
        parameter m_wheel(min = 0.0): f64 = 2.0;
        /// Inertia of one wheel about the axle \[kg.m2\], default 0.06.
        parameter I_wheelAxis(min = 0.0): f64 = 0.06;
        /// Inertia of one wheel about a diameter \[kg.m2\], default 0.12.
        parameter I_wheelLong(min = 0.0): f64 = 0.12;
        /// Distance between the wheels \[m\], default 1.
        structural track: f64 = 1.0;
        /// Start value of `x` \[m\], default 0.
        structural x_start: f64 = 0.0;
        /// Start value of `y` \[m\], default 0.
        structural y_start: f64 = 0.0;
        /// Start value of the heading `phi` \[rad\], default 0.
        structural phi_start: f64 = 0.0;
        /// Start values of the wheels' speeds \[rad/s\], default 0.
        structural der_theta_start: [f64; 2] = [0.0, 0.0];
        /// The middle of the axle (y: along the axle, z: up).
        connector frameMiddle: Frame;
        /// The centre of wheel 1 (at +track/2).
        connector frame1: Frame;
        /// The centre of wheel 2.
        connector frame2: Frame;
        /// Drive of wheel 1.
        connector axis1: crate::rotational::Flange;
        /// Drive of wheel 2.
        connector axis2: crate::rotational::Flange;
        /// Support of the drives.
        connector support: crate::rotational::Flange;
        /// The rolling contacts.
        component wheelSetJoint: joints::RollingWheelSet = joints::RollingWheelSet {
            radius: self.R_wheel, track: self.track, ..joints::RollingWheelSet::default()
        };
        /// Wheel 1's mass.
        component body1: Body = Body {
            m: self.m_wheel, I_11: self.I_wheelLong, I_22: self.I_wheelAxis, I_33: self.I_wheelLong,
            radius: 0.0, ..Body::default()
        };
        /// Wheel 2's mass.
        component body2: Body = Body {
            m: self.m_wheel, I_11: self.I_wheelLong, I_22: self.I_wheelAxis, I_33: self.I_wheelLong,
            radius: 0.0, ..Body::default()
        };
        /// x coordinate of the axle's middle \[m\].
        variable x(start = x_start, fixed = true): Real;
        /// y coordinate of the axle's middle \[m\].
        variable y(start = y_start, fixed = true): Real;
        /// Heading of the axle \[rad\].
        variable phi(start = phi_start, fixed = true): Real;
        /// Angle of wheel 1 \[rad\].
        variable theta1(start = 0.0, fixed = true): Real;
        /// Angle of wheel 2 \[rad\].
        variable theta2(start = 0.0, fixed = true): Real;
        /// Speed of wheel 1 \[rad/s\].
        variable der_theta1(start = der_theta_start[0], fixed = true): Real;
        /// Speed of wheel 2 \[rad/s\].
        variable der_theta2(start = der_theta_start[1], fixed = true): Real;
        equation {
            wheelSetJoint.x = x;
            wheelSetJoint.y = y;
            wheelSetJoint.phi = phi;
            wheelSetJoint.theta1 = theta1;
            wheelSetJoint.theta2 = theta2;
            der_theta1 = der(theta1);
            der_theta2 = der(theta2);
            connect(body1.frame_a, frame1);
            connect(body2.frame_a, frame2);
            connect(wheelSetJoint.frame1, frame1);
            connect(wheelSetJoint.frame2, frame2);
            connect(wheelSetJoint.axis1, axis1);
            connect(wheelSetJoint.axis2, axis2);
            connect(wheelSetJoint.support, support);
            connect(wheelSetJoint.frameMiddle, frameMiddle);
        }
    }
}
