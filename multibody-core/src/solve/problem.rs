//! A DAE problem: a simplified system with parameter values, initial values and a time
//! span, solved by IDA.

use crate::hash::HashMap;

use crate::Error;
use crate::codegen::dae::{CompiledDae, InputLayout};
use crate::codegen::{ExtendedJacobian, ExtendedWorkspace, JacobianWorkspace, Workspace};
use crate::expr::{Arena, Id, Node};
use crate::names::{closest, number};
use crate::simplify::SimplifiedSystem;

use super::dynamic::{self, Observer};
use super::error::{InitError, SolveError};
use super::ida::IdaStats;
use super::ida::{self, DaeFunctions, EvalError, IdaMatrix, IdaSettings, OutputMode};
use super::init::{InitInput, initialize};
use super::inputs::Drivers;
use super::ode;
use super::options::{LinearSolver, Method, SolverOptions};
use super::solution::{Segment, Solution, SolutionParts, Termination};

/// What the initialization did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct InitReport {
    /// Start values assumed fixed to complete the initial conditions (name, value).
    pub assumed: Vec<(String, f64)>,
    /// Newton iterations used.
    pub iterations: usize,
    /// The unknowns the initialization iterated on (the tearing variables of its
    /// nonlinear blocks), by name. Orientation matrix entries are never among them.
    pub iteration_variables: Vec<String>,
}

/// A simplified system with values: tunable parameters, initial values and a time span.
/// Creating one runs the consistent initialization; the compiled functions of the
/// system are shared, so many problems of one system cost no recompilation.
#[derive(Clone, Debug)]
pub struct DaeProblem<'a> {
    sys: &'a SimplifiedSystem,
    tspan: (f64, f64),
    params: Vec<f64>,
    u0: Vec<f64>,
    up0: Vec<f64>,
    report: InitReport,
    /// The values and guesses given (for the same problem on the system's dynamic
    /// variant, if one is needed).
    given: Option<Box<Given>>,
    /// The signals that drive the model's inputs.
    drivers: Drivers,
}

/// Values and guesses a problem was made with, and the value of every variable its
/// initialization found.
#[derive(Clone, Debug)]
struct Given {
    values: Vec<(String, f64)>,
    guesses: Vec<(String, f64)>,
    /// Per flat variable: its value at the initial time (`None` for variables the
    /// simplified system replaced).
    initial: Vec<Option<f64>>,
}

/// Evaluates parameter values: bindings may refer to other parameters.
#[allow(clippy::result_large_err)] // evaluated once per problem, reported to the user
pub(crate) fn parameter_values(
    sys: &SimplifiedSystem,
    overrides: &HashMap<usize, f64>,
) -> Result<Vec<f64>, InitError> {
    crate::model::evaluate_bindings(&sys.model.arena, &sys.model.parameter_values, overrides)
        .map_err(|missing| InitError::BadValue {
            model: sys.model.name.clone(),
            message: format!(
                "the values of {} depend on each other or on variables",
                missing
                    .iter()
                    .map(|&j| format!("`{}`", sys.model.parameters[j].name))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        })
}

/// `sys` compiled with dynamic states (compiled on first need, then kept by `sys`).
fn dynamic_variant_of(sys: &SimplifiedSystem, t: f64) -> Result<&SimplifiedSystem, Error> {
    let variant = sys
        .dynamic
        .variant
        .get_or_init(|| {
            crate::simplify::dynamic_variant(sys)
                .expect("a system that watches its states has a source")
                .map(Box::new)
                .map_err(|e| e.to_string())
        })
        .as_ref()
        .map_err(|message| SolveError {
            model: sys.model.name.clone(),
            t,
            flag: "DYNAMIC_STATES".into(),
            message: format!(
                "the static choice of states degrades, and the model with dynamic states does \
                 not compile: {message}"
            ),
        })?;
    Ok(variant)
}

/// How many selections of dynamic states the initialization tries before it gives up.
///
/// (With `pin`, the selected candidates' values are fixed: the point is known, only
/// its parametrization is chosen.)
const SELECTIONS_TRIED: usize = 24;

/// The initialization of a system with dynamic states: the selections to try, best
/// first (the candidates with fixed start values, then the static choice of states,
/// then the others), each with the fixed start values of its candidates moved to the
/// dynamic states; the first that initializes wins.
#[allow(clippy::result_large_err)] // once per problem, reported to the user
fn initialize_dynamic(
    sys: &SimplifiedSystem,
    t0: f64,
    params: Vec<f64>,
    starts: Vec<Option<f64>>,
    fixed: Vec<bool>,
    guesses: Vec<Option<f64>>,
    pin: bool,
) -> Result<super::init::InitResult, InitError> {
    let per_group: Vec<Vec<Vec<usize>>> = sys
        .dynamic
        .groups
        .iter()
        .map(|g| {
            // Candidates whose values are given (fixed, then with start values) first:
            // their values become those of the dynamic states.
            let rank = |i: usize| {
                let q = g.candidates[i];
                let fixed_here = fixed[q] || g.derivatives[i].is_some_and(|d| fixed[d]);
                let started =
                    starts[q].is_some() || g.derivatives[i].is_some_and(|d| starts[d].is_some());
                let preferred = g.preferred.contains(&i);
                (!fixed_here, !started, !preferred, -g.priorities[i], i)
            };
            let mut order: Vec<usize> = (0..g.candidates.len()).collect();
            order.sort_by(|&a, &b| {
                let (ra, rb) = (rank(a), rank(b));
                (ra.0, ra.1, ra.2)
                    .cmp(&(rb.0, rb.1, rb.2))
                    .then(ra.3.total_cmp(&rb.3))
                    .then(ra.4.cmp(&rb.4))
            });
            subsets(&order, g.n_states(), SELECTIONS_TRIED)
        })
        .collect();
    let mut first_error = None;
    for attempt in 0..SELECTIONS_TRIED {
        // Attempt k takes the k-th selection of every group (the last where a group has
        // fewer).
        let selections: Vec<&Vec<usize>> = per_group
            .iter()
            .map(|opts| &opts[attempt.min(opts.len() - 1)])
            .collect();
        if attempt > 0 && per_group.iter().all(|opts| attempt >= opts.len()) {
            break;
        }
        let (mut params, mut starts, mut fixed, mut guesses) = (
            params.clone(),
            starts.clone(),
            fixed.clone(),
            guesses.clone(),
        );
        for (g, sel) in sys.dynamic.groups.iter().zip(&selections) {
            g.select(sel, &mut params);
            for (j, &i) in sel.iter().enumerate() {
                let q = g.candidates[i];
                for (to, from) in [
                    (g.states[j], Some(q)),
                    (g.velocity_states[j], g.derivatives[i]),
                ] {
                    // A state without a start value starts at 0, as the candidate would.
                    starts[to] = from.and_then(|f| starts[f]).or(Some(0.0));
                    let Some(from) = from else { continue };
                    fixed[to] = pin || fixed[from];
                    fixed[from] = false;
                    if guesses[from].is_none() {
                        guesses[from] = starts[from];
                    }
                }
            }
        }
        match initialize(InitInput {
            sys,
            t0,
            params,
            starts,
            fixed,
            guesses,
        }) {
            Ok(init) => return Ok(init),
            Err(e) => {
                log::debug!("dynamic state selection {selections:?} does not initialize: {e}");
                first_error.get_or_insert(e);
            }
        }
    }
    Err(first_error.expect("at least one attempt"))
}

/// Up to `limit` subsets of `size` of `items`, in the lexicographic order of their
/// positions in `items` (the first the first `size` items).
fn subsets(items: &[usize], size: usize, limit: usize) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    let mut idx: Vec<usize> = (0..size).collect();
    if size > items.len() {
        return vec![items.to_vec()];
    }
    loop {
        let mut pick: Vec<usize> = idx.iter().map(|&k| items[k]).collect();
        pick.sort_unstable();
        out.push(pick);
        if out.len() >= limit {
            return out;
        }
        // Next combination.
        let Some(pos) = (0..size).rev().find(|&p| idx[p] < items.len() - size + p) else {
            return out;
        };
        idx[pos] += 1;
        for p in pos + 1..size {
            idx[p] = idx[p - 1] + 1;
        }
    }
}

