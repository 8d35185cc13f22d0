//! The analytic eigenmodes of a straight, homogeneous beam (Euler-Bernoulli bending,
//! lengthening as a rod) and the modal integrals a beam in a floating frame of reference
//! needs, by numerical quadrature of the shapes. Plain numbers, no model.

use multibody_core::model::StructuralValue;

/// How the beam's floating frame is attached, which fixes the modes' boundary
/// conditions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum BeamBoundary {
    /// Clamped at `frame_a`, free at `frame_b`: the frame is the beam's tangent frame
    /// at `frame_a` (a cantilever; the default).
    #[default]
    ClampedFree,
    /// Supported (no displacement, free slope) at both ends: the frame is the chord
    /// frame from `frame_a` to `frame_b`.
    SupportedSupported,
}

impl StructuralValue for BeamBoundary {
    /// 0 for clamped-free, 1 for supported-supported.
    fn structural_values(&self) -> Option<Vec<f64>> {
        Some(vec![match self {
            BeamBoundary::ClampedFree => 0.0,
            BeamBoundary::SupportedSupported => 1.0,
        }])
    }
}

impl BeamBoundary {
    /// The boundary recorded as `numbers` ([`StructuralValue`]).
    pub fn from_numbers(numbers: &[f64]) -> Option<BeamBoundary> {
        match numbers {
            [0.0] => Some(BeamBoundary::ClampedFree),
            [1.0] => Some(BeamBoundary::SupportedSupported),
            _ => None,
        }
    }
}

/// The cross-section of a beam.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CrossSection {
    /// A full rectangle `width` (along y) by `height` (along z) \[m\].
    Rectangle {
        /// Extent along y \[m\].
        width: f64,
        /// Extent along z \[m\].
        height: f64,
    },
    /// A full circle of `diameter` \[m\].
    Circle {
        /// Diameter \[m\].
        diameter: f64,
    },
    /// An I-profile (FlexibleBodies' `I_beam`): flanges `width` wide (along y) and
    /// `t_flange` thick at the top and bottom of the `height` (along z), joined by a
    /// central bar `t_bar` thick \[m\].
    IBeam {
        /// Outer extent along y (the flanges) \[m\].
        width: f64,
        /// Outer extent along z \[m\].
        height: f64,
        /// Thickness of the central bar \[m\].
        t_bar: f64,
        /// Thickness of the flanges \[m\].
        t_flange: f64,
    },
}

impl Default for CrossSection {
    /// The seed's I-profile: width 0.02, height 0.03, bar and flanges 0.001 m thick.
    fn default() -> Self {
        CrossSection::IBeam {
            width: 0.02,
            height: 0.03,
            t_bar: 0.001,
            t_flange: 0.001,
        }
    }
}

impl StructuralValue for CrossSection {
    /// A tag (0 rectangle, 1 circle, 2 I-profile) and the dimensions in declaration
    /// order.
    fn structural_values(&self) -> Option<Vec<f64>> {
        Some(match *self {
            CrossSection::Rectangle { width, height } => vec![0.0, width, height],
            CrossSection::Circle { diameter } => vec![1.0, diameter],
            CrossSection::IBeam {
                width,
                height,
                t_bar,
                t_flange,
            } => vec![2.0, width, height, t_bar, t_flange],
        })
    }
}

impl CrossSection {
    /// The section recorded as `numbers` ([`StructuralValue`]).
    pub fn from_numbers(numbers: &[f64]) -> Option<CrossSection> {
        match *numbers {
            [0.0, width, height] => Some(CrossSection::Rectangle { width, height }),
            [1.0, diameter] => Some(CrossSection::Circle { diameter }),
            [2.0, width, height, t_bar, t_flange] => Some(CrossSection::IBeam {
                width,
                height,
                t_bar,
                t_flange,
            }),
            _ => None,
        }
    }

    /// Extents along y and z \[m\].
    pub fn extents(&self) -> (f64, f64) {
        match *self {
            CrossSection::Rectangle { width, height }
            | CrossSection::IBeam { width, height, .. } => (width, height),
            CrossSection::Circle { diameter } => (diameter, diameter),
        }
    }
}

