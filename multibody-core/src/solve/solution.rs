//! The solution of a DAE problem: any variable of the model by name, at the output
//! times or interpolated at any time, and CSV export.

use std::io::Write;
use std::path::Path;
use std::sync::Arc;

use crate::codegen::Tape;
use crate::codegen::dae::InputLayout;
use crate::model::{Named, SharedText, Variable};
use crate::names::NameIndex;

use super::error::SolutionError;
use super::ida::IdaStats;
use super::problem::InitReport;

/// A solution: the unknowns and their derivatives at the reported times, and the
/// compiled observed function that gives every other variable from them.
#[derive(Clone, Debug)]
pub struct Solution {
    model: String,
    observed: Arc<Tape>,
    /// Names of the observed outputs and their lookup, shared with the compiled system.
    names: Arc<NameIndex>,
    layout: InputLayout,
    /// Names of the tunable parameters (the order of the segments' values), shared
    /// likewise.
    parameter_names: Arc<NameIndex>,
    /// Names of the unknowns (whose derivatives are `der(name)`), shared likewise.
    unknown_names: Arc<NameIndex>,
    /// The model's variables (their units), shared likewise.
    variables: Arc<Vec<Variable>>,
    /// The unit of each tunable parameter, in the order of `parameter_names`.
    parameter_units: Vec<SharedText>,
    differential: Vec<bool>,
    t: Vec<f64>,
    u: Vec<f64>,
    up: Vec<f64>,
    /// Stretches of the points with their parameter values (several where dynamic state
    /// selection changed its selection parameters), in order.
    segments: Vec<Segment>,
    stats: IdaStats,
    init: InitReport,
    events: Vec<Event>,
    terminated: Option<Termination>,
    /// The signals that drove the model's inputs.
    drivers: super::inputs::Drivers,
}

/// Where and why a `terminate(..)` of the model ended the simulation.
#[derive(Clone, Debug, PartialEq)]
pub struct Termination {
    /// When \[s\].
    pub t: f64,
    /// The message, with the path of the component that terminated.
    pub message: String,
}

/// An event of a solution: a relation of the model that changed its value. The
/// solution holds the left and the right limit at its time (two points, the first
/// ending one segment and the second starting the next).
#[derive(Clone, Debug, PartialEq)]
pub struct Event {
    /// When \[s\].
    pub t: f64,
    /// The relation, as written in the model (`ball.h < 0`).
    pub condition: String,
    /// Its value from the event on.
    pub value: bool,
    /// Whether its crossing function (`lhs - rhs`) rose through zero (else it fell, or
    /// the relation changed during the event iteration, without a crossing of its own).
    pub rising: bool,
}

/// A stretch of a solution's points computed with the same parameter values.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// The first point of the segment (the previous one ends just before it; two
    /// segments meet at a time that both hold, the left and the right limit).
    pub first: usize,
    /// The parameter values.
    pub params: Vec<f64>,
}

/// What a solution is made of (see [`Solution::new`]).
pub(crate) struct SolutionParts {
    /// The model's name.
    pub model: String,
    /// The compiled observed function.
    pub observed: Arc<Tape>,
    /// The names of its outputs.
    pub names: Arc<NameIndex>,
    /// The layout of its inputs.
    pub layout: InputLayout,
    /// The names of the tunable parameters.
    pub parameter_names: Arc<NameIndex>,
    /// The names of the unknowns.
    pub unknown_names: Arc<NameIndex>,
    /// The model's variables.
    pub variables: Arc<Vec<Variable>>,
    /// The unit of each tunable parameter.
    pub parameter_units: Vec<SharedText>,
    /// Per unknown: whether it is differential (interpolated by cubic Hermite).
    pub differential: Vec<bool>,
    /// The reported times, unknowns and derivatives (point-major).
    pub t: Vec<f64>,
    /// Unknowns.
    pub u: Vec<f64>,
    /// Their derivatives.
    pub up: Vec<f64>,
    /// Segments (at least one, the first starting at point 0).
    pub segments: Vec<Segment>,
    /// Integrator statistics.
    pub stats: IdaStats,
    /// What the initialization did.
    pub init: InitReport,
    /// The events, in time order.
    pub events: Vec<Event>,
    /// Where a `terminate(..)` ended the run.
    pub terminated: Option<Termination>,
    /// The signals that drove the model's inputs.
    pub drivers: super::inputs::Drivers,
}