/// Checks the parameter values `params` against the parameters' `min` and `max`.
#[allow(clippy::result_large_err)] // evaluated once per problem, reported to the user
fn check_ranges(sys: &SimplifiedSystem, params: &[f64]) -> Result<(), InitError> {
    for (p, &v) in sys.model.parameters.iter().zip(params) {
        let (below, above) = (v < p.min, v > p.max);
        if below || above {
            let (bound, which) = if below {
                (p.min, "minimum")
            } else {
                (p.max, "maximum")
            };
            return Err(InitError::BadValue {
                model: sys.model.name.clone(),
                message: format!(
                    "parameter `{}` = {} is {} its {which} {}",
                    p.name,
                    number(v),
                    if below { "below" } else { "above" },
                    number(bound)
                ),
            });
        }
    }
    Ok(())
}

/// Checks the components' conditions on the parameter values `params`.
#[allow(clippy::result_large_err)] // evaluated once per problem, reported to the user
fn check_assertions(sys: &SimplifiedSystem, params: &[f64]) -> Result<(), InitError> {
    for a in &sys.model.assertions {
        if eval_with_params(&sys.model.arena, a.condition, params) != Some(0.0) {
            continue;
        }
        let values: Vec<String> = sys
            .model
            .arena
            .leaves(a.condition)
            .into_iter()
            .filter_map(|l| match sys.model.arena.node(l) {
                Node::Param(j) => Some(format!(
                    "{} = {}",
                    sys.model.parameters[*j as usize].name, params[*j as usize]
                )),
                _ => None,
            })
            .collect();
        return Err(InitError::AssertionFailed {
            model: sys.model.name.clone(),
            component: a.component.to_string(),
            type_name: a.type_name.to_string(),
            message: a.message.to_string(),
            values: values.join(", "),
        });
    }
    Ok(())
}

fn eval_with_params(arena: &Arena, e: Id, params: &[f64]) -> Option<f64> {
    arena.eval(e, &|n: &Node| match n {
        Node::Param(k) => params.get(*k as usize).copied(),
        Node::Time => None,
        _ => None,
    })
}

impl<'a> DaeProblem<'a> {
    /// The problem's consistent initial point (after its initialization), where
    /// [`linearize`](super::linearize) may linearize the system: an equilibrium when
    /// the start values make one.
    pub fn operating_point(&self) -> super::OperatingPoint {
        super::OperatingPoint {
            t: self.tspan.0,
            u: self.u0.clone(),
            up: self.up0.clone(),
            params: self.params.clone(),
        }
    }

    /// A problem over `tspan` with `values`: a parameter name sets that parameter; a
    /// variable name sets its start value and makes it fixed (an initial condition).
    /// Everything else keeps the model's defaults. Runs the initialization.
    pub fn new(
        sys: &'a SimplifiedSystem,
        values: &[(&str, f64)],
        tspan: (f64, f64),
    ) -> Result<Self, Error> {
        Self::new_with_guesses(sys, values, &[], tspan)
    }

    /// Like [`new`](Self::new), with iteration guesses for variables (used by the
    /// initialization's Newton iterations only; not fixed).
    pub fn new_with_guesses(
        sys: &'a SimplifiedSystem,
        values: &[(&str, f64)],
        guesses: &[(&str, f64)],
        tspan: (f64, f64),
    ) -> Result<Self, Error> {
        Self::new_driven(sys, values, guesses, tspan, Drivers::default())
    }

    /// [`Self::new_with_guesses`] with the model's inputs driven by `drivers`.
    pub(crate) fn new_driven(
        sys: &'a SimplifiedSystem,
        values: &[(&str, f64)],
        guesses: &[(&str, f64)],
        tspan: (f64, f64),
        drivers: Drivers,
    ) -> Result<Self, Error> {
        if !(tspan.0.is_finite() && tspan.1.is_finite() && tspan.1 > tspan.0) {
            return Err(InitError::BadValue {
                model: sys.model.name.clone(),
                message: format!(
                    "the time span ({}, {}) must be finite and increasing",
                    number(tspan.0),
                    number(tspan.1)
                ),
            }
            .into());
        }
        // Shorter spans than this are lost in the rounding of the times themselves (or
        // underflow inside the integrator's step-size estimates).
        let shortest = (100.0 * f64::EPSILON * tspan.0.abs().max(tspan.1.abs())).max(1e-200);
        if tspan.1 - tspan.0 < shortest {
            return Err(InitError::BadValue {
                model: sys.model.name.clone(),
                message: format!(
                    "the time span ({}, {}) is too short to integrate: the end must exceed \
                     the start by at least {}",
                    number(tspan.0),
                    number(tspan.1),
                    number(shortest)
                ),
            }
            .into());
        }
        // Name lookups only when names are given: hashing every name of a large model
        // costs more than the rest of the set-up.
        let by_name = !(values.is_empty() && guesses.is_empty());
        let index = |names: &mut dyn Iterator<Item = &'a str>| -> HashMap<&'a str, usize> {
            if by_name {
                names.enumerate().map(|(i, n)| (n, i)).collect()
            } else {
                HashMap::default()
            }
        };
        let var_index = index(&mut sys.model.variables.iter().map(|v| &*v.name));
        let param_index = index(&mut sys.model.parameters.iter().map(|p| &*p.name));
        let unknown = |name: &str| {
            let base = name.split('[').next().unwrap_or(name);
            if sys.model.structural.iter().any(|s| s == base) {
                return InitError::StructuralParameter {
                    model: sys.model.name.clone(),
                    name: name.to_string(),
                };
            }
            let candidates = sys
                .model
                .variables
                .iter()
                .map(|v| &*v.name)
                .chain(sys.model.parameters.iter().map(|p| &*p.name));
            InitError::UnknownName {
                model: sys.model.name.clone(),
                name: name.to_string(),
                suggestions: closest(name, candidates, 3),
            }
        };
        let mut param_overrides = HashMap::default();
        let mut start_overrides = HashMap::default();
        let bad = |message: String| -> Error {
            InitError::BadValue {
                model: sys.model.name.clone(),
                message,
            }
            .into()
        };
        let mut given: HashMap<&str, ()> = HashMap::default();
        for &(name, v) in values {
            if given.insert(name, ()).is_some() {
                return Err(bad(format!("`{name}` is given twice in the values")));
            }
            if !v.is_finite() {
                return Err(bad(format!(
                    "the value {v} given for `{name}` is not finite"
                )));
            }
            if let Some(&j) = param_index.get(name) {
                if sys.model.evaluated_parameters[j] {
                    return Err(bad(format!(
                        "parameter `{name}` was evaluated at compile time (declared `evaluate`, or SimplifyOptions::evaluate_parameters); simplify the model again to change it"
                    )));
                }
                param_overrides.insert(j, v);
            } else if let Some(&i) = var_index.get(name) {
                start_overrides.insert(i, v);
            } else {
                return Err(unknown(name).into());
            }
        }
        let mut guess_values = vec![None; sys.model.variables.len()];
        let mut guessed: HashMap<&str, ()> = HashMap::default();
        for &(name, v) in guesses {
            if guessed.insert(name, ()).is_some() {
                return Err(bad(format!("`{name}` is given twice in the guesses")));
            }
            if !v.is_finite() {
                return Err(bad(format!(
                    "the guess {v} given for `{name}` is not finite"
                )));
            }
            match var_index.get(name) {
                Some(&i) => guess_values[i] = Some(v),
                None if param_index.contains_key(name) => {
                    return Err(bad(format!(
                        "`{name}` is a parameter: give its value with the values, not as a guess"
                    )));
                }
                None => return Err(unknown(name).into()),
            }
        }
        let mut params = parameter_values(sys, &param_overrides)?;
        drivers
            .apply(tspan.0, &mut params)
            .map_err(|e| bad(e.message))?;
        if let Some(j) = params.iter().position(|p| !p.is_finite()) {
            return Err(bad(format!(
                "parameter `{}` evaluates to {}",
                sys.model.parameters[j].name, params[j]
            )));
        }
        check_ranges(sys, &params)?;
        check_assertions(sys, &params)?;
        let mut starts = Vec::with_capacity(sys.model.variables.len());
        let mut fixed = Vec::with_capacity(sys.model.variables.len());
        for (i, v) in sys.model.variables.iter().enumerate() {
            if let Some(&s) = start_overrides.get(&i) {
                starts.push(Some(s));
                fixed.push(true);
                continue;
            }
            let s = match sys.model.starts[i] {
                Some(e) => {
                    let value =
                        eval_with_params(&sys.model.arena, e, &params).ok_or_else(|| {
                            bad(format!(
                                "the start value of `{}` is not an expression of parameters",
                                v.name
                            ))
                        })?;
                    if !value.is_finite() {
                        return Err(bad(format!(
                            "the start value of `{}` evaluates to {value}",
                            v.name
                        )));
                    }
                    Some(value)
                }
                None => None,
            };
            starts.push(s);
            fixed.push(v.fixed);
        }
        let init = if sys.dynamic.groups.is_empty() {
            let init = initialize(InitInput {
                sys,
                t0: tspan.0,
                params,
                starts: starts.clone(),
                fixed: fixed.clone(),
                guesses: guess_values.clone(),
            });
            match init {
                Ok(init) => init,
                // The static choice of states may be singular right here: the model with
                // dynamic states chooses others.
                Err(e) if sys.dynamic.source.is_some() => {
                    log::info!(
                        "model `{}`: initialization with the static choice of states failed \
                         ({e}); trying dynamic states",
                        sys.model.name
                    );
                    let variant = dynamic_variant_of(sys, tspan.0)?;
                    return DaeProblem::new_driven(variant, values, guesses, tspan, drivers)
                        .map_err(|_| Error::from(e));
                }
                Err(e) => return Err(e.into()),
            }
        } else {
            let (starts, fixed, guesses) = (starts.clone(), fixed.clone(), guess_values.clone());
            initialize_dynamic(sys, tspan.0, params, starts, fixed, guesses, false)?
        };
        // Relations hold at the initial point what they evaluate to there.
        let init = super::events::settle_initial_relations(sys, tspan.0, init, |params| {
            let (starts, fixed, guesses) = (starts.clone(), fixed.clone(), guess_values.clone());
            if sys.dynamic.groups.is_empty() {
                initialize(InitInput {
                    sys,
                    t0: tspan.0,
                    params,
                    starts,
                    fixed,
                    guesses,
                })
                .map_err(Error::from)
            } else {
                initialize_dynamic(sys, tspan.0, params, starts, fixed, guesses, false)
                    .map_err(Error::from)
            }
        })?;
        let given = sys.dynamic.source.is_some().then(|| {
            let own =
                |list: &[(&str, f64)]| list.iter().map(|&(n, v)| (n.to_string(), v)).collect();
            let mut initial = vec![None; sys.model.variables.len()];
            for (k, slot) in sys.reduction.slots.iter().enumerate() {
                if slot.order == 0 {
                    initial[slot.var] = Some(init.slot_values[k]);
                }
            }
            Box::new(Given {
                values: own(values),
                guesses: own(guesses),
                initial,
            })
        });
        Ok(DaeProblem::from_init(sys, tspan, init, given, drivers))
    }

