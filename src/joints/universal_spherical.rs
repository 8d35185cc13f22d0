//! The universal-spherical rod: a massless rod with a universal joint at one end and a
//! spherical joint at the other, one length constraint that closes a loop analytically.

use crate::frames::{
    Mat3, Orientation, Vec3, absolute_rotation, resolve_relative, resolve1, resolve2,
};
use crate::interfaces::Frame;
use crate::numeric::{cross, normalize};
use crate::prelude::*;

/// The unit vector along `v` (x when `v` is zero: the component reports that).
fn normalized(v: [f64; 3]) -> [f64; 3] {
    normalize(v).unwrap_or([1.0, 0.0, 0.0])
}

component! {
    /// A massless rod from `frame_a` to `frame_b`, with a universal joint at `frame_a`
    /// (first axis `n1_a` fixed in `frame_a`, second axis across the rod) and a spherical
    /// joint at `frame_b` (MSL `Joints.UniversalSpherical`). It imposes one constraint,
    /// the rod length, solved by tearing on the coordinate of the loop it closes instead
    /// of a whole chain of joint angles. It is no branch towards `frame_b` (a loop closes
    /// there); `frame_ia`, fixed in the rod at `frame_a`'s origin, takes its orientation
    /// from `frame_a`, which must be on the side of the root. The rod length is
    /// `|rRod_ia|`, or with `compute_rod_length` computed at initialization from the
    /// loop (then another coordinate of the loop must be fixed, `rRod_ia` giving only the
    /// direction). The universal joint's second axis must not become parallel to `n1_a`.
    ///
    /// Inside assemblies that solve their loop analytically (`JointUSR`), the rod is
    /// built with `kinematic_constraint: false`: it then imposes no length constraint and
    /// the assembly binds `constraint_residue` itself (MSL's modifier
    /// `constraintResidue = rod1.f_rod - f_rod`), to determine the rod force.
    #[type_name = "MultiBody.Joints.UniversalSpherical"]
    pub struct UniversalSpherical {
        /// First axis of the universal joint, fixed in `frame_a`.
        structural n1_a: [f64; 3] = [0.0, 0.0, 1.0];
        /// Vector from `frame_a` to `frame_b` in the rod's frame `frame_ia` (when all
        /// angles are zero, `frame_ia` coincides with `frame_a`) \[m\].
        structural rRod_ia: [f64; 3] = [1.0, 0.0, 0.0];
        /// Compute the rod length at initialization instead of taking `|rRod_ia|`.
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
        /// Frame of the universal joint's end.
        connector frame_a: Frame;
        /// Frame of the spherical joint's end.
        connector frame_b: Frame;
        /// Frame fixed in the rod at the origin of `frame_a`.
        connector frame_ia: Frame;
        /// Length of the rod \[m\], computed at initialization: `|rRod_ia|`, or with
        /// `compute_rod_length` from the loop (the default is the guess).
        parameter rodLength(fixed = false): f64 = 1.0;
        /// Force in the rod, positive when it is pressed \[N\].
        variable f_rod: Real;
        /// The residue whose zero is this rod's one equation: `|rRod_0|^2 - rodLength^2`
        /// \[m2\] with `kinematic_constraint`, otherwise bound by the enclosing assembly.
        variable constraint_residue: Real;
        /// Unit vector along the rod, from `frame_a` to `frame_b`, resolved in `frame_a`.
        variable eRod_a: Vec3;
        /// Force at `frame_b` transverse to the rod that balances the torque `frame_ia`
        /// transmits through the universal joint, resolved in `frame_a` \[N\] (the
        /// rod's force on `frame_b` is `-f_rod * eRod_a + f_b_a1`).
        variable f_b_a1: Vec3;
        initial_equation {
            if !compute_rod_length {
                rodLength = (rRod_ia[0] * rRod_ia[0] + rRod_ia[1] * rRod_ia[1] + rRod_ia[2] * rRod_ia[2]).sqrt();
            }
        }
        equation {
            assert(
                normalize(rRod_ia).is_some(),
                format!("the rod rRod_ia = {} must not be zero", multibody_core::model::show_values(&rRod_ia))
            );
            assert(
                normalize(cross(n1_a, rRod_ia)).is_some(),
                format!(
                    "the axis n1_a = {} must be nonzero and not parallel to rRod_ia = {}",
                    multibody_core::model::show_values(&n1_a),
                    multibody_core::model::show_values(&rRod_ia)
                )
            );
            let e_rod_ia = normalized(rRod_ia);
            let e2_ia = normalized(cross(n1_a, e_rod_ia));
            let e3_ia = cross(e_rod_ia, e2_ia);
            let n1 = Vec3::constant(n1_a);
            // The rod from frame_a to frame_b, resolved in the world.
            let rRod_0 = frame_b.r_0 - frame_a.r_0;
            0.0 = constraint_residue;
            if kinematic_constraint {
                constraint_residue = rRod_0.dot(rRod_0) - rodLength * rodLength;
            }
            let r_rod_a = resolve2(&frame_a.R, rRod_0);
            eRod_a = r_rod_a.scale(1.0 / rodLength);
            let e_rod_a = eRod_a;
            let n2_a = n1.cross(e_rod_a);
            let length_n2_a = n2_a.dot(n2_a).sqrt();
            let e2_a = n2_a.scale(1.0 / length_n2_a);
            let e3_a = e_rod_a.cross(e2_a);
            // d(rRod_a)/dt / rodLength, through frame_a's angular velocity.
            let der_r_rod_a_l = (resolve2(&frame_a.R, rRod_0.der()) - frame_a.R.w.cross(r_rod_a))
                .scale(1.0 / rodLength);
            let w_rel_ia1 = Vec3::new(
                e3_a.dot(n1.cross(der_r_rod_a_l)) / length_n2_a,
                -e3_a.dot(der_r_rod_a_l),
                e2_a.dot(der_r_rod_a_l),
            );
            // frame_a -> rod frame (rows e_rod_a, e2_a, e3_a) -> frame_ia (constant).
            let rows = Mat3([e_rod_a.to_array(), e2_a.to_array(), e3_a.to_array()]);
            let columns = Mat3::constant([
                [e_rod_ia[0], e2_ia[0], e3_ia[0]],
                [e_rod_ia[1], e2_ia[1], e3_ia[1]],
                [e_rod_ia[2], e2_ia[2], e3_ia[2]],
            ]);
            let r_rel_ia = Orientation::new(columns.mul_mat(rows), columns.mul_vec(w_rel_ia1));
            frame_ia.r_0 = frame_a.r_0;
            branch(frame_a.R, frame_ia.R);
            frame_ia.R = absolute_rotation(&frame_a.R, &r_rel_ia);
            let f_ia_a = resolve1(&r_rel_ia, frame_ia.f);
            let t_ia_a = resolve1(&r_rel_ia, frame_ia.t);
            f_b_a1 = e2_a.scale(-n1.dot(t_ia_a) / (rodLength * n1.dot(e3_a)))
                + e3_a.scale(e2_a.dot(t_ia_a) / rodLength);
            let f_b_a = f_b_a1 - e_rod_a.scale(f_rod);
            frame_b.f = resolve_relative(f_b_a, &frame_a.R, &frame_b.R);
            frame_b.t = Vec3::zero();
            Vec3::zero() = frame_a.f + f_b_a + f_ia_a;
            Vec3::zero() = frame_a.t + t_ia_a + r_rod_a.cross(f_b_a);
        }
    }
}
