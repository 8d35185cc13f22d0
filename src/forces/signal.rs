//! Forces and torques between two frames given by signals (MSL `Forces.Force`,
//! `Forces.Torque`, `Forces.ForceAndTorque`).

use super::resolve::{ResolveFrame, ResolveIn};
use crate::blocks::RealInput3;
use crate::frames::{Orientation, Vec3, resolve1, resolve2};
use crate::interfaces::Frame;
use crate::prelude::*;

/// The orientation a signal is resolved in (MSL's `R` chosen by `resolveInFrame`):
/// `None` for the world.
pub(crate) fn resolving_frame<'a>(
    resolve_in: ResolveIn,
    frame_a: &'a Orientation,
    frame_b: &'a Orientation,
    frame_resolve: &'a Orientation,
) -> Option<&'a Orientation> {
    match resolve_in {
        ResolveIn::World => None,
        ResolveIn::FrameA => Some(frame_a),
        ResolveIn::FrameB => Some(frame_b),
        ResolveIn::FrameResolve => Some(frame_resolve),
    }
}

/// `v`, given in `frame` (`None`: the world), resolved in the world.
pub(crate) fn to_world(frame: Option<&Orientation>, v: Vec3) -> Vec3 {
    frame.map_or(v, |r| resolve1(r, v))
}

component! {
    /// A force between two frames given by a signal (MSL `Forces.Force`): `force` acts
    /// on `frame_b`, its reaction (with the torque of the lever arm) on `frame_a`.
    /// `force` is resolved in the frame `resolve_in` chooses; for `FrameResolve`, in the
    /// frame connected to `frame_resolve`, which receives no force.
    #[type_name = "MultiBody.Forces.Force"]
    pub struct Force {
        /// The frame `force` is resolved in (MSL `resolveInFrame`, default `frame_b`).
        structural resolve_in: ResolveIn = ResolveIn::FrameB;
        /// The force acting on `frame_b` \[N\].
        connector force: RealInput3;
        /// Frame receiving the reaction.
        connector frame_a: Frame;
        /// Frame receiving the force.
        connector frame_b: Frame;
        extends ResolveFrame { frame_resolve } = ResolveFrame { used: resolve_in == ResolveIn::FrameResolve };
        equation {
            let r_in = resolving_frame(resolve_in, &frame_a.R, &frame_b.R, &frame_resolve.R);
            let f_b_0 = -to_world(r_in, *force);
            if resolve_in == ResolveIn::FrameB {
                frame_b.f = -force;
            } else {
                frame_b.f = resolve2(&frame_b.R, f_b_0);
            }
            frame_b.t = Vec3::zero();
            let r_0 = frame_b.r_0 - frame_a.r_0;
            Vec3::zero() = frame_a.f + resolve2(&frame_a.R, f_b_0);
            Vec3::zero() = frame_a.t + resolve2(&frame_a.R, r_0.cross(f_b_0));
        }
    }
}

component! {
    /// A torque between two frames given by a signal (MSL `Forces.Torque`): `torque`
    /// acts on `frame_b`, its reaction on `frame_a`. `torque` is resolved in the frame
    /// `resolve_in` chooses; for `FrameResolve`, in the frame connected to
    /// `frame_resolve`, which receives no torque.
    #[type_name = "MultiBody.Forces.Torque"]
    pub struct Torque {
        /// The frame `torque` is resolved in (MSL `resolveInFrame`, default `frame_b`).
        structural resolve_in: ResolveIn = ResolveIn::FrameB;
        /// The torque acting on `frame_b` \[N.m\].
        connector torque: RealInput3;
        /// Frame receiving the reaction.
        connector frame_a: Frame;
        /// Frame receiving the torque.
        connector frame_b: Frame;
        extends ResolveFrame { frame_resolve } = ResolveFrame { used: resolve_in == ResolveIn::FrameResolve };
        equation {
            let r_in = resolving_frame(resolve_in, &frame_a.R, &frame_b.R, &frame_resolve.R);
            let t_b_0 = -to_world(r_in, *torque);
            frame_a.f = Vec3::zero();
            frame_b.f = Vec3::zero();
            if resolve_in == ResolveIn::FrameB {
                frame_b.t = -torque;
            } else {
                frame_b.t = resolve2(&frame_b.R, t_b_0);
            }
            Vec3::zero() = frame_a.t + resolve2(&frame_a.R, t_b_0);
        }
    }
}

component! {
    /// A force and a torque between two frames given by signals (MSL
    /// `Forces.ForceAndTorque`): `force` and `torque` act on `frame_b`, their reactions
    /// (with the torque of the lever arm) on `frame_a`. Both are resolved in the frame
    /// `resolve_in` chooses; for `FrameResolve`, in the frame connected to
    /// `frame_resolve`, which receives neither.
    #[type_name = "MultiBody.Forces.ForceAndTorque"]
    pub struct ForceAndTorque {
        /// The frame `force` and `torque` are resolved in (MSL `resolveInFrame`,
        /// default `frame_b`).
        structural resolve_in: ResolveIn = ResolveIn::FrameB;
        /// The force acting on `frame_b` \[N\].
        connector force: RealInput3;
        /// The torque acting on `frame_b` \[N.m\].
        connector torque: RealInput3;
        /// Frame receiving the reactions.
        connector frame_a: Frame;
        /// Frame receiving the force and the torque.
        connector frame_b: Frame;
        extends ResolveFrame { frame_resolve } = ResolveFrame { used: resolve_in == ResolveIn::FrameResolve };
        equation {
            let r_in = resolving_frame(resolve_in, &frame_a.R, &frame_b.R, &frame_resolve.R);
            let f_b_0 = -to_world(r_in, *force);
            let t_b_0 = -to_world(r_in, *torque);
            if resolve_in == ResolveIn::FrameB {
                frame_b.f = -force;
                frame_b.t = -torque;
            } else {
                frame_b.f = resolve2(&frame_b.R, f_b_0);
                frame_b.t = resolve2(&frame_b.R, t_b_0);
            }
            let r_0 = frame_b.r_0 - frame_a.r_0;
            Vec3::zero() = frame_a.f + resolve2(&frame_a.R, f_b_0);
            Vec3::zero() = frame_a.t + resolve2(&frame_a.R, t_b_0 + r_0.cross(f_b_0));
        }
    }
}