impl Solution {
    pub(crate) fn new(p: SolutionParts) -> Solution {
        debug_assert!(p.segments.first().is_some_and(|s| s.first == 0));
        Solution {
            model: p.model,
            observed: p.observed,
            names: p.names,
            layout: p.layout,
            parameter_names: p.parameter_names,
            unknown_names: p.unknown_names,
            variables: p.variables,
            parameter_units: p.parameter_units,
            differential: p.differential,
            t: p.t,
            u: p.u,
            up: p.up,
            segments: p.segments,
            stats: p.stats,
            init: p.init,
            events: p.events,
            terminated: p.terminated,
            drivers: p.drivers,
        }
    }

    /// Where and why a `terminate(..)` of the model ended the run before the final
    /// time (the solution then ends there); `None` when it ran to the end.
    pub fn terminated(&self) -> Option<&Termination> {
        self.terminated.as_ref()
    }

    /// The events of the run (relations that changed their value), in time order.
    pub fn events(&self) -> &[Event] {
        &self.events
    }

    /// The stretches of points computed with the same parameter values: one, unless
    /// events or dynamic state selection changed them during the run.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// The segment of point `k`.
    fn segment_of(&self, k: usize) -> usize {
        self.segments
            .partition_point(|s| s.first <= k)
            .saturating_sub(1)
    }

    /// The model's name.
    pub fn model(&self) -> &str {
        &self.model
    }

    /// The reported times (the initial time first, the final time last).
    pub fn t(&self) -> &[f64] {
        &self.t
    }

    /// Names of every variable the solution can give.
    pub fn names(&self) -> &[SharedText] {
        self.names.names()
    }

    /// Integrator statistics.
    pub fn statistics(&self) -> &IdaStats {
        &self.stats
    }

    /// What the initialization assumed.
    pub fn init_report(&self) -> &InitReport {
        &self.init
    }

    /// The unknowns `u` at reported point `k` (`None` past the last point).
    pub fn unknowns_at(&self, k: usize) -> Option<&[f64]> {
        let n = self.layout.n;
        if k >= self.t.len() {
            return None;
        }
        self.u.get(k * n..(k + 1) * n)
    }

    /// The value of the tunable parameter `name` in this solution: its default, the
    /// problem's override, or the value computed at initialization (a rod length).
    pub fn parameter(&self, name: impl Named) -> Result<f64, SolutionError> {
        let name = name.name();
        let name: &str = &name;
        self.parameter_names
            .position(name)
            .and_then(|k| self.segments[0].params.get(k).copied())
            .ok_or_else(|| SolutionError::UnknownParameter {
                name: name.to_string(),
                suggestions: self.parameter_names.closest(name, 3),
            })
    }

    /// Where `name`'s values are in the buffer [`Self::evaluate`] fills: an output of the
    /// observed function; past those, the derivative of a differential unknown,
    /// `der(x)`; past those, a tunable parameter (constant within a segment); last,
    /// `time`.
    fn lookup(&self, name: &str) -> Result<usize, SolutionError> {
        if let Some(i) = self.names.position(name) {
            return Ok(i);
        }
        if name == "time" {
            return Ok(self.out_len() - 1);
        }
        let outputs = self.observed.n_outputs();
        let derivative = derivative_of(name);
        if let Some(inner) = derivative
            && let Some(k) = self.unknown_names.position(inner)
            && self.differential.get(k) == Some(&true)
        {
            return Ok(outputs + k);
        }
        if let Some(j) = self.parameter_names.position(name)
            && j < self.layout.n_params
        {
            return Ok(outputs + self.layout.n + j);
        }
        let suggestions = match derivative {
            Some(inner) => {
                let states = self
                    .unknown_names
                    .names()
                    .iter()
                    .zip(&self.differential)
                    .filter(|(_, d)| **d)
                    .map(|(n, _)| &**n);
                crate::names::closest(inner, states, 3)
                    .into_iter()
                    .map(|n| format!("der({n})"))
                    .collect()
            }
            None => {
                let variables = self.names.names().iter().map(|s| &**s);
                let parameters = self.parameter_names.names().iter().map(|s| &**s);
                crate::names::closest(name, variables.chain(parameters), 3)
            }
        };
        Err(SolutionError::UnknownVariable {
            name: name.to_string(),
            suggestions,
        })
    }

