//! Forces between frames (MSL `MultiBody.Forces`): massless line forces (springs and
//! dampers acting along the line between two frames), and forces and torques given by
//! signals, resolved in a frame of choice.
//!
//! Line forces do not relate the orientations of their frames: they are no branch of
//! the orientation graph, so a mechanism closed only by line forces has no kinematic
//! loop.

mod line;
mod resolve;
mod signal;
mod world_signal;

pub use line::*;
pub use resolve::*;
pub use signal::*;
pub use world_signal::*;
