//! The spherical-spherical rod: spherical joints at both ends, one length constraint,
//! an optional point mass in the middle.

use crate::frames::{Vec3, resolve_relative, resolve2};
use crate::interfaces::Frame;
use crate::prelude::*;
use crate::world::gravity_acceleration;

component! {
    /// A rod from `frame_a` to `frame_b` with a spherical joint at each end (MSL
    /// `Joints.SphericalSpherical`): one constraint, the rod length, and no torque at
    /// either end. It relates no orientations (both frames get theirs from elsewhere: it
    /// is a cut of the orientation graph), so it closes a loop with one equation instead
    /// of the six of a cut joint. The rod's spin about its own axis is not modelled (its
    /// only inertia is the optional point mass `m` in the middle).
    ///
    /// The rod length is the parameter `rodLength`, or with `compute_rod_length` it is
    /// computed at initialization from the loop (then another coordinate of the loop must
    /// be fixed, and `rodLength` is only a guess). Inside assemblies that solve their
    /// loop analytically (`JointSSP`), the rod is built with `kinematic_constraint:
    /// false` and the assembly binds `constraint_residue` itself (MSL's modifier
    /// `constraintResidue = rod1.f_rod - f_rod`).
    #[type_name = "MultiBody.Joints.SphericalSpherical"]
    pub struct SphericalSpherical {
        /// Compute the rod length at initialization instead of taking `rodLength`.
        structural compute_rod_length: bool = false;
        /// The rod imposes its length as a kinematic constraint on the loop (MSL
        /// `kinematicConstraint`, default true): `constraint_residue` is bound to
        /// `|rRod_0|^2 - rodLength^2`. Set it to false only inside assemblies, which then
        /// bind `constraint_residue` themselves. (MSL writes `rRod_0` through the frames'
        /// orientation matrices when true, for its tool's index reduction; here positions
        /// are differentiated directly and `rRod_0 = frame_b.r_0 - frame_a.r_0` in both
        /// cases.)
        structural kinematic_constraint: bool = true;
        /// Diameter of the spheres when rendered \[m\].
        structural sphere_diameter: f64 = 0.1;
        /// Diameter of the rod when rendered \[m\].
        structural rod_diameter: f64 = 0.05;
        /// Length of the rod \[m\] (with `compute_rod_length` a guess, computed at
        /// initialization).
        parameter rodLength(fixed = !compute_rod_length): f64 = 1.0;
        /// Point mass in the middle of the rod \[kg\]. With 0 when the model is built
        /// (the default) the rod is massless and its mass equations are left out; a
        /// positive value may then be changed per problem.
        parameter m: f64 = 0.0;
        /// Frame at the first spherical joint.
        connector frame_a: Frame;
        /// Frame at the second spherical joint.
        connector frame_b: Frame;
        /// Force in the rod on `frame_a`, positive when directed from `frame_a` to
        /// `frame_b` (the rod is pressed) \[N\].
        variable f_rod: Real;
        /// The residue whose zero is this rod's one equation: `|rRod_0|^2 - rodLength^2`
        /// \[m2\] with `kinematic_constraint`, otherwise bound by the enclosing assembly.
        variable constraint_residue: Real;
        /// Vector from `frame_a` to `frame_b`, resolved in world \[m\].
        variable rRod_0: Vec3;
        /// Unit vector along the rod, from `frame_a` to `frame_b`, resolved in `frame_a`.
        variable eRod_a: Vec3;
        /// Position of the point mass, resolved in world (0 without mass) \[m\].
        variable r_CM_0(state_priority = StateSelect::Avoid.priority()): Vec3;
        /// Velocity of the point mass, resolved in world (0 without mass) \[m/s\].
        variable v_CM_0(state_priority = StateSelect::Avoid.priority()): Vec3;
        /// The share of the inertial and gravity force of the point mass taken at
        /// `frame_b`, resolved in `frame_a` (0 without mass; the rod's force on
        /// `frame_b` is `f_b_a1 - f_rod * eRod_a`) \[N\].
        variable f_b_a1: Vec3;
        equation {
            rRod_0 = frame_b.r_0 - frame_a.r_0;
            0.0 = constraint_residue;
            if kinematic_constraint {
                constraint_residue = rRod_0.dot(rRod_0) - rodLength * rodLength;
            }
            let r_rod_a = resolve2(&frame_a.R, rRod_0);
            eRod_a = r_rod_a.scale(1.0 / rodLength);
            frame_a.t = Vec3::zero();
            frame_b.t = Vec3::zero();
            if self.m > 0.0 {
                r_CM_0 = frame_a.r_0 + rRod_0.scale(0.5);
                v_CM_0 = der(r_CM_0);
                // m (a - g) at the middle, resolved in frame_a: its part across the rod is
                // shared equally by both ends, its part along the rod goes to frame_b.
                let f_cm_a = resolve2(&frame_a.R, der(v_CM_0) - gravity_acceleration(r_CM_0)).scale(m);
                let f_cm_e = eRod_a.scale(f_cm_a.dot(eRod_a));
                frame_a.f = (f_cm_a - f_cm_e).scale(0.5) + eRod_a.scale(f_rod);
                f_b_a1 = (f_cm_a + f_cm_e).scale(0.5);
            } else {
                r_CM_0 = Vec3::zero();
                v_CM_0 = Vec3::zero();
                frame_a.f = eRod_a.scale(f_rod);
                f_b_a1 = Vec3::zero();
            }
            frame_b.f = resolve_relative(f_b_a1 - eRod_a.scale(f_rod), &frame_a.R, &frame_b.R);
        }
    }
}
