//! One frame: the ground grid, the parts at the frame's time, and the time label.

use std::collections::HashMap;

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos as TextPos, VPos};

use super::RenderOptions;
use super::camera::Camera;
use super::geom::{V3, axpy, basis, dot, normalize};
use super::mesh::Mesh;
use super::raster::{Canvas, headlight};
use super::scene::Scene;

/// Lines of the ground grid along each direction, at most.
const MAX_GRID_LINES: f64 = 200.0;
/// Colour of the time label.
const LABEL_COLOR: [u8; 3] = [30, 30, 30];

/// The ground grid: lines in the plane normal to the up vector, below the mechanism.
pub(crate) struct Ground {
    lines: Vec<(V3, V3)>,
}

/// The 1, 2, 5 times a power of ten at or above `x`.
fn nice(x: f64) -> f64 {
    let p = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * p)
        .find(|&s| s >= x * 0.999)
        .unwrap_or(10.0 * p)
}

impl Ground {
    /// A grid under `points` (every frame origin at every frame time).
    pub(crate) fn new(points: &[V3], options: &RenderOptions) -> Ground {
        let Some(up) = normalize(options.up) else {
            return Ground { lines: Vec::new() };
        };
        let (e1, e2) = basis(up, [1.0, 0.0, 0.0]);
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        let pts: Vec<V3> = if points.is_empty() {
            vec![options.look_at]
        } else {
            points.to_vec()
        };
        for p in pts.iter().filter(|p| p.iter().all(|x| x.is_finite())) {
            let c = [dot(*p, e1), dot(*p, e2), dot(*p, up)];
            for i in 0..3 {
                lo[i] = lo[i].min(c[i]);
                hi[i] = hi[i].max(c[i]);
            }
        }
        if !lo[0].is_finite() {
            return Ground { lines: Vec::new() };
        }
        let extent = (0..3).map(|i| hi[i] - lo[i]).fold(0.5, f64::max);
        let spacing = options
            .grid_spacing
            .filter(|s| *s > 0.0 && s.is_finite())
            .unwrap_or_else(|| nice(extent / 8.0));
        let level = options.grid_level.unwrap_or(lo[2] - 0.1 * extent);
        let pad = 0.25 * extent + spacing;
        let range = |i: usize| {
            let a = ((lo[i] - pad) / spacing).floor();
            let b = ((hi[i] + pad) / spacing).ceil().min(a + MAX_GRID_LINES);
            (a * spacing, b * spacing, (b - a) as usize)
        };
        let (u0, u1, nu) = range(0);
        let (v0, v1, nv) = range(1);
        let at = |u: f64, v: f64| axpy(axpy(up.map(|x| x * level), u, e1), v, e2);
        let mut lines = Vec::with_capacity(nu + nv + 2);
        for k in 0..=nu {
            let u = u0 + k as f64 * spacing;
            lines.push((at(u, v0), at(u, v1)));
        }
        for k in 0..=nv {
            let v = v0 + k as f64 * spacing;
            lines.push((at(u0, v), at(u1, v)));
        }
        Ground { lines }
    }
}

/// A glyph's coverage (0..1) in a cell of the label's monospace font.
struct Glyph {
    width: usize,
    height: usize,
    coverage: Vec<f64>,
}

/// Draws a frame's pixels.
pub(crate) struct Painter {
    camera: Camera,
    light: V3,
    ground: Ground,
    font_size: u32,
    glyphs: HashMap<char, Glyph>,
    /// See [`Painter::ink_top`].
    ink_top: Option<usize>,
    mesh: Mesh,
}

impl Painter {
    pub(crate) fn new(camera: Camera, ground: Ground, height: u32) -> Painter {
        multibody_core::plot::register_fonts();
        Painter {
            light: headlight(&camera),
            camera,
            ground,
            font_size: (height / 28).max(11),
            glyphs: HashMap::new(),
            ink_top: None,
            mesh: Mesh::default(),
        }
    }

