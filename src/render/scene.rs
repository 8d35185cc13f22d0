//! The parts of a model that are drawn: found by walking the `System` tree by type
//! name, sized by their structural parameters, placed by the frame variables of the
//! solution.

use std::collections::HashMap;

use crate::System;
use crate::parts::{BeamBoundary, CrossSection, mode_shapes};

use super::geom::{V3, norm};
use super::mesh::Mesh;
use super::part::{BODY_COLOR, Geometry, JOINT_COLOR, Part, Pos, ROD_COLOR, Rot, SPRING_COLOR};

/// The drawable parts of a model and the solution variables they need.
pub(crate) struct Scene {
    parts: Vec<Part>,
    /// Names of the variables read from the solution (`b1.frame_a.r_0[1]`, ...).
    pub names: Vec<String>,
    /// For each name, the component that needs it (for error messages).
    pub owners: Vec<String>,
    index: HashMap<String, usize>,
}

/// A structural parameter of `sys` as numbers, if recorded with `len` entries.
fn param<const N: usize>(sys: &System, name: &str) -> Option<[f64; N]> {
    sys.structural_value(name)
        .and_then(|v| <[f64; N]>::try_from(v).ok())
}

fn scalar(sys: &System, name: &str) -> Option<f64> {
    param::<1>(sys, name).map(|v| v[0])
}

/// The length of a box or cylinder: `length`, by default `|r - r_shape|`.
fn shape_length(sys: &System) -> f64 {
    scalar(sys, "length").unwrap_or_else(|| {
        let r = param::<3>(sys, "r").unwrap_or([0.0; 3]);
        let r_shape = param::<3>(sys, "r_shape").unwrap_or([0.0; 3]);
        norm(std::array::from_fn(|i| r[i] - r_shape[i]))
    })
}

/// Intervals along a flexible beam at which its bent shape is drawn.
const BEAM_STATIONS: usize = 24;

/// `path.local`, or `local` at the root.
fn join(path: &str, local: &str) -> String {
    if path.is_empty() {
        local.to_string()
    } else {
        format!("{path}.{local}")
    }
}

impl Scene {
    /// The parts of `model`; the world's axes `axes_length` long (0 hides them).
    pub(crate) fn new(model: &System, axes_length: f64) -> Scene {
        let mut scene = Scene {
            parts: Vec::new(),
            names: Vec::new(),
            owners: Vec::new(),
            index: HashMap::new(),
        };
        if !scene.collect(model, axes_length) {
            scene.walk(model, axes_length);
        }
        scene
    }

    fn walk(&mut self, sys: &System, axes_length: f64) {
        for sub in sys.subsystems.iter().filter(|s| !s.is_connector()) {
            if !self.collect(sub, axes_length) {
                self.walk(sub, axes_length);
            }
        }
    }

    fn signal(&mut self, owner: &str, name: String) -> usize {
        if let Some(&i) = self.index.get(&name) {
            return i;
        }
        self.index.insert(name.clone(), self.names.len());
        self.names.push(name);
        self.owners.push(owner.to_string());
        self.names.len() - 1
    }

    fn pos(&mut self, sys: &System, frame: &str) -> Pos {
        std::array::from_fn(|i| {
            self.signal(
                &sys.path,
                join(&sys.path, &format!("{frame}.r_0[{}]", i + 1)),
            )
        })
    }

    fn rot(&mut self, sys: &System, frame: &str) -> Rot {
        std::array::from_fn(|k| {
            let name = format!("{frame}.R.T[{},{}]", k / 3 + 1, k % 3 + 1);
            self.signal(&sys.path, join(&sys.path, &name))
        })
    }

