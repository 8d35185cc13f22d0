//! One axis of the robot.

use super::{Controller, GearType1, GearType2, Motor};
use crate::blocks::{Constant, RealInput};
use crate::prelude::*;
use crate::rotational::{Flange, InitializeFlange};

component! {
    /// One axis of the robot with a gearbox of type 1 (MSL `RobotR3.Utilities.AxisType1`):
    /// controller, motor and gearbox; the load flange starts at the reference angle and
    /// speed, at rest.
    #[type_name = "RobotR3.AxisType1"]
    pub struct AxisType1 {
        /// Gain of the position controller [1], default 10.
        parameter kp: f64 = 10.0;
        /// Gain of the speed controller [1], default 1.
        parameter ks: f64 = 1.0;
        /// Time constant of the speed controller's integrator [s], default 0.01.
        parameter Ts: f64 = 0.01;
        /// Gain of the motor [N.m/A], default 1.1616.
        parameter k: f64 = 1.1616;
        /// Time constant of the motor's current controller [rad/s], default 4590.
        parameter w: f64 = 4590.0;
        /// Damping of the motor's current controller [1], default 0.6.
        parameter D: f64 = 0.6;
        /// Moment of inertia of the motor [kg.m2], default 0.0013.
        parameter J(min = 0.0): f64 = 0.0013;
        /// Gear ratio [1], default -105.
        parameter ratio: f64 = -105.0;
        /// Viscous friction torque at zero speed [N.m], default 0.4.
        structural Rv0: f64 = 0.4;
        /// Viscous friction coefficient [N.m.s/rad], default 0.13 / 160.
        structural Rv1: f64 = 0.13 / 160.0;
        /// Maximum static friction torque over `Rv0` [1], default 1.
        parameter peak(min = 1.0): f64 = 1.0;
        /// Spring constant of the gearbox's shaft [N.m/rad], default 43.
        parameter c(min = 0.0): f64 = 43.0;
        /// Damping constant of the gearbox's shaft [N.m.s/rad], default 0.005.
        parameter cd(min = 0.0): f64 = 0.005;
        /// Whether the axis starts with its bearing friction stuck (default false). MSL's
        /// initial equations are then redundant (the shaft's initial acceleration follows
        /// from the load's) and leave the stuck friction torque open, which Dymola keeps
        /// at its start value 0 (the motor alone holds the load); this option says so:
        /// the shaft's acceleration equation is left out and the friction torque starts
        /// at 0.
        structural start_stuck: bool = false;
        /// The axis's output (load side).
        connector flange: Flange;
        /// Reference angle of the axis [rad].
        connector angle_ref: RealInput;
        /// Reference speed of the axis [rad/s].
        connector speed_ref: RealInput;
        /// The gearbox.
        component gear: GearType1 = GearType1 {
            Rv0: self.Rv0, Rv1: self.Rv1, peak: self.peak, i: self.ratio, c: self.c, d: self.cd,
            start_without_acceleration: !self.start_stuck,
        };
        /// The motor with its current controller.
        component motor: Motor = Motor { J: self.J, k: self.k, w: self.w, D: self.D };
        /// The axis controller.
        component controller: Controller = Controller {
            kp: self.kp, ks: self.ks, Ts: self.Ts, ratio: self.ratio, ..Controller::default()
        };
        /// Initial angle, speed and acceleration of the load flange.
        component initializeFlange: InitializeFlange;
        /// Initial acceleration 0.
        component const_a: Constant = Constant { k: 0.0 };
        equation {
            connect(gear.flange_b, flange);
            connect(gear.flange_b, initializeFlange.flange);
            connect(motor.flange_motor, gear.flange_a);
            connect(motor.current_ref, controller.current_ref);
            connect(motor.motorAngle, controller.motorAngle);
            connect(motor.motorSpeed, controller.motorSpeed);
            connect(angle_ref, controller.angle_ref);
            connect(speed_ref, controller.speed_ref);
            connect(angle_ref, initializeFlange.phi_start);
            connect(speed_ref, initializeFlange.w_start);
            connect(const_a.y, initializeFlange.a_start);
        }
        initial_equation {
            if start_stuck {
                gear.bearingFriction.sa = 0.0;
            }
        }
    }
}

