//! Static line plots of simulation results, written as PNG files.
//!
//! A figure is a grid of [`Panel`]s (subplots), each holding one or more
//! [`Series`] (curves). [`plot_panels`] lays the panels out row by row,
//! [`PlotOptions::columns`] panels per row, like Julia's `plot(p1, p2)`, and
//! draws each one with a white background, axis labels, a framed legend in
//! the top-right corner and distinct colours from a fixed palette.
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

mod font;
mod solution;

use std::path::Path;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

pub use font::register_fonts;
pub use solution::{plot, plot_figure};

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
    /// `height * rows` pixels tall. Default 500.
    pub height: u32,
    /// Maximum number of panels side by side in one row; further panels go
    /// to new rows. Capped at the number of panels, so two panels with the
    /// default of 2 sit side by side and one panel takes the full width.
    /// 0 means the default, 2.
    pub columns: usize,
    /// Line width of the curves in pixels (0 is drawn as 1). Default 2.
    pub line_width: u32,
}

impl Default for PlotOptions {
    fn default() -> Self {
        Self {
            width: 1200,
            height: 500,
            columns: 2,
            line_width: 2,
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

/// Line colours, in order of the series in a panel (Julia Plots' default palette).
const PALETTE: [RGBColor; 10] = [
    RGBColor(0, 154, 250),
    RGBColor(227, 111, 71),
    RGBColor(62, 164, 78),
    RGBColor(195, 113, 210),
    RGBColor(172, 142, 24),
    RGBColor(0, 170, 174),
    RGBColor(237, 94, 147),
    RGBColor(198, 130, 37),
    RGBColor(0, 159, 129),
    RGBColor(155, 126, 233),
];

const FONT: &str = "sans-serif";
const TITLE_SIZE: u32 = 22;
const AXIS_DESC_SIZE: u32 = 18;
const TICK_SIZE: u32 = 15;
const LEGEND_SIZE: u32 = 16;
const X_LABEL_AREA: u32 = 58;
const TICK_LEN: u32 = 5;
/// Largest figure in pixels (2^26, 192 MiB of RGB), as for animations.
const MAX_PIXELS: u64 = 1 << 26;

const X_TICKS: usize = 8;
const Y_TICKS: usize = 8;

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
    (options.width, options.height.saturating_mul(rows))
}

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
    register_fonts();
    let mut buffer = vec![255u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(backend_error)?;
        let (columns, rows) = grid(panels.len(), options);
        let areas = root.split_evenly((rows, columns));
        for (i, (panel, area)) in panels.iter().zip(areas.iter()).enumerate() {
            draw_panel(panel, area, options)
                .map_err(|e| PlotError::Backend(format!("{}: {e}", panel_name(i, panel))))?;
        }
        root.present().map_err(backend_error)?;
    }
    Ok(buffer)
}

fn backend_error<E: std::fmt::Display>(e: E) -> PlotError {
    PlotError::Backend(e.to_string())
}

type DrawResult<T> = Result<T, Box<dyn std::error::Error>>;

/// Smallest and largest finite value of `values`, if any.
fn finite_bounds<'a>(values: impl Iterator<Item = &'a f64>) -> Option<(f64, f64)> {
    values
        .filter(|v| v.is_finite())
        .fold(None, |acc, &v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// Axis range from data bounds: `margin` (a fraction of the span) added on
/// both sides; a zero span becomes `±1` (at 0) or `±10 %` of the value.
fn padded_range((lo, hi): (f64, f64), margin: f64) -> (f64, f64) {
    let span = hi - lo;
    if span > 0.0 && span.is_finite() {
        let pad = span * margin;
        let (a, b) = (lo - pad, hi + pad);
        if a.is_finite() && b.is_finite() {
            (a, b)
        } else {
            (lo, hi)
        }
    } else {
        let d = if lo == 0.0 { 1.0 } else { lo.abs() * 0.1 };
        (lo - d, hi + d)
    }
}

/// Formats a tick value for an axis spanning `span`: plain decimals without
/// trailing zeros for moderate magnitudes, scientific notation otherwise.
fn format_tick(v: f64, span: f64) -> String {
    let a = v.abs();
    if a == 0.0 || a < span * 1e-9 {
        return "0".into();
    }
    if !(1e-3..1e6).contains(&a) {
        let s = format!("{v:.3e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        return format!("{}e{exponent}", trim_zeros(mantissa));
    }
    let decimals = (3.0 - span.log10().floor()).clamp(0.0, 12.0) as usize;
    let s = trim_zeros(&format!("{v:.decimals$}")).to_string();
    if s == "-0" { "0".into() } else { s }
}

fn trim_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// Splits a series into runs of consecutive finite points.
fn finite_runs(s: &Series) -> Vec<Vec<(f64, f64)>> {
    let mut runs = Vec::new();
    let mut run = Vec::new();
    for (&t, &y) in s.t.iter().zip(&s.y) {
        if t.is_finite() && y.is_finite() {
            run.push((t, y));
        } else if !run.is_empty() {
            runs.push(std::mem::take(&mut run));
        }
    }
    if !run.is_empty() {
        runs.push(run);
    }
    runs
}

/// Where a text's anchor point sits along the text direction.
#[derive(Clone, Copy)]
enum Align {
    Start,
    Center,
    End,
}

/// Draws `text` in black on `area` (area coordinates). Along the text the
/// anchor `at` is aligned per `align`; across it, `at` is the middle of the
/// capital letters. `vertical` text reads bottom to top. Characters are
/// placed one by one from the font's metrics (see [`font::SansMetrics`]).
fn draw_text(
    area: &Area<'_>,
    metrics: &font::SansMetrics,
    text: &str,
    size: u32,
    at: (i32, i32),
    align: Align,
    vertical: bool,
) -> DrawResult<()> {
    let size_f = f64::from(size);
    let (glyphs, width) = metrics.layout(text, size_f);
    let shift = match align {
        Align::Start => 0,
        Align::Center => width / 2,
        Align::End => width,
    };
    // plotters puts the baseline size/2 below the requested top.
    let baseline = (metrics.cap_height(size_f) / 2.0).round() as i32;
    let half = (size_f / 2.0) as i32;
    let mut style = TextStyle::from((FONT, size_f).into_font())
        .color(&BLACK)
        .pos(Pos::new(HPos::Left, VPos::Top));
    if vertical {
        style = style.transform(FontTransform::Rotate270);
    }
    for (c, offset) in glyphs {
        let pos = if vertical {
            (at.0 + baseline - half, at.1 + shift - offset)
        } else {
            (at.0 - shift + offset, at.1 + baseline - half)
        };
        area.draw(&Text::new(c.to_string(), pos, style.clone()))?;
    }
    Ok(())
}

type Area<'a> = DrawingArea<BitMapBackend<'a>, Shift>;

fn draw_panel(panel: &Panel, area: &Area<'_>, options: &PlotOptions) -> DrawResult<()> {
    let metrics = font::sans_metrics().ok_or("cannot read the embedded DejaVu Sans metrics")?;
    let t_bounds = finite_bounds(panel.series.iter().flat_map(|s| {
        s.t.iter()
            .zip(&s.y)
            .filter(|(_, y)| y.is_finite())
            .map(|(t, _)| t)
    }));
    let y_bounds = finite_bounds(panel.series.iter().flat_map(|s| {
        s.t.iter()
            .zip(&s.y)
            .filter(|(t, _)| t.is_finite())
            .map(|(_, y)| y)
    }));
    let (Some(t_bounds), Some(y_bounds)) = (t_bounds, y_bounds) else {
        return Err("no finite points".into());
    };
    let (x0, x1) = padded_range(t_bounds, 0.01);
    let (y0, y1) = padded_range(y_bounds, 0.05);
    let (x_span, y_span) = (x1 - x0, y1 - y0);

    // The tick positions plotters' mesh uses for `x_labels(n)` / `y_labels(n)`.
    let x_ticks = RangedCoordf64::from(x0..x1).key_points(X_TICKS);
    let y_ticks = RangedCoordf64::from(y0..y1).key_points(Y_TICKS);
    let y_tick_labels: Vec<String> = y_ticks.iter().map(|&v| format_tick(v, y_span)).collect();
    let tick_width = y_tick_labels
        .iter()
        .map(|l| metrics.width(l, f64::from(TICK_SIZE)))
        .max()
        .unwrap_or(0);
    let tick_width = u32::try_from(tick_width).unwrap_or(0);
    let desc_cap = metrics.cap_height(f64::from(AXIS_DESC_SIZE)).round() as i32;

    let title = panel.title.as_deref().filter(|t| !t.is_empty());
    let x_label = if panel.x_label.is_empty() {
        "t [s]"
    } else {
        panel.x_label.as_str()
    };
    let desc_room = if panel.y_label.is_empty() {
        0
    } else {
        desc_cap as u32 + 14
    };
    let y_label_area = TICK_LEN + 6 + tick_width + desc_room + 8;
    let margin_top = if title.is_some() { TITLE_SIZE + 20 } else { 16 };

    let mut chart = ChartBuilder::on(area)
        .margin_top(margin_top)
        .margin_bottom(4)
        .margin_left(6)
        .margin_right(20)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(y_label_area)
        .build_cartesian_2d(x0..x1, y0..y1)?;

    // plotters draws grid and tick marks; its own labels are hidden because its
    // ab_glyph text placement ignores side bearings (see `draw_text`).
    chart
        .configure_mesh()
        .x_labels(X_TICKS)
        .y_labels(Y_TICKS)
        .label_style(TextStyle::from((FONT, f64::from(TICK_SIZE)).into_font()).color(&TRANSPARENT))
        .set_all_tick_mark_size(TICK_LEN)
        .bold_line_style(BLACK.mix(0.1))
        .light_line_style(TRANSPARENT)
        .axis_style(BLACK.mix(0.8))
        .draw()?;

    let line_width = options.line_width.max(1);
    let mut legend = Vec::new();
    for (k, s) in panel.series.iter().enumerate() {
        let style = PALETTE[k % PALETTE.len()].stroke_width(line_width);
        let (lines, points): (Vec<_>, Vec<_>) =
            finite_runs(s).into_iter().partition(|r| r.len() > 1);
        // Thick polylines are drawn with miter joins, which spike where a dense curve
        // turns sharply within a pixel: keep one point per pixel and draw the segments
        // one by one.
        for run in lines {
            let mut kept: Vec<(f64, f64)> = Vec::with_capacity(run.len());
            let mut last_px = None;
            for (i, &p) in run.iter().enumerate() {
                let px = chart.backend_coord(&p);
                if last_px != Some(px) || i + 1 == run.len() {
                    kept.push(p);
                    last_px = Some(px);
                }
            }
            chart.draw_series(
                kept.windows(2)
                    .map(|w| PathElement::new(vec![w[0], w[1]], style)),
            )?;
        }
        let radius = line_width.max(2);
        chart.draw_series(
            points
                .into_iter()
                .map(|p| Circle::new(p[0], radius, style.filled())),
        )?;
        if !s.label.is_empty() {
            legend.push((s.label.as_str(), style));
        }
    }

    // Text, in area coordinates.
    let (bx, by) = area.get_base_pixel();
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    let (left, right, top, bottom) = (xr.start - bx, xr.end - bx, yr.start - by, yr.end - by);
    let tick_len = TICK_LEN as i32;
    let tick_cap = metrics.cap_height(f64::from(TICK_SIZE)).round() as i32;
    for &v in &x_ticks {
        let (px, _) = chart.backend_coord(&(v, y0));
        let at = (px - bx, bottom + tick_len + 6 + tick_cap / 2);
        draw_text(
            area,
            metrics,
            &format_tick(v, x_span),
            TICK_SIZE,
            at,
            Align::Center,
            false,
        )?;
    }
    for (&v, label) in y_ticks.iter().zip(&y_tick_labels) {
        let (_, py) = chart.backend_coord(&(x0, v));
        let at = (left - tick_len - 6, py - by);
        draw_text(area, metrics, label, TICK_SIZE, at, Align::End, false)?;
    }
    let x_mid = (left + right) / 2;
    let x_desc_at = (x_mid, bottom + X_LABEL_AREA as i32 - 10 - desc_cap / 2);
    draw_text(
        area,
        metrics,
        x_label,
        AXIS_DESC_SIZE,
        x_desc_at,
        Align::Center,
        false,
    )?;
    if !panel.y_label.is_empty() {
        let at = (
            left - tick_len - 6 - tick_width as i32 - 12 - desc_cap / 2,
            (top + bottom) / 2,
        );
        draw_text(
            area,
            metrics,
            &panel.y_label,
            AXIS_DESC_SIZE,
            at,
            Align::Center,
            true,
        )?;
    }
    if let Some(title) = title {
        draw_text(
            area,
            metrics,
            title,
            TITLE_SIZE,
            (x_mid, top / 2 + 2),
            Align::Center,
            false,
        )?;
    }

    if !legend.is_empty() {
        let size = f64::from(LEGEND_SIZE);
        let text_w = legend
            .iter()
            .map(|(l, _)| metrics.width(l, size))
            .max()
            .unwrap_or(0);
        let row = LEGEND_SIZE as i32 + 8;
        let (pad, sample) = (10, 28);
        let w = pad + sample + 8 + text_w + pad;
        let h = legend.len() as i32 * row + 8;
        let (lx1, ly0) = (right - 10, top + 10);
        let (lx0, ly1) = (lx1 - w, ly0 + h);
        area.draw(&Rectangle::new(
            [(lx0, ly0), (lx1, ly1)],
            WHITE.mix(0.9).filled(),
        ))?;
        area.draw(&Rectangle::new(
            [(lx0, ly0), (lx1, ly1)],
            RGBColor(110, 110, 110),
        ))?;
        for (i, (label, style)) in legend.iter().enumerate() {
            let y = ly0 + 4 + row / 2 + i as i32 * row;
            area.draw(&PathElement::new(
                vec![(lx0 + pad, y), (lx0 + pad + sample, y)],
                *style,
            ))?;
            draw_text(
                area,
                metrics,
                label,
                LEGEND_SIZE,
                (lx0 + pad + sample + 8, y),
                Align::Start,
                false,
            )?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn demo_panels() -> Vec<Panel> {
        let t: Vec<f64> = (0..=200).map(|i| f64::from(i) * 0.05).collect();
        let sin = t.iter().map(|t| t.sin()).collect();
        let cos = t.iter().map(|t| t.cos()).collect();
        vec![
            Panel {
                title: None,
                x_label: String::new(),
                y_label: "x [m]".into(),
                series: vec![
                    Series {
                        label: "sin(t)".into(),
                        t: t.clone(),
                        y: sin,
                    },
                    Series {
                        label: "cos(t)".into(),
                        t: t.clone(),
                        y: cos,
                    },
                ],
            },
            Panel {
                title: Some("Constant".into()),
                x_label: "time [s]".into(),
                y_label: "F [N]".into(),
                series: vec![Series {
                    label: "F = 9.81".into(),
                    t: t.clone(),
                    y: vec![9.81; t.len()],
                }],
            },
        ]
    }

    fn pixel(buf: &[u8], w: u32, x: u32, y: u32) -> [u8; 3] {
        let i = 3 * (y as usize * w as usize + x as usize);
        [buf[i], buf[i + 1], buf[i + 2]]
    }

    fn unique_temp_png(tag: &str) -> std::path::PathBuf {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_nanos())
            .unwrap_or(0);
        std::env::temp_dir().join(format!(
            "multibody-plot-{tag}-{}-{nanos}.png",
            std::process::id()
        ))
    }

    #[test]
    fn buffer_has_curves_and_legend_text() {
        let panels = demo_panels();
        let options = PlotOptions::default();
        let (w, h) = figure_size(panels.len(), &options);
        assert_eq!((w, h), (1200, 500));
        let buf = render_to_buffer(&panels, &options).unwrap();
        assert_eq!(buf.len(), (w * h * 3) as usize);
        assert!(buf.iter().any(|&b| b != 255), "figure is all white");

        // Legend of the first panel: top-right of its plotting area (x < 600).
        let mut dark = 0;
        for y in 15..200 {
            for x in 380..595 {
                let [r, g, b] = pixel(&buf, w, x, y);
                if r < 60 && g < 60 && b < 60 {
                    dark += 1;
                }
            }
        }
        assert!(dark > 50, "no legend text found ({dark} dark pixels)");

        let near = |p: [u8; 3], c: RGBColor| {
            (i32::from(p[0]) - i32::from(c.0)).abs() < 12
                && (i32::from(p[1]) - i32::from(c.1)).abs() < 12
                && (i32::from(p[2]) - i32::from(c.2)).abs() < 12
        };
        let count = |c: RGBColor, xs: std::ops::Range<u32>| {
            let mut n = 0;
            for y in 0..h {
                for x in xs.clone() {
                    if near(pixel(&buf, w, x, y), c) {
                        n += 1;
                    }
                }
            }
            n
        };
        assert!(
            count(PALETTE[0], 0..600) > 300,
            "first curve colour missing"
        );
        assert!(
            count(PALETTE[1], 0..600) > 300,
            "second curve colour missing"
        );
        assert!(count(PALETTE[0], 600..1200) > 300, "constant curve missing");
        assert_eq!(
            count(PALETTE[1], 600..1200),
            0,
            "second panel uses one colour only"
        );
    }

    /// Width, height, bit depth and colour type from a PNG's IHDR chunk (the first
    /// chunk, right after the 8-byte signature; PNG specification, section 11.2.2).
    fn png_header(bytes: &[u8]) -> (u32, u32, u8, u8) {
        assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"), "not a PNG");
        assert_eq!(&bytes[12..16], b"IHDR", "the first chunk is not IHDR");
        let be =
            |i: usize| u32::from_be_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]);
        (be(16), be(20), bytes[24], bytes[25])
    }

    #[test]
    fn writes_png_file() {
        let path = unique_temp_png("demo");
        let options = PlotOptions {
            width: 900,
            height: 300,
            ..PlotOptions::default()
        };
        plot_panels(&demo_panels(), &path, &options).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        // The asked size (two panels side by side: one row), 8-bit RGB (colour type 2).
        assert_eq!(png_header(&bytes), (900, 300, 8, 2));
        assert!(bytes.len() > 1000);
        if std::env::var_os("MULTIBODY_KEEP_PLOT").is_none() {
            let _ = std::fs::remove_file(&path);
        }
    }

    #[test]
    fn layout_rows_and_columns() {
        let o = PlotOptions::default();
        assert_eq!(grid(1, &o), (1, 1));
        assert_eq!(grid(2, &o), (2, 1));
        assert_eq!(grid(3, &o), (2, 2));
        assert_eq!(figure_size(3, &o), (1200, 1000));
        let o1 = PlotOptions {
            columns: 1,
            ..o.clone()
        };
        assert_eq!(grid(3, &o1), (1, 3));
        let o0 = PlotOptions { columns: 0, ..o };
        assert_eq!(grid(5, &o0), (2, 3));
    }

    #[test]
    fn three_panels_with_nan_render() {
        let mut panels = demo_panels();
        let t: Vec<f64> = (0..50).map(f64::from).collect();
        let mut y: Vec<f64> = t.iter().map(|t| t * t).collect();
        y[10] = f64::NAN;
        y[12] = f64::NAN; // isolated point 11 becomes a dot
        panels.push(Panel {
            series: vec![Series {
                label: String::new(),
                t,
                y,
            }],
            ..Panel::default()
        });
        let options = PlotOptions {
            columns: 2,
            ..PlotOptions::default()
        };
        let buf = render_to_buffer(&panels, &options).unwrap();
        assert_eq!(buf.len(), 1200 * 1000 * 3);
        // The third panel (bottom left, x < 600, y >= 500) draws y = t^2 in the first
        // palette colour, and nothing else in that colour (no legend: empty label).
        let (w, h) = (1200u32, 1000u32);
        let near = |p: [u8; 3], c: RGBColor| {
            (i32::from(p[0]) - i32::from(c.0)).abs() < 12
                && (i32::from(p[1]) - i32::from(c.1)).abs() < 12
                && (i32::from(p[2]) - i32::from(c.2)).abs() < 12
        };
        let columns: Vec<Vec<u32>> = (0..600)
            .map(|x| {
                (500..h)
                    .filter(|&y| near(pixel(&buf, w, x, y), PALETTE[0]))
                    .collect()
            })
            .collect();
        let drawn: Vec<usize> = (0..600).filter(|&x| !columns[x].is_empty()).collect();
        let (xa, xb) = (drawn[0], *drawn.last().unwrap());
        let rows = drawn.iter().flat_map(|&x| columns[x].iter().copied());
        let (r_top, r_bottom) = rows.fold((u32::MAX, 0), |(a, b), r| (a.min(r), b.max(r)));
        // The curve spans most of the panel both ways.
        assert!(
            xb - xa > 400 && r_bottom - r_top > 300,
            "{xa}..{xb}, {r_top}..{r_bottom}"
        );
        // Pixel column -> t and t -> row, linear between the curve's ends (t = 0 at the
        // bottom left, t = 49 at the top right, up to the line's half width).
        let t_of = |x: usize| 49.0 * (x - xa) as f64 / (xb - xa) as f64;
        let x_of = |t: f64| xa as f64 + t / 49.0 * (xb - xa) as f64;
        let row_of =
            |t: f64| f64::from(r_bottom) - (t / 49.0).powi(2) * f64::from(r_bottom - r_top);
        // Within 3 pixels of a run's end (t = 0, 9, 13, 49) the line's caps and the
        // mapping's pixel rounding leave it open whether a column is drawn: skipped.
        let near = |x: usize, t: f64| (x as f64 - x_of(t)).abs() <= 3.0;
        for x in xa..=xb {
            let t = t_of(x);
            if [0.0, 9.0, 11.0, 13.0, 49.0].iter().any(|&end| near(x, end)) {
                continue;
            }
            if t > 9.0 && t < 13.0 {
                // NaN at t = 10 and 12 break the line: nothing between 9 and 13 but the
                // isolated point at t = 11.
                assert!(columns[x].is_empty(), "column {x} (t = {t:.2}) is drawn");
            } else {
                // The parabola passes through this column within 3 pixels (the line is
                // 2 pixels wide; its steepest part climbs 2 rows per column).
                let expected = row_of(t);
                let miss = columns[x]
                    .iter()
                    .map(|&r| (f64::from(r) - expected).abs())
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    miss <= 3.0,
                    "column {x} (t = {t:.2}): curve {miss} px from y = t^2"
                );
            }
        }
        // The isolated point at t = 11 is a dot at y = 121.
        assert!(
            (xa..=xb)
                .filter(|&x| near(x, 11.0))
                .flat_map(|x| columns[x].iter())
                .any(|&r| (f64::from(r) - row_of(11.0)).abs() <= 3.0),
            "no dot at t = 11"
        );
        let path = unique_temp_png("three");
        plot_panels(&panels, &path, &options).unwrap();
        assert_eq!(
            png_header(&std::fs::read(&path).unwrap()),
            (1200, 1000, 8, 2)
        );
        if std::env::var_os("MULTIBODY_KEEP_PLOT").is_none() {
            let _ = std::fs::remove_file(&path);
        }
    }

    #[test]
    fn errors() {
        let o = PlotOptions::default();
        assert!(matches!(
            render_to_buffer(&[], &o),
            Err(PlotError::Empty(_))
        ));
        assert!(matches!(
            render_to_buffer(&[Panel::default()], &o),
            Err(PlotError::Empty(_))
        ));

        let no_points = Panel {
            series: vec![Series {
                label: "a".into(),
                t: vec![],
                y: vec![],
            }],
            ..Panel::default()
        };
        assert!(matches!(
            render_to_buffer(&[no_points], &o),
            Err(PlotError::Empty(_))
        ));

        let mismatch = Panel {
            series: vec![Series {
                label: "bad".into(),
                t: vec![0.0, 1.0, 2.0],
                y: vec![1.0, 2.0],
            }],
            ..Panel::default()
        };
        match render_to_buffer(std::slice::from_ref(&mismatch), &o) {
            Err(PlotError::LengthMismatch { label, t, y }) => {
                assert_eq!((label.as_str(), t, y), ("bad", 3, 2))
            }
            other => panic!("expected LengthMismatch, got {other:?}"),
        }
        let path = unique_temp_png("mismatch");
        assert!(matches!(
            plot_panels(&[mismatch], &path, &o),
            Err(PlotError::LengthMismatch { .. })
        ));
        assert!(!path.exists());

        let all_nan = Panel {
            series: vec![Series {
                label: "nan".into(),
                t: vec![0.0, 1.0],
                y: vec![f64::NAN; 2],
            }],
            ..Panel::default()
        };
        assert!(matches!(
            render_to_buffer(&[all_nan], &o),
            Err(PlotError::Empty(_))
        ));

        let missing_dir = std::env::temp_dir()
            .join("multibody-no-such-dir-8d3f")
            .join("x.png");
        assert!(matches!(
            plot_panels(&demo_panels(), &missing_dir, &o),
            Err(PlotError::Io(_))
        ));
        let wrong_ext = std::env::temp_dir().join("x.jpg");
        assert!(matches!(
            plot_panels(&demo_panels(), &wrong_ext, &o),
            Err(PlotError::Io(_))
        ));
        let zero = PlotOptions {
            width: 0,
            ..PlotOptions::default()
        };
        assert!(matches!(
            render_to_buffer(&demo_panels(), &zero),
            Err(PlotError::Backend(_))
        ));
    }

    #[test]
    fn tick_format() {
        assert_eq!(format_tick(0.5, 2.2), "0.5");
        assert_eq!(format_tick(-1.0, 2.2), "-1");
        assert_eq!(format_tick(0.30000000000000004, 2.2), "0.3");
        assert_eq!(format_tick(1e-17, 2.2), "0");
        assert_eq!(format_tick(2.5e7, 1e7), "2.5e7");
        assert_eq!(format_tick(1.5e-5, 1e-5), "1.5e-5");
        assert_eq!(format_tick(9.81, 1.962), "9.81");
    }

    #[test]
    fn constant_and_zero_ranges() {
        assert_eq!(padded_range((0.0, 0.0), 0.05), (-1.0, 1.0));
        let (a, b) = padded_range((10.0, 10.0), 0.05);
        assert!((a - 9.0).abs() < 1e-12 && (b - 11.0).abs() < 1e-12);
        let (a, b) = padded_range((0.0, 10.0), 0.05);
        assert!((a + 0.5).abs() < 1e-12 && (b - 10.5).abs() < 1e-12);
    }

    #[test]
    fn glyph_metrics_place_narrow_glyphs() {
        let m = font::sans_metrics().expect("DejaVu Sans metrics");
        let (glyphs, width) = m.layout("10.5", 15.0);
        let offsets: Vec<i32> = glyphs.iter().map(|g| g.1).collect();
        assert_eq!(glyphs.iter().map(|g| g.0).collect::<String>(), "10.5");
        // '1' has a wide left bearing; every glyph starts right of the previous one.
        assert!(offsets[0] >= 1, "{offsets:?}");
        assert!(offsets.windows(2).all(|w| w[1] > w[0]), "{offsets:?}");
        assert!((25..40).contains(&width), "width {width}");
        assert_eq!(m.layout("a b", 15.0).0.len(), 2);
        let cap = m.cap_height(15.0);
        assert!((8.0..11.0).contains(&cap), "cap height {cap}");
    }

    #[test]
    fn single_panel_uses_full_width() {
        let mut panels = demo_panels();
        panels.truncate(1);
        let options = PlotOptions {
            width: 640,
            height: 360,
            ..PlotOptions::default()
        };
        assert_eq!(figure_size(1, &options), (640, 360));
        let buf = render_to_buffer(&panels, &options).unwrap();
        assert_eq!(buf.len(), 640 * 360 * 3);
    }

    #[test]
    fn register_fonts_is_idempotent_across_threads() {
        // Text needs the registered fonts (plotters has no system fonts here): threads
        // that register them concurrently, and then again, all draw the same figure,
        // with its legend text, as a single thread does.
        let options = PlotOptions {
            width: 400,
            height: 200,
            ..PlotOptions::default()
        };
        let draw = move || {
            register_fonts();
            register_fonts();
            render_to_buffer(&demo_panels()[..1], &options).expect("fonts available")
        };
        let handles: Vec<_> = (0..4).map(|_| std::thread::spawn(draw.clone())).collect();
        let buffers: Vec<Vec<u8>> = handles.into_iter().map(|h| h.join().unwrap()).collect();
        let reference = draw();
        for b in &buffers {
            assert!(b == &reference, "a thread drew a different figure");
        }
        // Text is the only black in the figure (axes and ticks are drawn at 80 %
        // black, (51, 51, 51); grid lines and the legend frame lighter): the legend
        // labels, tick labels and the axis description give about 240 pixels below 20.
        let black = reference
            .chunks(3)
            .filter(|p| p[0] < 20 && p[1] < 20 && p[2] < 20)
            .count();
        assert!(black > 100, "only {black} black pixels: text missing");
    }
}
