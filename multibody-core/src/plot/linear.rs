//! Plots of linear models: a Bode diagram of one input-output pair and the poles in the
//! complex plane.

use std::path::Path;

use super::{Panel, PlotError, PlotOptions, Series, plot_panels};
use crate::solve::LinearModel;

/// Writes the Bode diagram (magnitude in dB and phase in degrees over log10 of the
/// angular frequency) of input `input` to output `output` of `lin`, at `points`
/// frequencies spread logarithmically over `range` \[rad/s\], to the PNG at `path`.
pub fn plot_bode(
    lin: &LinearModel,
    (input, output): (usize, usize),
    range: (f64, f64),
    points: usize,
    path: impl AsRef<Path>,
) -> Result<(), PlotError> {
    let (lo, hi) = (range.0.max(f64::MIN_POSITIVE).log10(), range.1.log10());
    let n = points.max(2);
    let mut x = Vec::with_capacity(n);
    let (mut magnitude, mut phase) = (Vec::with_capacity(n), Vec::with_capacity(n));
    let mut unwrap = 0.0;
    let mut last: Option<f64> = None;
    for k in 0..n {
        let e = lo + (hi - lo) * k as f64 / (n - 1) as f64;
        let w = 10f64.powf(e);
        x.push(e);
        match lin.frequency_response(w) {
            Some(h) if input < h.ncols() && output < h.nrows() => {
                let g = h[(output, input)];
                magnitude.push(20.0 * g.norm().log10());
                let mut p = g.arg().to_degrees() + unwrap;
                if let Some(l) = last {
                    while p - l > 180.0 {
                        p -= 360.0;
                        unwrap -= 360.0;
                    }
                    while p - l < -180.0 {
                        p += 360.0;
                        unwrap += 360.0;
                    }
                }
                last = Some(p);
                phase.push(p);
            }
            _ => {
                magnitude.push(f64::NAN);
                phase.push(f64::NAN);
            }
        }
    }
    let label = format!(
        "{} -> {}",
        lin.inputs.get(input).map_or("?", String::as_str),
        lin.outputs.get(output).map_or("?", String::as_str)
    );
    let panel = |y: Vec<f64>, y_label: &str| Panel {
        title: None,
        x_label: "log10 w [rad/s]".into(),
        y_label: y_label.into(),
        series: vec![Series {
            label: label.clone(),
            t: x.clone(),
            y,
        }],
    };
    plot_panels(
        &[
            panel(magnitude, "magnitude [dB]"),
            panel(phase, "phase [deg]"),
        ],
        path.as_ref(),
        &PlotOptions {
            columns: 1,
            title: Some("Bode diagram".into()),
            ..PlotOptions::default()
        },
    )
}

/// Writes the poles of `lin` in the complex plane (each a cross) to the PNG at `path`.
pub fn plot_poles(lin: &LinearModel, path: impl AsRef<Path>) -> Result<(), PlotError> {
    let poles = lin.eigenvalues();
    let scale = poles.iter().map(|p| p.norm()).fold(0.0, f64::max).max(1e-3);
    let d = 0.03 * scale;
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for p in &poles {
        for (dx, dy) in [(-d, -d), (d, d)] {
            x.push(p.re + dx);
            y.push(p.im + dy);
        }
        x.push(f64::NAN);
        y.push(f64::NAN);
        for (dx, dy) in [(-d, d), (d, -d)] {
            x.push(p.re + dx);
            y.push(p.im + dy);
        }
        x.push(f64::NAN);
        y.push(f64::NAN);
    }
    // The axes through the origin.
    let axes = Series {
        label: String::new(),
        t: vec![-scale * 1.2, scale * 1.2, f64::NAN, 0.0, 0.0],
        y: vec![0.0, 0.0, f64::NAN, -scale * 1.2, scale * 1.2],
    };
    plot_panels(
        &[Panel {
            title: Some("poles".into()),
            x_label: "Re [1/s]".into(),
            y_label: "Im [1/s]".into(),
            series: vec![
                axes,
                Series {
                    label: "poles".into(),
                    t: x,
                    y,
                },
            ],
        }],
        path.as_ref(),
        &PlotOptions::default(),
    )
}
