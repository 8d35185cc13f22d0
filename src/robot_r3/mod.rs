//! The parts of MSL's robot `Mechanics.MultiBody.Examples.Systems.RobotR3`: the motor
//! with its current controller, the elastic gearbox with bearing friction, the
//! cascaded axis controller, the axis that combines them and the path planning. MSL
//! wires them through expandable bus connectors; here the signals are connectors of
//! their own, with the bus's names (`angle_ref`, `motorSpeed`, ...), connected directly.
//! [`OneAxis`] is MSL's one-axis test model, [`FullRobot`] the six-axis robot with its
//! [`MechanicalStructure`].

mod axis;
mod controller;
mod full_robot;
mod gear;
mod mechanics;
mod motor;
mod one_axis;
mod path;

pub use axis::*;
pub use controller::*;
pub use full_robot::*;
pub use gear::*;
pub use mechanics::*;
pub use motor::*;
pub use one_axis::*;
pub use path::*;
