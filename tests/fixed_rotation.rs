//! `FixedRotation` on a constant frame (the world's, or a `Fixed` one), followed by a
//! revolute joint and a body: a pendulum whose axis and arm are turned by the constant
//! rotation. Each run is compared with the pendulum equation integrated here in closed
//! form (a scalar ODE about the turned axis, by Runge-Kutta), with the energy of that
//! pendulum, and with the rotation matrix derived independently for each way to give a
//! FixedRotation. (A rotation about a coordinate axis on a constant frame used to be
//! "structurally singular": its orientation entries and angular velocity are constants
//! that only a second pass of alias elimination finds.)
//!
//! Conventions (MSL's): a frame's `R.T` maps world-resolved vectors into the frame; the
//! references use active rotations `R = T'` built by Rodrigues' formula here.

#![allow(missing_docs)]

#[path = "support/mechanics.rs"]
mod mechanics;

use mechanics::{cross, dot, rotation, vector};
use multibody::joints::Revolute;
use multibody::parts::{Body, Fixed, FixedRotation, RotationType};
use multibody::prelude::*;
use multibody::world::World;

const G: f64 = 9.80665;

type V3 = [f64; 3];
type M3 = [[f64; 3]; 3];

const EX: V3 = [1.0, 0.0, 0.0];
const EY: V3 = [0.0, 1.0, 0.0];
const EZ: V3 = [0.0, 0.0, 1.0];

/// Mass, isotropic inertia about the centre of mass, and the arm of the body in the
/// joint's frame_b.
const M: f64 = 1.3;
const I_CM: f64 = 0.02;
const P: V3 = [0.1, -0.4, 0.2];
/// Joint axis in FixedRotation's frame_b (the library normalizes it).
const N_JOINT: V3 = [1.0, 0.0, 1.0];

fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

fn unit(a: V3) -> V3 {
    scale(a, 1.0 / dot(a, a).sqrt())
}

fn mv(a: &M3, v: V3) -> V3 {
    std::array::from_fn(|i| (0..3).map(|k| a[i][k] * v[k]).sum())
}

fn mul(a: &M3, b: &M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn tr(a: &M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

/// Rodrigues' formula: the active rotation about `axis` (any length) by `angle`.
fn rot(axis: V3, angle: f64) -> M3 {
    let e = unit(axis);
    let (s, c) = angle.sin_cos();
    let k = [[0.0, -e[2], e[1]], [e[2], 0.0, -e[0]], [-e[1], e[0], 0.0]];
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let id = if i == j { 1.0 } else { 0.0 };
            id + s * k[i][j] + (1.0 - c) * (0..3).map(|l| k[i][l] * k[l][j]).sum::<f64>()
        })
    })
}

/// The pendulum in closed form: a body of mass M and inertia I_CM (isotropic) whose
/// centre of mass is at `arm` (world-resolved, at phi = 0) from a pivot on the fixed
/// world axis `e`. Its angle obeys J phi'' = -M g d(y_cm)/dphi with
/// J = M |e x arm|^2 + I_CM and d/dphi Rot(e, phi) arm = e x Rot(e, phi) arm; integrated
/// by classical Runge-Kutta with 2e-5 s steps (error far below 1e-9 over the run).
struct Reference {
    e: V3,
    arm: V3,
    j: f64,
}

impl Reference {
    fn new(e: V3, arm: V3) -> Self {
        let e = unit(e);
        let ea = cross(e, arm);
        Reference {
            e,
            arm,
            j: M * dot(ea, ea) + I_CM,
        }
    }

    /// The centre of mass relative to the pivot at angle `phi`.
    fn cm(&self, phi: f64) -> V3 {
        mv(&rot(self.e, phi), self.arm)
    }

    fn acceleration(&self, phi: f64) -> f64 {
        -M * G * cross(self.e, self.cm(phi))[1] / self.j
    }

    /// `(phi, w)` at each of `times` (increasing, from 0), from `(phi0, w0)`.
    fn solve(&self, phi0: f64, w0: f64, times: &[f64]) -> Vec<(f64, f64)> {
        let h: f64 = 2e-5;
        let (mut t, mut x, mut v) = (0.0, phi0, w0);
        let mut out = Vec::with_capacity(times.len());
        for &target in times {
            while t < target - 1e-12 {
                let dt = h.min(target - t);
                let a1 = self.acceleration(x);
                let (x2, v2) = (x + 0.5 * dt * v, v + 0.5 * dt * a1);
                let a2 = self.acceleration(x2);
                let (x3, v3) = (x + 0.5 * dt * v2, v + 0.5 * dt * a2);
                let a3 = self.acceleration(x3);
                let (x4, v4) = (x + dt * v3, v + dt * a3);
                let a4 = self.acceleration(x4);
                x += dt / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4);
                v += dt / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
                t += dt;
            }
            out.push((x, v));
        }
        out
    }

    /// Kinetic plus potential energy (pivot height aside).
    fn energy(&self, phi: f64, w: f64) -> f64 {
        0.5 * self.j * w * w + M * G * self.cm(phi)[1]
    }
}