/// Area and second moments of area of a cross-section: `(A, I_y, I_z)` with `I_y`
/// about y (bending in the xz plane) and `I_z` about z (bending in xy) \[m2, m4\].
pub fn section_properties(s: CrossSection) -> (f64, f64, f64) {
    match s {
        CrossSection::Rectangle { width, height } => (
            width * height,
            width * height.powi(3) / 12.0,
            height * width.powi(3) / 12.0,
        ),
        CrossSection::Circle { diameter } => {
            let r = diameter / 2.0;
            let i = std::f64::consts::PI * r.powi(4) / 4.0;
            (std::f64::consts::PI * r * r, i, i)
        }
        CrossSection::IBeam {
            width,
            height,
            t_bar,
            t_flange,
        } => {
            let web = height - 2.0 * t_flange;
            let area = 2.0 * width * t_flange + t_bar * web;
            // About y (bending in xz): flanges at +-(height - t_flange)/2.
            let d = (height - t_flange) / 2.0;
            let i_y = 2.0 * (width * t_flange.powi(3) / 12.0 + width * t_flange * d * d)
                + t_bar * web.powi(3) / 12.0;
            // About z (bending in xy).
            let i_z = 2.0 * t_flange * width.powi(3) / 12.0 + web * t_bar.powi(3) / 12.0;
            (area, i_y, i_z)
        }
    }
}

/// Saint-Venant's torsion constant `J_t` of a cross-section \[m4\]: the polar moment
/// of a circle, `a b^3 (1/3 - 0.21 (b/a) (1 - (b/a)^4 / 12))` of an `a` by `b`
/// rectangle (`a >= b`; Roark), the thin-walled open section's `sum s t^3 / 3` of an
/// I-profile.
pub fn torsion_constant(s: CrossSection) -> f64 {
    match s {
        CrossSection::Circle { diameter } => std::f64::consts::PI * diameter.powi(4) / 32.0,
        CrossSection::Rectangle { width, height } => {
            let (a, b) = (width.max(height), width.min(height));
            let r = b / a;
            a * b.powi(3) * (1.0 / 3.0 - 0.21 * r * (1.0 - r.powi(4) / 12.0))
        }
        CrossSection::IBeam {
            width,
            height,
            t_bar,
            t_flange,
        } => (2.0 * width * t_flange.powi(3) + (height - 2.0 * t_flange) * t_bar.powi(3)) / 3.0,
    }
}

/// The family of a mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModeKind {
    /// Displacement along x.
    Lengthening,
    /// Displacement along y, bending about z.
    BendingXy,
    /// Displacement along z, bending about y.
    BendingXz,
    /// Twist of the sections about x (no displacement; Saint-Venant torsion).
    Torsion,
}

/// `n`-th root (from 1) of `cos(b) cosh(b) = -1`: the clamped-free eigenvalues `beta_n
/// L` (1.8751, 4.6941, 7.8548, ...), by Newton from `(n - 1/2) pi`.
pub fn clamped_free_root(n: usize) -> f64 {
    let mut b = (n as f64 - 0.5) * std::f64::consts::PI;
    if n == 1 {
        b = 1.875;
    }
    for _ in 0..50 {
        // f = cos b cosh b + 1 scaled by 1/cosh b: cos b + 1/cosh b.
        let f = b.cos() + 1.0 / b.cosh();
        let df = -b.sin() - b.tanh() / b.cosh();
        let step = f / df;
        b -= step;
        if step.abs() < 1e-15 * b {
            break;
        }
    }
    b
}

/// One mode of a beam of length `l`: its shape, slope and curvature at `x`.
#[derive(Clone, Copy, Debug)]
pub struct Shape {
    /// Family.
    pub kind: ModeKind,
    /// Index in its family, from 1.
    pub n: usize,
    /// Boundary conditions.
    pub boundary: BeamBoundary,
    /// Length of the beam \[m\].
    pub l: f64,
}

