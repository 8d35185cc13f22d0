//! Forces and torques given by signals.

use crate::blocks::RealInput3;
use crate::frames::{Vec3, resolve1, resolve2};
use crate::interfaces::Frame;
use crate::prelude::*;

/// The frame a vector signal is resolved in (MSL `ResolveInFrameAB`, without
/// `frame_resolve`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ResolveIn {
    /// The world frame.
    World,
    /// `frame_a`.
    FrameA,
    /// `frame_b`.
    #[default]
    FrameB,
}

component! {
    /// A force between two frames given by a signal (MSL `Forces.Force`): `force` acts
    /// on `frame_b`, its reaction (with the torque of the lever arm) on `frame_a`.
    #[type_name = "MultiBody.Forces.Force"]
    pub struct Force {
        /// The frame `force` is resolved in (MSL default: `frame_b`).
        structural resolve_in: ResolveIn = ResolveIn::FrameB;
        /// The force acting on `frame_b` \[N\].
        connector force: RealInput3;
        /// Frame receiving the reaction.
        connector frame_a: Frame;
        /// Frame receiving the force.
        connector frame_b: Frame;
        equation {
            let f0 = match resolve_in {
                ResolveIn::World => *force,
                ResolveIn::FrameA => resolve1(&frame_a.R, *force),
                ResolveIn::FrameB => resolve1(&frame_b.R, *force),
            };
            let f_b_0 = -f0;
            let r_0 = frame_b.r_0 - frame_a.r_0;
            frame_b.f = resolve2(&frame_b.R, f_b_0);
            frame_b.t = Vec3::zero();
            Vec3::zero() = frame_a.f + resolve2(&frame_a.R, f_b_0);
            Vec3::zero() = frame_a.t + resolve2(&frame_a.R, r_0.cross(f_b_0));
        }
    }
}

component! {
    /// A torque between two frames given by a signal (MSL `Forces.Torque`): `torque`
    /// acts on `frame_b`, its reaction on `frame_a`.
    #[type_name = "MultiBody.Forces.Torque"]
    pub struct Torque {
        /// The frame `torque` is resolved in (MSL default: `frame_b`).
        structural resolve_in: ResolveIn = ResolveIn::FrameB;
        /// The torque acting on `frame_b` \[N.m\].
        connector torque: RealInput3;
        /// Frame receiving the reaction.
        connector frame_a: Frame;
        /// Frame receiving the torque.
        connector frame_b: Frame;
        equation {
            let t0 = match resolve_in {
                ResolveIn::World => *torque,
                ResolveIn::FrameA => resolve1(&frame_a.R, *torque),
                ResolveIn::FrameB => resolve1(&frame_b.R, *torque),
            };
            frame_a.f = Vec3::zero();
            frame_b.f = Vec3::zero();
            frame_b.t = resolve2(&frame_b.R, -t0);
            Vec3::zero() = frame_a.t + resolve2(&frame_a.R, -t0);
        }
    }
}

component! {
    /// A force on a frame given by a signal, with its reaction in the world (MSL
    /// `Forces.WorldForce`).
    #[type_name = "MultiBody.Forces.WorldForce"]
    pub struct WorldForce {
        /// Whether `force` is resolved in the world (true, MSL default) or in `frame_b`.
        structural resolve_in_world: bool = true;
        /// The force acting on `frame_b` \[N\].
        connector force: RealInput3;
        /// Frame receiving the force.
        connector frame_b: Frame;
        equation {
            if resolve_in_world {
                frame_b.f = -resolve2(&frame_b.R, *force);
            } else {
                frame_b.f = -force;
            }
            frame_b.t = Vec3::zero();
        }
    }
}

component! {
    /// A torque on a frame given by a signal, with its reaction in the world (MSL
    /// `Forces.WorldTorque`).
    #[type_name = "MultiBody.Forces.WorldTorque"]
    pub struct WorldTorque {
        /// Whether `torque` is resolved in the world (true, MSL default) or in `frame_b`.
        structural resolve_in_world: bool = true;
        /// The torque acting on `frame_b` \[N.m\].
        connector torque: RealInput3;
        /// Frame receiving the torque.
        connector frame_b: Frame;
        equation {
            if resolve_in_world {
                frame_b.t = -resolve2(&frame_b.R, *torque);
            } else {
                frame_b.t = -torque;
            }
            frame_b.f = Vec3::zero();
        }
    }
}
