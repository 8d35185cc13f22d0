//! Triangle meshes of the shapes parts are drawn with: cylinders, cones, boxes, spheres
//! and helical tubes, in world coordinates, each triangle with its flat-shading normal.

use std::f64::consts::TAU;

use super::geom::{V3, add, axpy, basis, cross, dot, norm, normalize, scale, sub};

/// Segments around a cylinder, cone or sphere.
const SEGMENTS: usize = 20;
/// Sides of the tube a helix is drawn with.
const TUBE_SIDES: usize = 6;
/// Points per winding of a helix.
const HELIX_STEPS: usize = 24;

/// A triangle with its outward face normal and its colour (RGB in 0..1).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tri {
    /// Corners in world coordinates \[m\].
    pub v: [V3; 3],
    /// Outward unit normal of the face it belongs to.
    pub n: V3,
    /// Colour, RGB in 0..1.
    pub color: [f64; 3],
}

/// Collects the triangles of one frame.
#[derive(Default)]
pub(crate) struct Mesh {
    /// The triangles.
    pub tris: Vec<Tri>,
}

impl Mesh {
    /// A planar polygon (convex, corners in order) as a triangle fan. Its normal is
    /// computed from the corners and turned to point along `outward`.
    fn polygon(&mut self, corners: &[V3], outward: V3, color: [f64; 3]) {
        if corners.len() < 3 {
            return;
        }
        // Newell's normal: robust for any convex polygon, also nearly degenerate ones.
        let mut n = [0.0; 3];
        for (i, a) in corners.iter().enumerate() {
            let b = corners[(i + 1) % corners.len()];
            n = add(n, cross(*a, b));
        }
        let Some(mut n) = normalize(n) else { return };
        if dot(n, outward) < 0.0 {
            n = scale(n, -1.0);
        }
        for i in 1..corners.len() - 1 {
            self.tris.push(Tri {
                v: [corners[0], corners[i], corners[i + 1]],
                n,
                color,
            });
        }
    }

    /// A closed cylinder of radius `r` from `a` to `b` (nothing when `a == b` or `r <= 0`).
    pub(crate) fn cylinder(&mut self, a: V3, b: V3, r: f64, color: [f64; 3]) {
        self.frustum(a, b, r, r, color);
    }

    /// A closed cone with base radius `r` at `a` and its tip at `b`.
    pub(crate) fn cone(&mut self, a: V3, b: V3, r: f64, color: [f64; 3]) {
        self.frustum(a, b, r, 0.0, color);
    }

    /// A closed truncated cone from `a` (radius `ra`) to `b` (radius `rb`).
    fn frustum(&mut self, a: V3, b: V3, ra: f64, rb: f64, color: [f64; 3]) {
        let Some(e) = normalize(sub(b, a)) else {
            return;
        };
        if !(ra > 0.0 || rb > 0.0) || !(ra.is_finite() && rb.is_finite()) {
            return;
        }
        let (u, v) = basis(e, [0.0, 1.0, 0.0]);
        let radial = |k: usize| {
            let phi = TAU * k as f64 / SEGMENTS as f64;
            add(scale(u, phi.cos()), scale(v, phi.sin()))
        };
        let ring_a: Vec<V3> = (0..SEGMENTS).map(|k| axpy(a, ra, radial(k))).collect();
        let ring_b: Vec<V3> = (0..SEGMENTS).map(|k| axpy(b, rb, radial(k))).collect();
        for k in 0..SEGMENTS {
            let k1 = (k + 1) % SEGMENTS;
            let out = add(radial(k), radial(k1));
            if rb > 0.0 {
                self.polygon(&[ring_a[k], ring_a[k1], ring_b[k1], ring_b[k]], out, color);
            } else {
                self.polygon(&[ring_a[k], ring_a[k1], b], out, color);
            }
        }
        if ra > 0.0 {
            self.polygon(&ring_a, scale(e, -1.0), color);
        }
        if rb > 0.0 {
            self.polygon(&ring_b, e, color);
        }
    }

