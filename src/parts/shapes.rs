//! Bodies with a shape: a body at the end of a rigid translation (MSL `BodyShape`), and
//! boxes and cylinders whose mass and inertia follow from their geometry and density
//! (MSL `BodyBox`, `BodyCylinder`).

use super::body::{Body, OrientationStates};
use super::fixed::FixedTranslation;
use super::mass_properties::{
    MassProperties, Placement, box_mass_properties, cylinder_mass_properties, placement_checks,
    positive,
};
use crate::interfaces::Frame;
use crate::numeric::{norm, sub};
use crate::prelude::*;

/// The [`Body`] of a shape component: its orientation states and start values (fields
/// of the same names on every shape), the rest defaults.
macro_rules! root_start {
    ($shape:expr) => {
        Body {
            orientation_states: $shape.orientation_states,
            sequence_angle_states: $shape.sequence_angle_states,
            angles_start: $shape.angles_start,
            sequence_start: $shape.sequence_start,
            angles_fixed: $shape.angles_fixed,
            w_0_start: $shape.w_0_start,
            w_0_fixed: $shape.w_0_fixed,
            z_0_start: $shape.z_0_start,
            z_0_fixed: $shape.z_0_fixed,
            ..Body::default()
        }
    };
}

/// `start` (see `root_start!`) with the given mass properties.
fn body_of(p: MassProperties, start: Body) -> Body {
    Body {
        m: p.m,
        r_CM: p.r_cm,
        I_11: p.inertia[0][0],
        I_22: p.inertia[1][1],
        I_33: p.inertia[2][2],
        I_21: p.inertia[1][0],
        I_31: p.inertia[2][0],
        I_32: p.inertia[2][1],
        ..start
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
        /// Orientation states if the body is the root of its mechanism (MSL
        /// `useQuaternions`; default a quaternion, see [`OrientationStates`]).
        structural orientation_states: OrientationStates = OrientationStates::Quaternion;
        /// Axis sequence of Cardan angle states, default {1, 2, 3} (as [`Body`]'s).
        structural sequence_angle_states: [usize; 3] = [1, 2, 3];
        /// Start orientation of `frame_a`: angles about the axes of `sequence_start` that
        /// rotate the world frame into it \[rad\], default {0, 0, 0} (as [`Body`]'s).
        structural angles_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Axis sequence of `angles_start`, default {1, 2, 3}.
        structural sequence_start: [usize; 3] = [1, 2, 3];
        /// Whether the start orientation is fixed at initialization, default false.
        structural angles_fixed: bool = false;
        /// Start angular velocity of `frame_a`, resolved in world \[rad/s\], default
        /// {0, 0, 0}.
        structural w_0_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Whether `w_0_start` is fixed at initialization, default false.
        structural w_0_fixed: bool = false;
        /// Start angular acceleration of `frame_a`, resolved in world \[rad/s2\],
        /// default {0, 0, 0}.
        structural z_0_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Whether `z_0_start` is fixed at initialization, default false.
        structural z_0_fixed: bool = false;
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
            radius: 0.0,
            ..root_start!(self)
        };
        equation {
            connect(frame_a, translation.frame_a);
            connect(frame_b, translation.frame_b);
            connect(frame_a, body.frame_a);
        }
    }
}

