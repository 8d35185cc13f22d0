//! A flexible beam in a floating frame of reference with analytic eigenmodes.

use super::beam_modes::{
    BeamBoundary, CrossSection, ModeData, ModeKind, mode_data, mode_shapes, section_properties,
};
use crate::blocks::StateVector;
use crate::frames::{
    Orientation, Vec3, absolute_rotation, axes_rotations, inverse_rotation, resolve1, resolve2,
};
use crate::interfaces::Frame;
use crate::prelude::*;
use crate::world::gravity_acceleration;

/// The modes of `beam`: per mode its data and its direction of displacement in the
/// beam's frame, in the order of the modal coordinates.
pub fn beam_modes(beam: &FlexibleBeam) -> Vec<(ModeData, [f64; 3])> {
    modes_of(
        beam.l,
        beam.cross_section,
        beam.rho,
        beam.E,
        beam.boundary,
        [beam.n_lengthening, beam.n_bending_xy, beam.n_bending_xz],
    )
}

/// The modes of a beam of length `l`, section `section`, density `rho` and Young's
/// modulus `e` with `counts` lengthening, xy-bending and xz-bending modes.
fn modes_of(
    l: f64,
    section: CrossSection,
    rho: f64,
    e: f64,
    boundary: BeamBoundary,
    counts: [usize; 3],
) -> Vec<(ModeData, [f64; 3])> {
    let (a, i_y, i_z) = section_properties(section);
    mode_shapes(l, boundary, counts)
        .into_iter()
        .map(|(shape, dir)| {
            let stiffness = match shape.kind {
                ModeKind::Lengthening => e * a,
                ModeKind::BendingXy => e * i_z,
                ModeKind::BendingXz => e * i_y,
            };
            (mode_data(shape, rho, a, stiffness), dir)
        })
        .collect()
}

