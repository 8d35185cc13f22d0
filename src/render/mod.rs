//! 3-D animation of mechanisms: a solution rendered to an animated GIF, or one frame of
//! it to PNG, with no second simulation (every frame position and orientation is a
//! variable of the solution).
//!
//! Parts are found in the model tree by their type and drawn by their shape, sized by
//! their structural parameters (a `radius` of 0 hides a part) and coloured by their
//! `color` parameter (RGB in 0..1; by default MSL's colours [`BODY_COLOR`],
//! [`ROD_COLOR`], [`JOINT_COLOR`] and [`SPRING_COLOR`]):
//!
//! | component | drawn as |
//! |---|---|
//! | `BodyShape`, `FixedTranslation` | a cylinder of `radius` from `frame_a` to `frame_b` |
//! | `BodyCylinder` | a cylinder of `diameter` from `frame_a` to `frame_b` |
//! | `BodyBox` | a box of `width` (along `width_direction`) and `height` from `frame_a` to `frame_b` |
//! | `Body` | a sphere of `radius` at the centre of mass (the default `r_CM`), a rod a third as thick to it |
//! | `Revolute`, `RevolutePlanarLoopConstraint` | a cylinder of `radius` and `length` along the axis, centred on `frame_a` |
//! | `Prismatic` | a square box of `width` along the axis from `frame_a` to `frame_b` |
//! | `Spherical` | a sphere of `radius` |
//! | `Spring`, `SpringDamperParallel` | a helix of 5 windings and coil `radius` between the frames |
//! | `World` | its x, y and z axes as red, green and blue arrows ([`RenderOptions::world_axes`]) |
//!
//! Composite joints (universal, cylindrical, planar) are drawn as the joints they are
//! made of. Faces are flat-shaded by their normals, back faces dropped and hidden
//! surfaces removed with a depth buffer; a grid is drawn on the ground (normal to
//! [`RenderOptions::up`], below the lowest frame) and the time in the top left corner.
//!
//! ```no_run
//! # use multibody::prelude::*;
//! # fn main() -> Result<(), multibody::Error> {
//! # let model = System::new("m");
//! # let sol: Solution = todo!();
//! use multibody::render::{RenderOptions, render};
//! let options = RenderOptions {
//!     camera: [4.0, -1.0, 4.0],
//!     look_at: [0.0, -1.0, 0.0],
//!     times: Some((0..=200).map(|k| 0.05 * k as f64).collect()),
//!     ..RenderOptions::default()
//! };
//! render(&model, &sol, "fourbar.gif", &options)?;
//! # Ok(())
//! # }
//! ```

mod camera;
mod error;
mod frame;
mod geom;
mod mesh;
mod part;
mod raster;
mod scene;

use std::path::Path;

use plotters::prelude::*;

use crate::{Solution, System};
use multibody_core::solve::SolutionError;

use camera::Camera;
pub use error::RenderError;
use frame::{Ground, Painter};
pub use part::{BODY_COLOR, JOINT_COLOR, ROD_COLOR, SPRING_COLOR};
use scene::Scene;

/// How to render: image size, camera, frame times, ground grid. Angles in degrees,
/// lengths in metres, points in world coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// Image width in pixels (default 600; at most 65535, and `width * height` at most
    /// 2^26).
    pub width: u32,
    /// Image height in pixels (default 600; at most 65535).
    pub height: u32,
    /// Position of the camera (default `[2.0, 1.5, 4.0]`).
    pub camera: [f64; 3],
    /// The point the camera looks at, in the middle of the image (default the origin).
    pub look_at: [f64; 3],
    /// The direction that is up in the image, and the normal of the ground grid
    /// (default `[0.0, 1.0, 0.0]`, against MSL's default gravity).
    pub up: [f64; 3],
    /// Vertical field of view in degrees (default 40).
    pub fov: f64,
    /// Times of the frames of an animation (default `None`: 100 frames evenly spaced
    /// from the first to the last time of the solution, both included).
    pub times: Option<Vec<f64>>,
    /// Time each frame of an animation is shown, in milliseconds (default 50; GIF
    /// stores it in hundredths of a second).
    pub frame_delay_ms: u32,
    /// Background colour, RGB (default white `[255, 255, 255]`).
    pub background: [u8; 3],
    /// Draw a grid on the ground (default `true`).
    pub grid: bool,
    /// Distance between grid lines (default `None`: 1, 2 or 5 times a power of ten,
    /// about an eighth of the size of the mechanism's motion).
    pub grid_spacing: Option<f64>,
    /// Height of the grid along `up` (default `None`: below the lowest frame origin over
    /// the whole solution, by a tenth of the size of the motion).
    pub grid_level: Option<f64>,
    /// Colour of the grid lines, RGB (default `[200, 200, 200]`).
    pub grid_color: [u8; 3],
    /// Length of the world's axes, drawn as arrows at the origin (default 0.5, MSL's
    /// axis length; 0 hides them).
    pub world_axes: f64,
    /// Write the time (`t = 1.25 s`) in the top left corner (default `true`).
    pub time_label: bool,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 600,
            height: 600,
            camera: [2.0, 1.5, 4.0],
            look_at: [0.0; 3],
            up: [0.0, 1.0, 0.0],
            fov: 40.0,
            times: None,
            frame_delay_ms: 50,
            background: [255; 3],
            grid: true,
            grid_spacing: None,
            grid_level: None,
            grid_color: [200; 3],
            world_axes: 0.5,
            time_label: true,
        }
    }
}

/// An RGB image, row by row from the top left corner, 3 bytes per pixel.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The pixels, `3 * width * height` bytes.
    pub rgb: Vec<u8>,
}

