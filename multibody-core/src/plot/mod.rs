//! Static line plots of simulation results, written as PNG files.
//!
//! [`plot`], [`plot_figure`] and [`Figure`] draw variables of solutions against time,
//! by name or by handle, with their units on the y axis; a [`Figure`] overlays several
//! solutions in one panel.
//!
//! Underneath, a figure is a grid of [`Panel`]s (subplots), each holding one or more
//! [`Series`] (curves). [`plot_panels`] lays the panels out row by row,
//! [`PlotOptions::columns`] panels per row, like Julia's `plot(p1, p2)`, and draws
//! each one with a white background, axis labels, a framed legend in the corner where
//! it covers no curve (above them when every corner would) and distinct colours from
//! a fixed palette. Figures are drawn at twice their size and scaled down, so lines
//! and text are smooth.
//!
//! Text is rendered with the DejaVu fonts embedded in the binary (see
//! [`register_fonts`]), so plotting works on machines without any system fonts.
//!
//! ```no_run
//! use multibody_core::plot::{Panel, PlotOptions, Series, plot_panels};
//! let t: Vec<f64> = (0..100).map(|i| i as f64 * 0.1).collect();
//! let y = t.iter().map(|t| t.sin()).collect();
//! let panel = Panel {
//!     y_label: "x [m]".into(),
//!     series: vec![Series { label: "x".into(), t, y }],
//!     ..Panel::default()
//! };
//! plot_panels(&[panel], std::path::Path::new("x.png"), &PlotOptions::default()).unwrap();
//! ```

mod draw;
mod font;
mod linear;
mod solution;
#[cfg(test)]
mod tests;

use std::path::Path;

use plotters::prelude::*;

pub use font::register_fonts;
pub use linear::{plot_bode, plot_poles};
pub use solution::{Figure, plot, plot_figure};

/// One curve: `y[i]` plotted against `t[i]`.
///
/// Points where `t` or `y` is not finite (NaN or infinite) are skipped and
/// break the line, leaving a gap.
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend entry; an empty label leaves the curve out of the legend.
    pub label: String,
    /// Abscissae (usually time in seconds).
    pub t: Vec<f64>,
    /// Ordinates; must have the same length as `t`.
    pub y: Vec<f64>,
}

/// One panel (subplot) of a figure.
#[derive(Clone, Debug, Default)]
pub struct Panel {
    /// Title drawn above the panel; `None` (or an empty string) draws none.
    pub title: Option<String>,
    /// Label of the horizontal axis; `"t [s]"` when empty.
    pub x_label: String,
    /// Label of the vertical axis; may be empty.
    pub y_label: String,
    /// The curves; a panel needs at least one.
    pub series: Vec<Series>,
}

/// Figure options for [`plot_panels`].
#[derive(Clone, Debug)]
pub struct PlotOptions {
    /// Width of the whole figure in pixels, shared by the panels of a row.
    /// Default 1200; a figure has at most 32768 pixels a side and 2^26 in all.
    pub width: u32,
    /// Height of one row of panels in pixels; the figure is
    /// `height * rows` pixels tall (and a band for the title). Default 500.
    pub height: u32,
    /// Maximum number of panels side by side in one row; further panels go
    /// to new rows. Capped at the number of panels, so two panels with the
    /// default of 2 sit side by side and one panel takes the full width.
    /// 0 means the default, 2.
    pub columns: usize,
    /// Line width of the curves in pixels (0 is drawn as 1). Default 2.
    pub line_width: u32,
    /// A title over the whole figure, in a band of its own. Default `None`.
    pub title: Option<String>,
}

impl Default for PlotOptions {
    fn default() -> Self {
        Self {
            width: 1200,
            height: 500,
            columns: 2,
            line_width: 2,
            title: None,
        }
    }
}

