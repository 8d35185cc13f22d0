//! Plots of solutions: variables by name or handle against time, one figure of one or
//! more panels, each optionally overlaying several solutions.

use std::path::Path;

use crate::Error;
use crate::model::Named;
use crate::solve::Solution;

use super::{Panel, PlotOptions, Series, plot_panels};

/// Plots variables of `sol` against time in one panel, written as a PNG; the y axis
/// is labelled with their unit.
///
/// ```no_run
/// # fn f(sol: &multibody_core::solve::Solution) -> Result<(), multibody_core::Error> {
/// multibody_core::plot::plot(sol, &["j1.phi", "j2.phi"], "angles.png")?;
/// # Ok(()) }
/// ```
pub fn plot<N: Named>(sol: &Solution, names: &[N], path: impl AsRef<Path>) -> Result<(), Error> {
    plot_figure(sol, &[names], path, &PlotOptions::default())
}

/// Plots several panels (each a list of variables), like Julia's
/// `plot(plot(sol, idxs=[...]), plot(sol, idxs=[...]))`.
pub fn plot_figure<N: Named>(
    sol: &Solution,
    panels: &[&[N]],
    path: impl AsRef<Path>,
    options: &PlotOptions,
) -> Result<(), Error> {
    let mut figure = Figure::new().options(options.clone());
    for names in panels {
        figure = figure.panel(sol, names);
    }
    figure.save(path)
}

/// A figure built panel by panel: variables of one or more solutions against time,
/// what Multibody.jl users draw with `plot` and `plot!`.
///
/// [`panel`](Self::panel) starts a panel, [`overlay`](Self::overlay) draws another
/// solution's curves in it with a label in their legend entries; the y axis is labelled
/// with the variables' unit. Errors (an unknown name) are reported by
/// [`save`](Self::save).
///
/// ```no_run
/// # use multibody_core::plot::Figure;
/// # fn f(damped: &multibody_core::solve::Solution, free: &multibody_core::solve::Solution)
/// # -> Result<(), multibody_core::Error> {
/// Figure::new()
///     .panel(damped, &["j1.phi"])
///     .overlay(free, &["j1.phi"], "without damping")
///     .title("Angle of the first joint")
///     .save("compare.png")?;
/// # Ok(()) }
/// ```
#[derive(Debug, Default)]
pub struct Figure {
    panels: Vec<Panel>,
    /// Per panel, the unit of each series (for the axis label).
    units: Vec<Vec<Option<String>>>,
    options: PlotOptions,
    title: Option<String>,
    error: Option<Error>,
}

impl Figure {
    /// An empty figure with the default options.
    pub fn new() -> Self {
        Figure::default()
    }

    /// Sets the figure's options (size, columns, line width, title).
    pub fn options(mut self, options: PlotOptions) -> Self {
        self.options = options;
        self
    }

    /// Starts a panel with variables of `sol`, each labelled with its name.
    pub fn panel<N: Named>(mut self, sol: &Solution, names: &[N]) -> Self {
        self.panels.push(Panel {
            x_label: "t [s]".into(),
            ..Panel::default()
        });
        self.units.push(Vec::new());
        self.add(sol, names, None);
        self
    }

    /// Starts a panel with variables of `sol`, each labelled `name (label)`: the first
    /// of several solutions compared in a panel, the others added with
    /// [`overlay`](Self::overlay).
    pub fn labelled_panel<N: Named>(mut self, sol: &Solution, names: &[N], label: &str) -> Self {
        self = self.panel::<&str>(sol, &[]);
        self.add(sol, names, Some(label));
        self
    }

    /// Adds variables of another solution to the last panel (the first one when there
    /// is none yet), each labelled `name (label)`.
    pub fn overlay<N: Named>(mut self, sol: &Solution, names: &[N], label: &str) -> Self {
        if self.panels.is_empty() {
            self = self.panel::<&str>(sol, &[]);
        }
        self.add(sol, names, Some(label));
        self
    }

    /// The figure's title, in a band over all panels (kept when [`Figure::options`] is
    /// called later).
    pub fn title(mut self, title: impl Into<String>) -> Self {
        self.title = Some(title.into());
        self
    }

    /// The title of the last panel (drawn over it).
    pub fn panel_title(mut self, title: impl Into<String>) -> Self {
        if let Some(p) = self.panels.last_mut() {
            p.title = Some(title.into());
        }
        self
    }

    /// The y-axis label of the last panel, instead of its unit.
    pub fn y_label(mut self, label: impl Into<String>) -> Self {
        if let Some(p) = self.panels.last_mut() {
            p.y_label = label.into();
        }
        if let Some(u) = self.units.last_mut() {
            u.clear();
        }
        self
    }

    /// The panels as drawn (units as axis labels), for [`plot_panels`].
    pub fn into_panels(mut self) -> Result<Vec<Panel>, Error> {
        if let Some(e) = self.error {
            return Err(e);
        }
        for (panel, units) in self.panels.iter_mut().zip(&self.units) {
            if panel.y_label.is_empty() {
                label_units(panel, units);
            }
        }
        Ok(self.panels)
    }

    /// Draws the figure into a PNG at `path`.
    pub fn save(self, path: impl AsRef<Path>) -> Result<(), Error> {
        let mut options = self.options.clone();
        if self.title.is_some() {
            options.title.clone_from(&self.title);
        }
        let panels = self.into_panels()?;
        plot_panels(&panels, path.as_ref(), &options)?;
        Ok(())
    }

    /// Appends series of `sol` to the last panel.
    fn add<N: Named>(&mut self, sol: &Solution, names: &[N], label: Option<&str>) {
        if self.error.is_some() || names.is_empty() {
            return;
        }
        let values = match sol.get_many(names) {
            Ok(v) => v,
            Err(e) => {
                self.error = Some(e.into());
                return;
            }
        };
        let (panel, units) = match (self.panels.last_mut(), self.units.last_mut()) {
            (Some(p), Some(u)) => (p, u),
            _ => return,
        };
        for (n, y) in names.iter().zip(values) {
            let name = n.name();
            panel.series.push(Series {
                label: match label {
                    Some(l) => format!("{name} ({l})"),
                    None => name.to_string(),
                },
                t: sol.t().to_vec(),
                y,
            });
            units.push(sol.unit(&*name));
        }
    }
}

/// Labels a panel's y axis with its series' unit: `[rad]` when they share one; when
/// they differ, each legend entry gets its unit and the axis lists them.
fn label_units(panel: &mut Panel, units: &[Option<String>]) {
    let mut distinct: Vec<&str> = Vec::new();
    for u in units.iter().flatten() {
        if !distinct.contains(&u.as_str()) {
            distinct.push(u);
        }
    }
    match distinct.as_slice() {
        [] => {}
        [one] if units.iter().all(Option::is_some) => panel.y_label = format!("[{one}]"),
        _ => {
            for (s, u) in panel.series.iter_mut().zip(units) {
                if let Some(u) = u {
                    s.label = format!("{} [{u}]", s.label);
                }
            }
            panel.y_label = format!("[{}]", distinct.join(", "));
        }
    }
}
