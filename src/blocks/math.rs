//! Static math blocks.

use super::interfaces::*;
use crate::prelude::*;

component! {
    /// Output the input times a gain (MSL `Blocks.Math.Gain`).
    #[type_name = "Blocks.Gain"]
    pub struct Gain {
        /// Gain.
        parameter k: f64 = 1.0;
        /// Input.
        connector u: RealInput;
        /// Output `k * u`.
        connector y: RealOutput;
        equation {
            y = k * u;
        }
    }
}

component! {
    /// Weighted sum of two inputs (MSL `Blocks.Math.Add`).
    #[type_name = "Blocks.Add"]
    pub struct Add {
        /// Gain of the first input.
        parameter k1: f64 = 1.0;
        /// Gain of the second input.
        parameter k2: f64 = 1.0;
        /// First input.
        connector u1: RealInput;
        /// Second input.
        connector u2: RealInput;
        /// Output `k1 u1 + k2 u2`.
        connector y: RealOutput;
        equation {
            y = k1 * u1 + k2 * u2;
        }
    }
}

component! {
    /// Weighted sum of three inputs (MSL `Blocks.Math.Add3`).
    #[type_name = "Blocks.Add3"]
    pub struct Add3 {
        /// Gain of the first input, default 1.
        parameter k1: f64 = 1.0;
        /// Gain of the second input, default 1.
        parameter k2: f64 = 1.0;
        /// Gain of the third input, default 1.
        parameter k3: f64 = 1.0;
        /// First input.
        connector u1: RealInput;
        /// Second input.
        connector u2: RealInput;
        /// Third input.
        connector u3: RealInput;
        /// Output `k1 u1 + k2 u2 + k3 u3`.
        connector y: RealOutput;
        equation {
            y = k1 * u1 + k2 * u2 + k3 * u3;
        }
    }
}

component! {
    /// Difference of a reference and a feedback signal (MSL `Blocks.Math.Feedback`).
    #[type_name = "Blocks.Feedback"]
    pub struct Feedback {
        /// Reference input.
        connector u1: RealInput;
        /// Feedback input.
        connector u2: RealInput;
        /// Output `u1 - u2`.
        connector y: RealOutput;
        equation {
            y = u1 - u2;
        }
    }
}

component! {
    /// Limits a signal to `[y_min, y_max]` (MSL `Blocks.Nonlinear.Limiter`).
    #[type_name = "Blocks.Limiter"]
    pub struct Limiter {
        /// Upper limit.
        parameter y_max: f64 = 1.0;
        /// Lower limit.
        parameter y_min: f64 = -1.0;
        /// Input.
        connector u: RealInput;
        /// Output `min(max(u, y_min), y_max)`.
        connector y: RealOutput;
        equation {
            y = min(max(u, y_min), y_max);
        }
    }
}
