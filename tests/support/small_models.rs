//! Small models shared by the event, ensemble and integrator tests (each test file
//! includes this module and uses what it needs).

#![allow(dead_code)]

use multibody::joints::Revolute;
use multibody::parts::{Body, FixedTranslation};
use multibody::prelude::*;
use multibody::world::World;

/// A pendulum of a point mass of 1 kg on a massless link of tunable length `link.r[1]`
/// (1 m), turning about z in gravity along -y.
pub fn point_pendulum() -> System {
    system! {
        name: "pendulum";
        world = World::default();
        joint = Revolute::default();
        link = FixedTranslation { r: [1.0, 0.0, 0.0] };
        bob = Body { m: 1.0, I_11: 0.0, I_22: 0.0, I_33: 0.0 };
        connect(world.frame_b, joint.frame_a);
        connect(joint.frame_b, link.frame_a);
        connect(link.frame_b, bob.frame_a);
    }
    .into()
}

component! {
    /// A ball bouncing on the ground `h = 0` with a coefficient of restitution `e`.
    pub struct BouncingBall {
        /// Gravity \[m/s2\].
        parameter g: f64 = 9.81;
        /// Coefficient of restitution.
        parameter e: f64 = 0.8;
        /// Height \[m\].
        variable h(start = 1.0, fixed = true): Real;
        /// Velocity \[m/s\].
        variable v(start = 0.0, fixed = true): Real;
        /// Number of bounces.
        variable bounces(start = 0.0): Real;
        equation {
            der(h) = v;
            der(v) = -g;
            when lt(h, 0.0) {
                reinit(v, -e * pre(v));
                bounces = pre(bounces) + 1.0;
            }
        }
    }
}
