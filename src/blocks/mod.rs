//! Signal blocks (MSL `Modelica.Blocks`): sources (also periodic, tables from rows or
//! files, point-to-point moves), math, continuous (linear of any order, PID), discrete
//! (sampled) and logical (switching) blocks. Inputs and outputs are causal signals: a
//! `RealInput` is connected to exactly one `RealOutput`.

mod combi;
mod continuous;
pub(crate) use continuous::bessel_follow;
mod discrete;
mod interfaces;
mod kinematic;
mod linear;
mod logical;
mod math;
mod periodic;
mod sources;
mod table_file;

pub use combi::*;
pub use continuous::*;
pub use discrete::*;
pub use interfaces::*;
pub use kinematic::*;
pub use linear::*;
pub use logical::*;
pub use math::*;
pub use periodic::*;
pub use sources::*;
pub use table_file::read_table;