    /// A flexible beam's geometry: its modes from its structural parameters, their
    /// coordinates from the solution; `None` when a parameter is not recorded.
    fn beam(&mut self, sys: &System) -> Option<Geometry> {
        let count = |name| scalar(sys, name).map(|n| n as usize);
        let counts = [
            count("n_lengthening")?,
            count("n_bending_xy")?,
            count("n_bending_xz")?,
            count("n_torsion")?,
        ];
        let boundary = BeamBoundary::from_numbers(sys.structural_value("boundary")?)?;
        let section = CrossSection::from_numbers(sys.structural_value("cross_section")?)?;
        let l = scalar(sys, "l")?;
        let modes = mode_shapes(l, boundary, counts);
        let evals: Vec<_> = modes.iter().map(|(shape, _)| shape.evaluator()).collect();
        let stations = (0..=BEAM_STATIONS)
            .map(|k| {
                let x = l * k as f64 / BEAM_STATIONS as f64;
                let d = modes
                    .iter()
                    .zip(&evals)
                    .map(|((_, dir), eval)| dir.map(|c| c * eval(x)[0]))
                    .collect();
                (x, d)
            })
            .collect();
        let q = (1..=modes.len())
            .map(|i| self.signal(&sys.path, join(&sys.path, &format!("q.x[{i}]"))))
            .collect();
        let (width, height) = section.extents();
        Some(Geometry::Beam {
            a: self.pos(sys, "frame_a"),
            rot: self.rot(sys, "frame_a"),
            stations,
            q,
            width,
            height,
        })
    }

