//! Bodies with a shape: a body at the end of a rigid translation (MSL `BodyShape`), and
//! boxes and cylinders whose mass and inertia follow from their geometry and density
//! (MSL `BodyBox`, `BodyCylinder`).

use super::body::{Body, OrientationStates};
use super::fixed::FixedTranslation;
use crate::frames::t_from_nxy;
use crate::interfaces::Frame;
use crate::numeric::norm;
use crate::prelude::*;

/// Mass properties computed from a shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassProperties {
    /// Mass \[kg\].
    pub m: f64,
    /// Centre of mass, resolved in `frame_a` \[m\].
    pub r_cm: [f64; 3],
    /// Inertia about the centre of mass, resolved in `frame_a` \[kg.m2\].
    pub inertia: [[f64; 3]; 3],
}

/// `T' D T` for a diagonal `D`: the inertia of a shape whose axes are the rows of `T`.
fn rotate_inertia(t: [[f64; 3]; 3], d: [f64; 3]) -> [[f64; 3]; 3] {
    let mut out = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            out[i][j] = (0..3).map(|k| t[k][i] * d[k] * t[k][j]).sum();
        }
    }
    out
}

/// Mass properties of a box from `frame_a` along `r` (MSL `BodyBox` rules): length
/// `|r|`, `width` and `height` across it (`width_direction` sets the width axis), an
/// inner box hollowing it out, and a density.
pub fn box_mass_properties(
    r: [f64; 3],
    width: f64,
    height: f64,
    inner_width: f64,
    inner_height: f64,
    width_direction: [f64; 3],
    density: f64,
) -> MassProperties {
    let l = norm(r);
    let (w, h, wi, hi) = (width, height, inner_width, inner_height);
    let mo = density * l * w * h;
    let mi = density * l * wi * hi;
    let d = [
        (mo * (w * w + h * h) - mi * (wi * wi + hi * hi)) / 12.0,
        (mo * (l * l + h * h) - mi * (l * l + hi * hi)) / 12.0,
        (mo * (l * l + w * w) - mi * (l * l + wi * wi)) / 12.0,
    ];
    let t = t_from_nxy(r, width_direction);
    MassProperties {
        m: mo - mi,
        r_cm: [r[0] / 2.0, r[1] / 2.0, r[2] / 2.0],
        inertia: rotate_inertia(t, d),
    }
}

/// Mass properties of a cylinder from `frame_a` along `r` (MSL `BodyCylinder` rules).
pub fn cylinder_mass_properties(
    r: [f64; 3],
    diameter: f64,
    inner_diameter: f64,
    density: f64,
) -> MassProperties {
    let l = norm(r);
    let (ro, ri) = (diameter / 2.0, inner_diameter / 2.0);
    let mo = density * std::f64::consts::PI * l * ro * ro;
    let mi = density * std::f64::consts::PI * l * ri * ri;
    let i22 = (mo * (l * l + 3.0 * ro * ro) - mi * (l * l + 3.0 * ri * ri)) / 12.0;
    let t = t_from_nxy(r, [0.0, 1.0, 0.0]);
    MassProperties {
        m: mo - mi,
        r_cm: [r[0] / 2.0, r[1] / 2.0, r[2] / 2.0],
        inertia: rotate_inertia(t, [(mo * ro * ro - mi * ri * ri) / 2.0, i22, i22]),
    }
}

/// The [`Body`] with given mass properties.
fn body_of(p: MassProperties, states: OrientationStates) -> Body {
    Body {
        m: p.m,
        r_CM: p.r_cm,
        I_11: p.inertia[0][0],
        I_22: p.inertia[1][1],
        I_33: p.inertia[2][2],
        I_21: p.inertia[1][0],
        I_31: p.inertia[2][0],
        I_32: p.inertia[2][1],
        orientation_states: states,
        ..Body::default()
    }
}

component! {
    /// A body at the end of a rigid translation `r` from `frame_a` to `frame_b` (MSL
    /// `BodyShape`): `translation` carries the frames, `body` the mass at `frame_a`.
    /// Its tunable parameters are those of `body` (`b1.body.m`) and `translation`.
    #[type_name = "MultiBody.Parts.BodyShape"]
    pub struct BodyShape {
        /// Vector from `frame_a` to `frame_b`, resolved in `frame_a` \[m\].
        structural r: [f64; 3] = [0.0, 0.0, 0.0];
        /// Centre of mass relative to `frame_a` \[m\]; `None` puts it at `r/2`.
        structural r_CM: Option<[f64; 3]> = None;
        /// Mass \[kg\].
        structural m: f64 = 1.0;
        /// Inertia about the centre of mass, resolved in `frame_a`: diagonal
        /// `(I_11, I_22, I_33)` \[kg.m2\].
        structural I_diag: [f64; 3] = [0.001, 0.001, 0.001];
        /// Inertia off-diagonal elements `(I_21, I_31, I_32)` \[kg.m2\].
        structural I_offdiag: [f64; 3] = [0.0, 0.0, 0.0];
        /// Orientation states if the body is the root of its mechanism.
        structural orientation_states: OrientationStates = OrientationStates::Cardan;
        /// Radius when rendered \[m\] (0 hides it).
        structural radius: f64 = 0.02;
        /// Colour when rendered, RGB in 0..1 (MSL's body colour).
        structural color: [f64; 3] = crate::render::BODY_COLOR;
        /// First frame (the body's).
        connector frame_a: Frame;
        /// Second frame, `r` from `frame_a`.
        connector frame_b: Frame;
        /// The rigid translation from `frame_a` to `frame_b`.
        component translation: FixedTranslation = FixedTranslation { r: self.r, radius: self.radius, color: self.color };
        /// The mass, at `frame_a`.
        component body: Body = Body {
            m: self.m,
            r_CM: self.r_CM.unwrap_or([self.r[0] / 2.0, self.r[1] / 2.0, self.r[2] / 2.0]),
            I_11: self.I_diag[0],
            I_22: self.I_diag[1],
            I_33: self.I_diag[2],
            I_21: self.I_offdiag[0],
            I_31: self.I_offdiag[1],
            I_32: self.I_offdiag[2],
            orientation_states: self.orientation_states,
            radius: 0.0,
            ..Body::default()
        };
        equation {
            connect(frame_a, translation.frame_a);
            connect(frame_b, translation.frame_b);
            connect(frame_a, body.frame_a);
        }
    }
}

