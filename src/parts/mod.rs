//! Rigid parts (MSL `MultiBody.Parts`): fixed frames, translations and rotations, and
//! bodies with mass and inertia.

mod body;
mod fixed;
mod shapes;

pub use body::*;
pub use fixed::*;
pub use shapes::*;
