//! The world: the inertial frame and the gravity field (MSL `MultiBody.World`).
//!
//! A model holds one `World` instance named `world` (as MSL's `inner world`): bodies read
//! its gravity parameters by that name.

use crate::frames::{Vec3, null_rotation};
use crate::interfaces::Frame;
use crate::prelude::*;

component! {
    /// The inertial frame at the origin, and uniform gravity `g` along `n` (or, with
    /// `point_gravity = 1`, point gravity `-mu/|r|^2` towards the origin). Name the
    /// instance `world`.
    #[type_name = "MultiBody.World"]
    pub struct World {
        /// Gravity acceleration magnitude \[m/s2\].
        parameter g: f64 = 9.80665;
        /// Direction of gravity, resolved in world (need not be a unit vector).
        parameter n: [f64; 3] = [0.0, -1.0, 0.0];
        /// Gravity field constant of point gravity \[m3/s2\] (the earth's by default).
        parameter mu: f64 = 3.986004418e14;
        /// 1 for point gravity towards the world origin, 0 for uniform gravity; evaluated
        /// at compile time (MSL's structural `gravityType`), so the other field costs
        /// nothing.
        parameter point_gravity(evaluate = true): f64 = 0.0;
        /// The world frame.
        connector frame_b: Frame;
        equation {
            root(frame_b.R);
            frame_b.r_0 = Vec3::zero();
            frame_b.R = null_rotation();
        }
    }
}

/// The gravity acceleration at the world position `r` (resolved in world), from the
/// parameters of the model's `world`.
pub fn gravity_acceleration(r: Vec3) -> Vec3 {
    let g = Expr::param("world.g");
    let n = Vec3(std::array::from_fn(|i| {
        Expr::param(&format!("world.n[{}]", i + 1))
    }));
    let mu = Expr::param("world.mu");
    let point = Expr::param("world.point_gravity");
    let uniform = n.scale(g / n.norm());
    let d = r.norm();
    let radial = r.scale(-mu / (d * d * d));
    Vec3(std::array::from_fn(|i| {
        Expr::if_else(point.gt(0.5), radial.0[i], uniform.0[i])
    }))
}
