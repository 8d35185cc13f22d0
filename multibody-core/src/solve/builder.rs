//! [`ProblemBuilder`]: a problem's values and guesses named by typed handles or by
//! text, one at a time.

use crate::Error;
use crate::model::Named;
use crate::simplify::SimplifiedSystem;

use super::error::InitError;
use super::inputs::{Drivers, InputSignal};
use super::problem::DaeProblem;

/// Collects the values and guesses of a [`DaeProblem`], each named by a typed handle's
/// field (`m.j1.phi`) or by its path (`"j1.phi"`); [`build`](Self::build) runs
/// [`DaeProblem::new_with_guesses`].
///
/// ```
/// use multibody_core::model::System;
/// use multibody_core::simplify::structural_simplify;
/// use multibody_core::solve::{DaeProblem, SolverOptions};
///
/// // x'' = -k x
/// let mut sys = System::new("oscillator");
/// let (x, v) = (sys.var("x"), sys.var("v"));
/// let k = sys.param("k", 4.0);
/// sys.equation(x.der(), v);
/// sys.equation(v.der(), -k * x);
/// let ssys = structural_simplify(&sys)?;
/// let problem = DaeProblem::builder(&ssys, (0.0, 1.0))
///     .value(x, 0.5) // a start value, fixed (a variable's handle)
///     .value("k", 9.0) // a parameter (by name)
///     .build()?;
/// let sol = problem.solve(&SolverOptions::default())?;
/// // x = 0.5 cos(3 t)
/// assert!((sol.final_value(x)? - 0.5 * 3.0f64.cos()).abs() < 1e-4);
/// # Ok::<(), multibody_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct ProblemBuilder<'a> {
    sys: &'a SimplifiedSystem,
    tspan: (f64, f64),
    values: Vec<(String, f64)>,
    guesses: Vec<(String, f64)>,
    inputs: Vec<(String, InputSignal)>,
}

impl<'a> ProblemBuilder<'a> {
    /// A problem of `sys` over `tspan` with the model's defaults.
    pub fn new(sys: &'a SimplifiedSystem, tspan: (f64, f64)) -> Self {
        ProblemBuilder {
            sys,
            tspan,
            values: Vec::new(),
            guesses: Vec::new(),
            inputs: Vec::new(),
        }
    }

    /// Sets a parameter, or a variable's start value and makes it fixed (an initial
    /// condition), as in [`DaeProblem::new`].
    pub fn value(mut self, name: impl Named, value: f64) -> Self {
        self.values.push((name.name().into_owned(), value));
        self
    }

    /// Sets several values (see [`value`](Self::value)).
    pub fn values<N: Named>(mut self, values: &[(N, f64)]) -> Self {
        for (n, v) in values {
            self.values.push((n.name().into_owned(), *v));
        }
        self
    }

    /// An iteration guess for a variable: used by the initialization's Newton
    /// iterations only, not fixed.
    pub fn guess(mut self, name: impl Named, value: f64) -> Self {
        self.guesses.push((name.name().into_owned(), value));
        self
    }

    /// Drives an input of the model (see
    /// [`SimplifyOptions::inputs`](crate::simplify::SimplifyOptions::inputs)) by the
    /// function of time `f` during the solve (a constant input is a
    /// [`value`](Self::value)).
    pub fn input(self, name: impl Named, f: impl Fn(f64) -> f64 + Send + Sync + 'static) -> Self {
        self.input_signal(name, InputSignal::new(f))
    }

    /// Drives an input of the model by `signal` (a function or a table).
    pub fn input_signal(mut self, name: impl Named, signal: InputSignal) -> Self {
        self.inputs.push((name.name().into_owned(), signal));
        self
    }

    /// Checks the values, guesses and inputs and runs the initialization.
    pub fn build(self) -> Result<DaeProblem<'a>, Error> {
        let values: Vec<(&str, f64)> = self.values.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        let guesses: Vec<(&str, f64)> =
            self.guesses.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        let drivers = drivers(self.sys, &self.inputs, &self.values)?;
        DaeProblem::new_driven(self.sys, &values, &guesses, self.tspan, drivers)
    }
}

impl<'a> DaeProblem<'a> {
    /// A [`ProblemBuilder`] of `sys` over `tspan`: values and guesses by typed handle.
    pub fn builder(sys: &'a SimplifiedSystem, tspan: (f64, f64)) -> ProblemBuilder<'a> {
        ProblemBuilder::new(sys, tspan)
    }
}

/// The drivers of `inputs` (each an input of `sys`, driven once and given no value).
fn drivers(
    sys: &SimplifiedSystem,
    inputs: &[(String, InputSignal)],
    values: &[(String, f64)],
) -> Result<Drivers, Error> {
    let bad = |message: String| -> Error {
        InitError::BadValue {
            model: sys.model.name.clone(),
            message,
        }
        .into()
    };
    let names = sys.inputs();
    let mut out: Vec<(usize, String, InputSignal)> = Vec::with_capacity(inputs.len());
    for (name, signal) in inputs {
        let Some(k) = names.iter().position(|n| n == name) else {
            let what = if names.is_empty() {
                "the model has no inputs (SimplifyOptions::inputs names them)".to_string()
            } else {
                format!("its inputs are {}", crate::names::list(&names, 12))
            };
            return Err(bad(format!(
                "`{name}` is not an input of the model: {what}"
            )));
        };
        if out.iter().any(|(_, n, _)| n == name) {
            return Err(bad(format!("the input `{name}` is driven twice")));
        }
        if values.iter().any(|(n, _)| n == name) {
            return Err(bad(format!(
                "the input `{name}` is given both a value and a signal"
            )));
        }
        signal
            .check()
            .map_err(|m| bad(format!("the signal of the input `{name}`: {m}")))?;
        out.push((sys.model.inputs[k], name.clone(), signal.clone()));
    }
    Ok(Drivers::new(out))
}