    /// The unit of a variable or tunable parameter as declared (`"rad"`, `"m/s"`; for
    /// `der(x)`, x's unit per second), or `None` when it declares none.
    pub fn unit(&self, name: impl Named) -> Option<String> {
        let name = name.name();
        let (inner, per_second) = match derivative_of(&name) {
            Some(inner) => (inner, true),
            None => (&*name, false),
        };
        let unit: &str = match self.variables.iter().find(|v| &*v.name == inner) {
            Some(v) => &v.unit,
            None => {
                let j = self.parameter_names.position(inner)?;
                self.parameter_units.get(j)?
            }
        };
        if unit.is_empty() {
            return None;
        }
        Some(if per_second {
            per_second_unit(unit)
        } else {
            unit.to_string()
        })
    }

    /// Evaluates the observed function at `t`: `Err` with the reason when it fails.
    fn evaluate(
        &self,
        t: f64,
        u: &[f64],
        up: &[f64],
        ws: &mut crate::codegen::Workspace,
        inputs: &mut [f64],
        out: &mut [f64],
    ) -> Result<(), String> {
        let n = self.layout.n;
        inputs[InputLayout::TIME] = t;
        if n > 0 {
            let u0 = self.layout.u(0);
            inputs[u0..u0 + n].copy_from_slice(u);
            let up0 = self.layout.up(0);
            inputs[up0..up0 + n].copy_from_slice(up);
        }
        let outputs = self.observed.n_outputs();
        if let Err(e) = self.drivers.load(t, inputs, self.layout) {
            out.iter_mut().for_each(|v| *v = f64::NAN);
            return Err(e.message);
        }
        out[outputs..outputs + n].copy_from_slice(up);
        for j in 0..self.layout.n_params {
            out[outputs + n + j] = inputs[self.layout.param(j)];
        }
        out[outputs + n + self.layout.n_params] = t;
        self.observed
            .eval(inputs, ws, &mut out[..outputs])
            .map_err(|e| {
                out[..outputs].iter_mut().for_each(|v| *v = f64::NAN);
                e.message
            })
    }

    /// The length of the buffer [`Self::evaluate`] fills: the observed outputs, the
    /// derivatives of the unknowns, the parameters and the time.
    fn out_len(&self) -> usize {
        self.observed.n_outputs() + self.layout.n + self.layout.n_params + 1
    }

    /// Outputs `idx` of an evaluation at `t` (`result` of [`Self::evaluate`]) appended
    /// to `series`; an error names the first that is not finite.
    fn collect(
        &self,
        idx: &[usize],
        names: &[&str],
        t: f64,
        out: &[f64],
        result: Result<(), String>,
        series: &mut [Vec<f64>],
    ) -> Result<(), SolutionError> {
        for (k, (s, &i)) in series.iter_mut().zip(idx).enumerate() {
            let v = out[i];
            if !v.is_finite() {
                return Err(SolutionError::NotFinite {
                    name: names[k].to_string(),
                    t,
                    value: v,
                    reason: result.err(),
                });
            }
            s.push(v);
        }
        Ok(())
    }

    /// The inputs of the observed function with the parameter values of segment `seg`.
    fn inputs(&self, seg: usize) -> Vec<f64> {
        let mut inputs = vec![0.0; self.layout.len()];
        self.set_params(seg, &mut inputs);
        inputs
    }

    fn set_params(&self, seg: usize, inputs: &mut [f64]) {
        let params = &self.segments[seg].params;
        for (j, &p) in params.iter().enumerate().take(self.layout.n_params) {
            inputs[self.layout.param(j)] = p;
        }
    }

    /// The values of a variable (a path, `"j1.phi"` or `"der(j1.w)"`, or a handle's
    /// field, `model.j1.phi`) at the reported times.
    ///
    /// Every variable of the model can be read, every tunable parameter (constant), and
    /// `time` (the reported times, as [`Solution::t`]).
    /// Derivatives `der(x)` can be read where the model computes them: for the states
    /// and the other unknowns the integrator differentiates, for variables defined as
    /// derivatives (`w = der(phi)` makes `der(phi)` readable), for the derivatives index
    /// reduction introduced, and for aliases of all these (`x = ±y + parameters`). Other
    /// derivatives are an error that lists the closest readable names.
    pub fn get(&self, name: impl Named) -> Result<Vec<f64>, SolutionError> {
        Ok(self.get_many(&[name])?.pop().expect("one series"))
    }

