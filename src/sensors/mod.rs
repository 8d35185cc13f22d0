//! Ideal sensors (MSL `MultiBody.Sensors`): they measure without acting (no force or
//! torque), except the cut sensors and `Power`, which sit rigidly in a connection.

use crate::blocks::{RealOutput, RealOutput3};
use crate::frames::{
    Vec3, axes_rotations_angles_expr, invalid_sequence, relative_rotation, resolve_relative,
    resolve1, resolve2, usable_sequence, valid_sequence,
};
use crate::interfaces::Frame;
use crate::prelude::*;

use crate::forces::ResolveFrame;
pub use crate::forces::{ResolveIn, ResolveInA};

component! {
    /// The position of `frame_b` relative to `frame_a` (MSL `Sensors.RelativePosition`),
    /// resolved in `frame_a` by default, or in the frame connected to `frame_resolve`.
    #[type_name = "MultiBody.Sensors.RelativePosition"]
    pub struct RelativePosition {
        /// The frame the result is resolved in (MSL default: `frame_a`).
        structural resolve_in: ResolveIn = ResolveIn::FrameA;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        extends ResolveFrame { frame_resolve } = ResolveFrame { used: resolve_in == ResolveIn::FrameResolve };
        /// `frame_b.r_0 - frame_a.r_0`, resolved as chosen \[m\].
        connector r_rel: RealOutput3;
        equation {
            let d = frame_b.r_0 - frame_a.r_0;
            r_rel = match resolve_in {
                ResolveIn::World => d,
                ResolveIn::FrameA => resolve2(&frame_a.R, d),
                ResolveIn::FrameB => resolve2(&frame_b.R, d),
                ResolveIn::FrameResolve => resolve2(&frame_resolve.R, d),
            };
            frame_a.f = Vec3::zero();
            frame_a.t = Vec3::zero();
            frame_b.f = Vec3::zero();
            frame_b.t = Vec3::zero();
        }
    }
}

component! {
    /// The velocity of `frame_b` relative to `frame_a`: the derivative of the relative
    /// position resolved in `frame_a` (MSL `Sensors.RelativeVelocity`), then resolved
    /// as chosen (in `frame_a` by default, or in the frame connected to
    /// `frame_resolve`).
    #[type_name = "MultiBody.Sensors.RelativeVelocity"]
    pub struct RelativeVelocity {
        /// The frame the result is resolved in (MSL default: `frame_a`).
        structural resolve_in: ResolveIn = ResolveIn::FrameA;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        extends ResolveFrame { frame_resolve } = ResolveFrame { used: resolve_in == ResolveIn::FrameResolve };
        /// Relative velocity, resolved as chosen \[m/s\].
        connector v_rel: RealOutput3;
        /// Relative position resolved in `frame_a` \[m\].
        variable r_rel_a: Vec3;
        /// Its derivative \[m/s\].
        variable v_rel_a: Vec3;
        equation {
            r_rel_a = resolve2(&frame_a.R, frame_b.r_0 - frame_a.r_0);
            v_rel_a = der(r_rel_a);
            v_rel = match resolve_in {
                ResolveIn::World => resolve1(&frame_a.R, v_rel_a),
                ResolveIn::FrameA => v_rel_a,
                ResolveIn::FrameB => resolve_relative(v_rel_a, &frame_a.R, &frame_b.R),
                ResolveIn::FrameResolve => {
                    resolve_relative(v_rel_a, &frame_a.R, &frame_resolve.R)
                }
            };
            frame_a.f = Vec3::zero();
            frame_a.t = Vec3::zero();
            frame_b.f = Vec3::zero();
            frame_b.t = Vec3::zero();
        }
    }
}

component! {
    /// The position of a frame (MSL `Sensors.AbsolutePosition`), resolved in the frame
    /// itself by default, in the world, or in the frame connected to `frame_resolve`.
    #[type_name = "MultiBody.Sensors.AbsolutePosition"]
    pub struct AbsolutePosition {
        /// The frame the result is resolved in (MSL default: `frame_a`).
        structural resolve_in: ResolveInA = ResolveInA::FrameA;
        /// The frame.
        connector frame_a: Frame;
        extends ResolveFrame { frame_resolve } = ResolveFrame { used: resolve_in == ResolveInA::FrameResolve };
        /// Its position \[m\].
        connector r: RealOutput3;
        equation {
            r = match resolve_in {
                ResolveInA::World => frame_a.r_0,
                ResolveInA::FrameA => resolve2(&frame_a.R, frame_a.r_0),
                ResolveInA::FrameResolve => resolve2(&frame_resolve.R, frame_a.r_0),
            };
            frame_a.f = Vec3::zero();
            frame_a.t = Vec3::zero();
        }
    }
}

