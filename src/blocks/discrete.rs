//! Sampled blocks (MSL `Modelica.Blocks.Discrete`): outputs that change only at the
//! sample instants `start_time + k sample_period`, each a time event.

use super::interfaces::{RealInput, RealOutput};
use crate::prelude::*;

component! {
    /// Ideal sampler (MSL `Blocks.Discrete.Sampler`): at each sample instant the output
    /// takes the input's value and holds it until the next one (0 before the first).
    #[type_name = "Blocks.Discrete.Sampler"]
    pub struct Sampler {
        /// Sample period \[s\] (greater than 0), default 0.1.
        parameter sample_period(min = 0.0): f64 = 0.1;
        /// First sample instant \[s\], default 0.
        parameter start_time: f64 = 0.0;
        /// Input.
        connector u: RealInput;
        /// The input at the last sample instant.
        connector y: RealOutput;
        equation {
            assert(gt(sample_period, 0.0), "the sample period must be greater than 0");
            when sample(start_time, sample_period) {
                y = u;
            }
        }
    }
}

component! {
    /// Zero-order hold (MSL `Blocks.Discrete.ZeroOrderHold`): at each sample instant
    /// the output takes the input's value and holds it until the next one (`y_start`
    /// before the first).
    #[type_name = "Blocks.Discrete.ZeroOrderHold"]
    pub struct ZeroOrderHold {
        /// Sample period \[s\] (greater than 0), default 0.1.
        parameter sample_period(min = 0.0): f64 = 0.1;
        /// First sample instant \[s\], default 0.
        parameter start_time: f64 = 0.0;
        /// Output before the first sample instant, default 0.
        parameter y_start: f64 = 0.0;
        /// Input.
        connector u: RealInput;
        /// Held output.
        connector y: RealOutput;
        /// The held value.
        variable y_sample(start = y_start): Real;
        equation {
            assert(gt(sample_period, 0.0), "the sample period must be greater than 0");
            when sample(start_time, sample_period) {
                y_sample = u;
            }
            y = y_sample;
        }
    }
}

component! {
    /// Unit delay (MSL `Blocks.Discrete.UnitDelay`): at each sample instant the output
    /// takes the value the input had just before it, `y = pre(u)` (`y_start` before the
    /// first); fed by another block sampled at the same instants, the output lags it by
    /// one period.
    #[type_name = "Blocks.Discrete.UnitDelay"]
    pub struct UnitDelay {
        /// Sample period \[s\] (greater than 0), default 0.1.
        parameter sample_period(min = 0.0): f64 = 0.1;
        /// First sample instant \[s\], default 0.
        parameter start_time: f64 = 0.0;
        /// Output before the first sample instant, default 0.
        parameter y_start: f64 = 0.0;
        /// Input.
        connector u: RealInput;
        /// Delayed output.
        connector y: RealOutput;
        /// The delayed value.
        variable y_sample(start = y_start): Real;
        equation {
            assert(gt(sample_period, 0.0), "the sample period must be greater than 0");
            when sample(start_time, sample_period) {
                y_sample = pre(u);
            }
            y = y_sample;
        }
    }
}
