//! 1-D rotational mechanics (MSL `Modelica.Mechanics.Rotational`): flanges carry an
//! absolute angle `phi` \[rad\] and a cut torque `tau` \[N.m\] (positive into the
//! component).

mod components;
mod friction;
mod interfaces;
mod sensors;
mod sources;

pub use components::*;
pub use friction::*;
pub use interfaces::*;
pub use sensors::*;
pub use sources::*;
