//! The 3-D frame connector (MSL `MultiBody.Interfaces.Frame`).

use crate::frames::{Orientation, Vec3};
use crate::prelude::*;

connector! {
    /// A coordinate system fixed to a component. Its position `r_0` is resolved in the
    /// world frame, its orientation `R` rotates the world frame into it, and the cut
    /// force `f` and torque `t` act on the component at the frame's origin, resolved in
    /// the frame itself (positive into the component).
    pub struct Frame {
        /// Position of the origin, resolved in world \[m\].
        potential r_0: Vec3;
        /// Orientation relative to the world (overdetermined: related through the
        /// virtual connection graph).
        overdetermined R: Orientation;
        /// Cut force, resolved in this frame \[N\].
        flow f: Vec3;
        /// Cut torque about the origin, resolved in this frame \[N.m\].
        flow t: Vec3;
    }
}
