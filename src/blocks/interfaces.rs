//! Signal connectors and the initialization choices of continuous blocks.

use crate::prelude::*;

connector! {
    /// A real input signal (MSL `RealInput`): the connector is the signal itself.
    pub struct RealInput = input Real;
}

connector! {
    /// A real output signal (MSL `RealOutput`).
    pub struct RealOutput = output Real;
}

connector! {
    /// A vector of three real input signals (MSL `RealInput[3]`).
    pub struct RealInput3 = input Vec3;
}

connector! {
    /// A vector of three real output signals (MSL `RealOutput[3]`).
    pub struct RealOutput3 = output Vec3;
}

/// How a continuous block initializes its state (MSL `Modelica.Blocks.Types.Init`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Init {
    /// No initial equation: the start values are used as guesses (the state's start is
    /// assumed fixed if nothing else determines it).
    #[default]
    NoInit,
    /// The derivatives of the states are zero at the start.
    SteadyState,
    /// The states equal their start values (`x_start`, `y_start`).
    InitialState,
    /// The output equals `y_start`.
    InitialOutput,
}