/// Errors from [`plot_panels`].
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The output file could not be written (missing parent directory,
    /// unsupported extension, I/O or encoding failure).
    #[error("cannot write plot: {0}")]
    Io(String),
    /// Drawing failed inside plotters, or the figure size is zero.
    #[error("plotting failed: {0}")]
    Backend(String),
    /// Nothing to draw: no panels, a panel with no series, a series with no
    /// points, or a panel whose points are all non-finite.
    #[error("nothing to plot: {0}")]
    Empty(String),
    /// A series whose `t` and `y` have different lengths.
    #[error("series `{label}` has {t} time points but {y} values")]
    LengthMismatch {
        /// The series' label.
        label: String,
        /// `t.len()`.
        t: usize,
        /// `y.len()`.
        y: usize,
    },
}

/// Draws the panels into one PNG at `path` (parent directories must exist;
/// the extension must be `.png`, any case).
///
/// See [`PlotOptions`] for the layout; the figure is `options.width` by
/// `options.height * rows` pixels.
pub fn plot_panels(panels: &[Panel], path: &Path, options: &PlotOptions) -> Result<(), PlotError> {
    let is_png = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png {
        return Err(PlotError::Io(format!(
            "{}: the file name must end in .png",
            path.display()
        )));
    }
    if let Some(parent) = path.parent()
        && !parent.as_os_str().is_empty()
        && !parent.is_dir()
    {
        return Err(PlotError::Io(format!(
            "directory {} does not exist",
            parent.display()
        )));
    }
    let buffer = render_to_buffer(panels, options)?;
    let (w, h) = figure_size(panels.len(), options);
    let mut backend = BitMapBackend::new(path, (w, h));
    backend
        .blit_bitmap((0, 0), (w, h), &buffer)
        .map_err(|e| PlotError::Backend(e.to_string()))?;
    backend
        .present()
        .map_err(|e| PlotError::Io(format!("{}: {e}", path.display())))?;
    log::debug!(
        "plot: wrote {} ({w}x{h}, {} panels)",
        path.display(),
        panels.len()
    );
    Ok(())
}

/// Effective number of columns and rows for `n` panels.
fn grid(n: usize, options: &PlotOptions) -> (usize, usize) {
    let columns = if options.columns == 0 {
        2
    } else {
        options.columns
    };
    let columns = columns.min(n).max(1);
    (columns, n.div_ceil(columns).max(1))
}

/// Pixel size of the figure for `n` panels.
fn figure_size(n: usize, options: &PlotOptions) -> (u32, u32) {
    let (_, rows) = grid(n, options);
    let rows = u32::try_from(rows).unwrap_or(u32::MAX);
    let band = if has_title(options) { TITLE_BAND } else { 0 };
    (
        options.width,
        options.height.saturating_mul(rows).saturating_add(band),
    )
}

/// Whether the figure has a title band.
fn has_title(options: &PlotOptions) -> bool {
    options.title.as_deref().is_some_and(|t| !t.is_empty())
}

/// Height of the band of a figure's title, in pixels.
const TITLE_BAND: u32 = 44;
/// Largest figure in pixels (2^26, 192 MiB of RGB), as for animations.
const MAX_PIXELS: u64 = 1 << 26;
/// Figures are drawn this many times larger and scaled down (smooth lines and text),
/// unless that would exceed [`MAX_PIXELS`].
const SUPERSAMPLING: u32 = 2;

/// Checks the panels before anything is drawn.
fn validate(panels: &[Panel]) -> Result<(), PlotError> {
    if panels.is_empty() {
        return Err(PlotError::Empty("no panels".into()));
    }
    for (i, panel) in panels.iter().enumerate() {
        let name = panel_name(i, panel);
        if panel.series.is_empty() {
            return Err(PlotError::Empty(format!("{name} has no series")));
        }
        for s in &panel.series {
            if s.t.len() != s.y.len() {
                return Err(PlotError::LengthMismatch {
                    label: s.label.clone(),
                    t: s.t.len(),
                    y: s.y.len(),
                });
            }
            if s.t.is_empty() {
                return Err(PlotError::Empty(format!(
                    "series `{}` in {name} has no points",
                    s.label
                )));
            }
        }
        let any_finite = panel.series.iter().any(|s| {
            s.t.iter()
                .zip(&s.y)
                .any(|(t, y)| t.is_finite() && y.is_finite())
        });
        if !any_finite {
            return Err(PlotError::Empty(format!("{name} has no finite points")));
        }
    }
    Ok(())
}