impl Shape {
    /// The wavenumber: `beta_n` of bending, `k_n` of lengthening and torsion \[1/m\].
    /// Torsion modes are clamped-free with either boundary (the sections at `frame_a`
    /// turn with it about x).
    pub fn wavenumber(&self) -> f64 {
        let pi = std::f64::consts::PI;
        let n = self.n as f64;
        match (self.kind, self.boundary) {
            (ModeKind::Lengthening, BeamBoundary::ClampedFree) | (ModeKind::Torsion, _) => {
                (2.0 * n - 1.0) * pi / (2.0 * self.l)
            }
            (ModeKind::Lengthening, BeamBoundary::SupportedSupported) => n * pi / self.l,
            (_, BeamBoundary::ClampedFree) => clamped_free_root(self.n) / self.l,
            (_, BeamBoundary::SupportedSupported) => n * pi / self.l,
        }
    }

    /// Value, first and second derivative at `x` (`0 <= x <= l`). Clamped-free
    /// bending: `cosh bx - cos bx - s (sinh bx - sin bx)` with `s` making the free end
    /// free, written with decaying exponentials so that high modes stay accurate; the
    /// others sines.
    pub fn eval(&self, x: f64) -> [f64; 3] {
        self.evaluator()(x)
    }

    /// [`Self::eval`] with the wavenumber and the constants of the shape found once,
    /// for evaluating at many points.
    pub fn evaluator(&self) -> impl Fn(f64) -> [f64; 3] + use<> {
        let b = self.wavenumber();
        let bl = b * self.l;
        let bending = matches!(self.kind, ModeKind::BendingXy | ModeKind::BendingXz)
            && self.boundary == BeamBoundary::ClampedFree;
        // s = (cosh bl + cos bl) / (sinh bl + sin bl); 1 - s in a stable form, and
        // (1 - s) e^bl, moderate.
        let s = (bl.cosh() + bl.cos()) / (bl.sinh() + bl.sin());
        let scaled = (-(-bl).exp() + bl.sin() - bl.cos()) / (bl.sinh() + bl.sin()) * bl.exp();
        move |x| {
            let z = b * x;
            if !bending {
                let (s, c) = z.sin_cos();
                return [s, b * c, -b * b * s];
            }
            // cosh z - s sinh z = ((1 - s) e^z + (1 + s) e^-z) / 2.
            let e = (z - bl).exp(); // e^z scaled by e^-bl
            let ch_sh = 0.5 * (scaled * e + (1.0 + s) * (-z).exp());
            let sh_ch = 0.5 * (scaled * e - (1.0 + s) * (-z).exp()); // d/dz of the above
            let (sz, cz) = z.sin_cos();
            let v = ch_sh - cz + s * sz;
            let d1 = b * (sh_ch + sz + s * cz);
            let d2 = b * b * (ch_sh + cz - s * sz);
            [v, d1, d2]
        }
    }
}

/// The shapes of a beam of length `l` with `counts` lengthening, xy-bending,
/// xz-bending and torsion modes, each with its direction of displacement in the beam's
/// frame (zero for torsion), in the order of the beam's modal coordinates.
pub fn mode_shapes(l: f64, boundary: BeamBoundary, counts: [usize; 4]) -> Vec<(Shape, [f64; 3])> {
    let families = [
        (ModeKind::Lengthening, [1.0, 0.0, 0.0]),
        (ModeKind::BendingXy, [0.0, 1.0, 0.0]),
        (ModeKind::BendingXz, [0.0, 0.0, 1.0]),
        (ModeKind::Torsion, [0.0, 0.0, 0.0]),
    ];
    families
        .into_iter()
        .zip(counts)
        .flat_map(|((kind, dir), count)| {
            (1..=count).map(move |n| {
                let shape = Shape {
                    kind,
                    n,
                    boundary,
                    l,
                };
                (shape, dir)
            })
        })
        .collect()
}

/// The modal data of one mode for a beam of density `rho`, area `a` and stiffness
/// `stiffness` (`E A` for lengthening, `E I` for bending). For torsion `a` is the polar
/// moment `I_p` and `stiffness` is `G J_t`: the mass is then in kg m2, `first` in kg m
/// (the twist's coupling to the rotation about x), and the stiffness in N m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModeData {
    /// Family.
    pub kind: ModeKind,
    /// Modal mass `rho A int phi^2` \[kg\].
    pub mass: f64,
    /// Modal stiffness `E A int phi'^2` or `E I int phi''^2` \[N/m\].
    pub stiffness: f64,
    /// `rho A int phi` \[kg\].
    pub first: f64,
    /// `rho A int x phi` \[kg m\].
    pub first_x: f64,
    /// Shape at the end `x = l`.
    pub tip: f64,
    /// Slope at the end.
    pub tip_slope: f64,
}

