//! Electrical sensors (MSL `Electrical.Analog.Sensors`).

use super::Pin;
use crate::blocks::RealOutput;
use crate::prelude::*;

component! {
    /// Measures the current from `p` to `n` without a voltage drop (MSL
    /// `Analog.Sensors.CurrentSensor`).
    #[type_name = "Electrical.CurrentSensor"]
    pub struct CurrentSensor {
        /// Positive pin.
        connector p: Pin;
        /// Negative pin.
        connector n: Pin;
        /// The current from `p` to `n` [A].
        connector i: RealOutput;
        equation {
            p.v = n.v;
            0.0 = p.i + n.i;
            i = p.i;
        }
    }
}

component! {
    /// Measures the voltage between `p` and `n` without a current (MSL
    /// `Analog.Sensors.VoltageSensor`).
    #[type_name = "Electrical.VoltageSensor"]
    pub struct VoltageSensor {
        /// Positive pin.
        connector p: Pin;
        /// Negative pin.
        connector n: Pin;
        /// The voltage `p.v - n.v` [V].
        connector v: RealOutput;
        equation {
            p.i = 0.0;
            n.i = 0.0;
            v = p.v - n.v;
        }
    }
}