    /// The problem of `sys` over `tspan` that `init` initialized.
    fn from_init(
        sys: &'a SimplifiedSystem,
        tspan: (f64, f64),
        init: super::init::InitResult,
        given: Option<Box<Given>>,
        drivers: Drivers,
    ) -> DaeProblem<'a> {
        let (u0, up0) = unknowns_of(sys, &init.slot_values);
        DaeProblem {
            sys,
            tspan,
            params: init.params,
            u0,
            up0,
            report: InitReport {
                assumed: init.assumed,
                iterations: init.iterations,
                iteration_variables: init.iteration_variables,
            },
            given,
            drivers,
        }
    }

    /// The same problem on the system compiled with dynamic states (compiled now if it
    /// was not yet), from this problem's initial point: every variable keeps the value
    /// this initialization gave it, and the dynamic states are chosen where that point
    /// lets them be.
    fn on_dynamic_variant(&self) -> Result<DaeProblem<'a>, Error> {
        let sys = self.sys;
        let variant = dynamic_variant_of(sys, self.tspan.0)?;
        let t0 = self.tspan.0;
        let given = self
            .given
            .as_deref()
            .expect("kept for a system with a source");
        // The variant has the same variables and parameters first (the same model,
        // flattened the same way), then those of its dynamic states.
        let mut params = parameter_values(variant, &HashMap::default())?;
        params[..self.params.len()].copy_from_slice(&self.params);
        let mut starts: Vec<Option<f64>> = vec![None; variant.model.variables.len()];
        starts[..given.initial.len()].copy_from_slice(&given.initial);
        let guesses = starts.clone();
        let fixed = vec![false; variant.model.variables.len()];
        let init = match initialize_dynamic(variant, t0, params, starts, fixed, guesses, true) {
            Ok(init) => init,
            Err(e) => {
                log::debug!("the initial point does not initialize the dynamic states: {e}");
                // The variant initializes from the values given.
                let values: Vec<(&str, f64)> =
                    given.values.iter().map(|(n, v)| (n.as_str(), *v)).collect();
                let guesses: Vec<(&str, f64)> = given
                    .guesses
                    .iter()
                    .map(|(n, v)| (n.as_str(), *v))
                    .collect();
                return DaeProblem::new_driven(
                    variant,
                    &values,
                    &guesses,
                    self.tspan,
                    self.drivers.clone(),
                );
            }
        };
        Ok(DaeProblem::from_init(
            variant,
            self.tspan,
            init,
            self.given.clone(),
            self.drivers.clone(),
        ))
    }

    /// The consistent initial unknowns `u(t0)`, in the order of
    /// [`SimplifiedSystem::unknowns`].
    pub fn initial_unknowns(&self) -> &[f64] {
        &self.u0
    }

    /// The consistent initial derivatives `u'(t0)`.
    pub fn initial_derivatives(&self) -> &[f64] {
        &self.up0
    }

    /// The parameter values (including those computed at initialization), in the
    /// order of [`SimplifiedSystem::parameters`].
    pub fn parameter_values(&self) -> &[f64] {
        &self.params
    }

    /// What the initialization assumed and how it went.
    pub fn init_report(&self) -> &InitReport {
        &self.report
    }

    /// The time span.
    pub fn tspan(&self) -> (f64, f64) {
        self.tspan
    }

    /// The system.
    pub fn system(&self) -> &SimplifiedSystem {
        self.sys
    }

    /// The residual `F(t0, u0, u'0)` at the initial values (all zero when they are
    /// consistent).
    pub fn initial_residual(&self) -> Vec<f64> {
        let c = &self.sys.compiled;
        let mut f =
            CompiledFunctions::new(c, &self.params, false).with_drivers(self.drivers.clone());
        let mut out = vec![0.0; self.u0.len()];
        let _ = f.residual(self.tspan.0, &self.u0, &self.up0, &mut out);
        out
    }

    /// Integrates with IDA. Where the system has dynamic states, the integration stops
    /// whenever their selection should change, and restarts from the same point with
    /// the new selection (the solution then has several segments).
    pub fn solve(&self, options: &SolverOptions) -> Result<Solution, Error> {
        let sys = self.sys;
        if let Err(message) = options.check(self.tspan) {
            return Err(SolveError {
                model: sys.model.name.clone(),
                t: self.tspan.0,
                flag: "BAD_OPTION".into(),
                message,
            }
            .into());
        }
        let output_times = options.output_times.as_ref().map(|times| {
            let mut ts: Vec<f64> = times
                .iter()
                .copied()
                .filter(|&t| t > self.tspan.0 && t <= self.tspan.1)
                .collect();
            ts.sort_by(f64::total_cmp);
            ts.dedup();
            if ts.last() != Some(&self.tspan.1) {
                ts.push(self.tspan.1);
            }
            ts
        });
        // A static choice of states that may degrade is watched; where it does, the
        // problem is solved on the model with dynamic states instead.
        let watched = sys.dynamic.groups.is_empty() && sys.dynamic.source.is_some();
        match self.run_segments(options, output_times.as_deref(), watched) {
            Err(Degraded::Static { t }) => {
                log::info!(
                    "model `{}`: the static choice of states degrades at t = {t}; solving with \
                     dynamic states",
                    sys.model.name
                );
                self.on_dynamic_variant()?.solve(options)
            }
            Err(Degraded::Error(e)) => Err(e),
            Ok(solution) => Ok(solution),
        }
    }

    /// Integrates the segments of the run (see [`Self::solve`]); with `watched`, stops
    /// where the static choice of states degrades or the integration fails.
    fn run_segments(
        &self,
        options: &SolverOptions,
        output_times: Option<&[f64]>,
        watched: bool,
    ) -> Result<Solution, Degraded> {
        let sys = self.sys;
        let n = self.u0.len();
        let mut run = Run {
            t: Vec::new(),
            u: Vec::new(),
            up: Vec::new(),
            segments: Vec::new(),
            stats: IdaStats::default(),
            points_left: options.max_points,
            events: super::events::History::new(sys, self.tspan),
            specialized: None,
            terminated: None,
            stiff: false,
            workspaces: None,
        };
        let (mut t0, mut u0, mut up0) = (self.tspan.0, self.u0.clone(), self.up0.clone());
        let mut params = self.params.clone();
        let mut observer = Observer::new(&sys.compiled.observed, sys.compiled.layout)
            .with_drivers(self.drivers.clone());
        let mut bridges = 0;
        // The end of the stretch being integrated with relaxed tolerances across a
        // singular point (`None` outside one), and the relaxation.
        let mut bridge_end: Option<f64> = None;
        let mut relaxation = BRIDGE_RELAXATION;
        if let Some(roots) = super::events::initial_samples(sys, (t0, &u0, &up0), &params) {
            // An event at the initial time belongs to the initialization (where
            // `initial()` holds): the solution starts at its right limit.
            (u0, up0) = self
                .at_event(&mut params, (t0, u0, up0), &roots, options, &mut run)
                .map_err(Degraded::Error)?;
        }
        while run.terminated.is_none() {
            let segment = Segment {
                first: run.t.len(),
                params: params.clone(),
            };
            let time_event = super::events::next_time_event(sys, &params, t0, self.tspan.1);
            let t_end = bridge_end
                .unwrap_or(self.tspan.1)
                .min(time_event.unwrap_or(f64::INFINITY));
            let mut times: Option<Vec<f64>> = output_times.map(|ts| {
                ts.iter()
                    .copied()
                    .filter(|&t| t > t0 && t <= t_end)
                    .collect()
            });
            if let Some(ts) = times.as_mut()
                && ts.last() != Some(&t_end)
            {
                // A stretch that ends between output times ends with a point of its own.
                ts.push(t_end);
            }
            let segment_options;
            let options_here = match bridge_end {
                Some(_) => {
                    segment_options = SolverOptions {
                        rtol: options.rtol * relaxation,
                        atol: options.atol * relaxation,
                        ..options.clone()
                    };
                    &segment_options
                }
                None => options,
            };
            let end = self
                .integrate_segment(
                    &params,
                    (t0, t_end),
                    (&u0, &up0),
                    times,
                    options_here,
                    &mut observer,
                    &mut run,
                    watched,
                )
                .map_err(|e| Degraded::Error(super::events::in_mode(e, &run.events)))?;
            run.segments.push(segment);
            // A segment that reaches the next time event ends at that event.
            let end = match end {
                SegmentEnd::Done if time_event == Some(t_end) => {
                    let k = run.t.len() - 1;
                    SegmentEnd::Event {
                        t: run.t[k],
                        y: run.u[k * n..(k + 1) * n].to_vec(),
                        yp: run.up[k * n..(k + 1) * n].to_vec(),
                        roots: super::events::time_event_roots(sys, &params, run.t[k]),
                    }
                }
                other => other,
            };
            match end {
                SegmentEnd::Done if bridge_end.is_some() && t_end < self.tspan.1 => {
                    // Across the singular point: on with the asked tolerances from the
                    // stretch's last point.
                    bridge_end = None;
                    let k = run.t.len() - 1;
                    t0 = run.t[k];
                    u0 = run.u[k * n..(k + 1) * n].to_vec();
                    up0 = run.up[k * n..(k + 1) * n].to_vec();
                }
                SegmentEnd::Done => break,
                SegmentEnd::StaticDegraded { t } => return Err(Degraded::Static { t }),
                SegmentEnd::Event { t, y, yp, roots } => {
                    // The event's point ends this segment (the left limit) and, once
                    // the relations have settled, starts the next (the right limit).
                    (u0, up0) = self
                        .at_event(&mut params, (t, y, yp), &roots, options, &mut run)
                        .map_err(Degraded::Error)?;
                    t0 = t;
                    if run.terminated.is_none() && super::events::at_stop_time(self.tspan, t) {
                        // A time event at the stop time: its right limit ends the run.
                        run.point_segment(t, &u0, &up0, &params, sys)
                            .map_err(Degraded::Error)?;
                        break;
                    }
                }
                SegmentEnd::Switch { t, y, yp, decision } => {
                    // The point where the selection changes ends this segment (it has
                    // it) and starts the next, with the new selection.
                    for (g, sel) in sys.dynamic.groups.iter().zip(&decision.selections) {
                        g.select(sel, &mut params);
                    }
                    let (y, yp) = dynamic::restart_point(
                        &observer,
                        &sys.dynamic.groups,
                        &decision.selections,
                        &y,
                        &yp,
                    );
                    (t0, u0, up0) = (t, y, yp);
                }
                SegmentEnd::Failed { error, last } => {
                    // The constraints themselves are singular here (every selection of
                    // states is): cross with relaxed tolerances from the last step, more
                    // relaxed if a relaxed stretch fails too.
                    if bridge_end.is_some() {
                        relaxation *= BRIDGE_RELAXATION;
                    } else {
                        relaxation = BRIDGE_RELAXATION;
                    }
                    let usable = bridges < MAX_BRIDGES && options.rtol * relaxation <= BRIDGE_RTOL;
                    let Some((t_fail, _, _)) = last.filter(|_| usable) else {
                        return Err(Degraded::Error(super::events::in_mode(error, &run.events)));
                    };
                    bridges += 1;
                    // Start somewhat before the failure (the integrator needs room to
                    // build up its order), at a point of the failed segment.
                    let length = BRIDGE_LENGTH * (self.tspan.1 - self.tspan.0);
                    let first = run.segments.last().map_or(0, |s| s.first);
                    let k = (first..run.t.len())
                        .rev()
                        .find(|&k| run.t[k] <= t_fail - length)
                        .unwrap_or(first);
                    t0 = run.t[k];
                    u0 = run.u[k * n..(k + 1) * n].to_vec();
                    up0 = run.up[k * n..(k + 1) * n].to_vec();
                    // The restart point is the first point of the next segment (the
                    // failed one keeps its points before it, if any).
                    run.truncate(k);
                    if run.segments.last().is_some_and(|s| s.first >= k) {
                        run.segments.pop();
                    }
                    bridge_end = Some((t_fail + length).min(self.tspan.1));
                    log::info!(
                        "model `{}`: the integration crosses a singular configuration near t = \
                         {t_fail} with tolerances relaxed {relaxation}-fold from t = {t0} to {}",
                        sys.model.name,
                        bridge_end.unwrap_or(t_fail)
                    );
                }
            }
            debug_assert_eq!(u0.len(), n);
        }
        if !sys.model.events.terminal.is_empty() {
            self.terminal_event(&mut params, options, &mut run)
                .map_err(Degraded::Error)?;
        }
        Ok(Solution::new(SolutionParts {
            model: sys.model.name.clone(),
            observed: sys.compiled.observed.clone(),
            names: sys.compiled.observed_names.clone(),
            layout: sys.compiled.layout,
            parameter_names: sys.parameter_index(),
            unknown_names: sys.unknown_index(),
            variables: sys.model.variables.clone(),
            parameter_units: sys
                .model
                .parameters
                .iter()
                .map(|p| p.unit.clone())
                .collect(),
            differential: sys
                .sorted
                .mass_matrix_diagonal
                .iter()
                .map(|&m| m == 1.0)
                .collect(),
            t: run.t,
            u: run.u,
            up: run.up,
            segments: run.segments,
            stats: run.stats,
            init: self.report.clone(),
            events: run.events.events,
            terminated: run.terminated,
            drivers: self.drivers.clone(),
        }))
    }

    /// Settles the event at `t` (left limit `(y, yp)`, crossing functions `roots`; see
    /// [`super::events::settle`]) and returns the right limit. Where a `terminate(..)`
    /// ends the run there, the right limit is its last point, a segment of its own.
    fn at_event(
        &self,
        params: &mut [f64],
        (t, y, yp): (f64, Vec<f64>, Vec<f64>),
        roots: &[i32],
        options: &SolverOptions,
        run: &mut Run,
    ) -> Result<(Vec<f64>, Vec<f64>), Error> {
        self.drivers.apply(t, params).map_err(|e| SolveError {
            model: self.sys.model.name.clone(),
            t,
            flag: "INPUT".into(),
            message: e.message,
        })?;
        let settled = super::events::settle(
            self.sys,
            self.tspan,
            params,
            (t, y, yp),
            roots,
            options,
            (&mut run.events, &mut run.specialized),
            &mut run.workspaces,
        )?;
        if let Some(message) = settled.terminated {
            run.point_segment(t, &settled.y, &settled.yp, params, self.sys)?;
            run.terminated = Some(Termination { t, message });
        }
        Ok((settled.y, settled.yp))
    }

    /// The terminal event at the run's last point, where `terminal()` holds: its right
    /// limit becomes the last point.
    fn terminal_event(
        &self,
        params: &mut [f64],
        options: &SolverOptions,
        run: &mut Run,
    ) -> Result<(), Error> {
        let Some(&t) = run.t.last() else {
            return Ok(());
        };
        let n = self.u0.len();
        let k = run.t.len() - 1;
        let (y, yp) = (
            run.u[k * n..(k + 1) * n].to_vec(),
            run.up[k * n..(k + 1) * n].to_vec(),
        );
        let roots = vec![0; self.sys.model.events.relations.len()];
        run.events.terminal = true;
        let terminated = run.terminated.take();
        let (y, yp) = self.at_event(params, (t, y, yp), &roots, options, run)?;
        run.terminated = terminated.or(run.terminated.take());
        run.point_segment(t, &y, &yp, params, self.sys)
    }

    /// Integrates one segment from `start` with `params`, appending its points to
    /// `run` (the first one included); returns where dynamic state selection stopped
    /// it, if it did, with the new selections.
    #[allow(clippy::too_many_arguments)]
    fn integrate_segment(
        &self,
        params: &[f64],
        (t0, t_end): (f64, f64),
        (u0, up0): (&[f64], &[f64]),
        output_times: Option<Vec<f64>>,
        options: &SolverOptions,
        observer: &mut Observer<'_>,
        run: &mut Run,
        watched: bool,
    ) -> Result<SegmentEnd, Error> {
        let sys = self.sys;
        let specialized = run.specialized.take();
        let specialized = specialized_for(sys, params, options, specialized);
        let result = self.integrate_with(
            specialized.as_ref().map_or(&sys.compiled, |(_, c)| c),
            params,
            (t0, t_end),
            (u0, up0),
            output_times,
            options,
            observer,
            run,
            watched,
        );
        run.specialized = specialized;
        result
    }

    /// [`Self::integrate_segment`] with the compiled functions `c`.
    #[allow(clippy::too_many_arguments)]
    fn integrate_with(
        &self,
        c: &CompiledDae,
        params: &[f64],
        (t0, t_end): (f64, f64),
        (u0, up0): (&[f64], &[f64]),
        output_times: Option<Vec<f64>>,
        options: &SolverOptions,
        observer: &mut Observer<'_>,
        run: &mut Run,
        watched: bool,
    ) -> Result<SegmentEnd, Error> {
        let sys = self.sys;
        let n = u0.len();
        let method = ode_method(sys, c, options.method).map_err(|message| SolveError {
            model: sys.model.name.clone(),
            t: t0,
            flag: "BAD_METHOD".into(),
            message,
        })?;
        let (settings, extended) = ida_settings(sys, c, options, method.is_none());
        // Once `Auto` found the model stiff, later segments start with BDF.
        let method = method.map(|m| match m {
            ode::OdeMethod::Auto if run.stiff => ode::OdeMethod::CvodeBdf,
            m => m,
        });
        let output = match output_times {
            Some(ts) if !ts.is_empty() => OutputMode::Times(ts),
            _ => OutputMode::EveryStep { t_end },
        };
        let mut f = CompiledFunctions::recycling(c, params, extended, run.workspaces.take())
            .with_drivers(self.drivers.clone())
            .with_crossings(sys);
        let first = run.t.len();
        let mut exceeded = None;
        let mut decision = None;
        // The last step, where a failed integration may be taken up again.
        let mut last: Option<(f64, Vec<f64>, Vec<f64>)> = None;
        // Steps in a row too short to advance: the integration stalls at a singular
        // configuration.
        let shortest = STALL_STEP * (t_end - t0).abs().max(f64::MIN_POSITIVE);
        let (mut short_steps, mut stalled) = (0usize, None);
        let mut degraded = None;
        let mut monitor = |t: f64, y: &[f64], yp: &[f64]| {
            if let Some((tl, _, _)) = &last {
                if t - tl < shortest {
                    short_steps += 1;
                    if short_steps > STALL_STEPS {
                        stalled = Some(t);
                        return false;
                    }
                } else {
                    short_steps = 0;
                }
            }
            if watched {
                if dynamic::static_degraded(observer, &sys.dynamic.candidates, t, y, yp, params) {
                    degraded = Some(t);
                    return false;
                }
                return true;
            }
            decision = dynamic::check(observer, &sys.dynamic.groups, t, y, yp, params);
            match &mut last {
                Some((tl, yl, ypl)) => {
                    *tl = t;
                    yl.copy_from_slice(y);
                    ypl.copy_from_slice(yp);
                }
                None => last = Some((t, y.to_vec(), yp.to_vec())),
            }
            decision.is_none()
        };
        let dynamic = !sys.dynamic.groups.is_empty() || watched;
        let mut on_output = |t: f64, u: &[f64], up: &[f64]| {
            if run.points_left == 0 {
                exceeded = Some(t);
                return false;
            }
            run.points_left -= 1;
            run.t.push(t);
            run.u.extend_from_slice(u);
            run.up.extend_from_slice(up);
            true
        };
        type Monitor<'m> = Option<&'m mut dyn FnMut(f64, &[f64], &[f64]) -> bool>;
        let monitor: Monitor<'_> = if dynamic { Some(&mut monitor) } else { None };
        let result = match method {
            None => ida::integrate_monitored(
                &mut f,
                t0,
                u0,
                up0,
                &settings,
                &output,
                &mut on_output,
                monitor,
            ),
            Some(m) => ode::integrate_monitored(
                &mut ode::ExplicitDae::new(&mut f),
                m,
                t0,
                u0,
                &settings,
                &output,
                &mut on_output,
                monitor,
            ),
        };
        // The crossing functions' relations; the workspaces go to what follows (the
        // projection, the event, the next segment).
        let crossing_relations = f.crossing_relations();
        run.workspaces = Some(f.into_workspaces());
        if let Some(t) = exceeded {
            return Err(SolveError {
                model: sys.model.name.clone(),
                t,
                flag: "MAX_POINTS".into(),
                message: format!(
                    "more than {} reported points (SolverOptions::max_points)",
                    options.max_points
                ),
            }
            .into());
        }
        if let Some(t) = degraded {
            return Ok(SegmentEnd::StaticDegraded { t });
        }
        let integrated = match result {
            Ok(r) => r,
            Err(e) if watched => return Ok(SegmentEnd::StaticDegraded { t: e.t }),
            Err(e) => {
                let error: Error = SolveError {
                    model: sys.model.name.clone(),
                    t: e.t,
                    flag: e.flag.clone(),
                    message: e.message.clone(),
                }
                .into();
                let singular = matches!(
                    e.flag.as_str(),
                    "IDA_CONV_FAIL"
                        | "IDA_ERR_FAIL"
                        | "CV_CONV_FAILURE"
                        | "CV_ERR_FAILURE"
                        | "ARK_CONV_FAILURE"
                        | "ARK_ERR_FAILURE"
                );
                if dynamic && singular {
                    // Points reported after the last step (interpolated outputs) are
                    // dropped: the integration is taken up again from that step.
                    if let Some((tl, _, _)) = &last {
                        while run.t.len() > first && run.t.last().is_some_and(|&t| t > *tl) {
                            run.t.pop();
                            run.u.truncate(run.t.len() * n);
                            run.up.truncate(run.t.len() * n);
                        }
                    }
                    if options.project_outputs {
                        project(
                            c,
                            (params, &self.drivers),
                            &sys.sorted.mass_matrix_diagonal,
                            (t0, u0, up0),
                            run,
                            first,
                        );
                    }
                    return Ok(SegmentEnd::Failed { error, last });
                }
                return Err(error);
            }
        };
        run.stats.add(&integrated.stats);
        run.stiff |= integrated.switched;
        // Where the selection changes, the segment ends with a point of its own (at
        // an event, the integrator reported it).
        if let Some((t, y, yp)) = &integrated.stopped
            && integrated.roots.is_empty()
        {
            run.push(t.to_owned(), y, yp, sys)?;
        }
        if options.project_outputs {
            project(
                c,
                (params, &self.drivers),
                &sys.sorted.mass_matrix_diagonal,
                (t0, u0, up0),
                run,
                first,
            );
        }
        if let Some(t) = stalled {
            return Ok(SegmentEnd::Failed {
                error: SolveError {
                    model: sys.model.name.clone(),
                    t,
                    flag: "STALLED".into(),
                    message: format!(
                        "more than {STALL_STEPS} steps in a row shorter than {} (a singular \
                         configuration?)",
                        crate::names::number(shortest)
                    ),
                }
                .into(),
                last,
            });
        }
        let roots = relation_roots(
            &crossing_relations,
            &integrated.roots,
            sys.model.events.relations.len(),
        );
        Ok(match integrated.stopped {
            Some((t, y, yp)) if !integrated.roots.is_empty() => {
                SegmentEnd::Event { t, y, yp, roots }
            }
            Some((t, y, yp)) => SegmentEnd::Switch {
                t,
                y,
                yp,
                decision: decision.expect("the monitor stopped it"),
            },
            None => SegmentEnd::Done,
        })
    }
}

