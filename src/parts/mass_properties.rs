//! Mass, centre of mass and inertia of boxes and cylinders from their geometry and
//! density, by MSL's rules (`Parts.BodyBox`, `Parts.BodyCylinder`).
//!
//! MSL's quirk is kept: the mass and the centre of mass follow `length_direction`
//! (`r_CM = r_shape + normalize(length_direction) length / 2`), while the principal axes
//! of the inertia follow `r` (`R = from_nxy(r, width_direction)`); both agree when
//! `length_direction` is parallel to `r`, as it is by default with `r_shape = 0`.

use crate::frames::t_from_nxy;
use crate::numeric::{add, normalize, scale};

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

/// Where a shape lies relative to `frame_a` (all resolved in `frame_a`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Placement {
    /// `frame_a` to `frame_b`; the x axis of the principal axes \[m\].
    pub r: [f64; 3],
    /// `frame_a` to the shape's origin \[m\].
    pub r_shape: [f64; 3],
    /// Direction of the length from the shape's origin (any length).
    pub length_direction: [f64; 3],
    /// Length of the shape \[m\].
    pub length: f64,
}

impl Placement {
    /// `r_shape + normalize(length_direction) length / 2` (NaN for a zero direction, which
    /// the components reject).
    fn centre(&self) -> [f64; 3] {
        let e = normalize(self.length_direction).unwrap_or([f64::NAN; 3]);
        add(self.r_shape, scale(e, self.length / 2.0))
    }
}

/// `T' D T` for a diagonal `D`: the inertia of a shape whose axes are the rows of `T`
/// (MSL `resolveDyade1`).
fn rotate_inertia(t: [[f64; 3]; 3], d: [f64; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| t[k][i] * d[k] * t[k][j]).sum()))
}

/// A box `width` by `height` in cross-section with an inner box `inner_width` by
/// `inner_height` cut out along its whole length (MSL `BodyBox`).
pub(crate) fn box_mass_properties(
    at: &Placement,
    [w, h]: [f64; 2],
    [wi, hi]: [f64; 2],
    width_direction: [f64; 3],
    density: f64,
) -> MassProperties {
    let l = at.length;
    let mo = density * l * w * h;
    let mi = density * l * wi * hi;
    let d = [
        (mo * (w * w + h * h) - mi * (wi * wi + hi * hi)) / 12.0,
        (mo * (l * l + h * h) - mi * (l * l + hi * hi)) / 12.0,
        (mo * (l * l + w * w) - mi * (l * l + wi * wi)) / 12.0,
    ];
    MassProperties {
        m: mo - mi,
        r_cm: at.centre(),
        inertia: rotate_inertia(t_from_nxy(at.r, width_direction), d),
    }
}

/// A cylinder of `diameter`, hollowed to a tube by `inner_diameter` (MSL
/// `BodyCylinder`).
pub(crate) fn cylinder_mass_properties(
    at: &Placement,
    diameter: f64,
    inner_diameter: f64,
    density: f64,
) -> MassProperties {
    let l = at.length;
    let (ro, ri) = (diameter / 2.0, inner_diameter / 2.0);
    let mo = density * std::f64::consts::PI * l * ro * ro;
    let mi = density * std::f64::consts::PI * l * ri * ri;
    let i22 = (mo * (l * l + 3.0 * ro * ro) - mi * (l * l + 3.0 * ri * ri)) / 12.0;
    let axial = (mo * ro * ro - mi * ri * ri) / 2.0;
    MassProperties {
        m: mo - mi,
        r_cm: at.centre(),
        inertia: rotate_inertia(t_from_nxy(at.r, [0.0, 1.0, 0.0]), [axial, i22, i22]),
    }
}

/// The checks shared by boxes and cylinders, as `(holds, message)` pairs naming the
/// parameter and its value.
pub(crate) fn placement_checks(at: &Placement) -> Vec<(bool, String)> {
    let finite = |v: [f64; 3]| v.iter().all(|x| x.is_finite());
    vec![
        (
            finite(at.r),
            format!("parameter `r` = {:?} must be finite", at.r),
        ),
        (
            finite(at.r_shape),
            format!("parameter `r_shape` = {:?} must be finite", at.r_shape),
        ),
        (
            normalize(at.length_direction).is_some(),
            format!(
                "parameter `length_direction` = {:?} must be a finite, non-zero vector \
                 (its default is r - r_shape)",
                at.length_direction
            ),
        ),
        (
            at.length.is_finite() && at.length > 0.0,
            format!(
                "parameter `length` = {} must be positive (its default is |r - r_shape|)",
                at.length
            ),
        ),
    ]
}

/// `(value > 0 and finite, message)` for a size parameter.
pub(crate) fn positive(name: &str, value: f64) -> (bool, String) {
    (
        value.is_finite() && value > 0.0,
        format!("parameter `{name}` = {value} must be positive"),
    )
}
