//! Forces and torques on one frame given by signals, with their reaction in the world
//! (MSL `Forces.WorldForce`, `Forces.WorldTorque`, `Forces.WorldForceAndTorque`). As in
//! MSL, the reaction on the world is not computed.

use super::resolve::{ResolveFrame, ResolveInB};
use crate::blocks::RealInput3;
use crate::frames::{Orientation, Vec3, resolve_relative, resolve2};
use crate::interfaces::Frame;
use crate::prelude::*;

/// `v`, resolved in the frame `resolve_in` chooses, resolved in `frame_b` (MSL
/// `BasicWorldForce`'s three cases).
fn in_frame_b(
    resolve_in: ResolveInB,
    v: Vec3,
    frame_b: &Orientation,
    frame_resolve: &Orientation,
) -> Vec3 {
    match resolve_in {
        ResolveInB::World => resolve2(frame_b, v),
        ResolveInB::FrameB => v,
        ResolveInB::FrameResolve => resolve_relative(v, frame_resolve, frame_b),
    }
}

component! {
    /// A force on a frame given by a signal, with its reaction in the world (MSL
    /// `Forces.WorldForce`). `force` is resolved in the frame `resolve_in` chooses; for
    /// `FrameResolve`, in the frame connected to `frame_resolve`, which receives no
    /// force.
    #[type_name = "MultiBody.Forces.WorldForce"]
    pub struct WorldForce {
        /// The frame `force` is resolved in (MSL `resolveInFrame`, default the world).
        structural resolve_in: ResolveInB = ResolveInB::World;
        /// The force acting on `frame_b` \[N\].
        connector force: RealInput3;
        /// Frame receiving the force.
        connector frame_b: Frame;
        extends ResolveFrame { frame_resolve } = ResolveFrame { used: resolve_in == ResolveInB::FrameResolve };
        equation {
            frame_b.f = -in_frame_b(resolve_in, *force, &frame_b.R, &frame_resolve.R);
            frame_b.t = Vec3::zero();
        }
    }
}

component! {
    /// A torque on a frame given by a signal, with its reaction in the world (MSL
    /// `Forces.WorldTorque`). `torque` is resolved in the frame `resolve_in` chooses;
    /// for `FrameResolve`, in the frame connected to `frame_resolve`, which receives no
    /// torque.
    #[type_name = "MultiBody.Forces.WorldTorque"]
    pub struct WorldTorque {
        /// The frame `torque` is resolved in (MSL `resolveInFrame`, default the world).
        structural resolve_in: ResolveInB = ResolveInB::World;
        /// The torque acting on `frame_b` \[N.m\].
        connector torque: RealInput3;
        /// Frame receiving the torque.
        connector frame_b: Frame;
        extends ResolveFrame { frame_resolve } = ResolveFrame { used: resolve_in == ResolveInB::FrameResolve };
        equation {
            frame_b.t = -in_frame_b(resolve_in, *torque, &frame_b.R, &frame_resolve.R);
            frame_b.f = Vec3::zero();
        }
    }
}

component! {
    /// A force and a torque on a frame given by signals, with their reactions in the
    /// world (MSL `Forces.WorldForceAndTorque`). Both are resolved in the frame
    /// `resolve_in` chooses; for `FrameResolve`, in the frame connected to
    /// `frame_resolve`, which receives neither.
    #[type_name = "MultiBody.Forces.WorldForceAndTorque"]
    pub struct WorldForceAndTorque {
        /// The frame `force` and `torque` are resolved in (MSL `resolveInFrame`, default
        /// the world).
        structural resolve_in: ResolveInB = ResolveInB::World;
        /// The force acting on `frame_b` \[N\].
        connector force: RealInput3;
        /// The torque acting on `frame_b` \[N.m\].
        connector torque: RealInput3;
        /// Frame receiving the force and the torque.
        connector frame_b: Frame;
        extends ResolveFrame { frame_resolve } = ResolveFrame { used: resolve_in == ResolveInB::FrameResolve };
        equation {
            frame_b.f = -in_frame_b(resolve_in, *force, &frame_b.R, &frame_resolve.R);
            frame_b.t = -in_frame_b(resolve_in, *torque, &frame_b.R, &frame_resolve.R);
        }
    }
}