/// The integrator's root information `roots` (one per crossing function, of the
/// relations `relations`) per relation of the system (`n`; 0 for the time events).
fn relation_roots(relations: &[usize], roots: &[i32], n: usize) -> Vec<i32> {
    let mut out = vec![0; n];
    for (&k, &r) in relations.iter().zip(roots) {
        out[k] = r;
    }
    out
}

/// Solves the algebraic unknowns of the points `first..` of `run` again from the
/// constraints (see [`SolverOptions::project_outputs`]); the segment started at `start`.
fn project(
    c: &CompiledDae,
    (params, drivers): (&[f64], &Drivers),
    mass: &[f64],
    (t0, u0, up0): (f64, &[f64], &[f64]),
    run: &mut Run,
    first: usize,
) {
    let n = u0.len();
    let recycled = run.workspaces.take();
    let mut plain =
        CompiledFunctions::recycling(c, params, false, recycled).with_drivers(drivers.clone());
    if let Some(mut projection) = super::project::Projection::new(&mut plain, mass, t0, u0, up0) {
        for k in first..run.t.len() {
            let span = k * n..(k + 1) * n;
            projection.apply(
                &mut plain,
                run.t[k],
                &mut run.u[span.clone()],
                &run.up[span],
            );
        }
    }
    run.workspaces = Some(plain.into_workspaces());
}

