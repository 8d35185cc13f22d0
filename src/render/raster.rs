//! Software rasterization: flat-shaded triangles and lines into an RGB image with a
//! depth buffer, back faces dropped.
//!
//! Shades are quantized to a few levels per colour so that a frame has few distinct
//! colours: GIF frames of at most 256 colours are encoded with an exact palette.

use super::camera::Camera;
use super::geom::{V3, dot, normalize, sub};
use super::mesh::Tri;

/// Brightness levels of a shaded colour.
const SHADE_LEVELS: f64 = 16.0;
/// Brightness of a face turned away from the light.
const AMBIENT: f64 = 0.35;

/// An RGB image with a depth buffer (inverse view depth; larger is nearer).
pub(crate) struct Canvas {
    pub width: usize,
    pub height: usize,
    /// Pixels, row by row, 3 bytes each.
    pub rgb: Vec<u8>,
    depth: Vec<f64>,
}

/// A colour in 0..1 as bytes.
pub(crate) fn to_bytes(c: [f64; 3]) -> [u8; 3] {
    c.map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8)
}

impl Canvas {
    /// A canvas filled with `background`.
    pub(crate) fn new(width: usize, height: usize, background: [u8; 3]) -> Canvas {
        let mut rgb = Vec::with_capacity(width * height * 3);
        for _ in 0..width * height {
            rgb.extend_from_slice(&background);
        }
        Canvas {
            width,
            height,
            rgb,
            depth: vec![0.0; width * height],
        }
    }

    fn plot(&mut self, x: usize, y: usize, iz: f64, c: [u8; 3]) {
        let i = y * self.width + x;
        if iz > self.depth[i] {
            self.depth[i] = iz;
            self.rgb[3 * i..3 * i + 3].copy_from_slice(&c);
        }
    }

    /// Draws a triangle flat-shaded by its normal against the light (a unit vector
    /// pointing towards the light), unless it faces away from the camera.
    pub(crate) fn triangle(&mut self, cam: &Camera, tri: &Tri, light: V3) {
        if dot(tri.n, sub(tri.v[0], cam.position())) >= 0.0 {
            return;
        }
        let lambert = dot(tri.n, light).max(0.0);
        let shade = ((AMBIENT + (1.0 - AMBIENT) * lambert) * SHADE_LEVELS).round() / SHADE_LEVELS;
        let color = to_bytes(tri.color.map(|c| c * shade));
        let view = tri.v.map(|p| cam.to_view(p));
        let clipped = clip_near(&view, cam.near);
        if clipped.len() < 3 {
            return;
        }
        let screen: Vec<[f64; 3]> = clipped.iter().map(|&v| cam.project(v)).collect();
        for i in 1..screen.len() - 1 {
            self.fill(screen[0], screen[i], screen[i + 1], color);
        }
    }

