//! Joints (MSL `MultiBody.Joints`): elementary joints with their coordinates as
//! preferred states, and cut joints that close kinematic loops.
//!
//! Every joint relates the orientations of its two frames as a branch of the
//! orientation graph, unless it is a cut (`iscut: true`): then it emits the three
//! residues between `frame_b`'s orientation and the one its coordinates imply, and each
//! frame gets its orientation from elsewhere.

mod composite;
mod planar_loop;
mod prismatic;
mod revolute;
mod spherical;

pub use composite::*;
pub use planar_loop::*;
pub use prismatic::*;
pub use revolute::*;
pub use spherical::*;

use crate::frames::Vec3;

/// The unit vector of an axis given by the user (panics on a zero axis: a structural
/// parameter error).
pub(crate) fn unit_axis(n: [f64; 3], what: &str) -> Vec3 {
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    assert!(l > 1e-12, "{what}: the axis n must not be zero");
    Vec3::constant([n[0] / l, n[1] / l, n[2] / l])
}

/// Default priority of joint coordinates as states (Multibody.jl's default joint
/// priority; above variables without preference, below an explicit `prefer`).
pub const JOINT_STATE_PRIORITY: f64 = 3.0;
