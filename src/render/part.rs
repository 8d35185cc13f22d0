//! How each kind of part is drawn: its shape, placed by the solution's frame variables
//! at one time.

use super::geom::{Rotation, V3, add, axpy, dot, normalize, scale, sub};
use super::mesh::Mesh;

/// MSL's body colour {0, 128, 255}.
pub const BODY_COLOR: [f64; 3] = [0.0, 128.0 / 255.0, 1.0];
/// MSL's rod colour {155, 155, 155} (fixed translations).
pub const ROD_COLOR: [f64; 3] = [155.0 / 255.0; 3];
/// MSL's joint colour {255, 0, 0}.
pub const JOINT_COLOR: [f64; 3] = [1.0, 0.0, 0.0];
/// A spring's colour (MSL's spring colour is {0, 0, 255}).
pub const SPRING_COLOR: [f64; 3] = [0.0, 0.0, 1.0];
/// Windings of a spring (MSL `numberOfWindings`).
const WINDINGS: f64 = 5.0;

/// Indices of the world position `r_0` of a frame in the signal table.
pub(crate) type Pos = [usize; 3];
/// Indices of the orientation `R.T` of a frame (row by row) in the signal table.
pub(crate) type Rot = [usize; 9];

/// How a part is drawn.
#[derive(Clone, Debug)]
pub(crate) enum Geometry {
    /// A cylinder between two frame origins (BodyShape, FixedTranslation, BodyCylinder).
    Rod { a: Pos, b: Pos, radius: f64 },
    /// A box between two frame origins; `width_dir` is resolved in frame `a` (BodyBox).
    Cuboid {
        a: Pos,
        b: Pos,
        rot: Rot,
        width_dir: V3,
        width: f64,
        height: f64,
    },
    /// A sphere at the centre of mass `r_cm` (resolved in the frame) and a rod to it
    /// a third as thick (Body).
    Mass {
        a: Pos,
        rot: Rot,
        r_cm: V3,
        radius: f64,
    },
    /// A cylinder centred on a frame along its axis `n` (Revolute).
    Hinge {
        a: Pos,
        rot: Rot,
        n: V3,
        length: f64,
        radius: f64,
    },
    /// A square box along the axis `n` from `frame_a` to `frame_b` (Prismatic).
    Slider {
        a: Pos,
        b: Pos,
        rot: Rot,
        n: V3,
        width: f64,
    },
    /// A sphere at a frame (Spherical).
    Ball { a: Pos, radius: f64 },
    /// A helix between two frame origins (springs).
    Coil { a: Pos, b: Pos, radius: f64 },
    /// The world's axes at the origin: x red, y green, z blue.
    Axes { length: f64 },
    /// A flexible beam along x of its frame `a`, bent by its modes: at each station
    /// along it, its `x` and per mode the displacement per unit of the modal
    /// coordinate at `q` (resolved in the frame); drawn as boxes `width` (along y) by
    /// `height` between the stations.
    Beam {
        a: Pos,
        rot: Rot,
        stations: Vec<(f64, Vec<V3>)>,
        q: Vec<usize>,
        width: f64,
        height: f64,
    },
}

/// The stations of a bent beam at one time, in the world.
fn beam_points(
    a: V3,
    rot: Rotation,
    stations: &[(f64, Vec<V3>)],
    q: &[usize],
    value: &dyn Fn(usize) -> f64,
) -> Vec<V3> {
    let q: Vec<f64> = q.iter().map(|&i| value(i)).collect();
    stations
        .iter()
        .map(|(x, modes)| {
            let local = modes
                .iter()
                .zip(&q)
                .fold([*x, 0.0, 0.0], |p, (d, &qi)| axpy(p, qi, *d));
            add(a, rot.resolve1(local))
        })
        .collect()
}

/// A part to draw.
#[derive(Clone, Debug)]
pub(crate) struct Part {
    pub geometry: Geometry,
    pub color: [f64; 3],
}

/// The orientation with the `R.T` entries at `r`.
fn rotation(r: &Rot, value: &dyn Fn(usize) -> f64) -> Rotation {
    Rotation(std::array::from_fn(|i| {
        std::array::from_fn(|j| value(r[3 * i + j]))
    }))
}