    /// Fills a screen-space triangle (column, row, inverse depth), depth-tested.
    fn fill(&mut self, a: [f64; 3], b: [f64; 3], c: [f64; 3], color: [u8; 3]) {
        let edge = |p: [f64; 3], q: [f64; 3], x: f64, y: f64| {
            (q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0])
        };
        let area = edge(a, b, c[0], c[1]);
        if area.is_nan() || area.abs() <= 1e-12 {
            return;
        }
        let xs = [a[0], b[0], c[0]];
        let ys = [a[1], b[1], c[1]];
        let lo = |v: [f64; 3], n: usize| {
            v.iter()
                .copied()
                .fold(f64::INFINITY, f64::min)
                .floor()
                .clamp(0.0, n as f64) as usize
        };
        let hi = |v: [f64; 3], n: usize| {
            v.iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max)
                .ceil()
                .clamp(0.0, n as f64) as usize
        };
        let (x0, x1) = (lo(xs, self.width), hi(xs, self.width));
        let (y0, y1) = (lo(ys, self.height), hi(ys, self.height));
        let inv = 1.0 / area;
        for y in y0..y1 {
            let py = y as f64 + 0.5;
            for x in x0..x1 {
                let px = x as f64 + 0.5;
                let wa = edge(b, c, px, py) * inv;
                let wb = edge(c, a, px, py) * inv;
                let wc = edge(a, b, px, py) * inv;
                if wa >= 0.0 && wb >= 0.0 && wc >= 0.0 {
                    self.plot(x, y, wa * a[2] + wb * b[2] + wc * c[2], color);
                }
            }
        }
    }

    /// Draws a one-pixel line between two world points, depth-tested.
    pub(crate) fn line(&mut self, cam: &Camera, p: V3, q: V3, color: [u8; 3]) {
        let (mut a, mut b) = (cam.to_view(p), cam.to_view(q));
        // Clip to the near plane.
        if a[2] < cam.near && b[2] < cam.near {
            return;
        }
        if a[2] < cam.near || b[2] < cam.near {
            let s = (cam.near - a[2]) / (b[2] - a[2]);
            let cut = std::array::from_fn(|i| a[i] + s * (b[i] - a[i]));
            if a[2] < cam.near {
                a = cut;
            } else {
                b = cut;
            }
        }
        let (a, b) = (cam.project(a), cam.project(b));
        // Clip to the image (Liang-Barsky); 1/z is affine along the screen segment.
        let d = [b[0] - a[0], b[1] - a[1]];
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        let bounds = [
            (-d[0], a[0]),
            (d[0], self.width as f64 - a[0]),
            (-d[1], a[1]),
            (d[1], self.height as f64 - a[1]),
        ];
        for (p, q) in bounds {
            if p == 0.0 {
                if q < 0.0 {
                    return;
                }
            } else if p < 0.0 {
                t0 = t0.max(q / p);
            } else {
                t1 = t1.min(q / p);
            }
        }
        if t0 > t1 {
            return;
        }
        let at = |t: f64| std::array::from_fn::<f64, 3, _>(|i| a[i] + t * (b[i] - a[i]));
        let (a, b) = (at(t0), at(t1));
        let steps = (b[0] - a[0]).abs().max((b[1] - a[1]).abs()).ceil().max(1.0) as usize;
        for k in 0..=steps {
            let t = k as f64 / steps as f64;
            let (x, y) = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
            let (xi, yi) = (x.floor(), y.floor());
            if xi >= 0.0 && yi >= 0.0 && (xi as usize) < self.width && (yi as usize) < self.height {
                self.plot(xi as usize, yi as usize, a[2] + t * (b[2] - a[2]), color);
            }
        }
    }
}

/// The part of a polygon (view coordinates) in front of the near plane `z = near`.
fn clip_near(poly: &[V3], near: f64) -> Vec<V3> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for i in 0..poly.len() {
        let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
        let (pin, qin) = (p[2] >= near, q[2] >= near);
        if pin {
            out.push(p);
        }
        if pin != qin {
            let s = (near - p[2]) / (q[2] - p[2]);
            out.push(std::array::from_fn(|k| p[k] + s * (q[k] - p[k])));
        }
    }
    out
}

/// The direction towards the light: from above, to the left of and behind the camera.
pub(crate) fn headlight(cam: &Camera) -> V3 {
    let (right, up, forward) = cam.axes();
    let l: V3 = std::array::from_fn(|i| -0.4 * right[i] + 0.7 * up[i] - 0.6 * forward[i]);
    normalize(l).unwrap_or(up)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera::new([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], 90.0, (100, 100)).unwrap()
    }

    fn tri(z: f64, n: V3, color: [f64; 3]) -> Tri {
        Tri {
            v: [[-1.0, -1.0, z], [1.0, -1.0, z], [0.0, 1.0, z]],
            n,
            color,
        }
    }

    #[test]
    fn nearer_triangles_win_and_back_faces_are_dropped() {
        let cam = camera();
        let light = [0.0, 0.0, 1.0];
        let mut c = Canvas::new(100, 100, [0, 0, 0]);
        c.triangle(&cam, &tri(0.0, [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]), light);
        c.triangle(&cam, &tri(-1.0, [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]), light);
        let centre = 3 * (50 * 100 + 50);
        assert_eq!(c.rgb[centre..centre + 3], [255, 0, 0]);
        // A face turned away from the camera is not drawn.
        let mut c = Canvas::new(100, 100, [0, 0, 0]);
        c.triangle(&cam, &tri(0.0, [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]), light);
        assert!(c.rgb.iter().all(|&b| b == 0));
    }

    #[test]
    fn lines_behind_the_camera_are_clipped() {
        let cam = camera();
        let mut c = Canvas::new(100, 100, [0, 0, 0]);
        // From in front of the camera to behind it: drawn up to the near plane only.
        c.line(&cam, [0.0, -1.0, 0.0], [0.0, -1.0, 10.0], [9, 9, 9]);
        let lit = c.rgb.chunks(3).filter(|p| p[0] == 9).count();
        assert!(lit > 10);
        c.line(&cam, [0.0, 0.0, 6.0], [1.0, 0.0, 7.0], [7, 7, 7]);
        assert!(c.rgb.chunks(3).all(|p| p[0] != 7));
    }
}
