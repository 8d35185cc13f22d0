//! Switching blocks with memory (MSL `Modelica.Blocks.Logical`), their Boolean outputs
//! as signals of 0 and 1.

use super::interfaces::{RealInput, RealOutput};
use crate::prelude::*;

component! {
    /// A hysteresis (MSL `Blocks.Logical.Hysteresis`): the output becomes 1 where the
    /// input rises above `u_high` and 0 where it falls below `u_low`, keeping its value
    /// in between (`y_start` until the first switch). Each switch is an event.
    #[type_name = "Blocks.Hysteresis"]
    pub struct Hysteresis {
        /// Switch off below this, default 0.
        parameter u_low: f64 = 0.0;
        /// Switch on above this (greater than `u_low`), default 1.
        parameter u_high: f64 = 1.0;
        /// Output before the first switch (0 or 1), default 0 (MSL `pre_y_start`).
        parameter y_start: f64 = 0.0;
        /// Input.
        connector u: RealInput;
        /// 1 when on, 0 when off.
        connector y: RealOutput;
        /// The state held between switches.
        variable on(start = y_start): Real;
        equation {
            assert(gt(u_high, u_low), "u_high must be greater than u_low");
            when gt(u, u_high) {
                on = 1.0;
            }
            when lt(u, u_low) {
                on = 0.0;
            }
            y = on;
        }
    }
}
