//! Rigid parts (MSL `MultiBody.Parts`): fixed frames, translations and rotations, and
//! bodies with mass and inertia, and drive trains on moving bodies.

mod body;
mod drive_train;
mod fixed;
mod mass_properties;
mod rolling_wheel;
mod shapes;
mod start_orientation;

pub use body::*;
pub use drive_train::*;
pub use fixed::*;
pub use mass_properties::MassProperties;
pub use rolling_wheel::*;
pub use shapes::*;
pub(crate) use start_orientation::{StartOrientation, given};