component! {
    /// One axis of the robot with a gearbox of type 2 (MSL `RobotR3.Utilities.AxisType2`,
    /// the axes 4 to 6): controller, motor and a rigid gearbox with bearing friction on
    /// the load side; the load flange starts at the reference angle and speed, at rest.
    #[type_name = "RobotR3.AxisType2"]
    pub struct AxisType2 {
        /// Gain of the position controller [1], default 10.
        parameter kp: f64 = 10.0;
        /// Gain of the speed controller [1], default 1.
        parameter ks: f64 = 1.0;
        /// Time constant of the speed controller's integrator [s], default 0.01.
        parameter Ts: f64 = 0.01;
        /// Gain of the motor [N.m/A], default 1.1616.
        parameter k: f64 = 1.1616;
        /// Time constant of the motor's current controller [rad/s], default 4590.
        parameter w: f64 = 4590.0;
        /// Damping of the motor's current controller [1], default 0.6.
        parameter D: f64 = 0.6;
        /// Moment of inertia of the motor [kg.m2], default 0.0013.
        parameter J(min = 0.0): f64 = 0.0013;
        /// Gear ratio [1], default -105.
        parameter ratio: f64 = -105.0;
        /// Viscous friction torque at zero speed [N.m], default 0.4.
        structural Rv0: f64 = 0.4;
        /// Viscous friction coefficient [N.m.s/rad], default 0.13 / 160.
        structural Rv1: f64 = 0.13 / 160.0;
        /// Maximum static friction torque over `Rv0` [1], default 1.
        parameter peak(min = 1.0): f64 = 1.0;
        /// Whether the axis starts with its bearing friction stuck (default false): the
        /// flange's initial acceleration then follows from the friction's lock, and the
        /// stuck friction torque starts at 0 in place of it (see
        /// [`AxisType1`]'s `start_stuck`).
        structural start_stuck: bool = false;
        /// The axis's output (load side).
        connector flange: Flange;
        /// Reference angle of the axis [rad].
        connector angle_ref: RealInput;
        /// Reference speed of the axis [rad/s].
        connector speed_ref: RealInput;
        /// The gearbox.
        component gear: GearType2 = GearType2 {
            Rv0: self.Rv0, Rv1: self.Rv1, peak: self.peak, i: self.ratio,
        };
        /// The motor with its current controller.
        component motor: Motor = Motor { J: self.J, k: self.k, w: self.w, D: self.D };
        /// The axis controller.
        component controller: Controller = Controller {
            kp: self.kp, ks: self.ks, Ts: self.Ts, ratio: self.ratio, ..Controller::default()
        };
        /// Initial angle, speed and acceleration of the load flange.
        component initializeFlange: InitializeFlange = InitializeFlange {
            use_a_start: !self.start_stuck, ..InitializeFlange::default()
        };
        /// Initial acceleration 0.
        component const_a: Constant = Constant { k: 0.0 };
        equation {
            connect(gear.flange_b, flange);
            connect(gear.flange_b, initializeFlange.flange);
            connect(motor.flange_motor, gear.flange_a);
            connect(motor.current_ref, controller.current_ref);
            connect(motor.motorAngle, controller.motorAngle);
            connect(motor.motorSpeed, controller.motorSpeed);
            connect(angle_ref, controller.angle_ref);
            connect(speed_ref, controller.speed_ref);
            connect(angle_ref, initializeFlange.phi_start);
            connect(speed_ref, initializeFlange.w_start);
            connect(const_a.y, initializeFlange.a_start);
        }
        initial_equation {
            if start_stuck {
                gear.bearingFriction.sa = 0.0;
            }
        }
    }
}
