//! Rotational sensors: ideal, massless, they do not influence the motion.

use super::interfaces::*;
use crate::blocks::RealOutput;
use crate::prelude::*;

component! {
    /// Measures the absolute angle of a flange (MSL `Rotational.Sensors.AngleSensor`).
    #[type_name = "Rotational.AngleSensor"]
    pub struct AngleSensor {
        /// Measured flange.
        connector flange: Flange;
        /// Absolute angle [rad].
        connector phi: RealOutput;
        equation {
            phi = flange.phi;
            0.0 = flange.tau;
        }
    }
}

component! {
    /// Measures the absolute angular velocity of a flange (MSL
    /// `Rotational.Sensors.SpeedSensor`).
    #[type_name = "Rotational.SpeedSensor"]
    pub struct SpeedSensor {
        /// Measured flange.
        connector flange: Flange;
        /// Absolute angular velocity [rad/s].
        connector w: RealOutput;
        equation {
            w = der(flange.phi);
            0.0 = flange.tau;
        }
    }
}

component! {
    /// Measures the torque transmitted from `flange_a` to `flange_b` (MSL
    /// `Rotational.Sensors.TorqueSensor`).
    #[type_name = "Rotational.TorqueSensor"]
    pub struct TorqueSensor {
        /// Left flange.
        connector flange_a: Flange;
        /// Right flange.
        connector flange_b: Flange;
        /// Torque in the flange, `flange_a.tau` [N.m].
        connector tau: RealOutput;
        equation {
            flange_a.phi = flange_b.phi;
            flange_a.tau = tau;
            0.0 = flange_a.tau + flange_b.tau;
        }
    }
}
