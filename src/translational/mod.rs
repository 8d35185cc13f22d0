//! 1-D translational mechanics (MSL `Modelica.Mechanics.Translational`): flanges
//! carry a position `s` \[m\] and a cut force `f` \[N\] (positive into the component).

use crate::blocks::bessel_follow;
use crate::blocks::{RealInput, RealOutput};
use crate::prelude::*;

mod friction;
pub use friction::*;

connector! {
    /// A translational flange (MSL `Flange_a` / `Flange_b`).
    pub struct Flange {
        /// Absolute position [m].
        potential s: Real;
        /// Cut force, positive into the component [N].
        flow f: Real;
    }
}

component! {
    /// Two flanges with a relative distance and a force between them (MSL
    /// `PartialCompliant`).
    #[type_name = "Translational.PartialCompliant"]
    pub struct PartialCompliant {
        /// Left flange.
        connector flange_a: Flange;
        /// Right flange.
        connector flange_b: Flange;
        /// Relative distance `flange_b.s - flange_a.s` [m].
        variable s_rel: Real;
        /// Force between the flanges, `flange_b.f` [N].
        variable f: Real;
        equation {
            s_rel = flange_b.s - flange_a.s;
            flange_b.f = f;
            flange_a.f = -f;
        }
    }
}

component! {
    /// A flange fixed at position `s0` (MSL `Translational.Components.Fixed`).
    #[type_name = "Translational.Fixed"]
    pub struct Fixed {
        /// Fixed position [m].
        parameter s0: f64 = 0.0;
        /// The fixed flange.
        connector flange: Flange;
        equation {
            flange.s = s0;
        }
    }
}

component! {
    /// A sliding mass of length `L` (MSL `Translational.Components.Mass`).
    #[type_name = "Translational.Mass"]
    pub struct Mass {
        /// Mass [kg] (at least 0).
        parameter m(min = 0.0): f64 = 1.0;
        /// Length of the mass (the flanges are `L/2` from its centre) [m].
        parameter L: f64 = 0.0;
        /// Start value of the position [m].
        structural s_start: f64 = 0.0;
        /// Start value of the velocity [m/s].
        structural v_start: f64 = 0.0;
        /// Priority of `s` and `v` as states (MSL default: `StateSelect.default`).
        structural state_priority: f64 = 0.0;
        /// Left flange.
        connector flange_a: Flange;
        /// Right flange.
        connector flange_b: Flange;
        /// Absolute position of the centre [m].
        variable s(start = s_start, state_priority = state_priority): Real;
        /// Absolute velocity [m/s].
        variable v(start = v_start, state_priority = state_priority): Real;
        /// Absolute acceleration [m/s2].
        variable a: Real;
        equation {
            flange_a.s = s - L / 2.0;
            flange_b.s = s + L / 2.0;
            v = der(s);
            a = der(v);
            m * a = flange_a.f + flange_b.f;
        }
    }
}

component! {
    /// A linear translational spring (MSL `Translational.Components.Spring`).
    #[type_name = "Translational.Spring"]
    pub struct Spring {
        /// Spring constant [N/m].
        parameter c(min = 0.0): f64 = 1.0;
        /// Unstretched spring length [m].
        parameter s_rel0: f64 = 0.0;
        extends PartialCompliant { flange_a, flange_b, s_rel, f };
        equation {
            f = c * (s_rel - s_rel0);
        }
    }
}

component! {
    /// Two flanges with the relative distance and speed preferred as states (MSL
    /// `PartialCompliantWithRelativeStates`): the base of dampers.
    #[type_name = "Translational.PartialCompliantWithRelativeStates"]
    pub struct PartialCompliantWithRelativeStates {
        /// Priority of `s_rel` and `v_rel` as states (MSL default: prefer).
        structural state_priority: f64 = StateSelect::Prefer.priority();
        /// Left flange.
        connector flange_a: Flange;
        /// Right flange.
        connector flange_b: Flange;
        /// Relative distance `flange_b.s - flange_a.s` [m].
        variable s_rel(state_priority = state_priority): Real;
        /// Relative velocity `der(s_rel)` [m/s].
        variable v_rel(state_priority = state_priority): Real;
        /// Relative acceleration `der(v_rel)` [m/s2].
        variable a_rel: Real;
        /// Force between the flanges, `flange_b.f` [N].
        variable f: Real;
        equation {
            s_rel = flange_b.s - flange_a.s;
            v_rel = der(s_rel);
            a_rel = der(v_rel);
            flange_b.f = f;
            flange_a.f = -f;
        }
    }
}