    /// A box from the centre of one end face `a` to the centre of the other `b`: `width`
    /// along `width_dir` (made normal to the axis), `height` normal to both.
    pub(crate) fn cuboid(
        &mut self,
        a: V3,
        b: V3,
        width_dir: V3,
        width: f64,
        height: f64,
        color: [f64; 3],
    ) {
        let Some(e) = normalize(sub(b, a)) else {
            return;
        };
        if !(width > 0.0 && height > 0.0) {
            return;
        }
        let (u, v) = basis(e, width_dir);
        let (hw, hh) = (width / 2.0, height / 2.0);
        let corner = |end: V3, su: f64, sv: f64| axpy(axpy(end, su * hw, u), sv * hh, v);
        let signs = [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)];
        let ca: Vec<V3> = signs.iter().map(|&(s, t)| corner(a, s, t)).collect();
        let cb: Vec<V3> = signs.iter().map(|&(s, t)| corner(b, s, t)).collect();
        for k in 0..4 {
            let k1 = (k + 1) % 4;
            let out = add(
                scale(u, signs[k].0 + signs[k1].0),
                scale(v, signs[k].1 + signs[k1].1),
            );
            self.polygon(&[ca[k], ca[k1], cb[k1], cb[k]], out, color);
        }
        self.polygon(&ca, scale(e, -1.0), color);
        self.polygon(&cb, e, color);
    }

    /// A sphere of radius `r` around `c`, faceted.
    pub(crate) fn sphere(&mut self, c: V3, r: f64, color: [f64; 3]) {
        if !(r > 0.0 && r.is_finite()) {
            return;
        }
        let (n_lon, n_lat) = (SEGMENTS, SEGMENTS / 2);
        let point = |i: usize, j: usize| {
            let theta = std::f64::consts::PI * j as f64 / n_lat as f64;
            let phi = TAU * i as f64 / n_lon as f64;
            let d = [
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ];
            axpy(c, r, d)
        };
        for j in 0..n_lat {
            for i in 0..n_lon {
                let i1 = (i + 1) % n_lon;
                let quad = [point(i, j), point(i1, j), point(i1, j + 1), point(i, j + 1)];
                let centroid = scale(quad.iter().fold([0.0; 3], |s, p| add(s, *p)), 0.25);
                let out = sub(centroid, c);
                if j == 0 {
                    self.polygon(&[quad[0], quad[2], quad[3]], out, color);
                } else if j == n_lat - 1 {
                    self.polygon(&[quad[0], quad[1], quad[2]], out, color);
                } else {
                    self.polygon(&quad, out, color);
                }
            }
        }
    }

    /// A helix of coil radius `r` with `windings` turns from `a` to `b`, drawn as a tube
    /// of radius `wire`.
    pub(crate) fn helix(
        &mut self,
        a: V3,
        b: V3,
        r: f64,
        windings: f64,
        wire: f64,
        color: [f64; 3],
    ) {
        let axis = sub(b, a);
        let Some(e) = normalize(axis) else { return };
        if !(r > 0.0 && wire > 0.0 && windings > 0.0 && windings.is_finite()) {
            return;
        }
        let (u, v) = basis(e, [0.0, 1.0, 0.0]);
        let steps = ((windings * HELIX_STEPS as f64).ceil() as usize).clamp(2, 10_000);
        // Rings of the tube: around each point of the helix, in the plane spanned by the
        // radial direction and the normal of the radial direction and the tangent.
        let rings: Vec<(V3, Vec<V3>)> = (0..=steps)
            .map(|k| {
                let s = k as f64 / steps as f64;
                let phi = TAU * windings * s;
                let radial = add(scale(u, phi.cos()), scale(v, phi.sin()));
                let centre = axpy(axpy(a, s, axis), r, radial);
                let tangent = add(
                    axis,
                    scale(
                        add(scale(u, -phi.sin()), scale(v, phi.cos())),
                        TAU * windings * r,
                    ),
                );
                let side = normalize(cross(tangent, radial)).unwrap_or(e);
                let ring = (0..TUBE_SIDES)
                    .map(|i| {
                        let psi = TAU * i as f64 / TUBE_SIDES as f64;
                        axpy(
                            axpy(centre, wire * psi.cos(), radial),
                            wire * psi.sin(),
                            side,
                        )
                    })
                    .collect();
                (centre, ring)
            })
            .collect();
        for w in rings.windows(2) {
            let ((c0, r0), (c1, r1)) = (&w[0], &w[1]);
            let mid = scale(add(*c0, *c1), 0.5);
            for i in 0..TUBE_SIDES {
                let i1 = (i + 1) % TUBE_SIDES;
                let quad = [r0[i], r0[i1], r1[i1], r1[i]];
                let centroid = scale(quad.iter().fold([0.0; 3], |s, p| add(s, *p)), 0.25);
                self.polygon(&quad, sub(centroid, mid), color);
            }
        }
    }

    /// An arrow from `a` to `b`: a shaft of radius `r` and a head three times as wide.
    pub(crate) fn arrow(&mut self, a: V3, b: V3, r: f64, color: [f64; 3]) {
        let l = norm(sub(b, a));
        let Some(e) = normalize(sub(b, a)) else {
            return;
        };
        let head = (5.0 * 2.0 * r).min(l / 2.0);
        let neck = axpy(b, -head, e);
        self.cylinder(a, neck, r, color);
        self.cone(neck, b, 3.0 * r, color);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every face of a closed convex mesh has its normal pointing away from the centre.
    fn normals_point_out(mesh: &Mesh, centre: V3) -> bool {
        mesh.tris.iter().all(|t| {
            let c = scale(add(add(t.v[0], t.v[1]), t.v[2]), 1.0 / 3.0);
            dot(t.n, sub(c, centre)) > 0.0
        })
    }

    #[test]
    fn convex_shapes_have_outward_normals() {
        let mut m = Mesh::default();
        m.cylinder([0.0, 0.0, 0.0], [1.0, 1.0, 0.0], 0.1, [1.0; 3]);
        assert_eq!(m.tris.len(), 2 * SEGMENTS + 2 * (SEGMENTS - 2));
        assert!(normals_point_out(&m, [0.5, 0.5, 0.0]));
        let mut m = Mesh::default();
        m.cuboid(
            [0.0; 3],
            [0.0, 0.0, 2.0],
            [1.0, 0.0, 0.0],
            0.2,
            0.1,
            [1.0; 3],
        );
        assert_eq!(m.tris.len(), 12);
        assert!(normals_point_out(&m, [0.0, 0.0, 1.0]));
        let mut m = Mesh::default();
        m.sphere([1.0, 2.0, 3.0], 0.5, [1.0; 3]);
        assert!(normals_point_out(&m, [1.0, 2.0, 3.0]));
        let mut m = Mesh::default();
        m.cone([0.0; 3], [0.0, 1.0, 0.0], 0.3, [1.0; 3]);
        assert!(normals_point_out(&m, [0.0, 0.25, 0.0]));
    }

    #[test]
    fn degenerate_shapes_draw_nothing() {
        let mut m = Mesh::default();
        m.cylinder([1.0; 3], [1.0; 3], 0.1, [1.0; 3]);
        m.cylinder([0.0; 3], [1.0; 3], 0.0, [1.0; 3]);
        m.sphere([0.0; 3], 0.0, [1.0; 3]);
        m.helix([0.0; 3], [0.0; 3], 0.1, 5.0, 0.01, [1.0; 3]);
        assert!(m.tris.is_empty());
    }

    #[test]
    fn helix_stays_on_its_coil() {
        let mut m = Mesh::default();
        let (r, wire) = (0.1, 0.01);
        m.helix([0.0; 3], [0.0, 0.0, 1.0], r, 5.0, wire, [1.0; 3]);
        for t in &m.tris {
            for p in t.v {
                let d = (p[0] * p[0] + p[1] * p[1]).sqrt();
                assert!((d - r).abs() <= wire * 1.01, "{p:?}");
                assert!(p[2] >= -wire && p[2] <= 1.0 + wire);
            }
        }
    }
}
