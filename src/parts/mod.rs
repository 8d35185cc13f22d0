//! Parts (MSL `MultiBody.Parts`): fixed frames, translations and rotations, bodies with
//! mass and inertia, drive trains on moving bodies, and a flexible beam of analytic
//! eigenmodes (FlexibleBodies' beam).

mod beam_modes;
mod body;
mod drive_train;
mod fixed;
mod flexible_beam;
mod mass_properties;
mod rolling_wheel;
mod shapes;
mod start_orientation;

pub use beam_modes::{
    BeamBoundary, CrossSection, ModeData, ModeKind, Shape, clamped_free_root, mode_data,
    mode_shapes, section_properties, torsion_constant,
};
pub use body::*;
pub use drive_train::*;
pub use fixed::*;
pub use flexible_beam::FlexibleBeam;
pub use mass_properties::MassProperties;
pub use rolling_wheel::*;
pub use shapes::*;
pub(crate) use start_orientation::{StartOrientation, given};