/// What a run is compared with: the world position of the joint (the pivot), and the
/// orientation `R` (frame axes resolved in the world, columns) of the joint's frame_a.
struct Geometry {
    pivot: V3,
    r_joint: M3,
}

/// Where the pendulum hangs from: the world frame, or a `Fixed` frame at `r`.
#[derive(Clone, Copy)]
enum Base {
    World,
    Fixed(V3),
}

/// world (-> Fixed) -> FixedRotation -> Revolute(N_JOINT) -> Body(P); with `reversed`
/// the FixedRotation is connected the other way round (its frame_b on the base).
fn pendulum(base: Base, fr: &FixedRotation, reversed: bool) -> System {
    let mut model = system! {
        name: "fr_pendulum";
        world = World::default();
        rev = Revolute { n: N_JOINT };
        body = Body { m: M, r_CM: P, I_11: I_CM, I_22: I_CM, I_33: I_CM };
        connect(rev.frame_b, body.frame_a);
    }
    .into_system();
    model.add("fr", fr);
    let base_frame = match base {
        Base::World => "world.frame_b",
        Base::Fixed(r) => {
            model.add("fixed", &Fixed { r });
            "fixed.frame_b"
        }
    };
    let (near, far) = if reversed {
        ("fr.frame_b", "fr.frame_a")
    } else {
        ("fr.frame_a", "fr.frame_b")
    };
    model.connect(base_frame, near);
    model.connect(far, "rev.frame_a");
    model
}

/// Simulates the pendulum and compares it with [`Reference`]: the joint angle and speed,
/// the energy, and the joint's frame_a (the FixedRotation's far frame), a constant.
fn check(name: &str, base: Base, fr: &FixedRotation, reversed: bool, geometry: &Geometry) {
    let model = pendulum(base, fr, reversed);
    let ssys = structural_simplify(&model).unwrap_or_else(|e| panic!("{name}: {e}"));
    // One degree of freedom: the joint angle and speed, nothing else.
    assert_eq!(ssys.states().len(), 2, "{name}: {:?}", ssys.states());
    let t_end = 3.0;
    let n = 300;
    let times: Vec<f64> = (0..=n).map(|k| k as f64 * t_end / n as f64).collect();
    let (phi0, w0) = (1.0, 0.0);
    let sol = DaeProblem::new(&ssys, &[("rev.phi", phi0), ("rev.w", w0)], (0.0, t_end))
        .and_then(|p| {
            p.solve(&SolverOptions {
                rtol: 1e-10,
                atol: 1e-12,
                output_times: Some(times.clone()),
                ..SolverOptions::default()
            })
        })
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let reference = Reference::new(mv(&geometry.r_joint, N_JOINT), mv(&geometry.r_joint, P));
    let expected = reference.solve(phi0, w0, sol.t());
    let (phi, w) = (sol.get("rev.phi").unwrap(), sol.get("rev.w").unwrap());
    let t_joint = rotation(&sol, "rev.frame_a");
    let r_joint = vector(&sol, "rev.frame_a.r_0");
    let r_cm = vector(&sol, "body.frame_a.r_0");
    let t_cm = rotation(&sol, "body.frame_a");
    let e0 = reference.energy(phi0, w0);
    let mut swing = 0.0f64;
    for (k, &t) in sol.t().iter().enumerate() {
        let (phi_ref, w_ref) = expected[k];
        swing = swing.max((phi[k] - phi0).abs());
        // rtol 1e-10 against a reference exact to 1e-12: measured at most 5e-8 in the
        // angle and 5e-8 (1 + |w|) in the speed. Released from rest, the pendulum never
        // comes near its upright position (where a slow passage would amplify the
        // integration error). An axis or arm turned by R' instead of R
        // swings differently by tenths of a radian.
        assert!(
            (phi[k] - phi_ref).abs() < 3e-7 && (w[k] - w_ref).abs() < 3e-7 * (1.0 + w_ref.abs()),
            "{name}: at {t}: phi {} w {}, closed form {phi_ref} {w_ref}",
            phi[k],
            w[k]
        );
        let energy = reference.energy(phi[k], w[k]);
        assert!(
            (energy - e0).abs() < 1e-7,
            "{name}: energy {energy} at {t}, {e0} at the start"
        );
        // The joint's frame_a is the constant (pivot, R): exact up to round-off.
        for i in 0..3 {
            for j in 0..3 {
                assert!(
                    (t_joint[k][i][j] - geometry.r_joint[j][i]).abs() < 1e-12,
                    "{name}: rev.frame_a.R.T[{},{}] = {} at {t}, expected {}",
                    i + 1,
                    j + 1,
                    t_joint[k][i][j],
                    geometry.r_joint[j][i]
                );
            }
            assert!(
                (r_joint[k][i] - geometry.pivot[i]).abs() < 1e-12,
                "{name}: rev.frame_a.r_0 = {:?} at {t}, expected {:?}",
                r_joint[k],
                geometry.pivot
            );
        }
        // The body's centre of mass where the closed form puts it.
        let cm = add(r_cm[k], mv(&tr(&t_cm[k]), P));
        let cm_ref = add(geometry.pivot, reference.cm(phi[k]));
        for i in 0..3 {
            assert!(
                (cm[i] - cm_ref[i]).abs() < 1e-10,
                "{name}: centre of mass {cm:?} at {t}, closed form {cm_ref:?}"
            );
        }
    }
    assert!(swing > 0.2, "{name}: the pendulum swung only {swing} rad");
}

