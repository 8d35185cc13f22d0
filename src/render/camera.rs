//! A perspective (pinhole) camera: world points to view coordinates and pixels.

use super::geom::{V3, cross, dot, norm, normalize, sub};

/// A pinhole camera at `position` looking at a point, with a vertical field of view.
///
/// View coordinates: `x` to the right, `y` up, `z` the depth along the line of sight.
/// A point at view coordinates `(x, y, z)` (with `z > 0`) lands on the image at column
/// `width/2 + f x/z` and row `height/2 - f y/z` (pixel `(i, j)` covers
/// `[i, i+1) x [j, j+1)`), where `f = (height/2) / tan(fov/2)`.
#[derive(Clone, Debug)]
pub(crate) struct Camera {
    position: V3,
    right: V3,
    up: V3,
    forward: V3,
    focal: f64,
    cx: f64,
    cy: f64,
    /// Distance of the near clipping plane \[m\].
    pub near: f64,
}

impl Camera {
    /// The camera, or why it cannot be built (coincident points, `up` along the line of
    /// sight, a field of view outside (0, 180) degrees).
    pub(crate) fn new(
        position: V3,
        look_at: V3,
        up: V3,
        fov_deg: f64,
        (width, height): (u32, u32),
    ) -> Result<Camera, String> {
        let finite = |v: V3| v.iter().all(|x| x.is_finite());
        if !(finite(position) && finite(look_at) && finite(up)) {
            return Err("camera position, look_at and up must be finite".into());
        }
        let distance = norm(sub(look_at, position));
        let forward = normalize(sub(look_at, position))
            .ok_or("the camera position and look_at point coincide")?;
        let right = normalize(cross(forward, up))
            .ok_or("the up vector is zero or along the line of sight")?;
        if !(fov_deg > 0.0 && fov_deg < 180.0) {
            return Err(format!(
                "the field of view must be between 0 and 180 degrees, not {fov_deg}"
            ));
        }
        Ok(Camera {
            position,
            right,
            up: cross(right, forward),
            forward,
            focal: 0.5 * height as f64 / (0.5 * fov_deg.to_radians()).tan(),
            cx: 0.5 * width as f64,
            cy: 0.5 * height as f64,
            near: 1e-3 * distance,
        })
    }

    /// The camera's position.
    pub(crate) fn position(&self) -> V3 {
        self.position
    }

    /// The unit vectors right, up and forward of the view, in world coordinates.
    pub(crate) fn axes(&self) -> (V3, V3, V3) {
        (self.right, self.up, self.forward)
    }

    /// View coordinates of a world point.
    pub(crate) fn to_view(&self, p: V3) -> V3 {
        let d = sub(p, self.position);
        [dot(d, self.right), dot(d, self.up), dot(d, self.forward)]
    }

    /// Image coordinates `(column, row)` and inverse depth `1/z` of a point in view
    /// coordinates with `z > 0`.
    pub(crate) fn project(&self, v: V3) -> [f64; 3] {
        let iz = 1.0 / v[2];
        [
            self.cx + self.focal * v[0] * iz,
            self.cy - self.focal * v[1] * iz,
            iz,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projects_like_a_pinhole() {
        let cam =
            Camera::new([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], 90.0, (100, 100)).unwrap();
        // f = 50 px: the point (1, 1, 0) is 5 m away, 10 px right and up of the centre.
        let p = cam.project(cam.to_view([1.0, 1.0, 0.0]));
        assert!((p[0] - 60.0).abs() < 1e-9 && (p[1] - 40.0).abs() < 1e-9);
        assert!((p[2] - 0.2).abs() < 1e-12);
    }

    #[test]
    fn rejects_degenerate_cameras() {
        let up = [0.0, 1.0, 0.0];
        assert!(Camera::new([1.0; 3], [1.0; 3], up, 45.0, (10, 10)).is_err());
        assert!(Camera::new([0.0, 5.0, 0.0], [0.0; 3], up, 45.0, (10, 10)).is_err());
        assert!(Camera::new([0.0, 0.0, 5.0], [0.0; 3], up, 180.0, (10, 10)).is_err());
        assert!(Camera::new([f64::NAN; 3], [0.0; 3], up, 45.0, (10, 10)).is_err());
    }
}
