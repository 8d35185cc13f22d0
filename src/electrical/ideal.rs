//! Ideal switching elements (MSL `Electrical.Analog.Ideal`): each is a point `s` moving
//! along a piecewise-linear characteristic, whose kink (`s = 0`, or the control's
//! switch) is an event.

use super::{OnePort, Pin};
use crate::blocks::RealInput;
use crate::prelude::*;

component! {
    /// An ideal diode (MSL `Analog.Ideal.IdealDiode`): a small resistance `Ron` when it
    /// conducts, a small conductance `Goff` when it blocks, with a knee at `Vknee`. It
    /// switches where the point `s` on its characteristic changes sign (an event).
    #[type_name = "Electrical.IdealDiode"]
    pub struct IdealDiode {
        /// Forward resistance when conducting \[Ohm\] (at least 0), default 1e-5.
        parameter Ron(min = 0.0): f64 = 1e-5;
        /// Backward conductance when blocking \[S\] (at least 0), default 1e-5.
        parameter Goff(min = 0.0): f64 = 1e-5;
        /// Forward threshold voltage \[V\] (at least 0), default 0.
        parameter Vknee(min = 0.0): f64 = 0.0;
        extends OnePort { p, n, v, i };
        /// Position on the characteristic (negative: blocking).
        variable s: Real;
        equation {
            let off = lt(s, 0.0);
            v = s * if_else(off, 1.0, Ron) + Vknee;
            i = s * if_else(off, Goff, 1.0) + Goff * Vknee;
        }
    }
}

component! {
    /// An ideal switch that opens while its control is true (MSL
    /// `Analog.Ideal.IdealOpeningSwitch`, the Boolean control as a signal: true above
    /// 0.5): a small resistance `Ron` when closed, a small conductance `Goff` when open.
    #[type_name = "Electrical.IdealOpeningSwitch"]
    pub struct IdealOpeningSwitch {
        /// Resistance when closed \[Ohm\] (at least 0), default 1e-5.
        parameter Ron(min = 0.0): f64 = 1e-5;
        /// Conductance when open \[S\] (at least 0), default 1e-5.
        parameter Goff(min = 0.0): f64 = 1e-5;
        /// Open above 0.5, closed below.
        connector control: RealInput;
        extends OnePort { p, n, v, i };
        /// Position on the characteristic.
        variable s: Real;
        equation {
            let open = gt(control, 0.5);
            v = s * if_else(open, 1.0, Ron);
            i = s * if_else(open, Goff, 1.0);
        }
    }
}

component! {
    /// An ideal switch that closes while its control is true (MSL
    /// `Analog.Ideal.IdealClosingSwitch`, the control as a signal: true above 0.5).
    #[type_name = "Electrical.IdealClosingSwitch"]
    pub struct IdealClosingSwitch {
        /// Resistance when closed \[Ohm\] (at least 0), default 1e-5.
        parameter Ron(min = 0.0): f64 = 1e-5;
        /// Conductance when open \[S\] (at least 0), default 1e-5.
        parameter Goff(min = 0.0): f64 = 1e-5;
        /// Closed above 0.5, open below.
        connector control: RealInput;
        extends OnePort { p, n, v, i };
        /// Position on the characteristic.
        variable s: Real;
        equation {
            let open = le(control, 0.5);
            v = s * if_else(open, 1.0, Ron);
            i = s * if_else(open, Goff, 1.0);
        }
    }
}

component! {
    /// An ideal operational amplifier (MSL `Analog.Ideal.IdealOpAmp`, a nullator-norator
    /// pair): no voltage between the inputs `p1`, `n1` and no current into them; the
    /// output port `p2`, `n2` takes whatever current and voltage the circuit needs.
    #[type_name = "Electrical.IdealOpAmp"]
    pub struct IdealOpAmp {
        /// Positive input.
        connector p1: Pin;
        /// Negative input.
        connector n1: Pin;
        /// Positive output.
        connector p2: Pin;
        /// Negative output.
        connector n2: Pin;
        /// Input voltage `p1.v - n1.v` [V].
        variable v1: Real;
        /// Output voltage `p2.v - n2.v` [V].
        variable v2: Real;
        /// Current into the input `p1` [A].
        variable i1: Real;
        /// Current into the output `p2` [A].
        variable i2: Real;
        equation {
            v1 = p1.v - n1.v;
            v2 = p2.v - n2.v;
            0.0 = p1.i + n1.i;
            0.0 = p2.i + n2.i;
            i1 = p1.i;
            i2 = p2.i;
            v1 = 0.0;
            i1 = 0.0;
        }
    }
}