/// Why a run of segments stopped early.
enum Degraded {
    /// The watched static choice of states degraded at `t`.
    Static { t: f64 },
    /// Anything else.
    Error(Error),
}

/// How the integration of a segment ended.
enum SegmentEnd {
    /// The watched static choice of states degraded (or the integration failed) at `t`.
    StaticDegraded { t: f64 },
    /// At its end time.
    Done,
    /// Dynamic state selection chose other states here.
    Switch {
        t: f64,
        y: Vec<f64>,
        yp: Vec<f64>,
        decision: dynamic::Decision,
    },
    /// A relation's crossing function passed through zero here (`roots` as
    /// [`ida::Integrated::roots`]).
    Event {
        t: f64,
        y: Vec<f64>,
        yp: Vec<f64>,
        roots: Vec<i32>,
    },
    /// The integrator failed where the selection is good (a singular configuration of
    /// the constraints themselves); `last` is its last step.
    Failed {
        error: Error,
        last: Option<(f64, Vec<f64>, Vec<f64>)>,
    },
}

/// A step shorter than this fraction of the span makes no progress.
const STALL_STEP: f64 = 1e-9;
/// So many such steps in a row stall the integration.
const STALL_STEPS: usize = 200;
/// Relaxation of the tolerances across a singular configuration.
const BRIDGE_RELAXATION: f64 = 10.0;
/// The loosest relative tolerance a crossing uses.
const BRIDGE_RTOL: f64 = 1e-5;
/// Length of the stretch integrated with relaxed tolerances, as a fraction of the span.
const BRIDGE_LENGTH: f64 = 2e-4;
/// Most singular configurations crossed in one run.
const MAX_BRIDGES: usize = 1000;

