//! Rotational connectors and partial models.

use crate::prelude::*;

connector! {
    /// A rotational flange (MSL `Flange_a` / `Flange_b`).
    pub struct Flange {
        /// Absolute rotation angle [rad].
        potential phi: Real;
        /// Cut torque in the flange, positive into the component [N.m].
        flow tau: Real;
    }
}

component! {
    /// Two flanges with a relative angle and a torque between them (MSL
    /// `PartialCompliant`): the base of springs and dampers.
    #[type_name = "Rotational.PartialCompliant"]
    pub struct PartialCompliant {
        /// Left flange.
        connector flange_a: Flange;
        /// Right flange.
        connector flange_b: Flange;
        /// Relative rotation angle `flange_b.phi - flange_a.phi` [rad].
        variable phi_rel: Real;
        /// Torque between the flanges, `flange_b.tau` [N.m].
        variable tau: Real;
        equation {
            phi_rel = flange_b.phi - flange_a.phi;
            flange_b.tau = tau;
            flange_a.tau = -tau;
        }
    }
}

component! {
    /// Two flanges with the relative angle and speed preferred as states (MSL
    /// `PartialCompliantWithRelativeStates`): the base of dampers.
    #[type_name = "Rotational.PartialCompliantWithRelativeStates"]
    pub struct PartialCompliantWithRelativeStates {
        /// Priority of `phi_rel` and `w_rel` as states (MSL default: prefer).
        structural state_priority: f64 = StateSelect::Prefer.priority();
        /// Left flange.
        connector flange_a: Flange;
        /// Right flange.
        connector flange_b: Flange;
        /// Relative rotation angle `flange_b.phi - flange_a.phi` [rad].
        variable phi_rel(state_priority = state_priority): Real;
        /// Relative angular velocity `der(phi_rel)` [rad/s].
        variable w_rel(state_priority = state_priority): Real;
        /// Relative angular acceleration `der(w_rel)` [rad/s2].
        variable a_rel: Real;
        /// Torque between the flanges, `flange_b.tau` [N.m].
        variable tau: Real;
        equation {
            phi_rel = flange_b.phi - flange_a.phi;
            w_rel = der(phi_rel);
            a_rel = der(w_rel);
            flange_b.tau = tau;
            flange_a.tau = -tau;
        }
    }
}