/// A FixedRotation about an axis by an angle in degrees, translating by `r`.
fn about(axis: V3, angle: f64, r: V3) -> FixedRotation {
    FixedRotation {
        r,
        n: axis,
        angle,
        ..Default::default()
    }
}

const R_FR: V3 = [0.2, 0.3, -0.1];

/// Rotations about each coordinate axis by 30, 90 (exactly axis-aligned), -90 and 180
/// degrees, and about a skew axis, on the world frame: frame_b of the FixedRotation is
/// at R_FR with axes R = Rot(n, angle).
#[test]
fn fixed_rotation_on_the_world_about_coordinate_axes() {
    for axis in [EX, EY, EZ, [1.0, 1.0, 1.0], [0.0, -2.0, 1.0]] {
        for angle in [30.0, 90.0, -90.0, 180.0] {
            let name = format!("world, n = {axis:?}, angle = {angle}");
            let geometry = Geometry {
                pivot: R_FR,
                r_joint: rot(axis, f64::to_radians(angle)),
            };
            check(
                &name,
                Base::World,
                &about(axis, angle, R_FR),
                false,
                &geometry,
            );
        }
    }
}

/// The same after a `Fixed` frame at (1, -0.5, 0.25) (also a constant root), and with
/// the FixedRotation connected backwards (frame_b on the fixed frame: frame_a's axes
/// are R' and its origin is at -R' r from frame_b).
#[test]
fn fixed_rotation_on_a_fixed_frame_both_ways_round() {
    let base_r = [1.0, -0.5, 0.25];
    for axis in [EX, EY, EZ, [1.0, 2.0, -1.0]] {
        for angle in [90.0, -30.0] {
            let r = rot(axis, f64::to_radians(angle));
            let forward = Geometry {
                pivot: add(base_r, R_FR),
                r_joint: r,
            };
            check(
                &format!("Fixed, n = {axis:?}, angle = {angle}"),
                Base::Fixed(base_r),
                &about(axis, angle, R_FR),
                false,
                &forward,
            );
            let backward = Geometry {
                pivot: add(base_r, scale(mv(&tr(&r), R_FR), -1.0)),
                r_joint: tr(&r),
            };
            check(
                &format!("Fixed, reversed, n = {axis:?}, angle = {angle}"),
                Base::Fixed(base_r),
                &about(axis, angle, R_FR),
                true,
                &backward,
            );
        }
    }
}

