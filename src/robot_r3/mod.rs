//! The parts of MSL's robot `Mechanics.MultiBody.Examples.Systems.RobotR3`: the motor
//! with its current controller, the elastic gearbox with bearing friction, the
//! cascaded axis controller, the axis that combines them and the path planning. MSL
//! wires them through expandable bus connectors; here the signals are connectors of
//! their own, with the bus's names (`angle_ref`, `motorSpeed`, ...), connected directly.
//! [`OneAxis`] is MSL's one-axis test model.

mod axis;
mod controller;
mod gear;
mod motor;
mod one_axis;
mod path;

pub use axis::*;
pub use controller::*;
pub use gear::*;
pub use motor::*;
pub use one_axis::*;
pub use path::*;
