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

component! {
    /// A discrete transfer function `y = (b[0] z^nb-1 + ...) / (a[0] z^na-1 + ...) u`
    /// sampled at `start_time + k sample_period` (MSL `Blocks.Discrete.TransferFunction`):
    /// the states start at 0, the output holds between the instants.
    #[type_name = "Blocks.Discrete.TransferFunction"]
    pub struct DiscreteTransferFunction {
        /// Numerator coefficients, highest power first, default `[1]`.
        structural b: Vec<f64> = vec![1.0];
        /// Denominator coefficients, highest power first (`a[0] != 0`), default `[1]`.
        structural a: Vec<f64> = vec![1.0];
        /// Sample period \[s\] (greater than 0), default 0.1.
        parameter sample_period(min = 0.0): f64 = 0.1;
        /// First sample instant \[s\], default 0.
        parameter start_time: f64 = 0.0;
        /// Input.
        connector u: RealInput;
        /// Output.
        connector y: RealOutput;
        /// The new value of the first state at the last instant.
        variable x1: Real;
        /// The states (`a.len() - 1`).
        component x: super::StateVector = super::StateVector { n: self.a.len().saturating_sub(1), start: Vec::new() };
        equation {
            assert(gt(sample_period, 0.0), "the sample period must be greater than 0");
            assert(!a.is_empty() && a[0] != 0.0, "a needs a nonzero first coefficient");
            assert(b.len() <= a.len(), "the transfer function must be proper: b no longer than a");
            let na = a.len().max(1);
            let nx = na - 1;
            let bb: Vec<f64> = std::iter::repeat_n(0.0, na.saturating_sub(b.len()))
                .chain(b.iter().copied())
                .collect();
            let a0 = a.first().copied().unwrap_or(1.0);
            when sample(start_time, sample_period) {
                x1 = (u - (1..na).fold(Expr::from(0.0), |s, i| s + a[i] * pre(x.x(i - 1)))) / a0;
                for i in 0..nx {
                    x.x(i) = if i == 0 { x1 } else { pre(x.x(i - 1)) };
                }
                y = (1..na).fold(bb[0] * x1, |s, i| s + bb[i] * pre(x.x(i - 1)));
            }
        }
    }
}
