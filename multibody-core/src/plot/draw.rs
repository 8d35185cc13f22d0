//! Drawing one panel: axes, ticks and their labels, curves, the legend where it covers
//! no curve, and the figure's title. Every length is given at scale 1 and multiplied by
//! the [`Scale`] the figure is drawn at.

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::font;
use super::{Panel, PlotOptions, Series};

/// Line colours, in order of the series in a panel (Julia Plots' default palette).
pub(super) const PALETTE: [RGBColor; 10] = [
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
const TITLE_SIZE: i32 = 22;
const AXIS_DESC_SIZE: i32 = 18;
const TICK_SIZE: i32 = 15;
const LEGEND_SIZE: i32 = 16;
const X_LABEL_AREA: i32 = 58;
const TICK_LEN: i32 = 5;
const X_TICKS: usize = 8;
const Y_TICKS: usize = 8;
/// Space between the legend and the plotting area's edges.
const LEGEND_INSET: i32 = 10;

/// How many device pixels a pixel of the finished figure is.
#[derive(Clone, Copy, Debug)]
pub(super) struct Scale(pub i32);

impl Scale {
    /// `n` pixels of the finished figure in device pixels.
    pub(super) fn px(self, n: i32) -> i32 {
        n * self.0
    }

    /// [`Self::px`] for sizes.
    fn upx(self, n: i32) -> u32 {
        u32::try_from(self.px(n)).unwrap_or(0)
    }
}

pub(super) type DrawResult<T> = Result<T, Box<dyn std::error::Error>>;

pub(super) type Area<'a> = DrawingArea<BitMapBackend<'a>, Shift>;

/// Smallest and largest finite value of `values`, if any.
pub(super) fn finite_bounds<'a>(values: impl Iterator<Item = &'a f64>) -> Option<(f64, f64)> {
    values
        .filter(|v| v.is_finite())
        .fold(None, |acc, &v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// Axis range from data bounds: `margin` (a fraction of the span) added on
/// both sides; a zero span becomes `±1` (at 0) or `±10 %` of the value.
pub(super) fn padded_range((lo, hi): (f64, f64), margin: f64) -> (f64, f64) {
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
pub(super) fn format_tick(v: f64, span: f64) -> String {
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
    size: i32,
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

fn metrics() -> DrawResult<&'static font::SansMetrics> {
    Ok(font::sans_metrics().ok_or("cannot read the embedded DejaVu Sans metrics")?)
}

/// Draws a figure's title centred in `band`.
pub(super) fn draw_title(band: &Area<'_>, title: &str, s: Scale) -> DrawResult<()> {
    let (w, h) = band.dim_in_pixel();
    let at = (i32::try_from(w / 2)?, i32::try_from(h / 2)? + s.px(4));
    draw_text(
        band,
        metrics()?,
        title,
        s.px(TITLE_SIZE + 2),
        at,
        Align::Center,
        false,
    )
}

/// The legend's entries and its size in device pixels.
pub(super) struct Legend<'p> {
    entries: Vec<(&'p str, ShapeStyle)>,
    width: i32,
    height: i32,
    row: i32,
}

impl<'p> Legend<'p> {
    pub(super) fn new(
        panel: &'p Panel,
        line_width: u32,
        metrics: &font::SansMetrics,
        s: Scale,
    ) -> Self {
        let entries: Vec<(&str, ShapeStyle)> = panel
            .series
            .iter()
            .enumerate()
            .filter(|(_, ser)| !ser.label.is_empty())
            .map(|(k, ser)| {
                let style = PALETTE[k % PALETTE.len()].stroke_width(line_width);
                (ser.label.as_str(), style)
            })
            .collect();
        let size = f64::from(s.px(LEGEND_SIZE));
        let text_w = entries
            .iter()
            .map(|(l, _)| metrics.width(l, size))
            .max()
            .unwrap_or(0);
        let row = s.px(LEGEND_SIZE + 8);
        let width = s.px(10 + 28 + 8) + text_w + s.px(10);
        let height = entries.len() as i32 * row + s.px(8);
        Legend {
            entries,
            width,
            height,
            row,
        }
    }

    /// Draws the legend with its top-left corner at `(x0, y0)` (area coordinates).
    fn draw(
        &self,
        area: &Area<'_>,
        metrics: &font::SansMetrics,
        (x0, y0): (i32, i32),
        s: Scale,
    ) -> DrawResult<()> {
        let (x1, y1) = (x0 + self.width, y0 + self.height);
        area.draw(&Rectangle::new(
            [(x0, y0), (x1, y1)],
            WHITE.mix(0.9).filled(),
        ))?;
        area.draw(&Rectangle::new(
            [(x0, y0), (x1, y1)],
            ShapeStyle::from(RGBColor(110, 110, 110)).stroke_width(s.upx(1)),
        ))?;
        let (pad, sample) = (s.px(10), s.px(28));
        for (i, (label, style)) in self.entries.iter().enumerate() {
            let y = y0 + s.px(4) + self.row / 2 + i as i32 * self.row;
            area.draw(&PathElement::new(
                vec![(x0 + pad, y), (x0 + pad + sample, y)],
                *style,
            ))?;
            draw_text(
                area,
                metrics,
                label,
                s.px(LEGEND_SIZE),
                (x0 + pad + sample + s.px(8), y),
                Align::Start,
                false,
            )?;
        }
        Ok(())
    }
}

/// The corners a legend may take, in order of preference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Corner {
    TopRight,
    TopLeft,
    BottomRight,
    BottomLeft,
}

/// A plotting area's size in device pixels and its data ranges, to place the legend
/// before anything is drawn.
pub(super) struct Frame {
    /// Width in device pixels.
    pub(super) width: i32,
    /// Height in device pixels.
    pub(super) height: i32,
    /// The time range.
    pub(super) x: (f64, f64),
    /// The value range.
    pub(super) y: (f64, f64),
}

impl Frame {
    /// The pixel of a data point, from the plotting area's top left.
    pub(super) fn pixel(&self, (t, y): (f64, f64)) -> (i32, i32) {
        let fx = (t - self.x.0) / (self.x.1 - self.x.0);
        let fy = (self.y.1 - y) / (self.y.1 - self.y.0);
        (
            (fx * f64::from(self.width)) as i32,
            (fy * f64::from(self.height)) as i32,
        )
    }

    /// The legend's box at `corner`: left, top, right, bottom.
    pub(super) fn legend_box(&self, corner: Corner, legend: &Legend<'_>, inset: i32) -> [i32; 4] {
        let left = match corner {
            Corner::TopRight | Corner::BottomRight => self.width - inset - legend.width,
            _ => inset,
        };
        let top = match corner {
            Corner::TopRight | Corner::TopLeft => inset,
            _ => self.height - inset - legend.height,
        };
        [left, top, left + legend.width, top + legend.height]
    }

    /// How many points of the curves (and of the segments between them, sampled at
    /// every pixel) fall into `bx`.
    pub(super) fn covered(&self, panel: &Panel, bx: [i32; 4]) -> usize {
        let inside = |(x, y): (i32, i32)| x >= bx[0] && x <= bx[2] && y >= bx[1] && y <= bx[3];
        let mut n = 0;
        for s in &panel.series {
            let mut last: Option<(i32, i32)> = None;
            for (&t, &y) in s.t.iter().zip(&s.y) {
                if !(t.is_finite() && y.is_finite()) {
                    last = None;
                    continue;
                }
                let p = self.pixel((t, y));
                if let Some(q) = last {
                    // Points along a long segment: a steep jump crosses the box too.
                    let steps = (p.0 - q.0).abs().max((p.1 - q.1).abs()).clamp(1, 4096);
                    for k in 1..steps {
                        let f = f64::from(k) / f64::from(steps);
                        let m = (
                            q.0 + (f * f64::from(p.0 - q.0)) as i32,
                            q.1 + (f * f64::from(p.1 - q.1)) as i32,
                        );
                        n += usize::from(inside(m));
                    }
                }
                n += usize::from(inside(p));
                last = Some(p);
            }
        }
        n
    }
}

/// Where the legend goes: the first corner it covers no curve at; when every corner
/// would, the top right with `frame`'s y range raised so that the curves (whose top is
/// `data_top`) pass below it, unless the legend is too tall for that.
pub(super) fn place_legend(
    panel: &Panel,
    legend: &Legend<'_>,
    frame: &mut Frame,
    data_top: f64,
    s: Scale,
) -> Corner {
    let inset = s.px(LEGEND_INSET);
    let corners = [
        Corner::TopRight,
        Corner::TopLeft,
        Corner::BottomRight,
        Corner::BottomLeft,
    ];
    let mut best = (usize::MAX, Corner::TopRight);
    for c in corners {
        let n = frame.covered(panel, frame.legend_box(c, legend, inset));
        if n == 0 {
            return c;
        }
        if n < best.0 {
            best = (n, c);
        }
    }
    // Room above the curves: the legend's height and a gap, as a fraction of the area.
    let f = f64::from(legend.height + inset + s.px(6)) / f64::from(frame.height.max(1));
    if f < 0.5 {
        let (y0, _) = frame.y;
        frame.y.1 = (data_top - f * y0) / (1.0 - f);
        return Corner::TopRight;
    }
    best.1
}

/// Draws one panel into `area`.
pub(super) fn draw_panel(
    panel: &Panel,
    area: &Area<'_>,
    options: &PlotOptions,
    s: Scale,
) -> DrawResult<()> {
    let metrics = metrics()?;
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
    let y_range = padded_range(y_bounds, 0.05);
    let line_width = s.upx(options.line_width.max(1) as i32);
    let legend = Legend::new(panel, line_width, metrics, s);

    let title = panel.title.as_deref().filter(|t| !t.is_empty());
    let x_label = if panel.x_label.is_empty() {
        "t [s]"
    } else {
        panel.x_label.as_str()
    };
    let margin_top = if title.is_some() {
        s.px(TITLE_SIZE + 20)
    } else {
        s.px(16)
    };
    let (margin_bottom, margin_left, margin_right) = (s.px(4), s.px(6), s.px(20));
    let desc_cap = metrics.cap_height(f64::from(s.px(AXIS_DESC_SIZE))).round() as i32;

    // The y tick labels' width depends on the range, which the legend may raise: place
    // the legend with the labels of the unraised range, then lay out with the final one.
    let y_label_area = |y: (f64, f64)| -> (i32, Vec<f64>, Vec<String>) {
        let ticks = RangedCoordf64::from(y.0..y.1).key_points(Y_TICKS);
        let labels: Vec<String> = ticks.iter().map(|&v| format_tick(v, y.1 - y.0)).collect();
        let tick_width = labels
            .iter()
            .map(|l| metrics.width(l, f64::from(s.px(TICK_SIZE))))
            .max()
            .unwrap_or(0);
        let desc_room = if panel.y_label.is_empty() {
            0
        } else {
            desc_cap + s.px(14)
        };
        let area = s.px(TICK_LEN + 6) + tick_width + desc_room + s.px(8);
        (area, ticks, labels)
    };
    let (area_w, area_h) = area.dim_in_pixel();
    let (label_area, _, _) = y_label_area(y_range);
    let mut frame = Frame {
        width: area_w as i32 - margin_left - margin_right - label_area,
        height: area_h as i32 - margin_top - margin_bottom - s.px(X_LABEL_AREA),
        x: (x0, x1),
        y: y_range,
    };
    let corner = if legend.entries.is_empty() {
        Corner::TopRight
    } else {
        place_legend(panel, &legend, &mut frame, y_bounds.1, s)
    };
    let (y0, y1) = frame.y;
    let x_span = x1 - x0;
    let (label_area, y_ticks, y_tick_labels) = y_label_area((y0, y1));
    let tick_width = label_area
        - s.px(TICK_LEN + 6 + 8)
        - if panel.y_label.is_empty() {
            0
        } else {
            desc_cap + s.px(14)
        };
    let x_ticks = RangedCoordf64::from(x0..x1).key_points(X_TICKS);

    let mut chart = ChartBuilder::on(area)
        .margin_top(margin_top)
        .margin_bottom(margin_bottom)
        .margin_left(margin_left)
        .margin_right(margin_right)
        .x_label_area_size(s.px(X_LABEL_AREA))
        .y_label_area_size(label_area)
        .build_cartesian_2d(x0..x1, y0..y1)?;

    // plotters draws grid and tick marks; its own labels are hidden because its
    // ab_glyph text placement ignores side bearings (see `draw_text`).
    chart
        .configure_mesh()
        .x_labels(X_TICKS)
        .y_labels(Y_TICKS)
        .label_style(
            TextStyle::from((FONT, f64::from(s.px(TICK_SIZE))).into_font()).color(&TRANSPARENT),
        )
        .set_all_tick_mark_size(s.px(TICK_LEN))
        .bold_line_style(ShapeStyle::from(BLACK.mix(0.1)).stroke_width(s.upx(1)))
        .light_line_style(TRANSPARENT)
        .axis_style(ShapeStyle::from(BLACK.mix(0.8)).stroke_width(s.upx(1)))
        .draw()?;

    for (k, ser) in panel.series.iter().enumerate() {
        let style = PALETTE[k % PALETTE.len()].stroke_width(line_width);
        let (lines, points): (Vec<_>, Vec<_>) =
            finite_runs(ser).into_iter().partition(|r| r.len() > 1);
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
        let radius = line_width.max(s.upx(2));
        chart.draw_series(
            points
                .into_iter()
                .map(|p| Circle::new(p[0], radius, style.filled())),
        )?;
    }

    // Text, in area coordinates.
    let (bx, by) = area.get_base_pixel();
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    let (left, right, top, bottom) = (xr.start - bx, xr.end - bx, yr.start - by, yr.end - by);
    let tick_len = s.px(TICK_LEN);
    let tick_cap = metrics.cap_height(f64::from(s.px(TICK_SIZE))).round() as i32;
    for &v in &x_ticks {
        let (px, _) = chart.backend_coord(&(v, y0));
        let at = (px - bx, bottom + tick_len + s.px(6) + tick_cap / 2);
        draw_text(
            area,
            metrics,
            &format_tick(v, x_span),
            s.px(TICK_SIZE),
            at,
            Align::Center,
            false,
        )?;
    }
    for (&v, label) in y_ticks.iter().zip(&y_tick_labels) {
        let (_, py) = chart.backend_coord(&(x0, v));
        let at = (left - tick_len - s.px(6), py - by);
        draw_text(area, metrics, label, s.px(TICK_SIZE), at, Align::End, false)?;
    }
    let x_mid = (left + right) / 2;
    let x_desc_at = (x_mid, bottom + s.px(X_LABEL_AREA - 10) - desc_cap / 2);
    draw_text(
        area,
        metrics,
        x_label,
        s.px(AXIS_DESC_SIZE),
        x_desc_at,
        Align::Center,
        false,
    )?;
    if !panel.y_label.is_empty() {
        let at = (
            left - tick_len - s.px(6) - tick_width - s.px(12) - desc_cap / 2,
            (top + bottom) / 2,
        );
        draw_text(
            area,
            metrics,
            &panel.y_label,
            s.px(AXIS_DESC_SIZE),
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
            s.px(TITLE_SIZE),
            (x_mid, top / 2 + s.px(2)),
            Align::Center,
            false,
        )?;
    }
    if !legend.entries.is_empty() {
        let inset = s.px(LEGEND_INSET);
        let placed = Frame {
            width: right - left,
            height: bottom - top,
            x: (x0, x1),
            y: (y0, y1),
        };
        let [lx, ly, _, _] = placed.legend_box(corner, &legend, inset);
        legend.draw(area, metrics, (left + lx, top + ly), s)?;
    }
    Ok(())
}
