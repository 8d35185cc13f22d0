//! Small 3-vector helpers for the renderer (plain `[f64; 3]`, no symbolic types).

/// A point or direction in world coordinates \[m\], and the vector helpers.
pub(crate) use crate::numeric::*;

/// Two unit vectors completing the unit vector `e` to a right-handed orthonormal basis
/// `(e, u, v)`; `u` is as close to `hint` as possible (any direction if `hint` is
/// parallel to `e`).
pub(crate) fn basis(e: V3, hint: V3) -> (V3, V3) {
    let project = |h: V3| normalize(axpy(h, -dot(h, e), e));
    let u = project(hint)
        .or_else(|| project([1.0, 0.0, 0.0]))
        .or_else(|| project([0.0, 1.0, 0.0]))
        .unwrap_or([0.0, 0.0, 1.0]);
    (u, cross(e, u))
}

/// A frame's orientation: the rows of `T` are the frame's axes resolved in the world
/// (`v_frame = T v_world`), so a frame-resolved vector is `T' v` in the world.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rotation(pub [[f64; 3]; 3]);

impl Rotation {
    /// The frame-resolved vector `v`, resolved in the world.
    pub(crate) fn resolve1(self, v: V3) -> V3 {
        let t = &self.0;
        std::array::from_fn(|i| t[0][i] * v[0] + t[1][i] * v[1] + t[2][i] * v[2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_orthonormal_and_follows_the_hint() {
        let e = normalize([1.0, 2.0, 2.0]).unwrap();
        let (u, v) = basis(e, [0.0, 1.0, 0.0]);
        assert!(dot(e, u).abs() < 1e-12 && dot(e, v).abs() < 1e-12 && dot(u, v).abs() < 1e-12);
        assert!((norm(u) - 1.0).abs() < 1e-12 && (norm(v) - 1.0).abs() < 1e-12);
        assert!(dot(u, [0.0, 1.0, 0.0]) > 0.0);
        // A hint parallel to the axis still gives a basis.
        let (u, _) = basis([0.0, 1.0, 0.0], [0.0, 2.0, 0.0]);
        assert!((norm(u) - 1.0).abs() < 1e-12 && u[1].abs() < 1e-12);
    }

    #[test]
    fn rotation_resolves_with_the_transpose() {
        // Frame rotated by 90 degrees about z: its x axis is the world's y axis.
        let r = Rotation([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]);
        assert_eq!(r.resolve1([1.0, 0.0, 0.0]), [0.0, 1.0, 0.0]);
    }
}