component! {
    /// The velocity of a frame (MSL `Sensors.AbsoluteVelocity`): the derivative of its
    /// world-resolved position, resolved in the frame itself by default, in the world,
    /// or in the frame connected to `frame_resolve`.
    #[type_name = "MultiBody.Sensors.AbsoluteVelocity"]
    pub struct AbsoluteVelocity {
        /// The frame the result is resolved in (MSL default: `frame_a`).
        structural resolve_in: ResolveInA = ResolveInA::FrameA;
        /// The frame.
        connector frame_a: Frame;
        extends ResolveFrame { frame_resolve } = ResolveFrame { used: resolve_in == ResolveInA::FrameResolve };
        /// Its velocity \[m/s\].
        connector v: RealOutput3;
        /// Velocity resolved in world \[m/s\].
        variable v_0: Vec3;
        equation {
            v_0 = der(frame_a.r_0);
            v = match resolve_in {
                ResolveInA::World => v_0,
                ResolveInA::FrameA => resolve2(&frame_a.R, v_0),
                ResolveInA::FrameResolve => resolve2(&frame_resolve.R, v_0),
            };
            frame_a.f = Vec3::zero();
            frame_a.t = Vec3::zero();
        }
    }
}

component! {
    /// The angles of the axis sequence that rotate `frame_a` into `frame_b` (MSL
    /// `Sensors.RelativeAngles`), each in (-pi, pi].
    #[type_name = "MultiBody.Sensors.RelativeAngles"]
    pub struct RelativeAngles {
        /// Axis sequence.
        structural sequence: [usize; 3] = [1, 2, 3];
        /// The first angle is chosen nearest this one \[rad\].
        structural guess_angle1: f64 = 0.0;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        /// The angles \[rad\].
        connector angles: RealOutput3;
        equation {
            let r_rel = relative_rotation(&frame_a.R, &frame_b.R);
            assert(valid_sequence(sequence), invalid_sequence("sequence", sequence));
            angles = axes_rotations_angles_expr(r_rel.T, usable_sequence(sequence), guess_angle1);
            frame_a.f = Vec3::zero();
            frame_a.t = Vec3::zero();
            frame_b.f = Vec3::zero();
            frame_b.t = Vec3::zero();
        }
    }
}

component! {
    /// The cut force between two rigidly connected frames (MSL `Sensors.CutForce`): the
    /// force the `frame_a` side exerts on the `frame_b` side, resolved in `frame_a`.
    #[type_name = "MultiBody.Sensors.CutForce"]
    pub struct CutForce {
        /// Whether the result is resolved in the world (otherwise in `frame_a`).
        structural resolve_in_world: bool = false;
        /// Side a.
        connector frame_a: Frame;
        /// Side b.
        connector frame_b: Frame;
        /// The cut force \[N\].
        connector force: RealOutput3;
        equation {
            branch(frame_a.R, frame_b.R);
            frame_b.r_0 = frame_a.r_0;
            frame_b.R = frame_a.R;
            Vec3::zero() = frame_a.f + frame_b.f;
            Vec3::zero() = frame_a.t + frame_b.t;
            if resolve_in_world {
                force = resolve1(&frame_a.R, frame_a.f);
            } else {
                force = frame_a.f;
            }
        }
    }
}

component! {
    /// The cut torque between two rigidly connected frames (MSL `Sensors.CutTorque`),
    /// resolved in `frame_a`.
    #[type_name = "MultiBody.Sensors.CutTorque"]
    pub struct CutTorque {
        /// Whether the result is resolved in the world (otherwise in `frame_a`).
        structural resolve_in_world: bool = false;
        /// Side a.
        connector frame_a: Frame;
        /// Side b.
        connector frame_b: Frame;
        /// The cut torque \[N.m\].
        connector torque: RealOutput3;
        equation {
            branch(frame_a.R, frame_b.R);
            frame_b.r_0 = frame_a.r_0;
            frame_b.R = frame_a.R;
            Vec3::zero() = frame_a.f + frame_b.f;
            Vec3::zero() = frame_a.t + frame_b.t;
            if resolve_in_world {
                torque = resolve1(&frame_a.R, frame_a.t);
            } else {
                torque = frame_a.t;
            }
        }
    }
}

component! {
    /// The power flowing from `frame_a` to `frame_b` through a rigid connection (MSL
    /// `Sensors.Power`).
    #[type_name = "MultiBody.Sensors.Power"]
    pub struct Power {
        /// Side a.
        connector frame_a: Frame;
        /// Side b.
        connector frame_b: Frame;
        /// Power \[W\].
        connector power: RealOutput;
        equation {
            branch(frame_a.R, frame_b.R);
            frame_b.r_0 = frame_a.r_0;
            frame_b.R = frame_a.R;
            Vec3::zero() = frame_a.f + frame_b.f;
            Vec3::zero() = frame_a.t + frame_b.t;
            power = frame_a.f.dot(resolve2(&frame_a.R, frame_a.r_0.der())) + frame_a.t.dot(frame_a.R.w);
        }
    }
}
