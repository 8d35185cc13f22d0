//! A flexible beam in a floating frame of reference with analytic eigenmodes.

use super::beam_modes::{
    BeamBoundary, CrossSection, ModeData, ModeKind, mode_data, mode_shapes, pair_integrals,
    section_properties, torsion_constant,
};
use crate::blocks::StateVector;
use crate::frames::{
    Orientation, Vec3, absolute_rotation, axes_rotations, axis, inverse_rotation, resolve1,
    resolve2,
};
use crate::interfaces::Frame;
use crate::prelude::*;
use crate::world::gravity_acceleration;

/// The modes of a beam of length `l`, section `section`, density `rho`, Young's
/// modulus `e` and Poisson's ratio `nu` with `counts` lengthening, xy-bending,
/// xz-bending and torsion modes.
fn modes_of(
    l: f64,
    section: CrossSection,
    rho: f64,
    e: f64,
    nu: f64,
    boundary: BeamBoundary,
    counts: [usize; 4],
) -> Vec<(ModeData, [f64; 3])> {
    let (a, i_y, i_z) = section_properties(section);
    let shear = e / (2.0 * (1.0 + nu));
    mode_shapes(l, boundary, counts)
        .into_iter()
        .map(|(shape, dir)| {
            // Torsion: rho I_p per length turning, G J_t stiff.
            let (per_length, stiffness) = match shape.kind {
                ModeKind::Lengthening => (a, e * a),
                ModeKind::BendingXy => (a, e * i_z),
                ModeKind::BendingXz => (a, e * i_y),
                ModeKind::Torsion => (i_y + i_z, shear * torsion_constant(section)),
            };
            (mode_data(shape, rho, per_length, stiffness), dir)
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
    /// across it), and `n_torsion` modes of twist about x (clamped-free with either
    /// boundary). `frame_b` is at the deformed end, turned by its twist and slopes. The
    /// modal coordinates `q.x[i]` (in the order lengthening, bending xy, bending xz,
    /// torsion) and their
    /// rates `qd.x[i]` are states, with modal damping `damping` (the ratio of critical
    /// damping of every mode).
    ///
    /// The equations are those of the floating frame of reference with the exact
    /// inertia of this displacement field (linear in the modal coordinates): the rigid
    /// motion with the deformation's first moment and its change of the inertia tensor,
    /// the inertial coupling of the modes to the rigid motion (translational,
    /// rotational, centrifugal) and to each other (centrifugal softening, Coriolis), and
    /// the end's force and torque on the modes through the exact axes of the rotations
    /// that turn `frame_b`. With `geometric_stiffening`, the bending modes
    /// are stiffened by the axial force from the inertial loads (centrifugal, axial
    /// acceleration) and the end's axial force (the second-order strain of a rotating
    /// beam; without it a fast spinning beam is far too soft). The twisted sections'
    /// rotary inertia couples torsion to the rotation about x and, for unequal second
    /// moments, to the rotation about y and z. Not modelled: the sections' rotation with
    /// the bending slopes (Rayleigh beam), warping, the shear centre's offset. Without
    /// geometric stiffening and damping the beam keeps its energy exactly, with whatever
    /// is attached at its ends (`kinetic_energy`, `elastic_energy`).
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
        /// Number of torsion modes, default 0.
        structural n_torsion: usize = 0;
        /// Poisson's ratio (shear modulus `E / (2 (1 + nu))`), default 0.3.
        structural nu: f64 = 0.3;
        /// Modal damping: ratio of critical damping of every mode, default 0.01.
        structural damping: f64 = 0.01;
        /// Stiffen the bending modes by the axial force (centrifugal, axial
        /// acceleration, end force), default `true`.
        structural geometric_stiffening: bool = true;
        /// The floating frame (the clamped or the first supported end).
        connector frame_a: Frame;
        /// The other end, moving and turning with the deformation.
        connector frame_b: Frame;
        /// Modal coordinates \[m per unit shape\].
        component q: StateVector = StateVector { n: self.n_lengthening + self.n_bending_xy + self.n_bending_xz + self.n_torsion, start: Vec::new() };
        /// Their rates.
        component qd: StateVector = StateVector { n: self.n_lengthening + self.n_bending_xy + self.n_bending_xz + self.n_torsion, start: Vec::new() };
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
        /// Kinetic energy of the beam \[J\].
        variable kinetic_energy: Real;
        /// Elastic energy of the modes \[J\].
        variable elastic_energy: Real;
        equation {
            let counts = [n_lengthening, n_bending_xy, n_bending_xz, n_torsion];
            let modes = modes_of(l, cross_section, rho, E, nu, boundary, counts);
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
            let n = modes.len();
            let dirs: Vec<Vec3> = modes.iter().map(|(_, dir)| Vec3::constant(*dir)).collect();
            // Sums over the modes, and over the modes of one kind.
            let over_modes = |f: &dyn Fn(usize, &ModeData) -> Vec3| -> Vec3 {
                modes.iter().enumerate().fold(Vec3::zero(), |acc, (i, (d, _))| acc + f(i, d))
            };
            let over_kind = |kind: ModeKind, f: &dyn Fn(usize, &ModeData) -> Expr| -> Expr {
                modes.iter().enumerate().fold(Expr::constant(0.0), |acc, (i, (d, _))| {
                    if d.kind == kind { acc + f(i, d) } else { acc }
                })
            };
            let ex = axis(1);
            let s = Vec3::constant([m * l / 2.0, 0.0, 0.0]) + over_modes(&|i, d| dirs[i].scale(d.first * q.x(i)));
            let sd = over_modes(&|i, d| dirs[i].scale(d.first * qd.x(i)));
            let sdd = over_modes(&|i, d| dirs[i].scale(d.first * der(qd.x(i))));
            let u = over_modes(&|i, d| dirs[i].scale(d.tip * q.x(i)));
            // Slopes at the end: about z from the xy modes, about y (negative) from xz.
            let slope_z = over_kind(ModeKind::BendingXy, &|i, d| d.tip_slope * q.x(i));
            let slope_zd = over_kind(ModeKind::BendingXy, &|i, d| d.tip_slope * qd.x(i));
            let slope_y = over_kind(ModeKind::BendingXz, &|i, d| -d.tip_slope * q.x(i));
            let slope_yd = over_kind(ModeKind::BendingXz, &|i, d| -d.tip_slope * qd.x(i));
            // Torsion: the twist at the end; per mode the coupling of the twisted
            // sections' inertia, rho I_p int phi (about x: `first`) and
            // rho (I_y - I_z) int phi (to the rotations about y and z).
            let over_torsion = |f: &dyn Fn(usize, &ModeData) -> Expr| over_kind(ModeKind::Torsion, f);
            let unequal = (i_y - i_z) / (i_y + i_z);
            let twist = over_torsion(&|i, d| d.tip * q.x(i));
            let twist_d = over_torsion(&|i, d| d.tip * qd.x(i));
            let twist_momentum = over_torsion(&|i, d| d.first * qd.x(i));
            let twist_inertia = |x: &dyn Fn(usize) -> Expr, v: Vec3| -> Vec3 {
                let k = over_torsion(&|i, d| unequal * d.first * x(i));
                Vec3::new(Expr::constant(0.0), k * v[2], k * v[1])
            };
            u_b = u;
            let r_b = Vec3::constant([l, 0.0, 0.0]) + u_b;
            // frame_b: at the deformed end, turned about x, y and z by the end's twist
            // and slopes.
            let r_rel: Orientation = axes_rotations([1, 2, 3], [twist, slope_y, slope_z], [twist_d, slope_yd, slope_zd]);
            branch(frame_a.R, frame_b.R);
            frame_b.r_0 = frame_a.r_0 + resolve1(&frame_a.R, r_b);
            if rooted(frame_a.R) {
                frame_b.R = absolute_rotation(&frame_a.R, &r_rel);
            } else {
                frame_a.R = absolute_rotation(&frame_b.R, &inverse_rotation(&r_rel));
            }
            // The end's force and torque, resolved in frame_a, and the axes about which the
            // slopes turn frame_b (y after the twist, z after the twist and the slope
            // about y): the end torque's work on the modes.
            let f_b = resolve1(&r_rel, frame_b.f);
            let t_b = resolve1(&r_rel, frame_b.t);
            let axis_y = Vec3::new(Expr::constant(0.0), cos(twist), sin(twist));
            let axis_z = Vec3::new(sin(slope_y), -sin(twist) * cos(slope_y), cos(twist) * cos(slope_y));
            // The modes' cross masses and geometric stiffnesses; per mode i the first
            // moment of the deformation and its rates weighted by the shape,
            // int phi_i u dm (zero cross masses of modes along one direction left out).
            let shapes: Vec<_> = mode_shapes(l, boundary, counts).into_iter().map(|(shape, _)| shape).collect();
            let pairs = pair_integrals(&shapes, rho, area);
            let coupled = |i: usize, j: usize| pairs.mass[i][j].abs() > 1e-9 * (pairs.mass[i][i] * pairs.mass[j][j]).sqrt();
            let weighted = |x: &dyn Fn(usize) -> Expr| -> Vec<Vec3> {
                (0..n)
                    .map(|i| (0..n).filter(|&j| coupled(i, j)).fold(Vec3::zero(), |acc, j| acc + dirs[j].scale(pairs.mass[i][j] * x(j))))
                    .collect()
            };
            let u_q = weighted(&|j| q.x(j));
            let u_qd = weighted(&|j| qd.x(j));
            let u_qdd = weighted(&|j| der(qd.x(j)));
            // The inertia tensor about frame_a times v: rigid, first and second order in q.
            let inertia = |v: Vec3| -> Vec3 {
                j0 * v
                    + over_modes(&|i, d| (v.scale(2.0 * dirs[i][0]) - ex.scale(dirs[i].dot(v)) - dirs[i].scale(v[0])).scale(d.first_x * q.x(i)))
                    + over_modes(&|i, _| (v.scale(dirs[i].dot(u_q[i])) - dirs[i].scale(u_q[i].dot(v))).scale(q.x(i)))
                    + twist_inertia(&|i| q.x(i), v)
            };
            // int r x u' dm and int r x u'' dm, and the Coriolis moment int r x (w x u') dm.
            let moment_of = |x: &dyn Fn(usize) -> Expr, u: &[Vec3]| -> Vec3 {
                over_modes(&|i, d| ex.cross(dirs[i]).scale(d.first_x * x(i)) + dirs[i].cross(u[i]).scale(q.x(i)))
            };
            let relative_momentum = moment_of(&|i| qd.x(i), &u_qd);
            let relative = moment_of(&|i| der(qd.x(i)), &u_qdd);
            let coriolis = over_modes(&|i, d| ex.cross(w_a.cross(dirs[i])).scale(d.first_x * qd.x(i)) + dirs[i].cross(w_a.cross(u_qd[i])).scale(q.x(i)));
            // Newton and Euler of the beam about frame_a.
            frame_a.f + f_b = acc.scale(m) + z_a.cross(s) + w_a.cross(w_a.cross(s)) + w_a.cross(sd).scale(2.0) + sdd;
            let twist_moment = ex.scale(over_torsion(&|i, d| d.first * der(qd.x(i)))) + w_a.cross(ex.scale(twist_momentum)) + twist_inertia(&|i| qd.x(i), w_a);
            let jw = inertia(w_a);
            frame_a.t + t_b + r_b.cross(f_b) = s.cross(acc) + inertia(z_a) + w_a.cross(jw) + coriolis.scale(2.0) + relative + twist_moment;
            // Energies.
            let v_a = resolve2(&frame_a.R, v_0);
            kinetic_energy = 0.5 * m * v_a.dot(v_a) + v_a.dot(w_a.cross(s)) + v_a.dot(sd) + 0.5 * w_a.dot(jw) + w_a.dot(relative_momentum) + w_a[0] * twist_momentum
                + modes.iter().enumerate().fold(Expr::constant(0.0), |acc, (i, (d, _))| acc + 0.5 * d.mass * qd.x(i) * qd.x(i));
            elastic_energy = modes.iter().enumerate().fold(Expr::constant(0.0), |acc, (i, (d, _))| acc + 0.5 * d.stiffness * q.x(i) * q.x(i));
            // The axial force along the beam (tension positive) is
            // f_b,x - rho A (acc_x (l - x) - (w_y^2 + w_z^2) (l^2 - x^2) / 2); its work on
            // the bending slopes stiffens the bending modes.
            let spin = w_a[1] * w_a[1] + w_a[2] * w_a[2];
            let geometric = |i: usize| -> Expr {
                if !geometric_stiffening || !matches!(modes[i].0.kind, ModeKind::BendingXy | ModeKind::BendingXz) {
                    return Expr::constant(0.0);
                }
                (0..n).filter(|&j| modes[j].0.kind == modes[i].0.kind).fold(Expr::constant(0.0), |total, j| {
                    total + (pairs.slope[i][j] * f_b[0] - pairs.slope_acceleration[i][j] * acc[0] + pairs.slope_spin[i][j] * spin) * q.x(j)
                })
            };
            // Each mode: its inertia, damping and stiffness against the inertial loads of
            // the rigid motion and of the other modes, and the end's force and torque.
            for (i, (d, dir)) in modes.iter().enumerate() {
                let dir_v = dirs[i];
                let omega = (d.stiffness / d.mass).sqrt();
                let rotational = ex.cross(dir_v).scale(d.first_x);
                let centrifugal = d.first_x * (dir_v.dot(w_a) * w_a[0] - dir[0] * w_a.dot(w_a));
                let modal = dir_v.dot(z_a.cross(u_q[i]) + w_a.cross(w_a.cross(u_q[i])) + w_a.cross(u_qd[i]).scale(2.0));
                let end_torque = match d.kind {
                    ModeKind::BendingXy => d.tip_slope * t_b.dot(axis_z),
                    ModeKind::BendingXz => -d.tip_slope * t_b.dot(axis_y),
                    ModeKind::Torsion => d.tip * t_b[0],
                    ModeKind::Lengthening => Expr::constant(0.0),
                };
                // The twisted sections: the rotation about x accelerates the mode, the
                // rotation about y and z twists unequal sections (rho (I_y - I_z) w_y w_z).
                let twist_load = if d.kind == ModeKind::Torsion {
                    d.first * z_a[0] - unequal * d.first * w_a[1] * w_a[2]
                } else {
                    Expr::constant(0.0)
                };
                d.mass * der(qd.x(i)) + 2.0 * damping * omega * d.mass * qd.x(i) + d.stiffness * q.x(i) + geometric(i)
                    = -(acc.scale(d.first).dot(dir_v) + rotational.dot(z_a) + centrifugal + modal + twist_load)
                        + d.tip * dir_v.dot(f_b) + end_torque;
            }
        }
    }
}
