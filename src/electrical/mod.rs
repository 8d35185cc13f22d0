//! Analog electrical circuits (MSL `Modelica.Electrical.Analog`): pins carry a
//! potential `v` \[V\] and a current `i` \[A\] (positive into the component).

use crate::blocks::RealInput;
use crate::prelude::*;
use crate::rotational;

mod ideal;
mod sensors;
pub use ideal::*;
pub use sensors::*;

connector! {
    /// An electrical pin (MSL `Pin`, `PositivePin`, `NegativePin`).
    pub struct Pin {
        /// Potential at the pin [V].
        potential v: Real;
        /// Current flowing into the pin [A].
        flow i: Real;
    }
}

component! {
    /// The ground of a circuit: potential 0 (MSL `Analog.Basic.Ground`).
    #[type_name = "Electrical.Ground"]
    pub struct Ground {
        /// The grounded pin.
        connector p: Pin;
        equation {
            p.v = 0.0;
        }
    }
}

component! {
    /// A component with two pins and one current through it (MSL `OnePort`).
    #[type_name = "Electrical.OnePort"]
    pub struct OnePort {
        /// Positive pin.
        connector p: Pin;
        /// Negative pin.
        connector n: Pin;
        /// Voltage drop `p.v - n.v` [V].
        variable v: Real;
        /// Current from `p` to `n` through the component [A].
        variable i: Real;
        equation {
            v = p.v - n.v;
            0.0 = p.i + n.i;
            i = p.i;
        }
    }
}

component! {
    /// An ideal linear resistor (MSL `Analog.Basic.Resistor`, without heating).
    #[type_name = "Electrical.Resistor"]
    pub struct Resistor {
        /// Resistance [Ohm].
        parameter R: f64 = 1.0;
        extends OnePort { p, n, v, i };
        equation {
            v = R * i;
        }
    }
}

component! {
    /// An ideal linear capacitor (MSL `Analog.Basic.Capacitor`).
    #[type_name = "Electrical.Capacitor"]
    pub struct Capacitor {
        /// Capacitance [F].
        parameter C: f64 = 1.0;
        extends OnePort { p, n, v, i };
        equation {
            i = C * der(v);
        }
    }
}

component! {
    /// An ideal linear inductor (MSL `Analog.Basic.Inductor`).
    #[type_name = "Electrical.Inductor"]
    pub struct Inductor {
        /// Inductance [H].
        parameter L: f64 = 1.0;
        extends OnePort { p, n, v, i };
        equation {
            L * der(i) = v;
        }
    }
}

component! {
    /// A constant voltage source (MSL `Analog.Sources.ConstantVoltage`).
    #[type_name = "Electrical.ConstantVoltage"]
    pub struct ConstantVoltage {
        /// Source voltage [V].
        parameter V: f64 = 1.0;
        extends OnePort { p, n, v, i };
        equation {
            v = V;
        }
    }
}

component! {
    /// A voltage source driven by a signal (MSL `Analog.Sources.SignalVoltage`).
    #[type_name = "Electrical.SignalVoltage"]
    pub struct SignalVoltage {
        /// The voltage `p.v - n.v` [V].
        connector v_ref: RealInput;
        extends OnePort { p, n, v, i };
        equation {
            v = v_ref;
        }
    }
}

component! {
    /// An electromotoric force: the ideal coupling of a circuit with a rotational
    /// flange, `v = k w`, `flange.tau = -k i` (MSL `Analog.Basic.EMF`). With
    /// `use_support` the housing is the `support` flange, otherwise it is fixed.
    #[type_name = "Electrical.EMF"]
    pub struct EMF {
        /// Transformation coefficient [N.m/A] (= [V.s/rad]).
        parameter k: f64 = 1.0;
        /// Whether the housing is a connector (`support`).
        structural use_support: bool = false;
        /// Positive pin.
        connector p: Pin;
        /// Negative pin.
        connector n: Pin;
        /// The shaft.
        connector flange: rotational::Flange;
        /// Housing (used only with `use_support`).
        connector support: rotational::Flange;
        /// Voltage drop `p.v - n.v` [V].
        variable v: Real;
        /// Current from `p` to `n` [A].
        variable i: Real;
        /// Angle of the shaft relative to the housing [rad].
        variable phi: Real;
        /// Angular velocity of the shaft relative to the housing [rad/s].
        variable w: Real;
        equation {
            v = p.v - n.v;
            0.0 = p.i + n.i;
            i = p.i;
            phi = flange.phi - support.phi;
            w = der(phi);
            k * w = v;
            flange.tau = -k * i;
            if use_support {
                support.tau = -flange.tau;
            } else {
                support.phi = 0.0;
            }
        }
    }
}
