//! Plots of solutions: variables by name against time.

use std::path::Path;

use crate::Error;
use crate::solve::Solution;

use super::{Panel, PlotOptions, Series, plot_panels};

/// Plots the named variables of `sol` against time in one panel, written as a PNG.
pub fn plot(sol: &Solution, names: &[&str], path: impl AsRef<Path>) -> Result<(), Error> {
    plot_figure(sol, &[names], path, &PlotOptions::default())
}

/// Plots several panels side by side (each a list of variable names), like Julia's
/// `plot(plot(sol, idxs=[...]), plot(sol, idxs=[...]))`.
pub fn plot_figure(
    sol: &Solution,
    panels: &[&[&str]],
    path: impl AsRef<Path>,
    options: &PlotOptions,
) -> Result<(), Error> {
    let mut out = Vec::with_capacity(panels.len());
    for names in panels {
        let values = sol.get_many(names)?;
        let series = names
            .iter()
            .zip(values)
            .map(|(n, y)| Series {
                label: n.to_string(),
                t: sol.t().to_vec(),
                y,
            })
            .collect();
        out.push(Panel {
            title: None,
            x_label: "t [s]".into(),
            y_label: String::new(),
            series,
        });
    }
    plot_panels(&out, path.as_ref(), options)?;
    Ok(())
}
