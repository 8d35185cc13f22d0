//! The planar revolute-revolute-revolute joint assembly.

use super::JointUSR;
use crate::frames::{Vec3, resolve1, resolve2};
use crate::interfaces::Frame;
use crate::prelude::*;
use crate::rotational;

component! {
    /// Three revolute joints with parallel axes and two rods between them, for planar
    /// loops (MSL `Joints.Assemblies.JointRRR`): rod 1 from the revolute at `frame_a` to
    /// the middle revolute (at `frame_im`), rod 2 from the revolute at `frame_b` to the
    /// middle one. Placed in a planar kinematic loop it closes the loop with no
    /// constraint and no states: the angles follow in closed form from the positions of
    /// `frame_a` and `frame_b`, so a chain of such loops needs no iteration at all. It
    /// is a `JointUSR` whose universal joint's first axis is `n_a` and whose revolute
    /// axis `n_b` is `n_a` resolved in `frame_b` at the initial time: in a planar loop
    /// the universal joint's second axis never turns, so it acts as a revolute. Only
    /// meaningful in planar loops (all axes parallel).
    ///
    /// As for `JointUSR`: `frame_a` and `frame_b` must get their orientation from
    /// outside; bodies on rod 1 are attached at `frame_ia`, on rod 2 at `frame_ib` or
    /// `frame_im`; `axis` and `bearing` are the flanges of the revolute at `frame_b`.
    #[type_name = "MultiBody.Joints.Assemblies.JointRRR"]
    pub struct JointRRR {
        /// Axis of the three revolute joints, resolved in `frame_a`.
        structural n_a: [f64; 3] = [0.0, 0.0, 1.0];
        /// Vector from `frame_a` to the middle revolute joint, resolved in `frame_ia`
        /// (parallel to `frame_a` when rod 1's angle is zero) \[m\].
        structural rRod1_ia: [f64; 3] = [1.0, 0.0, 0.0];
        /// Vector from `frame_ib` to the middle revolute joint, resolved in `frame_ib`
        /// \[m\].
        structural rRod2_ib: [f64; 3] = [-1.0, 0.0, 0.0];
        /// Offset of the angle of the revolute joint at `frame_b`:
        /// `jointUSR.revolute.angle = phi_offset + jointUSR.revolute.phi` \[deg\].
        structural phi_offset: f64 = 0.0;
        /// The configuration is the one whose revolute angle at `frame_b` is nearest
        /// `phi_offset + phi_guess` at the initial time \[deg\].
        structural phi_guess: f64 = 0.0;
        /// Frame of the revolute joint at the start of rod 1.
        connector frame_a: Frame;
        /// Frame of the revolute joint at the start of rod 2.
        connector frame_b: Frame;
        /// Frame fixed in rod 1 at the origin of `frame_a`.
        connector frame_ia: Frame;
        /// Frame fixed in rod 2 at the origin of `frame_b`.
        connector frame_ib: Frame;
        /// Frame fixed in rod 2 at the middle revolute joint, parallel to `frame_ib`.
        connector frame_im: Frame;
        /// Driving flange of the revolute joint at `frame_b`.
        connector axis: rotational::Flange;
        /// Housing flange of the revolute joint at `frame_b`.
        connector bearing: rotational::Flange;
        /// The assembly; its `n_b` is computed at initialization.
        component jointUSR: JointUSR = JointUSR {
            n1_a: self.n_a,
            rRod1_ia: self.rRod1_ia,
            rRod2_ib: self.rRod2_ib,
            phi_offset: self.phi_offset,
            phi_guess: self.phi_guess,
            compute_n_b: true,
            n_b: self.n_a,
        };
        initial_equation {
            // The axes are parallel: n_a resolved in frame_b (constant in a planar loop).
            jointUSR.n_b = resolve2(&frame_b.R, resolve1(&frame_a.R, Vec3::constant(n_a)));
        }
        equation {
            connect(jointUSR.frame_a, frame_a);
            connect(jointUSR.frame_b, frame_b);
            connect(jointUSR.frame_ia, frame_ia);
            connect(jointUSR.frame_ib, frame_ib);
            connect(jointUSR.frame_im, frame_im);
            connect(jointUSR.axis, axis);
            connect(jointUSR.bearing, bearing);
        }
    }
}
