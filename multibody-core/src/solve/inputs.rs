//! Input signals: functions of time (closures or tables) that drive the model's inputs
//! (see [`SimplifyOptions::inputs`](crate::simplify::SimplifyOptions::inputs)) during a
//! solve, set into the input's parameter slot wherever the compiled functions are
//! evaluated at a time.

use std::fmt;
use std::sync::Arc;

use crate::codegen::EvalError;
use crate::codegen::dae::InputLayout;

/// A function of time that drives an input of the model: a closure, or a table of
/// `(time, value)` points interpolated linearly (holding the first and last values
/// outside it; two points at one time make a jump, the later one holding from that time
/// on).
///
/// ```
/// use multibody_core::solve::InputSignal;
///
/// let ramp = InputSignal::table(vec![(0.0, 0.0), (1.0, 2.0), (1.0, -1.0)]);
/// assert_eq!(ramp.value(0.25), 0.5);
/// assert_eq!(ramp.value(1.0), -1.0);
/// assert_eq!(ramp.value(5.0), -1.0);
/// let wave = InputSignal::new(|t: f64| (2.0 * t).sin());
/// assert_eq!(wave.value(0.0), 0.0);
/// ```
#[derive(Clone)]
pub struct InputSignal(Signal);

#[derive(Clone)]
enum Signal {
    Function(Arc<dyn Fn(f64) -> f64 + Send + Sync>),
    Table(Arc<[(f64, f64)]>),
}

impl InputSignal {
    /// The signal `f(t)`.
    pub fn new(f: impl Fn(f64) -> f64 + Send + Sync + 'static) -> Self {
        InputSignal(Signal::Function(Arc::new(f)))
    }

    /// The table `points` (`(time, value)`, times non-decreasing; checked when a problem
    /// is built with it).
    pub fn table(points: Vec<(f64, f64)>) -> Self {
        InputSignal(Signal::Table(points.into()))
    }

    /// The signal's value at `t`.
    pub fn value(&self, t: f64) -> f64 {
        match &self.0 {
            Signal::Function(f) => f(t),
            Signal::Table(points) => interpolate(points, t),
        }
    }

    /// What is wrong with the signal, if anything (a table that is empty, not finite or
    /// not ordered in time).
    pub(crate) fn check(&self) -> Result<(), String> {
        let Signal::Table(points) = &self.0 else {
            return Ok(());
        };
        if points.is_empty() {
            return Err("its table is empty".into());
        }
        if let Some((t, v)) = points
            .iter()
            .find(|(t, v)| !(t.is_finite() && v.is_finite()))
        {
            return Err(format!(
                "its table has the point ({t}, {v}), which is not finite"
            ));
        }
        if let Some(w) = points.windows(2).find(|w| w[1].0 < w[0].0) {
            return Err(format!(
                "the times of its table decrease (from {} to {})",
                w[0].0, w[1].0
            ));
        }
        Ok(())
    }
}

impl fmt::Debug for InputSignal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0 {
            Signal::Function(_) => f.write_str("InputSignal(function)"),
            Signal::Table(points) => write!(f, "InputSignal(table of {} points)", points.len()),
        }
    }
}

/// `points` at `t`: linear between the two points around it, the end values outside.
fn interpolate(points: &[(f64, f64)], t: f64) -> f64 {
    let k = points.partition_point(|p| p.0 <= t);
    match k {
        0 => points.first().map_or(f64::NAN, |p| p.1),
        k if k == points.len() => points[k - 1].1,
        k => {
            let ((t0, v0), (t1, v1)) = (points[k - 1], points[k]);
            v0 + (v1 - v0) * (t - t0) / (t1 - t0)
        }
    }
}

/// The signals that drive a problem's inputs: per driven input, its parameter and name.
#[derive(Clone, Default)]
pub(crate) struct Drivers(Arc<[Driver]>);

struct Driver {
    param: usize,
    name: String,
    signal: InputSignal,
}

impl fmt::Debug for Drivers {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list()
            .entries(self.0.iter().map(|d| (&d.name, &d.signal)))
            .finish()
    }
}

impl Drivers {
    /// Drivers of the parameters `(param, name, signal)`.
    pub(crate) fn new(drivers: Vec<(usize, String, InputSignal)>) -> Self {
        Drivers(
            drivers
                .into_iter()
                .map(|(param, name, signal)| Driver {
                    param,
                    name,
                    signal,
                })
                .collect(),
        )
    }

    /// Sets the driven parameters of `params` to their values at `t`; an error names an
    /// input whose value is not finite.
    pub(crate) fn apply(&self, t: f64, params: &mut [f64]) -> Result<(), EvalError> {
        for d in self.0.iter() {
            if let Some(p) = params.get_mut(d.param) {
                *p = d.value(t)?;
            }
        }
        Ok(())
    }

    /// Sets the driven parameters' slots of a compiled function's `inputs` (laid out by
    /// `layout`) to their values at `t`.
    pub(crate) fn load(
        &self,
        t: f64,
        inputs: &mut [f64],
        layout: InputLayout,
    ) -> Result<(), EvalError> {
        for d in self.0.iter() {
            inputs[layout.param(d.param)] = d.value(t)?;
        }
        Ok(())
    }
}

impl Driver {
    fn value(&self, t: f64) -> Result<f64, EvalError> {
        let v = self.signal.value(t);
        if v.is_finite() {
            Ok(v)
        } else {
            Err(EvalError {
                message: format!("the input `{}` is {v} at t = {t}", self.name),
                // A shorter step may not reach the time where the signal fails.
                recoverable: true,
            })
        }
    }
}
