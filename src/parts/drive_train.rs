//! Drive trains on moving bodies (MSL `Parts.Mounting1D`, `Parts.Rotor1D`,
//! `Parts.BevelGear1D`): 1-D rotational elements whose housing is a 3-D frame, so that
//! their reaction and gyroscopic torques act on the body that carries them. Their angles
//! are relative to that frame.

use crate::frames::Vec3;
use crate::interfaces::Frame;
use crate::joints::{invalid_axis, unit_axis, valid_axis};
use crate::prelude::*;
use crate::rotational::Flange;

component! {
    /// The housing of 1-D elements fixed in a 3-D frame (MSL `Parts.Mounting1D`): its
    /// flange is fixed at `phi0` relative to `frame_a`, and the torque that the 1-D
    /// elements exert on their support acts on `frame_a` about the axis `n`.
    #[type_name = "MultiBody.Parts.Mounting1D"]
    pub struct Mounting1D {
        /// Angle of the housing's flange \[rad\], default 0.
        parameter phi0: f64 = 0.0;
        /// Axis of the support torque, resolved in `frame_a` (used as given, as MSL's),
        /// default {1, 0, 0}.
        structural n: [f64; 3] = [1.0, 0.0, 0.0];
        /// The flange fixed in the housing (connect the 1-D supports to it).
        connector flange_b: Flange;
        /// The frame in which the housing is fixed.
        connector frame_a: Frame;
        equation {
            assert(valid_axis(n), invalid_axis("n", n));
            flange_b.phi = phi0;
            frame_a.f = Vec3::zero();
            frame_a.t = Vec3::constant(n).scale(-flange_b.tau);
        }
    }
}

component! {
    /// A rotor of inertia `J` about the axis `n` of a body that carries it (MSL
    /// `Parts.Rotor1D` with `driveTrainMechanics3D`): its angle `phi`, speed `w` and
    /// acceleration `a` are relative to `frame_a`; the gyroscopic torque of its spin and
    /// the reaction of the carrier's acceleration act on `frame_a`. The rotor's mass and
    /// its inertia (including `J`) belong to a body fixed to the carrier; the torques of
    /// its drive reach the carrier through a [`Mounting1D`] or [`BevelGear1D`]. With
    /// `exact = false` the carrier's angular acceleration is left out of the rotor's
    /// equation (MSL's option against an algebraic loop).
    #[type_name = "MultiBody.Parts.Rotor1D"]
    pub struct Rotor1D {
        /// Moment of inertia about the axis \[kg.m2\], default 1.
        parameter J(min = 0.0): f64 = 1.0;
        /// Axis of rotation, resolved in `frame_a`, default {1, 0, 0}.
        structural n: [f64; 3] = [1.0, 0.0, 0.0];
        /// Whether the carrier's angular acceleration enters the rotor's equation
        /// (default true).
        structural exact: bool = true;
        /// Start value of the angle \[rad\], default 0.
        structural phi_start: f64 = 0.0;
        /// Start value of the speed \[rad/s\], default 0.
        structural w_start: f64 = 0.0;
        /// Driving flange.
        connector flange_a: Flange;
        /// Driven flange.
        connector flange_b: Flange;
        /// The frame of the carrier.
        connector frame_a: Frame;
        /// Angle of the rotor relative to `frame_a` \[rad\].
        variable phi(start = phi_start): Real;
        /// Speed of the rotor relative to `frame_a` \[rad/s\].
        variable w(start = w_start): Real;
        /// Acceleration of the rotor relative to `frame_a` \[rad/s2\].
        variable a: Real;
        /// Angular velocity of `frame_a`, resolved in `frame_a` \[rad/s\].
        variable w_a: Vec3;
        equation {
            assert(valid_axis(n), invalid_axis("n", n));
            let e = unit_axis(n);
            phi = flange_a.phi;
            phi = flange_b.phi;
            w = der(phi);
            a = der(w);
            w_a = frame_a.R.w;
            if exact {
                J * a = flange_a.tau + flange_b.tau - J * e.dot(der(w_a));
            } else {
                J * a = flange_a.tau + flange_b.tau;
            }
            frame_a.f = Vec3::zero();
            frame_a.t = w_a.cross(e.scale(J * w)) - e.scale(J * e.dot(der(w_a)));
        }
    }
}

component! {
    /// A gearbox between shafts of any directions in a bearing frame (MSL
    /// `Parts.BevelGear1D`): `flange_a.phi = ratio * flange_b.phi`, angles relative to
    /// `frame_a`, and the torques of both shafts' reactions act on `frame_a`.
    #[type_name = "MultiBody.Parts.BevelGear1D"]
    pub struct BevelGear1D {
        /// Speed ratio `w_a / w_b` \[1\], default 1.
        parameter ratio: f64 = 1.0;
        /// Axis of `flange_a`, resolved in `frame_a`, default {1, 0, 0}.
        structural n_a: [f64; 3] = [1.0, 0.0, 0.0];
        /// Axis of `flange_b`, resolved in `frame_a`, default {1, 0, 0}.
        structural n_b: [f64; 3] = [1.0, 0.0, 0.0];
        /// Input shaft.
        connector flange_a: Flange;
        /// Output shaft.
        connector flange_b: Flange;
        /// The bearing frame.
        connector frame_a: Frame;
        equation {
            assert(valid_axis(n_a), invalid_axis("n_a", n_a));
            assert(valid_axis(n_b), invalid_axis("n_b", n_b));
            let (e_a, e_b) = (unit_axis(n_a), unit_axis(n_b));
            flange_a.phi = ratio * flange_b.phi;
            0.0 = ratio * flange_a.tau + flange_b.tau;
            frame_a.f = Vec3::zero();
            frame_a.t = -(e_a.scale(flange_a.tau) + e_b.scale(flange_b.tau));
        }
    }
}