component! {
    /// A linear translational damper (MSL `Translational.Components.Damper`).
    #[type_name = "Translational.Damper"]
    pub struct Damper {
        /// Damping constant [N.s/m].
        parameter d(min = 0.0): f64 = 0.0;
        extends PartialCompliantWithRelativeStates { flange_a, flange_b, s_rel, v_rel, f };
        equation {
            f = d * v_rel;
        }
    }
}

component! {
    /// A spring and a damper in contact only (MSL `Translational.Components.ElastoGap`):
    /// while `s_rel < s_rel0` they push the flanges apart, never pull (the damping
    /// force is limited by the spring force); outside contact the force is zero. The
    /// start and the end of a contact are events.
    #[type_name = "Translational.ElastoGap"]
    pub struct ElastoGap {
        /// Spring constant [N/m] (at least 0), default 1.
        parameter c(min = 0.0): f64 = 1.0;
        /// Damping constant [N.s/m] (at least 0), default 1.
        parameter d(min = 0.0): f64 = 1.0;
        /// Relative distance where contact begins [m], default 0.
        parameter s_rel0: f64 = 0.0;
        /// Exponent of the spring force, `f_c = -c |s_rel - s_rel0|^n` (at least 1),
        /// default 1 (fixed when the model is built; a parameter in MSL).
        structural n: f64 = 1.0;
        extends PartialCompliantWithRelativeStates { flange_a, flange_b, s_rel, v_rel, f };
        /// Spring force [N].
        variable f_c: Real;
        /// Linear damping force [N].
        variable f_d2: Real;
        /// Damping force limited by the spring force [N].
        variable f_d: Real;
        equation {
            assert(n >= 1.0, format!("parameter `n` = {n} must be at least 1"));
            let contact = lt(s_rel, s_rel0);
            f_c = smooth(1, no_event(if_else(contact, -c * pow(abs(s_rel - s_rel0), n), 0.0)));
            f_d2 = if_else(contact, d * v_rel, 0.0);
            let limited = if_else(lt(f_d2, f_c), f_c, if_else(gt(f_d2, -f_c), -f_c, f_d2));
            f_d = smooth(0, no_event(if_else(contact, limited, 0.0)));
            f = if_else(contact, f_c + f_d, 0.0);
        }
    }
}

component! {
    /// Applies the input force `f` to `flange` (MSL `Translational.Sources.Force`); the
    /// reaction acts on `support` when `use_support`, otherwise on a fixed housing.
    #[type_name = "Translational.Force"]
    pub struct Force {
        /// Whether the reaction force acts on the `support` connector.
        structural use_support: bool = false;
        /// Force driving the flange [N].
        connector f: RealInput;
        /// Driven flange.
        connector flange: Flange;
        /// Housing (used only with `use_support`).
        connector support: Flange;
        equation {
            flange.f = -f;
            if use_support {
                support.f = f;
            } else {
                support.s = 0.0;
            }
        }
    }
}

component! {
    /// Forces the flange to follow the reference position `s_ref` (MSL
    /// `Translational.Sources.Position`): exactly (the reference is differentiated, so it
    /// must be smooth and cannot be a model input), or filtered by MSL's 2nd-order
    /// Bessel filter of cut-off frequency `f_crit` whose states are the
    /// flange's position and speed, and which starts at the reference position (an
    /// initial equation, as MSL).
    #[type_name = "Translational.Position"]
    pub struct Position {
        /// Follow the reference exactly rather than filtered (default false).
        structural exact: bool = false;
        /// Cut-off frequency of the filter when not exact [Hz] (default 50).
        parameter f_crit: f64 = 50.0;
        /// Reference position [m].
        connector s_ref: RealInput;
        /// Driven flange.
        connector flange: Flange;
        /// Position of the flange [m].
        variable s(state_priority = 10.0): Real;
        /// Speed of the flange [m/s].
        variable v(state_priority = 10.0): Real;
        /// Acceleration of the flange [m/s2].
        variable a: Real;
        initial_equation {
            if !exact {
                s = s_ref;
            }
        }
        equation {
            s = flange.s;
            v = der(s);
            a = der(v);
            if exact {
                s = s_ref;
            } else {
                a = bessel_follow(s_ref - s, v, f_crit);
            }
        }
    }
}

component! {
    /// Measures the absolute position of a flange (MSL
    /// `Translational.Sensors.PositionSensor`).
    #[type_name = "Translational.PositionSensor"]
    pub struct PositionSensor {
        /// Measured flange.
        connector flange: Flange;
        /// Absolute position [m].
        connector s: RealOutput;
        equation {
            s = flange.s;
            0.0 = flange.f;
        }
    }
}