/// The points and weights of Simpson's rule on 4 000 intervals of `[0, l]`.
fn simpson(l: f64) -> impl Iterator<Item = (f64, f64)> {
    const N: usize = 4000;
    let h = l / N as f64;
    (0..=N).map(move |i| {
        let weight = if i == 0 || i == N {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        (i as f64 * h, weight * h / 3.0)
    })
}

/// The modal data of `shape` by Simpson's rule on 4 000 intervals (`a` per unit length:
/// the area, or the polar moment for torsion; see [`ModeData`]).
pub fn mode_data(shape: Shape, rho: f64, a: f64, stiffness: f64) -> ModeData {
    let (mut mm, mut kk, mut f0, mut f1) = (0.0, 0.0, 0.0, 0.0);
    let eval = shape.evaluator();
    for (x, w) in simpson(shape.l) {
        let [v, d1, d2] = eval(x);
        mm += w * v * v;
        kk += w * if matches!(shape.kind, ModeKind::Lengthening | ModeKind::Torsion) {
            d1 * d1
        } else {
            d2 * d2
        };
        f0 += w * v;
        f1 += w * x * v;
    }
    let [tip, tip_slope, _] = eval(shape.l);
    ModeData {
        kind: shape.kind,
        mass: rho * a * mm,
        stiffness: stiffness * kk,
        first: rho * a * f0,
        first_x: rho * a * f1,
        tip,
        tip_slope,
    }
}

/// Integrals over pairs of modes of a beam of density `rho` and area `a`, for the
/// second-order terms of a floating frame of reference: each an `n x n` matrix in the
/// order of the shapes.
#[derive(Clone, Debug, PartialEq)]
pub struct PairIntegrals {
    /// `rho A int phi_i phi_j` \[kg\]: the modes' cross masses.
    pub mass: Vec<Vec<f64>>,
    /// `int phi_i' phi_j'` \[1/m\]: geometric stiffness per unit axial force.
    pub slope: Vec<Vec<f64>>,
    /// `rho A int (l - x) phi_i' phi_j'` \[kg/m\]: geometric stiffness per unit axial
    /// acceleration.
    pub slope_acceleration: Vec<Vec<f64>>,
    /// `rho A int (l^2 - x^2) / 2 phi_i' phi_j'` \[kg\]: geometric stiffness per unit
    /// squared angular velocity about the beam's transverse axes.
    pub slope_spin: Vec<Vec<f64>>,
}

/// The [`PairIntegrals`] of `shapes` (all of one length) by Simpson's rule on 4 000
/// intervals. Rows and columns of torsion modes are computed alike but mean nothing
/// (the twist displaces no point of the axis).
pub fn pair_integrals(shapes: &[Shape], rho: f64, a: f64) -> PairIntegrals {
    let n = shapes.len();
    let l = shapes.first().map_or(0.0, |s| s.l);
    let zero = || vec![vec![0.0; n]; n];
    let mut out = PairIntegrals {
        mass: zero(),
        slope: zero(),
        slope_acceleration: zero(),
        slope_spin: zero(),
    };
    let evals: Vec<_> = shapes.iter().map(Shape::evaluator).collect();
    for (x, w) in simpson(l) {
        let values: Vec<[f64; 3]> = evals.iter().map(|e| e(x)).collect();
        for (i, vi) in values.iter().enumerate() {
            for (j, vj) in values.iter().enumerate() {
                let slopes = w * vi[1] * vj[1];
                out.mass[i][j] += rho * a * w * vi[0] * vj[0];
                out.slope[i][j] += slopes;
                out.slope_acceleration[i][j] += rho * a * (l - x) * slopes;
                out.slope_spin[i][j] += rho * a * 0.5 * (l * l - x * x) * slopes;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sections_and_boundaries_are_recorded_as_numbers_and_read_back() {
        for s in [
            CrossSection::Rectangle {
                width: 0.1,
                height: 0.2,
            },
            CrossSection::Circle { diameter: 0.3 },
            CrossSection::default(),
        ] {
            let numbers = s.structural_values().unwrap();
            assert_eq!(CrossSection::from_numbers(&numbers), Some(s));
        }
        for b in [BeamBoundary::ClampedFree, BeamBoundary::SupportedSupported] {
            let numbers = b.structural_values().unwrap();
            assert_eq!(BeamBoundary::from_numbers(&numbers), Some(b));
        }
        assert_eq!(CrossSection::from_numbers(&[3.0, 1.0]), None);
    }

    #[test]
    fn pair_integrals_give_orthogonal_modes_and_the_southwell_coefficients() {
        // Clamped-free bending: the modes are orthogonal, and the centrifugal stiffening
        // of a beam spinning about its root, int (l^2 - x^2)/2 phi'^2 / int phi^2, is
        // Southwell's coefficient: 1.1933 and 6.4782 for the first two modes (Wright et
        // al. 1982, the limit of small speed).
        let l = 1.58;
        let shapes = mode_shapes(l, BeamBoundary::ClampedFree, [0, 3, 0, 0]);
        let shapes: Vec<Shape> = shapes.into_iter().map(|(s, _)| s).collect();
        let p = pair_integrals(&shapes, 2.0, 3.0);
        for i in 0..3 {
            for j in 0..3 {
                if i != j {
                    assert!(p.mass[i][j].abs() < 1e-9 * p.mass[i][i], "{i} {j}");
                }
            }
        }
        assert!((p.mass[0][0] - 6.0 * l).abs() < 1e-6);
        for (i, southwell) in [(0, 1.1933), (1, 6.4782)] {
            let c = p.slope_spin[i][i] / p.mass[i][i];
            assert!((c - southwell).abs() < 1e-4, "{i}: {c}");
        }
    }

    #[test]
    fn torsion_constants_are_the_handbook_ones() {
        // Roark: a square's J_t = 0.1406 a^4, a thin strip's b t^3 / 3, a circle's
        // polar moment.
        let square = torsion_constant(CrossSection::Rectangle {
            width: 0.1,
            height: 0.1,
        });
        assert!((square / 1e-4 - 0.1406).abs() < 3e-4, "{square}");
        let strip = torsion_constant(CrossSection::Rectangle {
            width: 0.001,
            height: 1.0,
        });
        assert!((strip / (1e-9 / 3.0) - 1.0).abs() < 1e-3, "{strip}");
        let circle = torsion_constant(CrossSection::Circle { diameter: 0.2 });
        assert!((circle - std::f64::consts::PI * 0.1f64.powi(4) / 2.0).abs() < 1e-15);
    }

    #[test]
    fn clamped_free_roots_are_the_textbook_ones() {
        for (n, want) in [
            (1, 1.875_104_068_7),
            (2, 4.694_091_132_9),
            (3, 7.854_757_438_2),
        ] {
            assert!(
                (clamped_free_root(n) - want).abs() < 1e-9,
                "{n}: {}",
                clamped_free_root(n)
            );
        }
    }

    #[test]
    fn clamped_free_shapes_meet_their_boundary_conditions() {
        for n in [1, 2, 5, 15] {
            let s = Shape {
                kind: ModeKind::BendingXy,
                n,
                boundary: BeamBoundary::ClampedFree,
                l: 1.58,
            };
            let [v0, d0, _] = s.eval(0.0);
            assert!(v0.abs() < 1e-9 && d0.abs() < 1e-9, "{n}: {v0} {d0}");
            // Free end: no moment (phi'') and no shear (phi''').
            let [_, _, m] = s.eval(s.l);
            let b = s.wavenumber();
            assert!(m.abs() < 1e-7 * b * b, "{n}: moment {m}");
            // |phi(l)| = 2 and int phi^2 = l for this normalization.
            let d = mode_data(s, 1.0, 1.0, 1.0);
            assert!((d.tip.abs() - 2.0).abs() < 1e-8, "{n}: tip {}", d.tip);
            assert!((d.mass - s.l).abs() < 1e-6, "{n}: {}", d.mass);
            assert!(
                (d.stiffness - b.powi(4) * s.l).abs() < 1e-6 * b.powi(4) * s.l,
                "{n}"
            );
        }
    }
}
