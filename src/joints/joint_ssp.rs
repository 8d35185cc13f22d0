//! The spherical-spherical-prismatic joint assembly.

use super::{PrismaticWithLengthConstraint, SphericalSpherical};
use crate::frames::{Vec3, resolve_relative, resolve2};
use crate::interfaces::Frame;
use crate::parts::FixedTranslation;
use crate::prelude::*;
use crate::translational;

component! {
    /// Two spherical joints and a prismatic joint in series, with rod 1 between the
    /// spherical joints (from `frame_a` to `frame_im`, optionally with a point mass in
    /// its middle) and rod 2 from the prismatic joint (at `frame_b`) to the second
    /// spherical joint (MSL `Joints.Assemblies.JointSSP`). Placed in a kinematic loop
    /// it closes the loop with no constraint and no states: the prismatic distance
    /// follows in closed form from the length of rod 1, and the force in rod 1 from the
    /// prismatic's force balance, so the loop needs no iteration over its coordinates.
    ///
    /// Orientation is propagated from `frame_b` to `frame_ib` and `frame_im`; `frame_b`
    /// must get its orientation from outside (rod 1 does not relate orientations, so
    /// `frame_a` must too). Bodies on rod 2 are attached at `frame_ib` or `frame_im`.
    /// The prismatic joint is driven through `axis` (its housing `bearing` is fixed at
    /// position 0); with nothing connected there its force is 0. Singular where rod 1
    /// is normal to the prismatic axis (`aux` = 0, the loop's dead points).
    ///
    /// The rod force includes the share of rod 1's inertial force taken at the second
    /// spherical joint (`rod1.f_b_a1`), as MSL's `JointUSP` and `JointUPS` do; MSL's
    /// `JointSSP` leaves that term out, which is exact only for `rod1Mass = 0` (its
    /// default, where both agree).
    #[type_name = "MultiBody.Joints.Assemblies.JointSSP"]
    pub struct JointSSP {
        /// Length of rod 1, the distance between the spherical joints \[m\] (the default
        /// of the tunable `rod1.rodLength`, which the assembly uses throughout).
        structural rod1Length: f64 = 1.0;
        /// Point mass in the middle of rod 1 \[kg\] (`rod1.m`; 0, the default, leaves its
        /// equations out).
        structural rod1Mass: f64 = 0.0;
        /// Axis of the prismatic joint, fixed in `frame_b`.
        structural n_b: [f64; 3] = [0.0, 0.0, 1.0];
        /// Vector from `frame_ib` to the second spherical joint, resolved in `frame_ib`
        /// \[m\] (the default of the tunable `rod2.r`, which the assembly uses
        /// throughout).
        structural rRod2_ib: [f64; 3] = [1.0, 0.0, 0.0];
        /// Offset of the prismatic distance: `prismatic.distance = s_offset +
        /// prismatic.s` \[m\].
        structural s_offset: f64 = 0.0;
        /// The prismatic distance's branch is the one nearest `s_offset + s_guess` at
        /// the initial time \[m\].
        structural s_guess: f64 = 0.0;
        /// Frame of the first spherical joint.
        connector frame_a: Frame;
        /// Frame of the prismatic joint (fixed in the body it is mounted on).
        connector frame_b: Frame;
        /// Frame fixed in rod 2 at the origin of `frame_b` (moved by the prismatic).
        connector frame_ib: Frame;
        /// Frame fixed in rod 2 at the second spherical joint, parallel to `frame_ib`.
        connector frame_im: Frame;
        /// Driving flange of the prismatic joint.
        connector axis: translational::Flange;
        /// Housing flange of the prismatic joint.
        connector bearing: translational::Flange;
        /// Rod 1, between the spherical joints, its length imposed by `prismatic` (no
        /// constraint of its own).
        component rod1: SphericalSpherical = SphericalSpherical {
            rodLength: self.rod1Length,
            m: self.rod1Mass,
            kinematic_constraint: false,
            ..SphericalSpherical::default()
        };
        /// Rod 2, from `frame_ib` to the second spherical joint.
        component rod2: FixedTranslation = FixedTranslation { r: self.rRod2_ib, ..FixedTranslation::default() };
        /// The prismatic joint from `frame_b` to `frame_ib`, its distance computed from
        /// the length of rod 1.
        component prismatic: PrismaticWithLengthConstraint = PrismaticWithLengthConstraint {
            length: rod1.rodLength,
            n: Vec3::constant(self.n_b),
            s_offset: self.s_offset,
            s_guess: self.s_guess,
            ..PrismaticWithLengthConstraint::default()
        };
        /// Denominator of the rod force: `e . eRod` in `frame_ib`; zero at the dead
        /// points of the loop.
        variable aux: Real;
        /// Force in rod 1, positive when it is pressed \[N\].
        variable f_rod: Real;
        equation {
            connect(prismatic.frame_a, frame_b);
            connect(prismatic.frame_b, rod2.frame_a);
            connect(prismatic.frame_b, frame_ib);
            connect(rod2.frame_b, rod1.frame_b);
            connect(rod2.frame_b, frame_im);
            connect(rod1.frame_a, frame_a);
            connect(prismatic.axis, axis);
            connect(prismatic.bearing, bearing);
            // The points the length constraint relates: the first spherical joint (seen
            // from frame_b, resolved in frame_b) and the second one (from frame_ib).
            prismatic.position_a = resolve2(&frame_b.R, frame_a.r_0 - frame_b.r_0);
            prismatic.position_b = rod2.r;
            // The prismatic's missing equation, f + e . prismatic.frame_b.f = 0, with
            // prismatic.frame_b.f from the balances of the nodes ib and im and of rod 2,
            // solved for the force in rod 1 (everything resolved in frame_ib).
            let e = Vec3::constant(n_b).scale(1.0 / Vec3::constant(n_b).norm());
            let e_rod = resolve_relative(rod1.eRod_a, &rod1.frame_a.R, &rod1.frame_b.R);
            let f_b_a1 = resolve_relative(rod1.f_b_a1, &rod1.frame_a.R, &rod1.frame_b.R);
            aux = e.dot(e_rod);
            f_rod = (-prismatic.f - e.dot(frame_ib.f + frame_im.f - f_b_a1))
                / no_event(if_else(lt(abs(aux), 1e-10), 1e-10, aux));
            rod1.constraint_residue = rod1.f_rod - f_rod;
        }
    }
}
