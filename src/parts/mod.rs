//! Rigid parts (MSL `MultiBody.Parts`): fixed frames, translations and rotations, and
//! bodies with mass and inertia.

mod body;
mod fixed;
mod mass_properties;
mod shapes;
mod start_orientation;

pub use body::*;
pub use fixed::*;
pub use mass_properties::MassProperties;
pub use shapes::*;
pub(crate) use start_orientation::{StartOrientation, given};
