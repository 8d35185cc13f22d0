//! Frames and orientations (MSL `Modelica.Mechanics.MultiBody.Frames`).
//!
//! An [`Orientation`] `R` rotates frame 1 into frame 2: `T` maps vector components,
//! `v2 = T v1`, and `w` is the angular velocity of frame 2 relative to frame 1,
//! resolved in frame 2. In a frame connector, frame 1 is the world. Rotations compose
//! to the left: `absolute_rotation(R1, R_rel)` has `T2 = T_rel T1`.
//!
//! The time derivative of an orientation is never taken through the entries of `T`:
//! declared orientations carry the rule `der(T) = -skew(w) T`, so differentiating
//! `resolve1(R, v)` gives `resolve1(R, der(v) + w x v)` (MSL's `resolve1_der`), and the
//! entries of `T` never become states.

mod orientation;
mod quaternion;

pub use multibody_core::expr::{Mat3, Vec3};
pub use orientation::*;
pub use quaternion::*;