    /// The values of several variables at the reported times (one evaluation of the
    /// observed function per time for all of them).
    pub fn get_many<N: Named>(&self, names: &[N]) -> Result<Vec<Vec<f64>>, SolutionError> {
        let names = crate::model::names(names);
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let idx: Vec<usize> = names
            .iter()
            .map(|n| self.lookup(n))
            .collect::<Result<_, _>>()?;
        let n = self.layout.n;
        let mut ws = self.observed.workspace();
        let mut seg = 0;
        let mut inputs = self.inputs(seg);
        let mut out = vec![0.0; self.out_len()];
        let mut series = vec![Vec::with_capacity(self.t.len()); names.len()];
        for (k, &t) in self.t.iter().enumerate() {
            if self.segments.get(seg + 1).is_some_and(|s| s.first <= k) {
                seg = self.segment_of(k);
                self.set_params(seg, &mut inputs);
            }
            let (u, up) = (&self.u[k * n..(k + 1) * n], &self.up[k * n..(k + 1) * n]);
            let r = self.evaluate(t, u, up, &mut ws, &mut inputs, &mut out);
            self.collect(&idx, &names, t, &out, r, &mut series)?;
        }
        Ok(series)
    }

    /// The value of a variable at the final time.
    pub fn final_value(&self, name: impl Named) -> Result<f64, SolutionError> {
        let name = name.name();
        let name: &str = &name;
        let i = self.lookup(name)?;
        let k = self.t.len() - 1;
        let n = self.layout.n;
        let mut ws = self.observed.workspace();
        let mut inputs = self.inputs(self.segment_of(k));
        let mut out = vec![0.0; self.out_len()];
        let (u, up) = (&self.u[k * n..(k + 1) * n], &self.up[k * n..(k + 1) * n]);
        let r = self.evaluate(self.t[k], u, up, &mut ws, &mut inputs, &mut out);
        let mut series = [Vec::new()];
        self.collect(&[i], &[name], self.t[k], &out, r, &mut series)?;
        Ok(series[0][0])
    }

    /// The unknowns and derivatives interpolated at `t`: cubic Hermite for
    /// differential unknowns, linear for algebraic ones.
    fn interpolate(&self, t: f64) -> Result<(Vec<f64>, Vec<f64>, usize), SolutionError> {
        let (t0, t1) = (self.t[0], *self.t.last().expect("non-empty"));
        if !(t >= t0 && t <= t1) {
            return Err(SolutionError::OutOfRange { t, t0, t1 });
        }
        let n = self.layout.n;
        let k = match self.t.partition_point(|&x| x <= t) {
            0 => 0,
            p => (p - 1).min(self.t.len().saturating_sub(2)),
        };
        if self.t.len() == 1 {
            return Ok((self.u[..n].to_vec(), self.up[..n].to_vec(), 0));
        }
        let (ta, tb) = (self.t[k], self.t[k + 1]);
        let h = tb - ta;
        let s = if h > 0.0 { (t - ta) / h } else { 0.0 };
        let (ua, ub) = (
            &self.u[k * n..(k + 1) * n],
            &self.u[(k + 1) * n..(k + 2) * n],
        );
        let (pa, pb) = (
            &self.up[k * n..(k + 1) * n],
            &self.up[(k + 1) * n..(k + 2) * n],
        );
        let (s2, s3) = (s * s, s * s * s);
        let (h00, h10, h01, h11) = (
            2.0 * s3 - 3.0 * s2 + 1.0,
            s3 - 2.0 * s2 + s,
            -2.0 * s3 + 3.0 * s2,
            s3 - s2,
        );
        let mut u = vec![0.0; n];
        let mut up = vec![0.0; n];
        for i in 0..n {
            if self.differential[i] && h > 0.0 {
                u[i] = h00 * ua[i] + h10 * h * pa[i] + h01 * ub[i] + h11 * h * pb[i];
                up[i] = (6.0 * s2 - 6.0 * s) / h * ua[i]
                    + (3.0 * s2 - 4.0 * s + 1.0) * pa[i]
                    + (-6.0 * s2 + 6.0 * s) / h * ub[i]
                    + (3.0 * s2 - 2.0 * s) * pb[i];
            } else {
                u[i] = (1.0 - s) * ua[i] + s * ub[i];
                up[i] = (1.0 - s) * pa[i] + s * pb[i];
            }
        }
        Ok((u, up, k))
    }

