//! The frame a vector signal is resolved in (MSL `Types.ResolveInFrameAB`,
//! `ResolveInFrameA`, `ResolveInFrameB`), shared by the signal forces and the sensors.
//!
//! Each component with such a choice has a `frame_resolve` connector (MSL's conditional
//! `frame_resolve`, which in our library always exists). With the `FrameResolve` choice
//! the vector is resolved in the frame connected there, which receives no force or
//! torque; it must be connected, or its orientation is not determined (an error naming
//! `frame_resolve`). With any other choice `frame_resolve` is fixed parallel to the
//! world at its origin (MSL `Interfaces.ZeroPosition`) and must stay unconnected
//! (in MSL the connector does not exist then): connected to a mechanism fixed in the
//! world it is reported as a second root of that mechanism, but connected to a free
//! mechanism it would fix it at the world's origin, which nothing can detect (our
//! connectors always exist and components cannot see whether they are connected).

/// The frame a vector is resolved in, for components between two frames (MSL
/// `ResolveInFrameAB`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ResolveIn {
    /// The world frame.
    World,
    /// `frame_a`.
    FrameA,
    /// `frame_b`.
    #[default]
    FrameB,
    /// The frame connected to `frame_resolve`.
    FrameResolve,
}

/// The frame a vector is resolved in, for components on one frame `frame_a` (MSL
/// `ResolveInFrameA`, the absolute sensors).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ResolveInA {
    /// The world frame.
    World,
    /// `frame_a`.
    #[default]
    FrameA,
    /// The frame connected to `frame_resolve`.
    FrameResolve,
}

/// The frame a vector is resolved in, for components acting on one frame `frame_b`
/// (MSL `ResolveInFrameB`, the world forces and torques).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ResolveInB {
    /// The world frame.
    #[default]
    World,
    /// `frame_b`.
    FrameB,
    /// The frame connected to `frame_resolve`.
    FrameResolve,
}

use crate::frames::{Vec3, null_rotation};
use crate::interfaces::Frame;
use crate::prelude::*;

component! {
    /// The `frame_resolve` connector of a component whose vectors may be resolved in a
    /// frame of the user's choice, with what that frame receives (the base of the signal
    /// forces and the sensors): nothing when `used`, otherwise MSL's `ZeroPosition`
    /// (a root parallel to the world at its origin).
    #[type_name = "MultiBody.Interfaces.ResolveFrame"]
    pub struct ResolveFrame {
        /// Whether the component's vectors are resolved in the frame connected to
        /// `frame_resolve` (default false).
        structural used: bool = false;
        /// The frame the component's vectors are resolved in when `resolve_in` is
        /// `FrameResolve` (connect it then; otherwise leave it unconnected).
        connector frame_resolve: Frame;
        equation {
            if used {
                frame_resolve.f = Vec3::zero();
                frame_resolve.t = Vec3::zero();
            } else {
                root(frame_resolve.R);
                frame_resolve.R = null_rotation();
                frame_resolve.r_0 = Vec3::zero();
            }
        }
    }
}