component! {
    /// A straight, homogeneous beam of length `l` along the x axis of `frame_a`, flexible
    /// (FlexibleBodies' beam, linear): its deformation is the sum of analytic eigenmodes
    /// of the Euler-Bernoulli beam (Rayleigh-Ritz): `n_lengthening` modes along x,
    /// `n_bending_xy` along y and `n_bending_xz` along z, in the floating frame of
    /// reference `frame_a` (with `ClampedFree`, the beam's tangent frame there: a
    /// cantilever; with `SupportedSupported`, its chord frame: the ends do not move
    /// across it). `frame_b` is at the deformed end, turned by its slopes. The modal
    /// coordinates `q.x[i]` (in the order lengthening, bending xy, bending xz) and their
    /// rates `qd.x[i]` are states, with modal damping `damping` (the ratio of critical
    /// damping of every mode).
    ///
    /// The equations are those of the floating frame of reference to first order in the
    /// deformation: the rigid motion with the deformation's first moment and its
    /// inertial coupling to the modes (translational and rotational), the centrifugal
    /// loads on the modes; the Coriolis coupling between modes, the deformation's
    /// change of the inertia tensor and geometric stiffening are left out (as in a
    /// first-order displacement field). Torsion is not modelled.
    #[type_name = "FlexibleBodies.Beam"]
    pub struct FlexibleBeam {
        /// Length \[m\], default 1.58 (the seed's beam).
        structural l: f64 = 1.58;
        /// Cross-section, default the seed's I-profile (width 0.02, height 0.03, bar
        /// and flanges 0.001 m).
        structural cross_section: CrossSection = CrossSection::default();
        /// Density \[kg/m3\], default 7850 (steel).
        structural rho: f64 = 7850.0;
        /// Young's modulus \[N/m2\], default 2.1e11.
        structural E: f64 = 2.1e11;
        /// Boundary conditions of the modes (the choice of the floating frame), default
        /// clamped-free.
        structural boundary: BeamBoundary = BeamBoundary::ClampedFree;
        /// Number of lengthening modes, default 0.
        structural n_lengthening: usize = 0;
        /// Number of bending modes in the xy plane, default 3.
        structural n_bending_xy: usize = 3;
        /// Number of bending modes in the xz plane, default 3.
        structural n_bending_xz: usize = 3;
        /// Modal damping: ratio of critical damping of every mode, default 0.01.
        structural damping: f64 = 0.01;
        /// The floating frame (the clamped or the first supported end).
        connector frame_a: Frame;
        /// The other end, moving and turning with the deformation.
        connector frame_b: Frame;
        /// Modal coordinates \[m per unit shape\].
        component q: StateVector = StateVector { n: self.n_lengthening + self.n_bending_xy + self.n_bending_xz, start: Vec::new() };
        /// Their rates.
        component qd: StateVector = StateVector { n: self.n_lengthening + self.n_bending_xy + self.n_bending_xz, start: Vec::new() };
        /// Position of `frame_a`, resolved in world \[m\].
        variable r_0: Vec3;
        /// Velocity of `frame_a`, resolved in world \[m/s\].
        variable v_0: Vec3;
        /// Acceleration of `frame_a`, resolved in world \[m/s2\].
        variable a_0: Vec3;
        /// Angular velocity of `frame_a`, resolved in it \[rad/s\].
        variable w_a: Vec3;
        /// Angular acceleration of `frame_a`, resolved in it \[rad/s2\].
        variable z_a: Vec3;
        /// Displacement of the free end from `{l, 0, 0}`, resolved in `frame_a` \[m\].
        variable u_b: Vec3;
        equation {
            let modes = modes_of(l, cross_section, rho, E, boundary, [n_lengthening, n_bending_xy, n_bending_xz]);
            let (area, i_y, i_z) = section_properties(cross_section);
            let m = rho * area * l;
            // The rigid beam about frame_a (a line with its sections' rotary inertia).
            let j0 = Mat3::constant([
                [rho * (i_y + i_z) * l, 0.0, 0.0],
                [0.0, m * l * l / 3.0 + rho * i_y * l, 0.0],
                [0.0, 0.0, m * l * l / 3.0 + rho * i_z * l],
            ]);
            r_0 = frame_a.r_0;
            v_0 = der(r_0);
            a_0 = der(v_0);
            w_a = frame_a.R.w;
            z_a = der(w_a);
            let acc = resolve2(&frame_a.R, a_0 - gravity_acceleration(frame_a.r_0));
            // First moment of mass, its rates, the end's displacement and slopes (sums
            // over the modes; the DSL reads `x = ...` as an equation, so no reassignment).
            for i in 0..modes.len() {
                der(q.x(i)) = qd.x(i);
            }
            let sum = |f: &dyn Fn(usize, &ModeData, Vec3) -> Vec3| -> Vec3 {
                modes
                    .iter()
                    .enumerate()
                    .fold(Vec3::zero(), |acc, (i, (d, dir))| acc + f(i, d, Vec3::constant(*dir)))
            };
            let ex = Vec3::constant([1.0, 0.0, 0.0]);
            let s = Vec3::constant([m * l / 2.0, 0.0, 0.0]) + sum(&|i, d, dir| dir.scale(d.first * q.x(i)));
            let sd = sum(&|i, d, dir| dir.scale(d.first * qd.x(i)));
            let sdd = sum(&|i, d, dir| dir.scale(d.first * der(qd.x(i))));
            let coupling_r = sum(&|i, d, dir| ex.cross(dir).scale(d.first_x * der(qd.x(i))));
            let u = sum(&|i, d, dir| dir.scale(d.tip * q.x(i)));
            // Slopes at the end: about z from the xy modes, about y (negative) from xz.
            let slope = |kind: ModeKind, sign: f64, x: &dyn Fn(usize) -> Expr| -> Expr {
                modes.iter().enumerate().fold(Expr::constant(0.0), |acc, (i, (d, _))| {
                    if d.kind == kind { acc + sign * d.tip_slope * x(i) } else { acc }
                })
            };
            let slope_z = slope(ModeKind::BendingXy, 1.0, &|i| q.x(i));
            let slope_zd = slope(ModeKind::BendingXy, 1.0, &|i| qd.x(i));
            let slope_y = slope(ModeKind::BendingXz, -1.0, &|i| q.x(i));
            let slope_yd = slope(ModeKind::BendingXz, -1.0, &|i| qd.x(i));
            u_b = u;
            let r_b = Vec3::constant([l, 0.0, 0.0]) + u_b;
            // frame_b: at the deformed end, turned about y and z by the end's slopes.
            let zero = Expr::constant(0.0);
            let r_rel: Orientation = axes_rotations([1, 2, 3], [zero, slope_y, slope_z], [zero, slope_yd, slope_zd]);
            branch(frame_a.R, frame_b.R);
            frame_b.r_0 = frame_a.r_0 + resolve1(&frame_a.R, r_b);
            if rooted(frame_a.R) {
                frame_b.R = absolute_rotation(&frame_a.R, &r_rel);
            } else {
                frame_a.R = absolute_rotation(&frame_b.R, &inverse_rotation(&r_rel));
            }
            // The end's force and torque, resolved in frame_a.
            let f_b = resolve1(&r_rel, frame_b.f);
            let t_b = resolve1(&r_rel, frame_b.t);
            // Newton and Euler of the beam about frame_a.
            frame_a.f + f_b = acc.scale(m) + z_a.cross(s) + w_a.cross(w_a.cross(s)) + w_a.cross(sd).scale(2.0) + sdd;
            frame_a.t + t_b + r_b.cross(f_b) = s.cross(acc) + j0 * z_a + w_a.cross(j0 * w_a) + coupling_r;
            // Each mode: its inertia, damping and stiffness against the rigid motion's
            // inertial loads and the end's force and torque.
            for (i, (d, dir)) in modes.iter().enumerate() {
                let dir_v = Vec3::constant(*dir);
                let omega = (d.stiffness / d.mass).sqrt();
                let rotational = ex.cross(dir_v).scale(d.first_x);
                let centrifugal = d.first_x * (dir_v.dot(w_a) * w_a[0] - dir[0] * w_a.dot(w_a));
                let end_torque = match d.kind {
                    ModeKind::BendingXy => d.tip_slope * t_b[2],
                    ModeKind::BendingXz => -d.tip_slope * t_b[1],
                    ModeKind::Lengthening => Expr::constant(0.0),
                };
                d.mass * der(qd.x(i)) + 2.0 * damping * omega * d.mass * qd.x(i) + d.stiffness * q.x(i)
                    = -(acc.scale(d.first).dot(dir_v) + rotational.dot(z_a) + centrifugal)
                        + d.tip * dir_v.dot(f_b) + end_torque;
            }
        }
    }
}
