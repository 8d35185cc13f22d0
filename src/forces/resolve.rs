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