/// The points and statistics of a run of segments.
struct Run {
    t: Vec<f64>,
    u: Vec<f64>,
    up: Vec<f64>,
    segments: Vec<Segment>,
    stats: IdaStats,
    points_left: usize,
    events: super::events::History,
    /// The compiled functions specialized to the parameters that events do not change,
    /// with those parameters' values (kept while they do not change).
    specialized: Option<(Vec<f64>, CompiledDae)>,
    /// Where and why a `terminate(..)` ended the run.
    terminated: Option<Termination>,
    /// Whether `Method::Auto` found the model stiff in an earlier segment (the later
    /// ones start with BDF).
    stiff: bool,
    /// The last segment's evaluation workspaces, for the next segment on the same
    /// compiled functions.
    workspaces: Option<Workspaces>,
}

/// The evaluation workspaces of a segment's compiled functions: kept for the next
/// segment on the same functions, their sparse LUs keep their column orders and
/// pivots (see [`CompiledFunctions::recycling`]).
pub(super) struct Workspaces {
    /// Id of the residual tape they were made for.
    tape: u64,
    ws: Workspace,
    jws: Option<JacobianWorkspace>,
    ews: Option<ExtendedWorkspace>,
    crossings: Option<Workspace>,
}

impl Run {
    /// Keeps the first `k` points.
    fn truncate(&mut self, k: usize) {
        let n = if self.t.is_empty() {
            0
        } else {
            self.u.len() / self.t.len()
        };
        self.points_left += self.t.len().saturating_sub(k);
        self.t.truncate(k);
        self.u.truncate(k * n);
        self.up.truncate(k * n);
    }

