//! The universal-spherical-revolute joint assembly.

use super::{RevoluteWithLengthConstraint, UniversalSpherical};
use crate::frames::{Vec3, resolve_relative, resolve2};
use crate::interfaces::Frame;
use crate::parts::FixedTranslation;
use crate::prelude::*;
use crate::rotational;

component! {
    /// A universal, a spherical and a revolute joint in series, with a rod from the
    /// universal joint (at `frame_a`) to the spherical joint (at `frame_im`) and a rod
    /// from the revolute joint (at `frame_b`) to the spherical joint (MSL
    /// `Joints.Assemblies.JointUSR`). Placed in a kinematic loop it closes the loop with
    /// no constraint and no states: the revolute angle follows in closed form from the
    /// length of rod 1, the universal joint's two angles from the direction of rod 1,
    /// and the force in rod 1 from the revolute's torque balance, so the loop needs no
    /// iteration over its joint angles.
    ///
    /// Orientation is propagated from `frame_a` to `frame_ia` and from `frame_b` to
    /// `frame_ib` and `frame_im`: both `frame_a` and `frame_b` must get their
    /// orientation from outside (from the root side of the mechanism); the loop is cut
    /// at the spherical joint. Bodies on rod 1 are attached at `frame_ia`, bodies on
    /// rod 2 at `frame_ib` or `frame_im`. The revolute is driven through `axis` (its
    /// housing `bearing` is fixed at angle 0); with nothing connected there its torque
    /// is 0. Singular where rod 1 becomes parallel to `n1_a` or where rod 1 is normal to
    /// the circle the spherical joint moves on (`aux` = 0, the loop's dead points).
    #[type_name = "MultiBody.Joints.Assemblies.JointUSR"]
    pub struct JointUSR {
        /// Axis 1 of the universal joint, fixed in `frame_a` (axis 2 is normal to it and
        /// to rod 1).
        structural n1_a: [f64; 3] = [0.0, 0.0, 1.0];
        /// Vector from `frame_a` to the spherical joint, resolved in `frame_ia` (when
        /// the universal joint's angles are zero, `frame_ia` coincides with `frame_a`)
        /// \[m\]; its length is rod 1's length.
        structural rRod1_ia: [f64; 3] = [1.0, 0.0, 0.0];
        /// Vector from `frame_ib` to the spherical joint, resolved in `frame_ib` \[m\]
        /// (the default of the tunable `rod2.r`, which the assembly uses throughout).
        structural rRod2_ib: [f64; 3] = [-1.0, 0.0, 0.0];
        /// Offset of the revolute angle: `revolute.angle = phi_offset + revolute.phi`
        /// \[deg\].
        structural phi_offset: f64 = 0.0;
        /// The revolute angle's branch is the one nearest `phi_offset + phi_guess` at
        /// the initial time \[deg\].
        structural phi_guess: f64 = 0.0;
        /// `n_b` is computed at initialization by an initial equation of the enclosing
        /// assembly (`JointRRR`), and its value here is only a guess.
        structural compute_n_b: bool = false;
        /// Axis of the revolute joint, fixed in `frame_b` (need not be a unit vector).
        parameter n_b(fixed = !compute_n_b): [f64; 3] = [0.0, 0.0, 1.0];
        /// Frame of the universal joint.
        connector frame_a: Frame;
        /// Frame of the revolute joint (fixed in the body the revolute is mounted on).
        connector frame_b: Frame;
        /// Frame fixed in rod 1 at the origin of `frame_a`.
        connector frame_ia: Frame;
        /// Frame fixed in rod 2 at the origin of `frame_b`.
        connector frame_ib: Frame;
        /// Frame fixed in rod 2 at the spherical joint, parallel to `frame_ib`.
        connector frame_im: Frame;
        /// Driving flange of the revolute joint.
        connector axis: rotational::Flange;
        /// Housing flange of the revolute joint.
        connector bearing: rotational::Flange;
        /// Rod 1, from `frame_a` to the spherical joint, its length imposed by
        /// `revolute` (no constraint of its own).
        component rod1: UniversalSpherical = UniversalSpherical {
            n1_a: self.n1_a,
            rRod_ia: self.rRod1_ia,
            kinematic_constraint: false,
            ..UniversalSpherical::default()
        };
        /// Rod 2, from `frame_ib` to the spherical joint.
        component rod2: FixedTranslation = FixedTranslation { r: self.rRod2_ib, ..FixedTranslation::default() };
        /// The revolute joint from `frame_b` to `frame_ib`, its angle computed from the
        /// length of rod 1.
        component revolute: RevoluteWithLengthConstraint = RevoluteWithLengthConstraint {
            lengthConstraint: rod1.rodLength,
            n: n_b,
            phi_offset: self.phi_offset,
            phi_guess: self.phi_guess,
            ..RevoluteWithLengthConstraint::default()
        };
        /// Denominator of the rod force: `(e x rRod2_ib) . eRod` in `frame_ib` \[m\];
        /// zero at the dead points of the loop.
        variable aux: Real;
        /// Force in rod 1, positive when it is pressed \[N\].
        variable f_rod: Real;
        equation {
            connect(revolute.frame_a, frame_b);
            connect(revolute.frame_b, rod2.frame_a);
            connect(revolute.frame_b, frame_ib);
            connect(rod2.frame_b, rod1.frame_b);
            connect(rod2.frame_b, frame_im);
            connect(rod1.frame_a, frame_a);
            connect(rod1.frame_ia, frame_ia);
            connect(revolute.axis, axis);
            connect(revolute.bearing, bearing);
            // The points the length constraint relates: the universal joint (seen from
            // frame_b, resolved in frame_b) and the spherical joint (from frame_ib).
            revolute.position_a = resolve2(&frame_b.R, frame_a.r_0 - frame_b.r_0);
            revolute.position_b = rod2.r;
            // The revolute's missing equation, tau + e . revolute.frame_b.t = 0, with
            // revolute.frame_b.t from the balances of the nodes ib and im and of rod 2,
            // solved for the force in rod 1 (everything resolved in frame_ib).
            let e = n_b.scale(1.0 / n_b.norm());
            let r2 = Vec3::from(rod2.r);
            let e_rod = resolve_relative(rod1.eRod_a, &rod1.frame_a.R, &rod1.frame_b.R);
            let f_b_a1 = resolve_relative(rod1.f_b_a1, &rod1.frame_a.R, &rod1.frame_b.R);
            aux = e.cross(r2).dot(e_rod);
            f_rod = (-revolute.tau
                - e.dot(frame_ib.t + frame_im.t + r2.cross(frame_im.f) - r2.cross(f_b_a1)))
                / no_event(if_else(lt(abs(aux), 1e-10), 1e-10, aux));
            rod1.constraint_residue = rod1.f_rod - f_rod;
        }
    }
}
