//! Frames fixed in the world, and rigid translations and rotations between two frames.

use crate::frames::{
    Orientation, Vec3, absolute_rotation, invalid_sequence, null_rotation, planar_rotation,
    resolve1, usable_sequence, valid_sequence,
};
use crate::interfaces::Frame;
use crate::prelude::*;

component! {
    /// A frame fixed in the world at position `r` (MSL `Parts.Fixed`): a definite root of
    /// the orientation graph.
    #[type_name = "MultiBody.Parts.Fixed"]
    pub struct Fixed {
        /// Position of `frame_b`, resolved in world \[m\].
        parameter r: [f64; 3] = [0.0, 0.0, 0.0];
        /// The fixed frame.
        connector frame_b: Frame;
        equation {
            root(frame_b.R);
            frame_b.r_0 = r;
            frame_b.R = null_rotation();
        }
    }
}

component! {
    /// A rigid, massless translation from `frame_a` to `frame_b` by `r`, resolved in
    /// `frame_a`; both frames have the same orientation (MSL `Parts.FixedTranslation`).
    #[type_name = "MultiBody.Parts.FixedTranslation"]
    pub struct FixedTranslation {
        /// Vector from `frame_a` to `frame_b`, resolved in `frame_a` \[m\].
        parameter r: [f64; 3] = [0.0, 0.0, 0.0];
        /// Radius when rendered \[m\] (0 hides it).
        structural radius: f64 = 0.02;
        /// Colour when rendered, RGB in 0..1 (MSL's rod colour, grey).
        structural color: [f64; 3] = crate::render::ROD_COLOR;
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        equation {
            branch(frame_a.R, frame_b.R);
            frame_b.r_0 = frame_a.r_0 + resolve1(&frame_a.R, r);
            frame_b.R = frame_a.R;
            Vec3::zero() = frame_a.f + frame_b.f;
            Vec3::zero() = frame_a.t + frame_b.t + r.cross(frame_b.f);
        }
    }
}

/// How a [`FixedRotation`] describes its rotation.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum RotationType {
    /// A rotation by an angle about an axis (MSL `RotationAxis`).
    #[default]
    RotationAxis,
    /// The x and y axes of `frame_b`, resolved in `frame_a` (MSL `TwoAxesVectors`).
    TwoAxesVectors,
    /// Angles about the axes of a sequence (MSL `PlanarRotationSequence`).
    PlanarRotationSequence,
}

component! {
    /// A rigid, massless translation by `r` followed by a fixed rotation (MSL
    /// `Parts.FixedRotation`). Angles are in degrees, as in MSL.
    #[type_name = "MultiBody.Parts.FixedRotation"]
    pub struct FixedRotation {
        /// Vector from `frame_a` to `frame_b`, resolved in `frame_a` \[m\].
        parameter r: [f64; 3] = [0.0, 0.0, 0.0];
        /// How the rotation is given.
        structural rotation_type: RotationType = RotationType::RotationAxis;
        /// Rotation axis, resolved in `frame_a` (for `RotationAxis`).
        structural n: [f64; 3] = [1.0, 0.0, 0.0];
        /// Rotation angle \[deg\] (for `RotationAxis`).
        structural angle: f64 = 0.0;
        /// x axis of `frame_b`, resolved in `frame_a` (for `TwoAxesVectors`).
        structural n_x: [f64; 3] = [1.0, 0.0, 0.0];
        /// y axis of `frame_b`, resolved in `frame_a` (for `TwoAxesVectors`).
        structural n_y: [f64; 3] = [0.0, 1.0, 0.0];
        /// Axis sequence (for `PlanarRotationSequence`).
        structural sequence: [usize; 3] = [1, 2, 3];
        /// Angles of the sequence \[deg\] (for `PlanarRotationSequence`).
        structural angles: [f64; 3] = [0.0, 0.0, 0.0];
        /// First frame.
        connector frame_a: Frame;
        /// Second frame.
        connector frame_b: Frame;
        equation {
            if rotation_type == RotationType::RotationAxis {
                assert(crate::joints::valid_axis(n), crate::joints::invalid_axis("n", n));
            }
            if rotation_type == RotationType::PlanarRotationSequence {
                assert(valid_sequence(sequence), invalid_sequence("sequence", sequence));
            }
            let r_rel: Orientation = fixed_rotation(rotation_type, n, angle, n_x, n_y, usable_sequence(sequence), angles);
            let r_inv = crate::frames::inverse_rotation(&r_rel);
            branch(frame_a.R, frame_b.R);
            frame_b.r_0 = frame_a.r_0 + resolve1(&frame_a.R, r);
            if rooted(frame_a.R) {
                frame_b.R = absolute_rotation(&frame_a.R, &r_rel);
                Vec3::zero() = frame_a.f + resolve1(&r_rel, frame_b.f);
                Vec3::zero() = frame_a.t + resolve1(&r_rel, frame_b.t) - r.cross(frame_a.f);
            } else {
                frame_a.R = absolute_rotation(&frame_b.R, &r_inv);
                Vec3::zero() = frame_b.f + resolve1(&r_inv, frame_a.f);
                Vec3::zero() = frame_b.t + resolve1(&r_inv, frame_a.t) + resolve1(&r_inv, r).cross(frame_b.f);
            }
        }
    }
}

/// The constant rotation of a [`FixedRotation`].
fn fixed_rotation(
    kind: RotationType,
    n: [f64; 3],
    angle_deg: f64,
    n_x: [f64; 3],
    n_y: [f64; 3],
    sequence: [usize; 3],
    angles_deg: [f64; 3],
) -> Orientation {
    let zero = Expr::constant(0.0);
    match kind {
        RotationType::RotationAxis => planar_rotation(
            crate::joints::unit_axis(n),
            Expr::constant(angle_deg.to_radians()),
            zero,
        ),
        RotationType::TwoAxesVectors => crate::frames::from_nxy(n_x, n_y),
        RotationType::PlanarRotationSequence => crate::frames::axes_rotations(
            sequence,
            angles_deg.map(|a| Expr::constant(a.to_radians())),
            [zero; 3],
        ),
    }
}
