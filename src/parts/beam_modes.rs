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
            [x] if *x == 0.0 => Some(BeamBoundary::ClampedFree),
            [x] if *x == 1.0 => Some(BeamBoundary::SupportedSupported),
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
            [t, width, height] if t == 0.0 => Some(CrossSection::Rectangle { width, height }),
            [t, diameter] if t == 1.0 => Some(CrossSection::Circle { diameter }),
            [t, width, height, t_bar, t_flange] if t == 2.0 => Some(CrossSection::IBeam {
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
            CrossSection::Rectangle { width, height } | CrossSection::IBeam { width, height, .. } => {
                (width, height)
            }
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

/// The family of a mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModeKind {
    /// Displacement along x.
    Lengthening,
    /// Displacement along y, bending about z.
    BendingXy,
    /// Displacement along z, bending about y.
    BendingXz,
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
    /// The wavenumber: `beta_n` of bending, `k_n` of lengthening \[1/m\].
    pub fn wavenumber(&self) -> f64 {
        let pi = std::f64::consts::PI;
        let n = self.n as f64;
        match (self.kind, self.boundary) {
            (ModeKind::Lengthening, BeamBoundary::ClampedFree) => {
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
        let b = self.wavenumber();
        match (self.kind, self.boundary) {
            (ModeKind::BendingXy | ModeKind::BendingXz, BeamBoundary::ClampedFree) => {
                let bl = b * self.l;
                // s = (cosh bl + cos bl) / (sinh bl + sin bl); 1 - s in a stable form.
                let s = (bl.cosh() + bl.cos()) / (bl.sinh() + bl.sin());
                let one_minus_s = (-(-bl).exp() + bl.sin() - bl.cos()) / (bl.sinh() + bl.sin());
                let z = b * x;
                // cosh z - s sinh z = ((1 - s) e^z + (1 + s) e^-z) / 2.
                let e = (z - bl).exp(); // e^z scaled by e^-bl
                let scaled = one_minus_s * bl.exp(); // (1 - s) e^bl, moderate
                let ch_sh = 0.5 * (scaled * e + (1.0 + s) * (-z).exp());
                let sh_ch = 0.5 * (scaled * e - (1.0 + s) * (-z).exp()); // d/dz of the above
                let (sz, cz) = z.sin_cos();
                let v = ch_sh - cz + s * sz;
                let d1 = b * (sh_ch + sz + s * cz);
                let d2 = b * b * (ch_sh + cz - s * sz);
                [v, d1, d2]
            }
            (ModeKind::Lengthening, BeamBoundary::ClampedFree)
            | (_, BeamBoundary::SupportedSupported) => {
                let (s, c) = (b * x).sin_cos();
                [s, b * c, -b * b * s]
            }
        }
    }
}

/// The shapes of a beam of length `l` with `counts` lengthening, xy-bending and
/// xz-bending modes, each with its direction of displacement in the beam's frame, in
/// the order of the beam's modal coordinates.
pub fn mode_shapes(l: f64, boundary: BeamBoundary, counts: [usize; 3]) -> Vec<(Shape, [f64; 3])> {
    let families = [
        (ModeKind::Lengthening, [1.0, 0.0, 0.0]),
        (ModeKind::BendingXy, [0.0, 1.0, 0.0]),
        (ModeKind::BendingXz, [0.0, 0.0, 1.0]),
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
/// `stiffness` (`E A` for lengthening, `E I` for bending).
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

/// The modal data of `shape` by Simpson's rule on 4 000 intervals.
pub fn mode_data(shape: Shape, rho: f64, a: f64, stiffness: f64) -> ModeData {
    const N: usize = 4000;
    let h = shape.l / N as f64;
    let (mut mm, mut kk, mut f0, mut f1) = (0.0, 0.0, 0.0, 0.0);
    for i in 0..=N {
        let x = i as f64 * h;
        let w = if i == 0 || i == N {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        } * h
            / 3.0;
        let [v, d1, d2] = shape.eval(x);
        mm += w * v * v;
        kk += w * if shape.kind == ModeKind::Lengthening {
            d1 * d1
        } else {
            d2 * d2
        };
        f0 += w * v;
        f1 += w * x * v;
    }
    let [tip, tip_slope, _] = shape.eval(shape.l);
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
