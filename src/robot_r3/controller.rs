//! The robot's axis controller.

use crate::blocks::{Add3, Feedback, Gain, Init, PI, RealInput, RealOutput};
use crate::component;

component! {
    /// The cascaded controller of one axis (MSL `RobotR3.Utilities.Controller`): a P
    /// controller of the motor angle with speed feed-forward, then a PI controller of
    /// the motor speed that gives the reference current.
    #[type_name = "RobotR3.Controller"]
    pub struct Controller {
        /// Gain of the position controller [1], default 10.
        parameter kp: f64 = 10.0;
        /// Gain of the speed controller [1], default 1.
        parameter ks: f64 = 1.0;
        /// Time constant of the speed controller's integrator [s], default 0.01.
        parameter Ts: f64 = 0.01;
        /// Gear ratio [1], default 1.
        parameter ratio: f64 = 1.0;
        /// Initialization of the speed controller's state (MSL: none), default
        /// `Init::NoInit`.
        structural pi_init: Init = Init::NoInit;
        /// Reference angle of the axis [rad].
        connector angle_ref: RealInput;
        /// Reference speed of the axis [rad/s].
        connector speed_ref: RealInput;
        /// Motor angle [rad].
        connector motorAngle: RealInput;
        /// Motor speed [rad/s].
        connector motorSpeed: RealInput;
        /// Reference current of the motor [A].
        connector current_ref: RealOutput;
        /// Reference angle to motor angle (the gear ratio).
        component gain1: Gain = Gain { k: self.ratio };
        /// Speed controller.
        component PI: PI = PI { k: self.ks, T: self.Ts, init: self.pi_init, ..PI::default() };
        /// Position error.
        component feedback1: Feedback;
        /// Position controller.
        component P: Gain = Gain { k: self.kp };
        /// Speed error with feed-forward.
        component add3: Add3 = Add3 { k3: -1.0, ..Add3::default() };
        /// Reference speed to motor speed (the gear ratio).
        component gain2: Gain = Gain { k: self.ratio };
        equation {
            connect(gain1.y, feedback1.u1);
            connect(feedback1.y, P.u);
            connect(P.y, add3.u2);
            connect(gain2.y, add3.u1);
            connect(add3.y, PI.u);
            connect(angle_ref, gain1.u);
            connect(speed_ref, gain2.u);
            connect(motorAngle, feedback1.u2);
            connect(motorSpeed, add3.u3);
            connect(PI.y, current_ref);
        }
    }
}
