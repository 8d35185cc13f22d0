//! Signal blocks (MSL `Modelica.Blocks`): sources, math and continuous (linear and
//! PID) blocks. Inputs and outputs are causal signals: a `RealInput` is connected to
//! exactly one `RealOutput`.

mod continuous;
mod interfaces;
mod math;
mod sources;

pub use continuous::*;
pub use interfaces::*;
pub use math::*;
pub use sources::*;
