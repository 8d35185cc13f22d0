//! Line forces: spring, damper, and both in parallel.

use crate::frames::{Vec3, null_rotation, resolve2};
use crate::interfaces::Frame;
use crate::prelude::*;

component! {
    /// The geometry of a line force between two frames (MSL `LineForceBase` and
    /// `PartialLineForce`): the force `f` acts along the line between the frames; `f > 0`
    /// is tension (it pulls the frames towards each other). No torques act on the frames
    /// (unless one is a root, below).
    ///
    /// A line force relates no orientations, so a frame where only line forces meet (the
    /// junction of springs in series) has no orientation: `fixed_rotation_at_frame_a`
    /// (`_b`) makes that frame a root parallel to the world (MSL
    /// `fixedRotationAtFrame_a`), whose torque is then whatever the connection needs.
    /// Nothing attached there may depend on that arbitrary orientation.
    #[type_name = "MultiBody.Forces.PartialLineForce"]
    pub struct PartialLineForce {
        /// Prevents a division by zero when the frames coincide \[m\].
        parameter s_small: f64 = 1e-10;
        /// Whether `frame_a` is a root with the world's orientation (its torque is then
        /// not zero) instead of a frame without torque.
        structural fixed_rotation_at_frame_a: bool = false;
        /// Whether `frame_b` is a root with the world's orientation (its torque is then
        /// not zero) instead of a frame without torque.
        structural fixed_rotation_at_frame_b: bool = false;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        /// Distance between the frame origins \[m\].
        variable length: Real;
        /// `max(length, s_small)` \[m\].
        variable s: Real;
        /// Unit vector from `frame_a` to `frame_b`, resolved in world.
        variable e_rel_0: Vec3;
        /// Tension force along the line \[N\].
        variable f: Real;
        equation {
            let r_rel_0 = frame_b.r_0 - frame_a.r_0;
            length = r_rel_0.norm();
            s = max(length, s_small);
            e_rel_0 = r_rel_0.scale(1.0 / s);
            frame_a.f = -resolve2(&frame_a.R, e_rel_0).scale(f);
            frame_b.f = resolve2(&frame_b.R, e_rel_0).scale(f);
            if fixed_rotation_at_frame_a {
                root(frame_a.R);
                frame_a.R = null_rotation();
            } else {
                frame_a.t = Vec3::zero();
            }
            if fixed_rotation_at_frame_b {
                root(frame_b.R);
                frame_b.R = null_rotation();
            } else {
                frame_b.t = Vec3::zero();
            }
        }
    }
}

component! {
    /// A linear, massless spring along the line between two frames (MSL
    /// `Forces.Spring`): tension `f = c (length - s_unstretched)`.
    #[type_name = "MultiBody.Forces.Spring"]
    pub struct Spring {
        /// Spring constant \[N/m\].
        parameter c: f64 = 1.0;
        /// Unstretched length \[m\].
        parameter s_unstretched: f64 = 0.0;
        /// Coil radius when rendered \[m\].
        structural radius: f64 = 0.05;
        /// Colour when rendered, RGB in 0..1 (MSL's spring colour, blue).
        structural color: [f64; 3] = crate::render::SPRING_COLOR;
        /// Whether `frame_a` is a root with the world's orientation, for line forces
        /// meeting without a body (MSL `fixedRotationAtFrame_a`).
        structural fixed_rotation_at_frame_a: bool = false;
        /// Whether `frame_b` is a root with the world's orientation, for line forces
        /// meeting without a body (MSL `fixedRotationAtFrame_b`).
        structural fixed_rotation_at_frame_b: bool = false;
        extends PartialLineForce { frame_a, frame_b, length, f } = PartialLineForce {
            fixed_rotation_at_frame_a: self.fixed_rotation_at_frame_a,
            fixed_rotation_at_frame_b: self.fixed_rotation_at_frame_b,
            ..PartialLineForce::default()
        };
        equation {
            f = c * (length - s_unstretched);
        }
    }
}

component! {
    /// A linear, massless damper along the line between two frames (MSL
    /// `Forces.Damper`): tension `f = d der(s)`.
    #[type_name = "MultiBody.Forces.Damper"]
    pub struct Damper {
        /// Damping constant \[N.s/m\].
        parameter d: f64 = 0.0;
        /// Whether `frame_a` is a root with the world's orientation, for line forces
        /// meeting without a body (MSL `fixedRotationAtFrame_a`).
        structural fixed_rotation_at_frame_a: bool = false;
        /// Whether `frame_b` is a root with the world's orientation, for line forces
        /// meeting without a body (MSL `fixedRotationAtFrame_b`).
        structural fixed_rotation_at_frame_b: bool = false;
        extends PartialLineForce { frame_a, frame_b, s, f } = PartialLineForce {
            fixed_rotation_at_frame_a: self.fixed_rotation_at_frame_a,
            fixed_rotation_at_frame_b: self.fixed_rotation_at_frame_b,
            ..PartialLineForce::default()
        };
        equation {
            f = d * der(s);
        }
    }
}

component! {
    /// A spring and a damper in parallel along the line between two frames (MSL
    /// `Forces.SpringDamperParallel`): `f = c (s - s_unstretched) + d der(s)`.
    #[type_name = "MultiBody.Forces.SpringDamperParallel"]
    pub struct SpringDamperParallel {
        /// Spring constant \[N/m\].
        parameter c: f64 = 1.0;
        /// Unstretched length \[m\].
        parameter s_unstretched: f64 = 0.0;
        /// Damping constant \[N.s/m\].
        parameter d: f64 = 0.0;
        /// Coil radius when rendered \[m\].
        structural radius: f64 = 0.05;
        /// Colour when rendered, RGB in 0..1 (MSL's spring colour, blue).
        structural color: [f64; 3] = crate::render::SPRING_COLOR;
        /// Whether `frame_a` is a root with the world's orientation, for line forces
        /// meeting without a body (MSL `fixedRotationAtFrame_a`).
        structural fixed_rotation_at_frame_a: bool = false;
        /// Whether `frame_b` is a root with the world's orientation, for line forces
        /// meeting without a body (MSL `fixedRotationAtFrame_b`).
        structural fixed_rotation_at_frame_b: bool = false;
        extends PartialLineForce { frame_a, frame_b, s, f } = PartialLineForce {
            fixed_rotation_at_frame_a: self.fixed_rotation_at_frame_a,
            fixed_rotation_at_frame_b: self.fixed_rotation_at_frame_b,
            ..PartialLineForce::default()
        };
        equation {
            f = c * (s - s_unstretched) + d * der(s);
        }
    }
}