    /// Adds the part `sys` is drawn as; `false` when its type is not drawn itself (its
    /// sub-components may be).
    fn collect(&mut self, sys: &System, axes_length: f64) -> bool {
        let kind = match sys.type_name.as_str() {
            "FlexibleBodies.Beam" => "FlexibleBodies.Beam",
            name => name.strip_prefix("MultiBody.").unwrap_or(""),
        };
        let color = |default| param::<3>(sys, "color").unwrap_or(default);
        let radius = |default| scalar(sys, "radius").unwrap_or(default);
        let geometry = match kind {
            "Parts.BodyShape" | "Parts.FixedTranslation" => {
                let (color, radius) = match kind {
                    "Parts.BodyShape" => (color(BODY_COLOR), radius(0.02)),
                    _ => (color(ROD_COLOR), radius(0.02)),
                };
                let (a, b) = (self.pos(sys, "frame_a"), self.pos(sys, "frame_b"));
                (radius > 0.0).then_some((Geometry::Rod { a, b, radius }, color))
            }
            "Parts.BodyCylinder" => {
                let d = scalar(sys, "diameter").unwrap_or(shape_length(sys) / 20.0);
                let (a, b) = (self.pos(sys, "frame_a"), self.pos(sys, "frame_b"));
                Some((
                    Geometry::Rod {
                        a,
                        b,
                        radius: d / 2.0,
                    },
                    color(BODY_COLOR),
                ))
            }
            "Parts.BodyBox" => {
                let width = scalar(sys, "width").unwrap_or(shape_length(sys) / 20.0);
                let height = scalar(sys, "height").unwrap_or(width);
                let width_dir = param::<3>(sys, "width_direction").unwrap_or([0.0, 1.0, 0.0]);
                let (a, b) = (self.pos(sys, "frame_a"), self.pos(sys, "frame_b"));
                let rot = self.rot(sys, "frame_a");
                let g = Geometry::Cuboid {
                    a,
                    b,
                    rot,
                    width_dir,
                    width,
                    height,
                };
                Some((g, color(BODY_COLOR)))
            }
            "Parts.Body" => {
                let radius = radius(0.05);
                let r_cm = std::array::from_fn(|i| {
                    let name = join(&sys.path, &format!("r_CM[{}]", i + 1));
                    sys.parameters
                        .iter()
                        .find(|p| *p.name == *name)
                        .and_then(|p| p.value.and_then(|v| v.as_f64()))
                        .unwrap_or(0.0)
                });
                (radius > 0.0).then(|| {
                    let (a, rot) = (self.pos(sys, "frame_a"), self.rot(sys, "frame_a"));
                    (
                        Geometry::Mass {
                            a,
                            rot,
                            r_cm,
                            radius,
                        },
                        color(BODY_COLOR),
                    )
                })
            }
            "Joints.Revolute" | "Joints.RevolutePlanarLoopConstraint" => {
                let radius = radius(0.05);
                let length = scalar(sys, "length").unwrap_or(0.1);
                let n = param::<3>(sys, "n").unwrap_or([0.0, 0.0, 1.0]);
                (radius > 0.0 && length > 0.0).then(|| {
                    let (a, rot) = (self.pos(sys, "frame_a"), self.rot(sys, "frame_a"));
                    (
                        Geometry::Hinge {
                            a,
                            rot,
                            n,
                            length,
                            radius,
                        },
                        color(JOINT_COLOR),
                    )
                })
            }
            "Joints.Prismatic" => {
                let width = scalar(sys, "width").unwrap_or(0.05);
                let n = param::<3>(sys, "n").unwrap_or([1.0, 0.0, 0.0]);
                (width > 0.0).then(|| {
                    let (a, b) = (self.pos(sys, "frame_a"), self.pos(sys, "frame_b"));
                    let rot = self.rot(sys, "frame_a");
                    (
                        Geometry::Slider {
                            a,
                            b,
                            rot,
                            n,
                            width,
                        },
                        color(JOINT_COLOR),
                    )
                })
            }
            "Joints.UniversalSpherical" | "Joints.SphericalSpherical" => {
                let rod = scalar(sys, "rod_diameter").unwrap_or(0.05) / 2.0;
                let ball = scalar(sys, "sphere_diameter").unwrap_or(0.1) / 2.0;
                let (a, b) = (self.pos(sys, "frame_a"), self.pos(sys, "frame_b"));
                if ball > 0.0 {
                    for at in [a, b] {
                        self.parts.push(Part {
                            geometry: Geometry::Ball {
                                a: at,
                                radius: ball,
                            },
                            color: JOINT_COLOR,
                        });
                    }
                }
                (rod > 0.0).then_some((Geometry::Rod { a, b, radius: rod }, ROD_COLOR))
            }
            "Joints.Spherical" => {
                let radius = radius(0.05);
                (radius > 0.0).then(|| {
                    let a = self.pos(sys, "frame_a");
                    (Geometry::Ball { a, radius }, color(JOINT_COLOR))
                })
            }
            "Forces.Spring" | "Forces.SpringDamperParallel" => {
                let radius = radius(0.05);
                (radius > 0.0).then(|| {
                    let (a, b) = (self.pos(sys, "frame_a"), self.pos(sys, "frame_b"));
                    (Geometry::Coil { a, b, radius }, color(SPRING_COLOR))
                })
            }
            "FlexibleBodies.Beam" => self.beam(sys).map(|g| (g, color(BODY_COLOR))),
            "World" => (axes_length > 0.0).then_some((
                Geometry::Axes {
                    length: axes_length,
                },
                [0.0; 3],
            )),
            _ => return false,
        };
        if let Some((geometry, color)) = geometry {
            self.parts.push(Part { geometry, color });
        }
        true
    }

    /// The points the parts are placed at (frame origins, centres of mass, the world's
    /// origin) at one time; `value(i)` is the `i`-th of [`Scene::names`] at that time.
    pub(crate) fn points(&self, value: &dyn Fn(usize) -> f64) -> Vec<V3> {
        let mut points = Vec::with_capacity(2 * self.parts.len());
        for part in &self.parts {
            part.points(value, &mut points);
        }
        points
    }

    /// The triangles of every part at one time; `value(i)` is the `i`-th of
    /// [`Scene::names`] at that time.
    pub(crate) fn mesh(&self, value: &dyn Fn(usize) -> f64, mesh: &mut Mesh) {
        for part in &self.parts {
            part.draw(value, mesh);
        }
    }
}