    /// Appends the point `(t, y, yp)` as a segment of its own with `params` (an event's
    /// left limit at the initial time, or the right limit a run ends with).
    fn point_segment(
        &mut self,
        t: f64,
        y: &[f64],
        yp: &[f64],
        params: &[f64],
        sys: &SimplifiedSystem,
    ) -> Result<(), Error> {
        self.segments.push(Segment {
            first: self.t.len(),
            params: params.to_vec(),
        });
        self.push(t, y, yp, sys)
    }

    /// Appends a point.
    fn push(&mut self, t: f64, y: &[f64], yp: &[f64], sys: &SimplifiedSystem) -> Result<(), Error> {
        if self.points_left == 0 {
            return Err(SolveError {
                model: sys.model.name.clone(),
                t,
                flag: "MAX_POINTS".into(),
                message: "more reported points than SolverOptions::max_points".into(),
            }
            .into());
        }
        self.points_left -= 1;
        self.t.push(t);
        self.u.extend_from_slice(y);
        self.up.extend_from_slice(yp);
        Ok(())
    }
}

/// The unknowns and their derivatives from the values of the slots.
pub(super) fn unknowns_of(sys: &SimplifiedSystem, slot_values: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let mut u = Vec::with_capacity(sys.sorted.unknowns.len());
    let mut up = Vec::with_capacity(sys.sorted.unknowns.len());
    for &l in &sys.sorted.unknowns {
        let s = sys.reduction.slot_of.get(l).expect("an unknown is a slot");
        u.push(slot_values[s]);
        up.push(sys.reduction.var_diff[s].map_or(0.0, |d| slot_values[d]));
    }
    (u, up)
}

/// The compiled functions of `sys` for `params` when they are specialized (see
/// [`SolverOptions::specialize_parameters`]): specialized to every parameter but those
/// that events change, which stay inputs, so that one specialization serves every
/// segment of a run with events. `cached` is reused when it was made for the same
/// values.
pub(super) fn specialized_for(
    sys: &SimplifiedSystem,
    params: &[f64],
    options: &SolverOptions,
    cached: Option<(Vec<f64>, CompiledDae)>,
) -> Option<(Vec<f64>, CompiledDae)> {
    if !options.specialize_parameters || sys.compiled.layout.n_params == 0 {
        return None;
    }
    let changing = sys.model.changing_parameters(params.len());
    let key: Vec<f64> = params
        .iter()
        .zip(&changing)
        .map(|(&p, &c)| if c { 0.0 } else { p })
        .collect();
    let same = |k: &[f64]| k.iter().zip(&key).all(|(a, b)| a.to_bits() == b.to_bits());
    if let Some((k, c)) = cached
        && same(&k)
    {
        return Some((k, c));
    }
    let values: Vec<Option<f64>> = params
        .iter()
        .zip(&changing)
        .map(|(&p, &c)| (!c).then_some(p))
        .collect();
    Some((key, sys.compiled.specialize_partly(&values)))
}

/// The ODE method a solve of `sys` with the compiled functions `c` uses for `method`:
/// `None` for IDA; an error naming the algebraic unknowns where an ODE method is asked
/// of a model that is not an ODE.
pub(super) fn ode_method(
    sys: &SimplifiedSystem,
    c: &CompiledDae,
    method: Method,
) -> Result<Option<ode::OdeMethod>, String> {
    if method == Method::Ida || sys.sorted.mass_matrix_diagonal.is_empty() {
        return Ok(None);
    }
    let explicit = sys.sorted.mass_matrix_diagonal.iter().all(|&m| m == 1.0) && c.is_explicit_ode();
    match (method, explicit) {
        (Method::Auto, true) => Ok(Some(ode::OdeMethod::Auto)),
        (Method::Auto, false) => Ok(None),
        (m, true) => Ok(m.ode()),
        (m, false) => {
            let names = sys.unknowns();
            let algebraic: Vec<&str> = names
                .iter()
                .zip(&sys.sorted.mass_matrix_diagonal)
                .filter(|(_, m)| **m != 1.0)
                .map(|(name, _)| name.as_str())
                .take(5)
                .collect();
            Err(if algebraic.is_empty() {
                format!(
                    "Method::{m:?} needs the model as an ODE, but some state derivatives \
                     are not computed from the states alone (they enter equations solved \
                     together with them); use Method::Ida or Method::Auto"
                )
            } else {
                format!(
                    "Method::{m:?} needs the model as an ODE, but it has algebraic unknowns \
                     ({}{}); use Method::Ida or Method::Auto",
                    algebraic.join(", "),
                    if algebraic.len() == 5 { ", ..." } else { "" }
                )
            })
        }
    }
}

/// IDA's settings for `sys` with the compiled functions `c` (the system's own, or
/// specialized to parameter values), and whether the extended Jacobian is used (never
/// analysed without `for_ida`: the ODE methods factor the plain Jacobian).
pub(super) fn ida_settings(
    sys: &SimplifiedSystem,
    c: &CompiledDae,
    options: &SolverOptions,
    for_ida: bool,
) -> (IdaSettings, bool) {
    let n = sys.sorted.mass_matrix_diagonal.len();
    let (matrix, extended) = match options.linear_solver {
        LinearSolver::Auto if n <= ida::DENSE_UP_TO => (IdaMatrix::Dense, false),
        LinearSolver::Auto | LinearSolver::Sparse => {
            (IdaMatrix::SparseLu, for_ida && c.extended().is_some())
        }
        LinearSolver::SparsePlain => (IdaMatrix::SparseLu, false),
        LinearSolver::Dense => (IdaMatrix::Dense, false),
        LinearSolver::DenseDifferenceQuotient => (IdaMatrix::DenseDifferenceQuotient, false),
    };
    let settings = IdaSettings {
        rtol: options.rtol,
        atol: options.atol,
        atol_vector: None,
        max_step: options.max_step,
        initial_step: options.initial_step,
        max_steps: options.max_steps,
        id: sys.sorted.mass_matrix_diagonal.clone(),
        suppress_alg: options.suppress_alg,
        matrix,
        calc_ic: false,
    };
    (settings, extended)
}

/// The crossing functions of a system's event relations, read from its observed
/// function.
struct Crossings<'c> {
    observed: &'c crate::codegen::Tape,
    ws: Workspace,
    out: Vec<f64>,
    /// The observed output of each crossing variable.
    outputs: Vec<usize>,
    /// The relation of each.
    relations: Vec<usize>,
    /// The shift of each: the hysteresis around the relation's current value where its
    /// crossing function starts at zero, else none (set at the first evaluation, the
    /// start of the integration).
    shifts: Vec<f64>,
    /// Whether `shifts` are set.
    started: bool,
    /// Whether a crossing output reads a derivative input (found when an ODE method
    /// first asks; IDA never does).
    reads_derivatives: std::cell::OnceCell<bool>,
}

/// The compiled residual and Jacobian with their workspaces, as IDA's callbacks.
pub(crate) struct CompiledFunctions<'c> {
    c: &'c CompiledDae,
    /// The crossing functions of the events, when the integration looks for them.
    crossings: Option<Crossings<'c>>,
    inputs: Vec<f64>,
    ws: Workspace,
    /// Workspace of the plain Jacobian, made on first use.
    jws: Option<JacobianWorkspace>,
    /// The extended Jacobian and its workspace, when it is used (asked of `c` once, in
    /// [`Self::new`]: the first call analyses it).
    ews: Option<(&'c ExtendedJacobian, ExtendedWorkspace)>,
    /// Recycled workspaces these functions do not use (kept for the next segment):
    /// the extended Jacobian's, the crossing functions'.
    parked: (Option<ExtendedWorkspace>, Option<Workspace>),
    layout: InputLayout,
    /// The signals that drive the model's inputs.
    drivers: Drivers,
}