impl Image {
    /// The colour of the pixel in column `x` and row `y` (`None` outside the image).
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        (x < self.width && y < self.height).then(|| {
            let i = 3 * (y as usize * self.width as usize + x as usize);
            [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
        })
    }
}

/// The most pixels an image may have (a 8192 x 8192 square).
const MAX_PIXELS: u64 = 1 << 26;

/// Everything a frame needs: the parts, their variables at the frame times, the painter.
struct Renderer {
    scene: Scene,
    /// `table[variable][frame]`.
    table: Vec<Vec<f64>>,
    times: Vec<f64>,
    painter: Painter,
}

impl Renderer {
    fn new(
        model: &System,
        sol: &Solution,
        times: &[f64],
        options: &RenderOptions,
    ) -> Result<Renderer, RenderError> {
        let (width, height) = (options.width, options.height);
        if width == 0
            || height == 0
            || width > 65535
            || height > 65535
            || u64::from(width) * u64::from(height) > MAX_PIXELS
        {
            return Err(RenderError::ImageSize { width, height });
        }
        if times.is_empty() {
            return Err(RenderError::NoFrames);
        }
        let (t0, t1) = match sol.t() {
            [] => return Err(RenderError::NoFrames),
            t => (t[0], t[t.len() - 1]),
        };
        if let Some(&t) = times.iter().find(|&&t| !(t >= t0 && t <= t1)) {
            return Err(RenderError::TimeOutOfRange { t, t0, t1 });
        }
        let camera = Camera::new(
            options.camera,
            options.look_at,
            options.up,
            options.fov,
            (width, height),
        )
        .map_err(RenderError::Camera)?;
        let scene = Scene::new(model, options.world_axes);
        let missing = |e: SolutionError| match e {
            SolutionError::UnknownVariable { ref name, .. } => {
                let i = scene.names.iter().position(|n| n == name);
                RenderError::MissingVariable {
                    component: i.map(|i| scene.owners[i].clone()).unwrap_or_default(),
                    source: e,
                }
            }
            SolutionError::OutOfRange { t, t0, t1 } => RenderError::TimeOutOfRange { t, t0, t1 },
            e => RenderError::MissingVariable {
                component: String::new(),
                source: e,
            },
        };
        let names: Vec<&str> = scene.names.iter().map(String::as_str).collect();
        let table = sol.sample(&names, times).map_err(missing)?;
        // The grid is sized by the whole solution, so that every frame has the same.
        let reported = sol.get_many(&names).map_err(missing)?;
        let points: Vec<[f64; 3]> = (0..sol.t().len())
            .flat_map(|k| scene.points(&|i| reported[i][k]))
            .collect();
        let ground = Ground::new(&points, options);
        Ok(Renderer {
            scene,
            table,
            times: times.to_vec(),
            painter: Painter::new(camera, ground, height),
        })
    }

    /// The pixels of frame `k`.
    fn frame(&mut self, k: usize, options: &RenderOptions) -> Vec<u8> {
        let label = options
            .time_label
            .then(|| format!("t = {:.2} s", self.times[k]));
        let table = &self.table;
        let value = |i: usize| table[i][k];
        self.painter
            .paint(&self.scene, &value, options, label.as_deref())
            .rgb
    }
}

fn write_error(path: &Path) -> impl Fn(String) -> RenderError + '_ {
    move |message| RenderError::Write {
        path: path.display().to_string(),
        message,
    }
}

/// Renders the solution of `model` at [`RenderOptions::times`] to an animated GIF at
/// `path` (looping forever).
pub fn render(
    model: &(impl AsRef<System> + ?Sized),
    solution: &Solution,
    path: impl AsRef<Path>,
    options: &RenderOptions,
) -> Result<(), RenderError> {
    let path = path.as_ref();
    let times = match &options.times {
        Some(t) => t.clone(),
        None => match solution.t() {
            [] => Vec::new(),
            t => {
                let (t0, t1) = (t[0], t[t.len() - 1]);
                (0..100).map(|k| t0 + (t1 - t0) * k as f64 / 99.0).collect()
            }
        },
    };
    let mut renderer = Renderer::new(model.as_ref(), solution, &times, options)?;
    let err = write_error(path);
    let size = (options.width, options.height);
    let mut backend =
        BitMapBackend::gif(path, size, options.frame_delay_ms).map_err(|e| err(e.to_string()))?;
    for k in 0..times.len() {
        let rgb = renderer.frame(k, options);
        backend
            .blit_bitmap((0, 0), size, &rgb)
            .map_err(|e| err(e.to_string()))?;
        backend.present().map_err(|e| err(e.to_string()))?;
    }
    Ok(())
}

/// Renders the solution of `model` at time `t` to an image in memory.
pub fn render_image(
    model: &(impl AsRef<System> + ?Sized),
    solution: &Solution,
    t: f64,
    options: &RenderOptions,
) -> Result<Image, RenderError> {
    let mut renderer = Renderer::new(model.as_ref(), solution, &[t], options)?;
    Ok(Image {
        width: options.width,
        height: options.height,
        rgb: renderer.frame(0, options),
    })
}

/// Renders the solution of `model` at time `t` to a PNG image at `path`.
pub fn render_frame(
    model: &(impl AsRef<System> + ?Sized),
    solution: &Solution,
    t: f64,
    path: impl AsRef<Path>,
    options: &RenderOptions,
) -> Result<(), RenderError> {
    let path = path.as_ref();
    let image = render_image(model, solution, t, options)?;
    let err = write_error(path);
    let size = (image.width, image.height);
    let mut backend = BitMapBackend::new(path, size);
    backend
        .blit_bitmap((0, 0), size, &image.rgb)
        .map_err(|e| err(e.to_string()))?;
    backend.present().map_err(|e| err(e.to_string()))
}
