//! The robot's gearbox.

use crate::prelude::*;
use crate::rotational::{BearingFriction, Flange, IdealGear, SpringDamper};

component! {
    /// The gearbox of the robot's axes 1 to 3 (MSL `RobotR3.Utilities.GearType1`):
    /// bearing friction `Rv0 + Rv1 w` on the motor side, an elastic, damped shaft and an
    /// ideal gear of ratio `i`; starts with the shaft at rest.
    #[type_name = "RobotR3.GearType1"]
    pub struct GearType1 {
        /// Gear ratio [1], default -105.
        parameter i: f64 = -105.0;
        /// Spring constant of the shaft [N.m/rad], default 43.
        parameter c(min = 0.0): f64 = 43.0;
        /// Damping constant of the shaft [N.m.s/rad], default 0.005.
        parameter d(min = 0.0): f64 = 0.005;
        /// Viscous friction torque at zero speed [N.m], default 0.4.
        structural Rv0: f64 = 0.4;
        /// Viscous friction coefficient [N.m.s/rad], default 0.13 / 160.
        structural Rv1: f64 = 0.13 / 160.0;
        /// Maximum static friction torque over `Rv0` [1], default 1 (MSL passes it to
        /// nothing: its bearing friction keeps peak 1).
        parameter peak(min = 1.0): f64 = 1.0;
        /// Whether the shaft also starts without acceleration, `der(spring.w_rel) = 0`
        /// (MSL; default true). Where the friction sticks at the start this follows from
        /// the load's initial acceleration, and the initial equations are redundant.
        structural start_without_acceleration: bool = true;
        /// Motor side.
        connector flange_a: Flange;
        /// Load side.
        connector flange_b: Flange;
        /// Ideal gear of ratio `i`.
        component gear: IdealGear = IdealGear { ratio: self.i, ..IdealGear::default() };
        /// Elasticity and damping of the shaft.
        component spring: SpringDamper = SpringDamper { c: self.c, d: self.d, ..SpringDamper::default() };
        /// Bearing friction on the motor side.
        component bearingFriction: BearingFriction = BearingFriction {
            tau_pos: vec![[0.0, self.Rv0], [1.0, self.Rv0 + self.Rv1]],
            ..BearingFriction::default()
        };
        equation {
            connect(spring.flange_b, gear.flange_a);
            connect(bearingFriction.flange_b, spring.flange_a);
            connect(gear.flange_b, flange_b);
            connect(bearingFriction.flange_a, flange_a);
        }
        initial_equation {
            spring.w_rel = 0.0;
            if start_without_acceleration {
                der(spring.w_rel) = 0.0;
            }
        }
    }
}

component! {
    /// The gearbox of the robot's axes 4 to 6 (MSL `RobotR3.Utilities.GearType2`): an
    /// ideal gear of ratio `i`, then bearing friction `Rv0 + Rv1 w` (static up to
    /// `peak Rv0`) on the load side; rigid, without states of its own.
    #[type_name = "RobotR3.GearType2"]
    pub struct GearType2 {
        /// Gear ratio [1], default -99.
        parameter i: f64 = -99.0;
        /// Viscous friction torque at zero speed [N.m], default 21.8.
        structural Rv0: f64 = 21.8;
        /// Viscous friction coefficient [N.m.s/rad], default 9.8.
        structural Rv1: f64 = 9.8;
        /// Maximum static friction torque over `Rv0` [1], default 26.7 / 21.8.
        parameter peak(min = 1.0): f64 = 26.7 / 21.8;
        /// Motor side.
        connector flange_a: Flange;
        /// Load side.
        connector flange_b: Flange;
        /// Ideal gear of ratio `i`.
        component gear: IdealGear = IdealGear { ratio: self.i, ..IdealGear::default() };
        /// Bearing friction on the load side.
        component bearingFriction: BearingFriction = BearingFriction {
            tau_pos: vec![[0.0, self.Rv0], [1.0, self.Rv0 + self.Rv1]],
            peak: self.peak,
            ..BearingFriction::default()
        };
        equation {
            connect(gear.flange_b, bearingFriction.flange_a);
            connect(bearingFriction.flange_b, flange_b);
            connect(gear.flange_a, flange_a);
        }
    }
}