/// The other two ways to give the rotation, on the world frame, with rotation matrices
/// derived by hand:
/// - TwoAxesVectors n_x = (0, 1, 0), n_y = (-1, 0, 0): frame_b's x along world y, its
///   y along -x: the rotation about z by 90 degrees;
/// - TwoAxesVectors n_x = (0, 0, 2), n_y = (1, 0, 1) (not orthogonal: y is made so):
///   e_x = z, e_y = x, e_z = e_x x e_y = y;
/// - PlanarRotationSequence {1, 2, 3} by (90, 0, 0): Rx(90); {3, 1, 2} by (90, 90, 0):
///   Rz(90) Rx(90) (about z, then the new x); {1, 2, 3} by (30, 45, 60):
///   Rx(30) Ry(45) Rz(60).
#[test]
fn fixed_rotation_on_the_world_for_every_rotation_type() {
    let deg = f64::to_radians;
    let columns = |x: V3, y: V3, z: V3| -> M3 { std::array::from_fn(|i| [x[i], y[i], z[i]]) };
    let cases: Vec<(&str, FixedRotation, M3)> = vec![
        (
            "TwoAxesVectors about z by 90",
            FixedRotation {
                r: R_FR,
                rotation_type: RotationType::TwoAxesVectors,
                n_x: [0.0, 1.0, 0.0],
                n_y: [-1.0, 0.0, 0.0],
                ..Default::default()
            },
            columns(EY, scale(EX, -1.0), EZ),
        ),
        (
            "TwoAxesVectors with n_y not orthogonal",
            FixedRotation {
                r: R_FR,
                rotation_type: RotationType::TwoAxesVectors,
                n_x: [0.0, 0.0, 2.0],
                n_y: [1.0, 0.0, 1.0],
                ..Default::default()
            },
            columns(EZ, EX, EY),
        ),
        (
            "PlanarRotationSequence {1,2,3} (90, 0, 0)",
            FixedRotation {
                r: R_FR,
                rotation_type: RotationType::PlanarRotationSequence,
                sequence: [1, 2, 3],
                angles: [90.0, 0.0, 0.0],
                ..Default::default()
            },
            rot(EX, deg(90.0)),
        ),
        (
            "PlanarRotationSequence {3,1,2} (90, 90, 0)",
            FixedRotation {
                r: R_FR,
                rotation_type: RotationType::PlanarRotationSequence,
                sequence: [3, 1, 2],
                angles: [90.0, 90.0, 0.0],
                ..Default::default()
            },
            mul(&rot(EZ, deg(90.0)), &rot(EX, deg(90.0))),
        ),
        (
            "PlanarRotationSequence {1,2,3} (30, 45, 60)",
            FixedRotation {
                r: R_FR,
                rotation_type: RotationType::PlanarRotationSequence,
                sequence: [1, 2, 3],
                angles: [30.0, 45.0, 60.0],
                ..Default::default()
            },
            mul(
                &mul(&rot(EX, deg(30.0)), &rot(EY, deg(45.0))),
                &rot(EZ, deg(60.0)),
            ),
        ),
    ];
    for (name, fr, r) in cases {
        check(
            name,
            Base::World,
            &fr,
            false,
            &Geometry {
                pivot: R_FR,
                r_joint: r,
            },
        );
    }
}

/// Two FixedRotations in series on the world (both constant) are the product of their
/// rotations: Rz(90) then Rx(90) about the new x.
#[test]
fn two_fixed_rotations_in_series_on_the_world() {
    let model = system! {
        name: "two_fr";
        world = World::default();
        fr1 = FixedRotation { n: EZ, angle: 90.0 };
        fr2 = FixedRotation { r: R_FR, n: EX, angle: 90.0 };
        rev = Revolute { n: N_JOINT };
        body = Body { m: M, r_CM: P, I_11: I_CM, I_22: I_CM, I_33: I_CM };
        connect(world.frame_b, fr1.frame_a);
        connect(fr1.frame_b, fr2.frame_a);
        connect(fr2.frame_b, rev.frame_a);
        connect(rev.frame_b, body.frame_a);
    }
    .into_system();
    let ssys = structural_simplify(&model).unwrap();
    assert_eq!(ssys.states().len(), 2, "{:?}", ssys.states());
    let deg = f64::to_radians;
    let r1 = rot(EZ, deg(90.0));
    let r = mul(&r1, &rot(EX, deg(90.0)));
    let sol = DaeProblem::new(&ssys, &[("rev.phi", 1.0), ("rev.w", 0.0)], (0.0, 2.0))
        .and_then(|p| {
            p.solve(&SolverOptions {
                rtol: 1e-10,
                atol: 1e-12,
                output_times: Some((0..=100).map(|k| k as f64 * 0.02).collect()),
                ..SolverOptions::default()
            })
        })
        .unwrap();
    let reference = Reference::new(mv(&r, N_JOINT), mv(&r, P));
    let expected = reference.solve(1.0, 0.0, sol.t());
    let phi = sol.get("rev.phi").unwrap();
    let pivot = vector(&sol, "rev.frame_a.r_0");
    let r_fr2 = mv(&r1, R_FR);
    for (k, &t) in sol.t().iter().enumerate() {
        assert!(
            (phi[k] - expected[k].0).abs() < 1e-7,
            "at {t}: phi {} closed form {}",
            phi[k],
            expected[k].0
        );
        for i in 0..3 {
            assert!(
                (pivot[k][i] - r_fr2[i]).abs() < 1e-12,
                "pivot {:?}",
                pivot[k]
            );
        }
    }
}
