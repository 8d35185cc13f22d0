//! Rotational sources: torques and prescribed motion.

use super::interfaces::*;
use crate::blocks::RealInput;
use crate::blocks::bessel_follow;
use crate::prelude::*;

component! {
    /// Applies the input torque `tau` to `flange` (MSL `Rotational.Sources.Torque`):
    /// positive `tau` accelerates the flange. The reaction acts on `support` when
    /// `use_support`, otherwise on a fixed housing.
    #[type_name = "Rotational.Torque"]
    pub struct Torque {
        /// Whether the reaction torque acts on the `support` connector.
        structural use_support: bool = false;
        /// Torque driving the flange [N.m].
        connector tau: RealInput;
        /// Driven flange.
        connector flange: Flange;
        /// Housing (used only with `use_support`).
        connector support: Flange;
        equation {
            flange.tau = -tau;
            if use_support {
                support.tau = tau;
            } else {
                support.phi = 0.0;
            }
        }
    }
}

component! {
    /// A constant torque, independent of speed (MSL `Rotational.Sources.ConstantTorque`).
    #[type_name = "Rotational.ConstantTorque"]
    pub struct ConstantTorque {
        /// The torque accelerating the flange [N.m].
        parameter tau_constant: f64 = 1.0;
        /// Driven flange.
        connector flange: Flange;
        /// Torque accelerating the flange, `-flange.tau` [N.m].
        variable tau: Real;
        equation {
            tau = -flange.tau;
            tau = tau_constant;
        }
    }
}

component! {
    /// A load torque quadratic in speed (MSL
    /// `Rotational.Sources.QuadraticSpeedDependentTorque`): the torque accelerating the
    /// flange is `tau_nominal (w / w_nominal)^2`, of the sign of `tau_nominal` whatever
    /// the direction of rotation (`torque_direction`, the default), else `tau_nominal
    /// w |w| / w_nominal^2` (it changes sign with the speed). A negative `tau_nominal`
    /// brakes a flange turning forwards (a fan, a propeller).
    #[type_name = "Rotational.QuadraticSpeedDependentTorque"]
    pub struct QuadraticSpeedDependentTorque {
        /// The accelerating torque at `w_nominal` [N.m] (default 1).
        parameter tau_nominal: f64 = 1.0;
        /// The speed at which the torque is `tau_nominal` [rad/s] (default 1, positive).
        parameter w_nominal(min = 0.0): f64 = 1.0;
        /// Whether the torque keeps its sign when the speed changes sign (default true).
        structural torque_direction: bool = true;
        /// Driven flange.
        connector flange: Flange;
        /// Angle of the flange [rad].
        variable phi: Real;
        /// Speed of the flange [rad/s].
        variable w: Real;
        /// Torque accelerating the flange, `-flange.tau` [N.m].
        variable tau: Real;
        equation {
            assert(gt(w_nominal, 0.0), "`w_nominal` must be positive");
            phi = flange.phi;
            w = der(phi);
            tau = -flange.tau;
            if torque_direction {
                tau = tau_nominal * (w / w_nominal) * (w / w_nominal);
            } else {
                tau = tau_nominal * w * abs(w) / (w_nominal * w_nominal);
            }
        }
    }
}

component! {
    /// Forces the flange to follow the reference angle `phi_ref` (MSL
    /// `Rotational.Sources.Position`): exactly (the reference is differentiated, so it
    /// must be smooth), or filtered by a critically damped 2nd-order Bessel filter of
    /// cut-off frequency `f_crit` whose states are the flange's angle and speed, and
    /// which starts at the reference angle (an initial equation, as MSL).
    #[type_name = "Rotational.Position"]
    pub struct Position {
        /// Follow the reference exactly rather than filtered.
        structural exact: bool = false;
        /// Cut-off frequency of the filter when not exact [Hz].
        parameter f_crit: f64 = 50.0;
        /// Reference angle [rad].
        connector phi_ref: RealInput;
        /// Driven flange.
        connector flange: Flange;
        /// Rotation angle of the flange [rad].
        variable phi(state_priority = 10.0): Real;
        /// Angular velocity of the flange [rad/s].
        variable w(state_priority = 10.0): Real;
        /// Angular acceleration of the flange [rad/s2].
        variable a: Real;
        initial_equation {
            // The filter starts on the reference (MSL: `if not exact then phi = phi_ref`).
            if !exact {
                phi = phi_ref;
            }
        }
        equation {
            phi = flange.phi;
            w = der(phi);
            a = der(w);
            if exact {
                phi = phi_ref;
            } else {
                a = bessel_follow(phi_ref - phi, w, f_crit);
            }
        }
    }
}

component! {
    /// Forces the flange to the reference speed `w_ref` (MSL `Rotational.Sources.Speed`):
    /// exactly, or through a first-order filter of cut-off frequency `f_crit`.
    #[type_name = "Rotational.Speed"]
    pub struct Speed {
        /// Follow the reference exactly rather than filtered.
        structural exact: bool = false;
        /// Cut-off frequency of the filter when not exact [Hz].
        parameter f_crit: f64 = 50.0;
        /// Reference speed [rad/s].
        connector w_ref: RealInput;
        /// Driven flange.
        connector flange: Flange;
        /// Rotation angle of the flange [rad].
        variable phi(state_priority = 10.0): Real;
        /// Angular velocity of the flange [rad/s].
        variable w(state_priority = 10.0): Real;
        /// Angular acceleration of the flange [rad/s2].
        variable a: Real;
        equation {
            phi = flange.phi;
            w = der(phi);
            a = der(w);
            if exact {
                w = w_ref;
            } else {
                a = (w_ref - w) * (2.0 * PI * f_crit);
            }
        }
    }
}