impl Part {
    /// The points the part is placed at (frame origins, its centre of mass, the world's
    /// origin) at one time; `value(i)` is the `i`-th variable of the scene then.
    pub(crate) fn points(&self, value: &dyn Fn(usize) -> f64, out: &mut Vec<V3>) {
        let pos = |p: &Pos| p.map(value);
        match &self.geometry {
            Geometry::Rod { a, b, .. }
            | Geometry::Cuboid { a, b, .. }
            | Geometry::Slider { a, b, .. }
            | Geometry::Coil { a, b, .. } => out.extend([pos(a), pos(b)]),
            Geometry::Mass { a, rot, r_cm, .. } => {
                let a = pos(a);
                out.extend([a, add(a, rotation(rot, value).resolve1(*r_cm))]);
            }
            Geometry::Hinge { a, .. } | Geometry::Ball { a, .. } => out.push(pos(a)),
            Geometry::Axes { .. } => out.push([0.0; 3]),
            Geometry::Beam {
                a,
                rot,
                stations,
                q,
                ..
            } => out.extend(beam_points(
                pos(a),
                rotation(rot, value),
                stations,
                q,
                value,
            )),
        }
    }

    /// Adds the part's triangles at one time; `value(i)` is the `i`-th variable of the
    /// scene then.
    pub(crate) fn draw(&self, value: &dyn Fn(usize) -> f64, mesh: &mut Mesh) {
        let pos = |p: &Pos| p.map(value);
        let rot = |r: &Rot| rotation(r, value);
        let c = self.color;
        match &self.geometry {
            Geometry::Rod { a, b, radius } => mesh.cylinder(pos(a), pos(b), *radius, c),
            Geometry::Cuboid {
                a,
                b,
                rot: r,
                width_dir,
                width,
                height,
            } => {
                let w = rot(r).resolve1(*width_dir);
                mesh.cuboid(pos(a), pos(b), w, *width, *height, c);
            }
            Geometry::Mass {
                a,
                rot: r,
                r_cm,
                radius,
            } => {
                let a = pos(a);
                let cm = add(a, rot(r).resolve1(*r_cm));
                mesh.cylinder(a, cm, radius / 3.0, c);
                mesh.sphere(cm, *radius, c);
            }
            Geometry::Hinge {
                a,
                rot: r,
                n,
                length,
                radius,
            } => {
                if let Some(e) = normalize(rot(r).resolve1(*n)) {
                    let a = pos(a);
                    let half = scale(e, length / 2.0);
                    mesh.cylinder(sub(a, half), add(a, half), *radius, c);
                }
            }
            Geometry::Slider {
                a,
                b,
                rot: r,
                n,
                width,
            } => {
                let r = rot(r);
                let (a, b) = (pos(a), pos(b));
                if let Some(e) = normalize(r.resolve1(*n)) {
                    // At least a fifth of the width long, so that it shows at s = 0.
                    let s = dot(sub(b, a), e);
                    let l = if s < 0.0 {
                        -(-s).max(width / 5.0)
                    } else {
                        s.max(width / 5.0)
                    };
                    let w = r.resolve1([0.0, 1.0, 0.0]);
                    mesh.cuboid(a, axpy(a, l, e), w, *width, *width, c);
                }
            }
            Geometry::Ball { a, radius } => mesh.sphere(pos(a), *radius, c),
            Geometry::Coil { a, b, radius } => {
                mesh.helix(pos(a), pos(b), *radius, WINDINGS, radius / 8.0, c);
            }
            Geometry::Beam {
                a,
                rot: r,
                stations,
                q,
                width,
                height,
            } => {
                let r = rot(r);
                let points = beam_points(pos(a), r, stations, q, value);
                let w = r.resolve1([0.0, 1.0, 0.0]);
                for pair in points.windows(2) {
                    mesh.cuboid(pair[0], pair[1], w, *width, *height, c);
                }
            }
            Geometry::Axes { length } => {
                let colors = [[0.9, 0.1, 0.1], [0.1, 0.7, 0.1], [0.1, 0.2, 0.9]];
                for (i, color) in colors.into_iter().enumerate() {
                    let mut tip = [0.0; 3];
                    tip[i] = *length;
                    mesh.arrow([0.0; 3], tip, length / 50.0, color);
                }
            }
        }
    }
}