impl<'c> CompiledFunctions<'c> {
    /// Functions of `c` at parameter values `params`; `extended` selects the extended
    /// Jacobian (when `c` has one; sparse LU only).
    pub(crate) fn new(c: &'c CompiledDae, params: &[f64], extended: bool) -> Self {
        Self::recycling(c, params, extended, None)
    }

    /// [`Self::new`] evaluating in `recycled`, the workspaces of an earlier segment,
    /// where they were made for the same residual (their sparse LUs keep their column
    /// orders and pivots; searching the orders again after each of EngineV6's events
    /// took a third of its solve).
    pub(super) fn recycling(
        c: &'c CompiledDae,
        params: &[f64],
        extended: bool,
        recycled: Option<Workspaces>,
    ) -> Self {
        let layout = c.layout;
        let mut inputs = vec![0.0; layout.len()];
        for (j, &p) in params.iter().enumerate().take(layout.n_params) {
            inputs[layout.param(j)] = p;
        }
        let mut w = recycled.filter(|w| w.tape == c.residual.id);
        // Asked only when wanted: the first call analyses the extended Jacobian.
        let ews = extended.then(|| c.extended()).flatten().map(|e| {
            let ws = w.as_mut().and_then(|w| w.ews.take());
            (e, ws.unwrap_or_else(|| e.workspace(&c.residual)))
        });
        let (ws, jws, parked, crossings) = match w {
            Some(w) => (w.ws, w.jws, w.ews, w.crossings),
            None => (c.residual.workspace(), None, None, None),
        };
        CompiledFunctions {
            c,
            crossings: None,
            inputs,
            ws,
            jws,
            ews,
            parked: (parked, crossings),
            layout,
            drivers: Drivers::default(),
        }
    }

    /// The workspaces, for the next segment ([`Self::recycling`]).
    pub(super) fn into_workspaces(self) -> Workspaces {
        let (parked_ews, parked_crossings) = self.parked;
        Workspaces {
            tape: self.c.residual.id,
            ws: self.ws,
            jws: self.jws,
            ews: self.ews.map(|(_, w)| w).or(parked_ews),
            crossings: self.crossings.map(|c| c.ws).or(parked_crossings),
        }
    }

    /// The same functions with the model's inputs driven by `drivers`.
    pub(crate) fn with_drivers(mut self, drivers: Drivers) -> Self {
        self.drivers = drivers;
        self
    }

    /// The same functions with the crossing functions of `sys`'s event relations (from
    /// `c`'s observed function; the crossing variable `k` is its output `k`'s flat
    /// variable).
    pub(crate) fn with_crossings(mut self, sys: &SimplifiedSystem) -> Self {
        // Time events stop the integration at their instants; the others are found.
        let found: Vec<usize> = (sys.model.events.relations.iter().enumerate())
            .filter(|(_, r)| r.time_event.is_none())
            .map(|(k, _)| k)
            .collect();
        if !found.is_empty() {
            let observed = &*self.c.observed;
            let relations = &sys.model.events.relations;
            let shifts = found
                .iter()
                .map(|&k| {
                    let r = &relations[k];
                    // A crossing function that starts at its zero starts on the side
                    // of its relation's value: by the hysteresis when only discrete
                    // equations read it, else by the least positive normal number (exactly at
                    // zero, it would be inactive where the integration starts, and its
                    // leaving zero would go unseen).
                    let value = self.inputs[self.layout.param(r.parameter)] != 0.0;
                    let band = if r.only_discrete {
                        super::events::HYSTERESIS
                    } else {
                        f64::MIN_POSITIVE
                    };
                    r.hysteresis(value, band)
                })
                .collect();
            let started = false;
            let ws = self.parked.1.take().unwrap_or_else(|| observed.workspace());
            self.crossings = Some(Crossings {
                reads_derivatives: std::cell::OnceCell::new(),
                observed,
                ws,
                out: vec![0.0; observed.n_outputs()],
                outputs: found.iter().map(|&k| relations[k].crossing).collect(),
                relations: found,
                shifts,
                started,
            });
        }
        self
    }

    /// Keeps the hysteresis of the crossing functions that start the integration at
    /// `(t, y, yp)` at zero; the others cross at zero exactly.
    fn start_crossings(&mut self, t: f64, y: &[f64], yp: &[f64]) -> Result<(), EvalError> {
        self.load(t, y, yp)?;
        let Some(c) = &mut self.crossings else {
            return Ok(());
        };
        c.started = true;
        c.observed.eval(&self.inputs, &mut c.ws, &mut c.out)?;
        for (shift, &k) in c.shifts.iter_mut().zip(&c.outputs) {
            if c.out[k].abs() > super::events::CROSSING_ZERO {
                *shift = 0.0;
            }
        }
        Ok(())
    }

    /// The relation of each crossing function.
    fn crossing_relations(&self) -> Vec<usize> {
        self.crossings
            .as_ref()
            .map_or_else(Vec::new, |c| c.relations.clone())
    }

    /// Loads the point `(t, y, yp)` and the inputs' values at `t`.
    fn load(&mut self, t: f64, y: &[f64], yp: &[f64]) -> Result<(), EvalError> {
        let n = self.layout.n;
        self.inputs[InputLayout::TIME] = t;
        if n > 0 {
            let u0 = self.layout.u(0);
            self.inputs[u0..u0 + n].copy_from_slice(y);
            let up0 = self.layout.up(0);
            self.inputs[up0..up0 + n].copy_from_slice(yp);
        }
        self.drivers.load(t, &mut self.inputs, self.layout)
    }
}

impl DaeFunctions for CompiledFunctions<'_> {
    fn len(&self) -> usize {
        self.layout.n
    }

    fn residual(
        &mut self,
        t: f64,
        y: &[f64],
        yp: &[f64],
        out: &mut [f64],
    ) -> Result<(), EvalError> {
        self.load(t, y, yp)?;
        self.c.residual.eval(&self.inputs, &mut self.ws, out)?;
        if let Some(i) = out.iter().position(|v| !v.is_finite()) {
            return Err(EvalError {
                message: format!("residual {i} is not finite at t = {t}"),
                recoverable: true,
            });
        }
        Ok(())
    }

    fn n_roots(&self) -> usize {
        self.crossings.as_ref().map_or(0, |c| c.outputs.len())
    }

    fn roots_read_derivatives(&self) -> bool {
        let (n, up) = (self.layout.n, self.layout.up(0));
        self.crossings.as_ref().is_some_and(|c| {
            *c.reads_derivatives
                .get_or_init(|| c.observed.outputs_read(&c.outputs, up..up + n))
        })
    }

    fn roots(&mut self, t: f64, y: &[f64], yp: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        if self.crossings.as_ref().is_some_and(|c| !c.started) {
            self.start_crossings(t, y, yp)?;
        }
        self.load(t, y, yp)?;
        if let Some(c) = &mut self.crossings {
            c.observed.eval(&self.inputs, &mut c.ws, &mut c.out)?;
            for ((g, &k), shift) in out.iter_mut().zip(&c.outputs).zip(&c.shifts) {
                *g = c.out[k] + shift;
            }
        }
        Ok(())
    }

    fn jacobian_pattern(&self) -> Option<(Vec<usize>, Vec<usize>)> {
        match &self.ews {
            Some((e, _)) => Some((e.col_ptr.clone(), e.row_idx.clone())),
            None => Some((
                self.c.jacobian().col_ptr.clone(),
                self.c.jacobian().row_idx.clone(),
            )),
        }
    }

    fn jacobian_dimension(&self) -> usize {
        match &self.ews {
            Some((e, _)) => e.dimension(),
            None => self.layout.n,
        }
    }

    fn jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        yp: &[f64],
        cj: f64,
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        self.load(t, y, yp)?;
        match &mut self.ews {
            Some((e, ews)) => e.eval(&self.c.residual, &self.inputs, cj, ews, values),
            None => {
                let c = self.c;
                let jws = self
                    .jws
                    .get_or_insert_with(|| c.jacobian().workspace(&c.residual));
                c.jacobian()
                    .eval(&c.residual, &self.inputs, cj, jws, values)
            }
        }
    }
}
