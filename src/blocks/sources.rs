//! Signal sources of time.

use super::interfaces::*;
use crate::prelude::*;

component! {
    /// A constant signal (MSL `Blocks.Sources.Constant`).
    #[type_name = "Blocks.Constant"]
    pub struct Constant {
        /// The value of the output.
        parameter k: f64 = 1.0;
        /// Output.
        connector y: RealOutput;
        equation {
            y = k;
        }
    }
}

component! {
    /// A step: `offset` before `start_time`, `offset + height` from then on (MSL
    /// `Blocks.Sources.Step`).
    #[type_name = "Blocks.Step"]
    pub struct Step {
        /// Height of the step.
        parameter height: f64 = 1.0;
        /// Offset of the output.
        parameter offset: f64 = 0.0;
        /// Time of the step [s].
        parameter start_time: f64 = 0.0;
        /// Output.
        connector y: RealOutput;
        equation {
            y = offset + if_else(lt(time, start_time), 0.0, height);
        }
    }
}

component! {
    /// A sine wave starting at `start_time` (MSL `Blocks.Sources.Sine`).
    #[type_name = "Blocks.Sine"]
    pub struct Sine {
        /// Amplitude.
        parameter amplitude: f64 = 1.0;
        /// Frequency [Hz].
        parameter f: f64 = 1.0;
        /// Phase [rad].
        parameter phase: f64 = 0.0;
        /// Offset of the output.
        parameter offset: f64 = 0.0;
        /// Output is `offset` before this time [s].
        parameter start_time: f64 = 0.0;
        /// Output.
        connector y: RealOutput;
        equation {
            y = offset
                + if_else(
                    lt(time, start_time),
                    0.0,
                    amplitude * sin(2.0 * PI * f * (time - start_time) + phase),
                );
        }
    }
}

component! {
    /// A ramp from `offset` to `offset + height` over `duration` from `start_time` (MSL
    /// `Blocks.Sources.Ramp`).
    #[type_name = "Blocks.Ramp"]
    pub struct Ramp {
        /// Height of the ramp.
        parameter height: f64 = 1.0;
        /// Duration of the ramp [s].
        parameter duration: f64 = 1.0;
        /// Offset of the output.
        parameter offset: f64 = 0.0;
        /// Start time of the ramp [s].
        parameter start_time: f64 = 0.0;
        /// Output.
        connector y: RealOutput;
        equation {
            y = offset
                + if_else(
                    lt(time, start_time),
                    0.0,
                    if_else(
                        lt(time, start_time + duration),
                        (time - start_time) * height / duration,
                        height,
                    ),
                );
        }
    }
}

component! {
    /// A constant vector signal (MSL `Blocks.Sources.Constant` three times, as MSL feeds
    /// the vector inputs of the 3-D forces), for inputs such as `RealInput3`.
    #[type_name = "Blocks.Constant3"]
    pub struct Constant3 {
        /// The value of the output (unit of the input it feeds).
        parameter k: [f64; 3] = [0.0, 0.0, 0.0];
        /// Output.
        connector y: RealOutput3;
        equation {
            y = k;
        }
    }
}

/// The default of [`RealExpression3::expression`]: zero.
fn zero3(_time: Expr) -> Vec3 {
    Vec3::zero()
}

component! {
    /// A vector signal given by an expression of time (MSL `Blocks.Sources.RealExpression`
    /// three times): `y = expression(time)`, e.g.
    /// `RealExpression3 { expression: |t| Vec3::new(sin(t), 0.0, 2.0 * t) }`. The
    /// function is called once, when the model is built, with the symbol `time`.
    #[type_name = "Blocks.RealExpression3"]
    pub struct RealExpression3 {
        /// The output as a function of the symbol `time` (unit of the input it feeds).
        structural expression: fn(Expr) -> Vec3 = zero3;
        /// Output.
        connector y: RealOutput3;
        equation {
            y = expression(time);
        }
    }
}
