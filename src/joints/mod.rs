//! Joints (MSL `MultiBody.Joints`): elementary joints with their coordinates as
//! preferred states, and cut joints that close kinematic loops.
//!
//! Every joint relates the orientations of its two frames as a branch of the
//! orientation graph, unless it is a cut (`iscut: true`): then it emits the three
//! residues between `frame_b`'s orientation and the one its coordinates imply, and each
//! frame gets its orientation from elsewhere.

mod composite;
mod gear_constraint;
mod joint_rrr;
mod joint_ssp;
mod joint_usr;
mod planar_loop;
mod prismatic;
mod prismatic_with_length_constraint;
mod revolute;
mod revolute_with_length_constraint;
mod rolling_wheel;
mod rolling_wheel_set;
mod spherical;
mod spherical_spherical;
mod universal_spherical;

pub use composite::*;
pub use gear_constraint::*;
pub use joint_rrr::*;
pub use joint_ssp::*;
pub use joint_usr::*;
pub use planar_loop::*;
pub use prismatic::*;
pub use prismatic_with_length_constraint::*;
pub use revolute::*;
pub use revolute_with_length_constraint::*;
pub use rolling_wheel::*;
pub use rolling_wheel_set::*;
pub use spherical::*;
pub use spherical_spherical::*;
pub use universal_spherical::*;

use crate::frames::Vec3;

/// Whether `n` can be an axis: finite, and not zero.
pub(crate) fn valid_axis(n: [f64; 3]) -> bool {
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    l.is_finite() && l > 1e-12
}

/// The message of a joint whose axis is not [`valid_axis`].
pub(crate) fn invalid_axis(name: &str, n: [f64; 3]) -> String {
    format!(
        "the axis {name} = {} must be a nonzero vector",
        multibody_core::model::show_values(&n)
    )
}

/// The unit vector of an axis given by the user; the z axis for an axis that is not
/// [`valid_axis`] (which the component reports: it asserts the axis is valid).
pub(crate) fn unit_axis(n: [f64; 3]) -> Vec3 {
    if !valid_axis(n) {
        return Vec3::constant([0.0, 0.0, 1.0]);
    }
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    Vec3::constant([n[0] / l, n[1] / l, n[2] / l])
}

/// Default priority of joint coordinates as states (Multibody.jl's default joint
/// priority; above variables without preference, below an explicit `prefer`).
pub const JOINT_STATE_PRIORITY: f64 = 3.0;

/// Two unit vectors spanning the plane normal to the unit axis `e` (MSL's choice in
/// `RevolutePlanarLoopConstraint`): `(ex, ey)` with `ex x ey = e`.
pub(crate) fn plane_basis(e: Vec3) -> (Vec3, Vec3) {
    let a = e.as_f64().expect("constant axis");
    let helper = if a[0].abs() > 0.1 {
        [0.0, 1.0, 0.0]
    } else if a[1].abs() > 0.1 {
        [0.0, 0.0, 1.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let c = e.cross(Vec3::constant(helper)).as_f64().expect("constant");
    let l = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    let ey = Vec3::constant([c[0] / l, c[1] / l, c[2] / l]);
    (ey.cross(e), ey)
}