    /// The pixels of the scene at one time (`value(i)` is the `i`-th variable of the
    /// scene at that time), labelled with `label` if given.
    pub(crate) fn paint(
        &mut self,
        scene: &Scene,
        value: &dyn Fn(usize) -> f64,
        options: &RenderOptions,
        label: Option<&str>,
    ) -> Canvas {
        let (w, h) = (options.width as usize, options.height as usize);
        let mut canvas = Canvas::new(w, h, options.background);
        if options.grid {
            for &(a, b) in &self.ground.lines {
                canvas.line(&self.camera, a, b, options.grid_color);
            }
        }
        self.mesh.tris.clear();
        scene.mesh(value, &mut self.mesh);
        for tri in &self.mesh.tris {
            canvas.triangle(&self.camera, tri, self.light);
        }
        if let Some(text) = label {
            self.label(&mut canvas, text);
        }
        canvas
    }

    /// The coverage of `c` in a cell of the monospace font: `3 size` rows, the glyph
    /// drawn from row `size` (plotters' text anchors are not exact, so the label is
    /// placed by its ink, see [`Painter::label`]).
    fn glyph(&mut self, c: char) -> &Glyph {
        let size = self.font_size;
        self.glyphs.entry(c).or_insert_with(|| {
            let width = (size as f64 * 0.62).ceil() as usize;
            let height = 3 * size as usize;
            // Drawn with some room to the left and right, then centred on its ink: the
            // glyphs of a monospace font sit in the middle of their cells.
            let bw = 3 * width;
            let mut buf = vec![255u8; bw * height * 3];
            {
                let mut backend = BitMapBackend::with_buffer(&mut buf, (bw as u32, height as u32));
                let style = TextStyle::from(("monospace", size as f64).into_font())
                    .color(&BLACK)
                    .pos(TextPos::new(HPos::Left, VPos::Top));
                let _ = backend.draw_text(&c.to_string(), &style, (width as i32, size as i32));
            }
            let ink: Vec<f64> = buf.chunks(3).map(|p| 1.0 - p[0] as f64 / 255.0).collect();
            let cols: Vec<usize> = (0..bw)
                .filter(|&x| (0..height).any(|y| ink[y * bw + x] > 0.05))
                .collect();
            let mut coverage = vec![0.0; width * height];
            if let (Some(&x0), Some(&x1)) = (cols.first(), cols.last()) {
                let shift = x0 as isize - ((width as isize - (x1 - x0 + 1) as isize) / 2);
                for y in 0..height {
                    for x in 0..width {
                        let sx = x as isize + shift;
                        if sx >= 0 && (sx as usize) < bw {
                            coverage[y * width + x] = ink[y * bw + sx as usize];
                        }
                    }
                }
            }
            Glyph {
                width,
                height,
                coverage,
            }
        })
    }

    /// The first row of a glyph cell with ink of a digit or capital letter.
    fn ink_top(&mut self) -> usize {
        if let Some(top) = self.ink_top {
            return top;
        }
        let top = "0123456789T"
            .chars()
            .filter_map(|c| {
                let g = self.glyph(c);
                (0..g.height).find(|&y| (0..g.width).any(|x| g.coverage[y * g.width + x] > 0.05))
            })
            .min()
            .unwrap_or(0);
        self.ink_top = Some(top);
        top
    }

    /// Writes `text` in the top left corner. Coverage is rounded to thirds, so that the
    /// label adds few colours to the frame.
    fn label(&mut self, canvas: &mut Canvas, text: &str) {
        let margin = (self.font_size / 2) as usize;
        let top = self.ink_top();
        let mut x0 = margin;
        for c in text.chars() {
            let g = self.glyph(c);
            let (cw, ch, cov) = (g.width, g.height, &g.coverage);
            for y in top..ch {
                for x in 0..cw {
                    let (px, py) = (x0 + x, margin + y - top);
                    let a = (cov[y * cw + x] * 3.0).round() / 3.0;
                    if a <= 0.0 || px >= canvas.width || py >= canvas.height {
                        continue;
                    }
                    let i = 3 * (py * canvas.width + px);
                    for k in 0..3 {
                        let under = canvas.rgb[i + k] as f64;
                        canvas.rgb[i + k] =
                            (under + a * (LABEL_COLOR[k] as f64 - under)).round() as u8;
                    }
                }
            }
            x0 += cw;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::nice;

    #[test]
    fn nice_steps() {
        assert_eq!(nice(0.3), 0.5);
        assert_eq!(nice(0.1), 0.1);
        assert_eq!(nice(1.5), 2.0);
        assert_eq!(nice(7.0), 10.0);
    }
}
