//! Rotational components: fixed flange, inertia, spring, damper, gear.

use super::interfaces::*;
use crate::prelude::*;

component! {
    /// A flange fixed in the housing at angle `phi0` (MSL `Rotational.Components.Fixed`).
    #[type_name = "Rotational.Fixed"]
    pub struct Fixed {
        /// Fixed offset angle of the housing [rad].
        parameter phi0: f64 = 0.0;
        /// The fixed flange.
        connector flange: Flange;
        equation {
            flange.phi = phi0;
        }
    }
}

component! {
    /// A rigid 1-D rotational inertia (MSL `Rotational.Components.Inertia`).
    #[type_name = "Rotational.Inertia"]
    pub struct Inertia {
        /// Moment of inertia [kg.m2] (at least 0).
        parameter J(min = 0.0): f64 = 1.0;
        /// Start value of the angle [rad] (a guess, or the assumed initial condition
        /// when `phi` is a state).
        structural phi_start: f64 = 0.0;
        /// Start value of the angular velocity [rad/s].
        structural w_start: f64 = 0.0;
        /// Priority of `phi` and `w` as states (MSL default: `StateSelect.default`).
        structural state_priority: f64 = 0.0;
        /// Left flange.
        connector flange_a: Flange;
        /// Right flange.
        connector flange_b: Flange;
        /// Absolute rotation angle [rad].
        variable phi(start = phi_start, state_priority = state_priority): Real;
        /// Absolute angular velocity [rad/s].
        variable w(start = w_start, state_priority = state_priority): Real;
        /// Absolute angular acceleration [rad/s2].
        variable a: Real;
        equation {
            phi = flange_a.phi;
            phi = flange_b.phi;
            w = der(phi);
            a = der(w);
            J * a = flange_a.tau + flange_b.tau;
        }
    }
}

component! {
    /// A linear 1-D rotational spring (MSL `Rotational.Components.Spring`).
    #[type_name = "Rotational.Spring"]
    pub struct Spring {
        /// Spring constant [N.m/rad].
        parameter c(min = 0.0): f64 = 1.0;
        /// Unstretched spring angle [rad].
        parameter phi_rel0: f64 = 0.0;
        extends PartialCompliant { flange_a, flange_b, phi_rel, tau };
        equation {
            tau = c * (phi_rel - phi_rel0);
        }
    }
}

component! {
    /// A linear 1-D rotational damper (MSL `Rotational.Components.Damper`).
    #[type_name = "Rotational.Damper"]
    pub struct Damper {
        /// Damping constant [N.m.s/rad].
        parameter d(min = 0.0): f64 = 0.0;
        extends PartialCompliantWithRelativeStates { flange_a, flange_b, phi_rel, tau, w_rel };
        equation {
            tau = d * w_rel;
        }
    }
}

component! {
    /// A linear spring and damper in parallel (MSL `Rotational.Components.SpringDamper`).
    #[type_name = "Rotational.SpringDamper"]
    pub struct SpringDamper {
        /// Spring constant [N.m/rad].
        parameter c(min = 0.0): f64 = 1.0;
        /// Damping constant [N.m.s/rad].
        parameter d(min = 0.0): f64 = 0.0;
        /// Unstretched spring angle [rad].
        parameter phi_rel0: f64 = 0.0;
        extends PartialCompliantWithRelativeStates { flange_a, flange_b, phi_rel, tau, w_rel };
        equation {
            tau = c * (phi_rel - phi_rel0) + d * w_rel;
        }
    }
}

component! {
    /// An ideal gear without inertia (MSL `Rotational.Components.IdealGear`):
    /// `flange_a.phi = ratio * flange_b.phi`. With `use_support` the housing is the
    /// `support` flange, otherwise it is fixed.
    #[type_name = "Rotational.IdealGear"]
    pub struct IdealGear {
        /// Transmission ratio `flange_a.phi / flange_b.phi` [1].
        parameter ratio: f64 = 1.0;
        /// Whether the housing is a connector (`support`) rather than fixed.
        structural use_support: bool = false;
        /// Driving flange.
        connector flange_a: Flange;
        /// Driven flange.
        connector flange_b: Flange;
        /// Housing (used only with `use_support`; otherwise its angle is 0).
        connector support: Flange;
        /// Angle of `flange_a` relative to the support [rad].
        variable phi_a: Real;
        /// Angle of `flange_b` relative to the support [rad].
        variable phi_b: Real;
        equation {
            phi_a = flange_a.phi - support.phi;
            phi_b = flange_b.phi - support.phi;
            phi_a = ratio * phi_b;
            0.0 = ratio * flange_a.tau + flange_b.tau;
            if use_support {
                0.0 = flange_a.tau + flange_b.tau + support.tau;
            } else {
                support.phi = 0.0;
            }
        }
    }
}

component! {
    /// Sets the initial angle, speed and acceleration of a flange from signals, without
    /// a torque on it (MSL `Rotational.Components.InitializeFlange`); its angle and speed
    /// are preferred as states.
    #[type_name = "Rotational.InitializeFlange"]
    pub struct InitializeFlange {
        /// Whether `phi_start` sets the initial angle, default true.
        structural use_phi_start: bool = true;
        /// Whether `w_start` sets the initial speed, default true.
        structural use_w_start: bool = true;
        /// Whether `a_start` sets the initial acceleration, default true.
        structural use_a_start: bool = true;
        /// Initial angle [rad].
        connector phi_start: crate::blocks::RealInput;
        /// Initial speed [rad/s].
        connector w_start: crate::blocks::RealInput;
        /// Initial acceleration [rad/s2].
        connector a_start: crate::blocks::RealInput;
        /// The flange to initialize.
        connector flange: Flange;
        /// The flange's angle [rad].
        variable phi_flange(state_priority = StateSelect::Prefer.priority()): Real;
        /// The flange's speed [rad/s].
        variable w_flange(state_priority = StateSelect::Prefer.priority()): Real;
        equation {
            phi_flange = flange.phi;
            w_flange = der(phi_flange);
            flange.tau = 0.0;
        }
        initial_equation {
            if use_phi_start {
                phi_flange = phi_start;
            }
            if use_w_start {
                w_flange = w_start;
            }
            if use_a_start {
                der(w_flange) = a_start;
            }
        }
    }
}