component! {
    /// A box from `frame_a` to `frame_b` = `frame_a + r` whose mass and inertia follow
    /// from its size and density (MSL `BodyBox`).
    #[type_name = "MultiBody.Parts.BodyBox"]
    pub struct BodyBox {
        /// Vector from `frame_a` to `frame_b`, resolved in `frame_a`; the box's length
        /// direction \[m\].
        structural r: [f64; 3] = [0.1, 0.0, 0.0];
        /// Width \[m\]; `None` is `|r|/20`.
        structural width: Option<f64> = None;
        /// Height \[m\]; `None` is the width.
        structural height: Option<f64> = None;
        /// Width of the inner cut-out \[m\].
        structural inner_width: f64 = 0.0;
        /// Height of the inner cut-out \[m\]; `None` is the inner width.
        structural inner_height: Option<f64> = None;
        /// Direction of the width, resolved in `frame_a`.
        structural width_direction: [f64; 3] = [0.0, 1.0, 0.0];
        /// Colour when rendered, RGB in 0..1 (MSL's body colour).
        structural color: [f64; 3] = crate::render::BODY_COLOR;
        /// Density \[kg/m3\] (steel).
        structural density: f64 = 7700.0;
        /// Orientation states if the body is the root of its mechanism.
        structural orientation_states: OrientationStates = OrientationStates::Cardan;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        /// The rigid translation from `frame_a` to `frame_b`.
        component translation: FixedTranslation = FixedTranslation { r: self.r, radius: 0.0, color: self.color };
        /// The mass, at `frame_a`.
        component body: Body = body_of(self.mass_properties(), self.orientation_states);
        equation {
            assert(norm(r) > 0.0, "the box's length |r| must not be zero");
            let (w, h) = self.outer_size();
            assert(
                w > 0.0 && h > 0.0,
                format!("the box's width {w} and height {h} must be positive")
            );
            assert(
                inner_width >= 0.0 && inner_width < w && self.inner_height.unwrap_or(inner_width) < h,
                "the inner box must be smaller than the box"
            );
            assert(density > 0.0, format!("the density {density} must be positive"));
            connect(frame_a, translation.frame_a);
            connect(frame_b, translation.frame_b);
            connect(frame_a, body.frame_a);
        }
    }
}

impl BodyBox {
    /// Width and height (their defaults: `|r|/20` and the width).
    fn outer_size(&self) -> (f64, f64) {
        let w = self.width.unwrap_or(norm(self.r) / 20.0);
        (w, self.height.unwrap_or(w))
    }

    /// The box's mass, centre of mass and inertia.
    pub fn mass_properties(&self) -> MassProperties {
        let (w, h) = self.outer_size();
        box_mass_properties(
            self.r,
            w,
            h,
            self.inner_width,
            self.inner_height.unwrap_or(self.inner_width),
            self.width_direction,
            self.density,
        )
    }
}

component! {
    /// A cylinder from `frame_a` to `frame_b` = `frame_a + r` whose mass and inertia
    /// follow from its size and density (MSL `BodyCylinder`).
    #[type_name = "MultiBody.Parts.BodyCylinder"]
    pub struct BodyCylinder {
        /// Vector from `frame_a` to `frame_b`, resolved in `frame_a`; the axis \[m\].
        structural r: [f64; 3] = [0.1, 0.0, 0.0];
        /// Diameter \[m\]; `None` is `|r|/20`.
        structural diameter: Option<f64> = None;
        /// Inner diameter \[m\] (a tube).
        structural inner_diameter: f64 = 0.0;
        /// Colour when rendered, RGB in 0..1 (MSL's body colour).
        structural color: [f64; 3] = crate::render::BODY_COLOR;
        /// Density \[kg/m3\] (steel).
        structural density: f64 = 7700.0;
        /// Orientation states if the body is the root of its mechanism.
        structural orientation_states: OrientationStates = OrientationStates::Cardan;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        /// The rigid translation from `frame_a` to `frame_b`.
        component translation: FixedTranslation = FixedTranslation { r: self.r, radius: 0.0, color: self.color };
        /// The mass, at `frame_a`.
        component body: Body = body_of(self.mass_properties(), self.orientation_states);
        equation {
            assert(norm(r) > 0.0, "the cylinder's length |r| must not be zero");
            let d = self.diameter.unwrap_or(norm(r) / 20.0);
            assert(d > 0.0, format!("the diameter {d} must be positive"));
            assert(
                inner_diameter >= 0.0 && inner_diameter < d,
                format!("the inner diameter {inner_diameter} must be smaller than the diameter {d}")
            );
            assert(density > 0.0, format!("the density {density} must be positive"));
            connect(frame_a, translation.frame_a);
            connect(frame_b, translation.frame_b);
            connect(frame_a, body.frame_a);
        }
    }
}

impl BodyCylinder {
    /// The cylinder's mass, centre of mass and inertia.
    pub fn mass_properties(&self) -> MassProperties {
        let d = self.diameter.unwrap_or(norm(self.r) / 20.0);
        cylinder_mass_properties(self.r, d, self.inner_diameter, self.density)
    }
}