component! {
    /// A box whose mass and inertia follow from its size and density (MSL `BodyBox`),
    /// between `frame_a` and `frame_b` = `frame_a + r`. The box starts at `r_shape` and
    /// extends `length` along `length_direction` (by default from `frame_a` to
    /// `frame_b`); its centre of mass is at `r_shape + e length / 2`, `e` the unit
    /// length direction. As in MSL, the principal axes of its inertia are `r` and
    /// `width_direction`, whatever `length_direction` is.
    #[type_name = "MultiBody.Parts.BodyBox"]
    pub struct BodyBox {
        /// Vector from `frame_a` to `frame_b`, resolved in `frame_a` \[m\] (MSL's
        /// start value).
        structural r: [f64; 3] = [0.1, 0.0, 0.0];
        /// Vector from `frame_a` to the box's origin, resolved in `frame_a` \[m\].
        structural r_shape: [f64; 3] = [0.0, 0.0, 0.0];
        /// Direction of the box's length, resolved in `frame_a` (any non-zero length);
        /// `None` is `r - r_shape`.
        structural length_direction: Option<[f64; 3]> = None;
        /// Length of the box \[m\]; `None` is `|r - r_shape|`.
        structural length: Option<f64> = None;
        /// Width \[m\]; `None` is `length/20`.
        structural width: Option<f64> = None;
        /// Height \[m\]; `None` is the width.
        structural height: Option<f64> = None;
        /// Width of the inner cut-out, `0 <= inner_width <= width` \[m\].
        structural inner_width: f64 = 0.0;
        /// Height of the inner cut-out, `0 <= inner_height <= height` \[m\]; `None` is
        /// the inner width.
        structural inner_height: Option<f64> = None;
        /// Direction of the width, resolved in `frame_a`.
        structural width_direction: [f64; 3] = [0.0, 1.0, 0.0];
        /// Colour when rendered, RGB in 0..1 (MSL's body colour).
        structural color: [f64; 3] = crate::render::BODY_COLOR;
        /// Density \[kg/m3\] (steel).
        structural density: f64 = 7700.0;
        /// Orientation states if the body is the root of its mechanism (MSL
        /// `useQuaternions`; default a quaternion, see [`OrientationStates`]).
        structural orientation_states: OrientationStates = OrientationStates::Quaternion;
        /// Axis sequence of Cardan angle states, default {1, 2, 3} (as [`Body`]'s).
        structural sequence_angle_states: [usize; 3] = [1, 2, 3];
        /// Start orientation of `frame_a`: angles about the axes of `sequence_start` that
        /// rotate the world frame into it \[rad\], default {0, 0, 0} (as [`Body`]'s).
        structural angles_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Axis sequence of `angles_start`, default {1, 2, 3}.
        structural sequence_start: [usize; 3] = [1, 2, 3];
        /// Whether the start orientation is fixed at initialization, default false.
        structural angles_fixed: bool = false;
        /// Start angular velocity of `frame_a`, resolved in world \[rad/s\], default
        /// {0, 0, 0}.
        structural w_0_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Whether `w_0_start` is fixed at initialization, default false.
        structural w_0_fixed: bool = false;
        /// Start angular acceleration of `frame_a`, resolved in world \[rad/s2\],
        /// default {0, 0, 0}.
        structural z_0_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Whether `z_0_start` is fixed at initialization, default false.
        structural z_0_fixed: bool = false;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        /// The rigid translation from `frame_a` to `frame_b`.
        component translation: FixedTranslation = FixedTranslation { r: self.r, radius: 0.0, color: self.color };
        /// The mass, at `frame_a`.
        component body: Body = body_of(self.mass_properties(), root_start!(self));
        equation {
            for (holds, message) in self.checks() {
                assert(holds, message);
            }
            connect(frame_a, translation.frame_a);
            connect(frame_b, translation.frame_b);
            connect(frame_a, body.frame_a);
        }
    }
}

impl BodyBox {
    /// Where the box lies, with MSL's defaults filled in.
    fn placement(&self) -> Placement {
        let d = sub(self.r, self.r_shape);
        Placement {
            r: self.r,
            r_shape: self.r_shape,
            length_direction: self.length_direction.unwrap_or(d),
            length: self.length.unwrap_or(norm(d)),
        }
    }

    /// Width and height (defaults: `length/20` and the width).
    fn outer_size(&self) -> [f64; 2] {
        let w = self.width.unwrap_or(self.placement().length / 20.0);
        [w, self.height.unwrap_or(w)]
    }

    /// Inner width and height (default of the height: the inner width).
    fn inner_size(&self) -> [f64; 2] {
        [
            self.inner_width,
            self.inner_height.unwrap_or(self.inner_width),
        ]
    }

    /// The parameter checks, as `(holds, message)` (MSL's asserts and ours).
    fn checks(&self) -> Vec<(bool, String)> {
        let ([w, h], [wi, hi]) = (self.outer_size(), self.inner_size());
        let mut checks = placement_checks(&self.placement());
        checks.extend([
            positive("width", w),
            positive("height", h),
            (
                (0.0..=w).contains(&wi),
                format!("parameter `inner_width` = {wi} must be in [0, width = {w}]"),
            ),
            (
                (0.0..=h).contains(&hi),
                format!("parameter `inner_height` = {hi} must be in [0, height = {h}]"),
            ),
            (
                self.width_direction.iter().all(|x| x.is_finite()),
                format!(
                    "parameter `width_direction` = {:?} must be finite",
                    self.width_direction
                ),
            ),
            positive("density", self.density),
        ]);
        checks
    }

    /// The box's mass, centre of mass and inertia (MSL `BodyBox`'s `m`, `r_CM`, `I`);
    /// meaningless (NaN) for parameters the component rejects.
    pub fn mass_properties(&self) -> MassProperties {
        box_mass_properties(
            &self.placement(),
            self.outer_size(),
            self.inner_size(),
            self.width_direction,
            self.density,
        )
    }
}