fn panel_name(i: usize, panel: &Panel) -> String {
    match panel.title.as_deref() {
        Some(title) if !title.is_empty() => format!("panel {} (`{title}`)", i + 1),
        _ => format!("panel {}", i + 1),
    }
}

/// Renders the figure into an RGB buffer (3 bytes per pixel, row-major,
/// size given by [`figure_size`]). [`plot_panels`] encodes this buffer.
pub(crate) fn render_to_buffer(
    panels: &[Panel],
    options: &PlotOptions,
) -> Result<Vec<u8>, PlotError> {
    validate(panels)?;
    let (w, h) = figure_size(panels.len(), options);
    if w == 0 || h == 0 {
        return Err(PlotError::Backend(format!("figure size {w}x{h} is empty")));
    }
    if u64::from(w) * u64::from(h) > MAX_PIXELS || w > 32_768 || h > 32_768 {
        return Err(PlotError::Backend(format!(
            "figure size {w}x{h} is too large: at most 32768 pixels a side and 2^26 \
             pixels in all"
        )));
    }
    let s = if u64::from(w) * u64::from(h) * u64::from(SUPERSAMPLING * SUPERSAMPLING) <= MAX_PIXELS
    {
        SUPERSAMPLING
    } else {
        1
    };
    register_fonts();
    let (sw, sh) = (w * s, h * s);
    let mut buffer = vec![255u8; sw as usize * sh as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, (sw, sh)).into_drawing_area();
        root.fill(&WHITE).map_err(backend_error)?;
        let scale = draw::Scale(s as i32);
        let root = match options.title.as_deref().filter(|t| !t.is_empty()) {
            Some(title) => {
                let (band, rest) = root.split_vertically(scale.px(TITLE_BAND as i32));
                draw::draw_title(&band, title, scale).map_err(backend_error)?;
                rest
            }
            None => root,
        };
        let (columns, rows) = grid(panels.len(), options);
        let areas = root.split_evenly((rows, columns));
        for (i, (panel, area)) in panels.iter().zip(areas.iter()).enumerate() {
            draw::draw_panel(panel, area, options, scale)
                .map_err(|e| PlotError::Backend(format!("{}: {e}", panel_name(i, panel))))?;
        }
        root.present().map_err(backend_error)?;
    }
    Ok(if s == 1 {
        buffer
    } else {
        downsample(&buffer, (w, h), s)
    })
}

/// Averages `s` x `s` blocks of an RGB buffer `s` times the size `(w, h)`.
fn downsample(buffer: &[u8], (w, h): (u32, u32), s: u32) -> Vec<u8> {
    let (w, h, s) = (w as usize, h as usize, s as usize);
    let sw = w * s;
    let mut out = vec![0u8; w * h * 3];
    let n = (s * s) as u32;
    for y in 0..h {
        for x in 0..w {
            let mut sum = [0u32; 3];
            for dy in 0..s {
                let row = (y * s + dy) * sw;
                for dx in 0..s {
                    let i = 3 * (row + x * s + dx);
                    for c in 0..3 {
                        sum[c] += u32::from(buffer[i + c]);
                    }
                }
            }
            let o = 3 * (y * w + x);
            for c in 0..3 {
                out[o + c] = ((sum[c] + n / 2) / n) as u8;
            }
        }
    }
    out
}

fn backend_error<E: std::fmt::Display>(e: E) -> PlotError {
    PlotError::Backend(e.to_string())
}