    /// The solution's point at `t` (interpolated; at an event, its right limit is
    /// reached from the time just after it), where [`linearize`](super::linearize) may
    /// linearize the system.
    pub fn operating_point(&self, t: f64) -> Result<super::OperatingPoint, SolutionError> {
        let (u, up, k) = self.interpolate(t)?;
        let mut params = self.segments[self.segment_of(k)].params.clone();
        // A driver that fails here failed in the solve already.
        let _ = self.drivers.apply(t, &mut params);
        Ok(super::OperatingPoint { t, u, up, params })
    }

    /// The value of a variable at any time of the solved interval, interpolated between
    /// the two reported points around `t`: the unknowns by cubic Hermite interpolation
    /// with their derivatives (algebraic ones linearly), and the variable computed from
    /// them. Its accuracy is that of the spacing of the reported points: with
    /// [`SolverOptions::output_times`](super::SolverOptions::output_times) coarser than
    /// the integrator's steps, report the times you need instead, or every step (the
    /// default).
    pub fn at(&self, name: impl Named, t: f64) -> Result<f64, SolutionError> {
        Ok(self.sample(&[name], &[t])?[0][0])
    }

    /// Several variables at several times: `result[variable][time]`.
    pub fn sample<N: Named>(
        &self,
        names: &[N],
        times: &[f64],
    ) -> Result<Vec<Vec<f64>>, SolutionError> {
        let names = crate::model::names(names);
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let idx: Vec<usize> = names
            .iter()
            .map(|n| self.lookup(n))
            .collect::<Result<_, _>>()?;
        let mut ws = self.observed.workspace();
        let mut inputs = self.inputs(0);
        let mut out = vec![0.0; self.out_len()];
        let mut series = vec![Vec::with_capacity(times.len()); names.len()];
        for &t in times {
            let (u, up, k) = self.interpolate(t)?;
            if self.segments.len() > 1 {
                self.set_params(self.segment_of(k), &mut inputs);
            }
            let r = self.evaluate(t, &u, &up, &mut ws, &mut inputs, &mut out);
            self.collect(&idx, &names, t, &out, r, &mut series)?;
        }
        Ok(series)
    }

    /// Writes `time` and every variable at the reported times as CSV.
    pub fn write_csv_all(&self, path: impl AsRef<Path>) -> Result<(), SolutionError> {
        self.write_csv::<&str>(path, &[])
    }

    /// Writes `time` and the named variables (all of them when `names` is empty, see
    /// [`write_csv_all`](Self::write_csv_all)) at the reported times as CSV.
    pub fn write_csv<N: Named>(
        &self,
        path: impl AsRef<Path>,
        names: &[N],
    ) -> Result<(), SolutionError> {
        let path = path.as_ref();
        let names: Vec<String> = if names.is_empty() {
            self.names.names().iter().map(|s| s.to_string()).collect()
        } else {
            crate::model::names(names)
        };
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let series = self.get_many(&names)?;
        let io = |e: std::io::Error| SolutionError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        };
        let file = std::fs::File::create(path).map_err(io)?;
        let mut w = std::io::BufWriter::new(file);
        let header: Vec<String> = std::iter::once("time".to_string())
            .chain(names.iter().map(|n| csv_field(n)))
            .collect();
        writeln!(w, "{}", header.join(",")).map_err(io)?;
        for (k, t) in self.t.iter().enumerate() {
            let mut line = format!("{t:e}");
            for s in &series {
                line.push_str(&format!(",{:e}", s[k]));
            }
            writeln!(w, "{line}").map_err(io)?;
        }
        w.flush().map_err(io)
    }
}

fn csv_field(s: &str) -> String {
    if s.contains(',') || s.contains('"') {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// `x` of a derivative's name `der(x)`.
fn derivative_of(name: &str) -> Option<&str> {
    let inner = name.trim().strip_prefix("der(")?.strip_suffix(')')?;
    Some(inner.trim())
}

/// The unit of a quantity's rate: `rad` -> `rad/s`, `m/s` -> `m/s2`.
fn per_second_unit(unit: &str) -> String {
    if let Some(base) = unit.strip_suffix("/s") {
        format!("{base}/s2")
    } else if let Some(base) = unit.strip_suffix("/s2") {
        format!("{base}/s3")
    } else {
        format!("{unit}/s")
    }
}