component! {
    /// A cylinder whose mass and inertia follow from its size and density (MSL
    /// `BodyCylinder`), between `frame_a` and `frame_b` = `frame_a + r`. The cylinder
    /// starts at `r_shape` and extends `length` along `length_direction` (by default
    /// from `frame_a` to `frame_b`); its centre of mass is at `r_shape + e length / 2`.
    /// As in MSL, the axis of its inertia is `r`, whatever `length_direction` is.
    #[type_name = "MultiBody.Parts.BodyCylinder"]
    pub struct BodyCylinder {
        /// Vector from `frame_a` to `frame_b`, resolved in `frame_a` \[m\] (MSL's
        /// start value).
        structural r: [f64; 3] = [0.1, 0.0, 0.0];
        /// Vector from `frame_a` to the cylinder's origin, resolved in `frame_a` \[m\].
        structural r_shape: [f64; 3] = [0.0, 0.0, 0.0];
        /// Direction of the cylinder's axis, resolved in `frame_a` (any non-zero
        /// length); `None` is `r - r_shape`.
        structural length_direction: Option<[f64; 3]> = None;
        /// Length of the cylinder \[m\]; `None` is `|r - r_shape|`.
        structural length: Option<f64> = None;
        /// Diameter \[m\]; `None` is `length/20`.
        structural diameter: Option<f64> = None;
        /// Inner diameter (a tube), `0 <= inner_diameter < diameter` \[m\].
        structural inner_diameter: f64 = 0.0;
        /// Colour when rendered, RGB in 0..1 (MSL's body colour).
        structural color: [f64; 3] = crate::render::BODY_COLOR;
        /// Density \[kg/m3\] (steel).
        structural density: f64 = 7700.0;
        /// Orientation states if the body is the root of its mechanism (MSL
        /// `useQuaternions`; default a quaternion, see [`OrientationStates`]).
        structural orientation_states: OrientationStates = OrientationStates::Quaternion;
        /// Axis sequence of Cardan angle states, default {1, 2, 3} (as [`Body`]'s).
        structural sequence_angle_states: [usize; 3] = [1, 2, 3];
        /// Start orientation of `frame_a`: angles about the axes of `sequence_start` that
        /// rotate the world frame into it \[rad\], default {0, 0, 0} (as [`Body`]'s).
        structural angles_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Axis sequence of `angles_start`, default {1, 2, 3}.
        structural sequence_start: [usize; 3] = [1, 2, 3];
        /// Whether the start orientation is fixed at initialization, default false.
        structural angles_fixed: bool = false;
        /// Start angular velocity of `frame_a`, resolved in world \[rad/s\], default
        /// {0, 0, 0}.
        structural w_0_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Whether `w_0_start` is fixed at initialization, default false.
        structural w_0_fixed: bool = false;
        /// Start angular acceleration of `frame_a`, resolved in world \[rad/s2\],
        /// default {0, 0, 0}.
        structural z_0_start: [f64; 3] = [0.0, 0.0, 0.0];
        /// Whether `z_0_start` is fixed at initialization, default false.
        structural z_0_fixed: bool = false;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        /// The rigid translation from `frame_a` to `frame_b`.
        component translation: FixedTranslation = FixedTranslation { r: self.r, radius: 0.0, color: self.color };
        /// The mass, at `frame_a`.
        component body: Body = body_of(self.mass_properties(), root_start!(self));
        equation {
            for (holds, message) in self.checks() {
                assert(holds, message);
            }
            connect(frame_a, translation.frame_a);
            connect(frame_b, translation.frame_b);
            connect(frame_a, body.frame_a);
        }
    }
}

impl BodyCylinder {
    /// Where the cylinder lies, with MSL's defaults filled in.
    fn placement(&self) -> Placement {
        let d = sub(self.r, self.r_shape);
        Placement {
            r: self.r,
            r_shape: self.r_shape,
            length_direction: self.length_direction.unwrap_or(d),
            length: self.length.unwrap_or(norm(d)),
        }
    }

    /// The diameter (default `length/20`).
    fn outer_diameter(&self) -> f64 {
        self.diameter.unwrap_or(self.placement().length / 20.0)
    }

    /// The parameter checks, as `(holds, message)` (MSL's asserts and ours).
    fn checks(&self) -> Vec<(bool, String)> {
        let (d, di) = (self.outer_diameter(), self.inner_diameter);
        let mut checks = placement_checks(&self.placement());
        checks.extend([
            positive("diameter", d),
            (
                di >= 0.0 && di < d,
                format!("parameter `inner_diameter` = {di} must be in [0, diameter = {d})"),
            ),
            positive("density", self.density),
        ]);
        checks
    }

    /// The cylinder's mass, centre of mass and inertia (MSL `BodyCylinder`'s `m`,
    /// `r_CM`, `I`); meaningless (NaN) for parameters the component rejects.
    pub fn mass_properties(&self) -> MassProperties {
        cylinder_mass_properties(
            &self.placement(),
            self.outer_diameter(),
            self.inner_diameter,
            self.density,
        )
    }
}
