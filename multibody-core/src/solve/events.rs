//! What happens at an event (Modelica's semantics, specification chapter 8): the
//! relations that crossed take their new values, the `when` clauses whose conditions
//! became true set their discrete variables and `reinit` their states, the model is
//! re-initialized around them (the differential unknowns kept: IDA's `IDACalcIC`),
//! and every relation and condition is evaluated again, round after round, until none
//! changes (the event iteration). The same settling applies to the relations at the
//! initial time.

use crate::Error;
use crate::expr::{Cmp, Id, Node};
use crate::simplify::SimplifiedSystem;

use super::dynamic::Observer;
use super::error::SolveError;
use super::ida;
use super::init::InitResult;
use super::options::SolverOptions;
use super::problem::{CompiledFunctions, Workspaces, ida_settings, specialized_for, unknowns_of};
use super::solution::Event;
use crate::codegen::dae::CompiledDae;

/// Rounds of the event iteration before it is given up.
const MAX_EVENT_ITERATIONS: usize = 20;

/// The error of an event iteration that does not settle: `changing` are the relations
/// that changed in its last round.
fn unsettled(sys: &SimplifiedSystem, t: f64, changing: &[String]) -> Error {
    SolveError {
        model: sys.model.name.clone(),
        t,
        flag: "EVENT_ITERATION".into(),
        message: format!(
            "the relations do not settle after {MAX_EVENT_ITERATIONS} rounds of the event \
             iteration; still changing: {}",
            changing.join(", ")
        ),
    }
    .into()
}

/// `init` again with its relations' values at its point (and the discrete equations'
/// values from them), until they agree with the values it used (Modelica evaluates the
/// relations at the initial time as they are).
/// `reinit` initializes with other parameter values.
pub(super) fn settle_initial_relations(
    sys: &SimplifiedSystem,
    t0: f64,
    mut init: InitResult,
    mut reinit: impl FnMut(Vec<f64>) -> Result<InitResult, Error>,
) -> Result<InitResult, Error> {
    let relations = &sys.model.events.relations;
    if relations.is_empty() {
        return Ok(init);
    }
    let mut observer = Observer::new(&sys.compiled.observed, sys.compiled.layout);
    let mut changing = Vec::new();
    for _ in 0..MAX_EVENT_ITERATIONS {
        let (u, up) = unknowns_of(sys, &init.slot_values);
        if !observer.load(t0, &u, &up, &init.params) {
            // Not evaluable there: the integration reports where.
            return Ok(init);
        }
        let mut params = init.params.clone();
        changing.clear();
        // The conditions of sample(..) become true at an event of their own.
        for r in relations.iter().filter(|r| !r.sample) {
            let value = r.holds(observer.base[r.crossing]);
            if (params[r.parameter] != 0.0) != value {
                params[r.parameter] = f64::from(u8::from(value));
                changing.push(r.text.clone());
            }
        }
        // The discrete equations from them (a friction element that starts at rest is
        // locked while it is initialized).
        update_discrete(sys, &mut params, &observer.base, t0, &mut changing)?;
        if changing.is_empty() {
            return Ok(init);
        }
        init = reinit(params)?;
    }
    Err(unsettled(sys, t0, &changing))
}

/// The crossing functions of an event at the initial point `(t0, y, yp)`: the
/// conditions of `sample(..)` whose first instant is the initial time (rising), when
/// there are such, or when the model uses `initial()` (there is an initial event then).
pub(super) fn initial_samples(
    sys: &SimplifiedSystem,
    (t0, y, yp): (f64, &[f64], &[f64]),
    params: &[f64],
) -> Option<Vec<i32>> {
    let relations = &sys.model.events.relations;
    // initial() and the discrete equations (evaluated first at the initial event).
    let initial = !sys.model.events.initial.is_empty() || !sys.model.events.equations.is_empty();
    if !initial && !relations.iter().any(|r| r.sample) {
        return None;
    }
    let mut observer = Observer::new(&sys.compiled.observed, sys.compiled.layout);
    if !observer.load(t0, y, yp, params) {
        return initial.then(|| vec![0; relations.len()]);
    }
    let roots: Vec<i32> = relations
        .iter()
        .map(|r| {
            let starts =
                r.sample && params[r.parameter] == 0.0 && r.holds(observer.base[r.crossing]);
            i32::from(starts)
        })
        .collect();
    (initial || roots.contains(&1)).then_some(roots)
}

/// The instant of the time event `c` (an expression of parameters) at `params`.
fn instant(sys: &SimplifiedSystem, c: Id, params: &[f64]) -> Option<f64> {
    sys.model.arena.eval(c, &|n| match *n {
        Node::Param(j) => params.get(j as usize).copied(),
        _ => None,
    })
}

/// Two instants closer than this (relative to the time) are one.
fn same_instant(t: f64) -> f64 {
    1e3 * f64::EPSILON * t.abs().max(1.0)
}

/// The next time event after `t0` and up to `t_end` at `params`: where the integration
/// stops exactly, without root finding.
pub(super) fn next_time_event(
    sys: &SimplifiedSystem,
    params: &[f64],
    t0: f64,
    t_end: f64,
) -> Option<f64> {
    let tol = same_instant(t0);
    sys.model
        .events
        .relations
        .iter()
        .filter_map(|r| instant(sys, r.time_event?, params))
        .filter(|&c| c > t0 + tol && c <= t_end + same_instant(t_end))
        .min_by(f64::total_cmp)
        .map(|c| c.min(t_end))
}

/// Whether `t` is the stop time of `tspan`.
pub(super) fn at_stop_time(tspan: (f64, f64), t: f64) -> bool {
    (t - tspan.1).abs() <= same_instant(tspan.1)
}

/// The crossing functions of the time event at `t`: rising for the relations of time
/// whose instant it is.
pub(super) fn time_event_roots(sys: &SimplifiedSystem, params: &[f64], t: f64) -> Vec<i32> {
    let tol = same_instant(t);
    sys.model
        .events
        .relations
        .iter()
        .map(|r| {
            let at = r
                .time_event
                .and_then(|c| instant(sys, c, params))
                .is_some_and(|c| (c - t).abs() <= tol);
            i32::from(at)
        })
        .collect()
}

/// The value of a `when` clause's expression `e` at a point: the flat variables'
/// values `base` (the observed function's first outputs), the parameters and time.
fn evaluate(sys: &SimplifiedSystem, e: Id, base: &[f64], params: &[f64], t: f64) -> Option<f64> {
    sys.model
        .arena
        .eval(e, &|n| match *n {
            Node::Var(i) => base.get(i as usize).copied(),
            Node::Param(j) => params.get(j as usize).copied(),
            Node::Time => Some(t),
            _ => None,
        })
        .filter(|v| v.is_finite())
}

/// The error of a `when` clause's expression that cannot be evaluated.
fn not_evaluable(sys: &SimplifiedSystem, t: f64, clause: &str, what: &str) -> Error {
    SolveError {
        model: sys.model.name.clone(),
        t,
        flag: "WHEN".into(),
        message: format!("in the when clause `{clause}`: {what} is not a finite value of variables, parameters and time"),
    }
    .into()
}

/// A crossing function this close to zero is at its zero (the root finding locates it
/// to about the rounding of time, where a crossing function is many orders of
/// magnitude smaller than this).
pub(super) const CROSSING_ZERO: f64 = 1e-8;

/// A relation read only by discrete equations (a friction element's `w_relfric > 0`)
/// whose crossing function is at zero changes only once it is this far beyond zero on
/// the other side, at an event or where an integration starts there (a hysteresis:
/// without it, a crossing function that stays at zero up to rounding, as the relative
/// speed of a stuck friction element, would generate events at every sign change of its
/// rounding errors, and one that starts exactly at zero would not be seen to leave it).
/// Relations that `when` clauses or the continuous equations read have none: a bouncing
/// ball's contact is exact (where an integration starts at their zero, their crossing
/// functions start the least positive normal number away from it, on the side of their value).
pub(super) const HYSTERESIS: f64 = 1e-10;

/// Times a relation takes the same value in quick succession before the events are
/// said to accumulate.
const ACCUMULATION_COUNT: usize = 10;
/// "Quick": within this fraction of the time span.
const ACCUMULATION_INTERVAL: f64 = 1e-9;

/// The events of a run so far: all of them, and per relation and value the time it
/// last took that value and how many times in a row it did so in quick succession.
pub(super) struct History {
    /// Every event, in time order.
    pub events: Vec<Event>,
    /// Whether the event being settled is the terminal one (`terminal()` holds).
    pub terminal: bool,
    /// The last event's time and what it switched (see [`in_mode`]).
    last_switch: Option<(f64, Vec<String>)>,
    last: Vec<[(f64, usize); 2]>,
    interval: f64,
}

impl History {
    /// The history of a run over `tspan` of `sys`.
    pub(super) fn new(sys: &SimplifiedSystem, tspan: (f64, f64)) -> Self {
        History {
            events: Vec::new(),
            terminal: false,
            last_switch: None,
            last: vec![[(f64::NEG_INFINITY, 0); 2]; sys.model.events.relations.len()],
            interval: ACCUMULATION_INTERVAL * (tspan.1 - tspan.0).abs(),
        }
    }

    /// Sets relation `k`'s parameter to `value`; records an event when that changes it.
    /// Fails where the relation's events accumulate (Zeno behaviour: a ball bouncing
    /// ever faster to rest), which no integration can pass.
    fn set(
        &mut self,
        sys: &SimplifiedSystem,
        params: &mut [f64],
        k: usize,
        value: bool,
        t: f64,
    ) -> Result<bool, Error> {
        let r = &sys.model.events.relations[k];
        let changed = (params[r.parameter] != 0.0) != value;
        if !changed {
            return Ok(false);
        }
        params[r.parameter] = f64::from(u8::from(value));
        self.events.push(Event {
            t,
            condition: r.text.clone(),
            value,
            rising: value == matches!(r.op, Cmp::Gt | Cmp::Ge),
        });
        let (last, count) = &mut self.last[k][usize::from(value)];
        *count = if t - *last < self.interval {
            *count + 1
        } else {
            0
        };
        *last = t;
        if *count >= ACCUMULATION_COUNT {
            return Err(SolveError {
                model: sys.model.name.clone(),
                t,
                flag: "EVENT_ACCUMULATION".into(),
                message: format!(
                    "events accumulate: `{}` became {value} {} times in a row within {} s of \
                     the previous time (Zeno behaviour); the model needs a condition that \
                     ends it (such as a ball coming to rest on the ground)",
                    r.text,
                    ACCUMULATION_COUNT + 1,
                    crate::names::number(self.interval)
                ),
            }
            .into());
        }
        Ok(true)
    }
}

/// Settles the event at `t` whose crossing functions `roots` (as
/// [`ida::Integrated::roots`]) ended the integration with the left limit `(y, yp)`:
/// returns the right limit, with `params` holding the new relation values and
/// discrete variables; the relations that changed are recorded in `events`.
/// `specialized` holds the compiled functions specialized for the run (see
/// [`specialized_for`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn settle(
    sys: &SimplifiedSystem,
    tspan: (f64, f64),
    params: &mut [f64],
    point: (f64, Vec<f64>, Vec<f64>),
    roots: &[i32],
    options: &SolverOptions,
    (history, specialized): (&mut History, &mut Option<(Vec<f64>, CompiledDae)>),
    workspaces: &mut Option<Workspaces>,
) -> Result<Settled, Error> {
    let cache = specialized_for(sys, params, options, specialized.take());
    let c = cache.as_ref().map_or(&sys.compiled, |(_, c)| c);
    let t = point.0;
    let before = event_values(sys, params);
    let result = settle_with(
        c,
        sys,
        tspan,
        params,
        point,
        roots,
        options,
        (history, workspaces),
    );
    let switch = switched(sys, &before, params);
    // Where the new mode has no consistent solution, say what switched.
    let result = result.map_err(|e| with_switch(e, t, &switch));
    history.last_switch = Some((t, switch));
    *specialized = cache;
    // initial() holds at the initial event only.
    for &p in &sys.model.events.initial {
        params[p] = 0.0;
    }
    result
}

/// [`settle`] with the compiled functions `c`.
#[allow(clippy::too_many_arguments)]
fn settle_with(
    c: &CompiledDae,
    sys: &SimplifiedSystem,
    tspan: (f64, f64),
    params: &mut [f64],
    (t, mut y, mut yp): (f64, Vec<f64>, Vec<f64>),
    roots: &[i32],
    options: &SolverOptions,
    (history, workspaces): (&mut History, &mut Option<Workspaces>),
) -> Result<Settled, Error> {
    let model = &sys.model.events;
    let mut terminated = None;
    let mut observer = Observer::new(&sys.compiled.observed, sys.compiled.layout);
    // Before the event: pre(x), and whether each when condition held.
    let mut held = vec![false; model.whens.len()];
    if !model.whens.is_empty() || !model.equations.is_empty() {
        if !observer.load(t, &y, &yp, params) {
            return Err(not_evaluable(
                sys,
                t,
                &model.whens[0].text,
                "the point before the event",
            ));
        }
        for &(p, v) in &model.pre {
            params[p] = observer.base[v];
        }
        for (w, h) in model.whens.iter().zip(&mut held) {
            *h = evaluate(sys, w.condition, &observer.base, params, t)
                .ok_or_else(|| not_evaluable(sys, t, &w.text, "the condition"))?
                != 0.0;
        }
    }
    let previous = pre_of_discrete(model);
    // At the initial event (the start, t = tspan.0), initial() becomes true; at the
    // terminal one, terminal().
    if t == tspan.0 && !history.terminal {
        for &p in &model.initial {
            params[p] = 1.0;
        }
    }
    if history.terminal {
        for &p in &model.terminal {
            params[p] = 1.0;
        }
    }
    for (k, (r, &dir)) in model.relations.iter().zip(roots).enumerate() {
        if dir != 0 {
            history.set(sys, params, k, r.holds_after_crossing(dir > 0), t)?;
        }
    }
    let tout1 = t + 1e-3 * (tspan.1 - tspan.0);
    let mut changing = Vec::new();
    for _ in 0..MAX_EVENT_ITERATIONS {
        // The mixed system at fixed pre values: the continuous unknowns with the
        // discrete values, then the relations and the discrete equations from them,
        // until they agree.
        // The segments' workspaces serve here too (their sparse LUs keep their orders).
        let mut consistent = |params: &[f64], y: &[f64], yp: &[f64]| {
            let (settings, extended) = ida_settings(sys, c, options, true);
            let mut f = CompiledFunctions::recycling(c, params, extended, workspaces.take());
            let r = ida::consistent_values(&mut f, t, y, yp, &settings, tout1);
            *workspaces = Some(f.into_workspaces());
            r.map_err(|e| {
                Error::from(SolveError {
                    model: sys.model.name.clone(),
                    t: e.t,
                    flag: e.flag,
                    message: e.message,
                })
            })
        };
        // The event parameters of each round, to recognize a cycle.
        let mut seen: Vec<Vec<f64>> = Vec::new();
        let mut settled = false;
        for _ in 0..MAX_EVENT_ITERATIONS {
            (y, yp) = consistent(params, &y, &yp)?;
            if !observer.load(t, &y, &yp, params) {
                return Ok(Settled { y, yp, terminated });
            }
            changing.clear();
            update_relations(
                sys,
                params,
                &observer.base,
                roots,
                t,
                history,
                &mut changing,
            )?;
            update_discrete(sys, params, &observer.base, t, &mut changing)?;
            if changing.is_empty() {
                settled = true;
                break;
            }
            let now = event_values(sys, params);
            if let Some(first) = seen.iter().position(|v| *v == now) {
                // The rounds cycle: search the relations that change in the cycle for
                // values that the point they give reproduces.
                let varying = varying_relations(sys, &seen[first..]);
                if let Some((y1, yp1)) =
                    search_consistent(sys, params, &varying, &mut observer, t, |p| {
                        consistent(p, &y, &yp)
                    })?
                {
                    (y, yp) = (y1, yp1);
                    settled = true;
                }
                break;
            }
            seen.push(now);
        }
        if !settled {
            return Err(unsettled(sys, t, &changing));
        }
        // Whether a clause of the current when/elsewhen chain fired this round.
        let mut chain_fired = false;
        for (w, h) in model.whens.iter().zip(&mut held) {
            let now = evaluate(sys, w.condition, &observer.base, params, t)
                .ok_or_else(|| not_evaluable(sys, t, &w.text, "the condition"))?
                != 0.0;
            if !w.elsewhen {
                chain_fired = false;
            }
            let fires = now && !*h && !chain_fired;
            chain_fired |= fires;
            if fires {
                // Every right-hand side at the point the round started from.
                let base = observer.base.clone();
                for &(p, e) in &w.assignments {
                    params[p] = evaluate(sys, e, &base, params, t)
                        .ok_or_else(|| not_evaluable(sys, t, &w.text, "an assigned value"))?;
                }
                for r in &w.reinits {
                    y[r.unknown] = evaluate(sys, r.value, &base, params, t)
                        .ok_or_else(|| not_evaluable(sys, t, &w.text, "a reinit value"))?;
                }
                if let Some(m) = &w.terminate {
                    terminated.get_or_insert_with(|| m.clone());
                }
                changing.push(format!("when {}", w.text));
            }
            *h = now;
        }
        // The next round's pre(v) of a discrete variable is its value from this one.
        for &(k, p) in &previous {
            if params[k] != params[p] {
                params[k] = params[p];
                changing.push(sys.model.parameters[p].description.to_string());
            }
        }
        if changing.is_empty() {
            return Ok(Settled { y, yp, terminated });
        }
    }
    Err(unsettled(sys, t, &changing))
}

/// Sets the relations from the crossing functions in `base` (the flat variables'
/// values); pushes those that changed to `changing`. `roots` are the crossings that
/// ended the integration.
fn update_relations(
    sys: &SimplifiedSystem,
    params: &mut [f64],
    base: &[f64],
    roots: &[i32],
    t: f64,
    history: &mut History,
    changing: &mut Vec<String>,
) -> Result<(), Error> {
    for (k, (r, &dir)) in sys.model.events.relations.iter().zip(roots).enumerate() {
        // A relation that crossed here keeps the value its crossing gave it while its
        // crossing function stays at zero (where evaluating it decides nothing); one
        // that a reinit or a discrete change moved away is evaluated.
        let g = base[r.crossing];
        if dir != 0 && g.abs() <= CROSSING_ZERO {
            continue;
        }
        // Read only by discrete equations, it has a hysteresis (see HYSTERESIS).
        let value = params[r.parameter] != 0.0;
        let shift = if r.only_discrete {
            r.hysteresis(value, HYSTERESIS)
        } else {
            0.0
        };
        if history.set(sys, params, k, r.holds(g + shift), t)? {
            changing.push(r.text.clone());
        }
    }
    Ok(())
}

/// Evaluates the discrete equations, each after those it reads, at the flat variables'
/// values `base`; pushes the variables that changed to `changing`.
fn update_discrete(
    sys: &SimplifiedSystem,
    params: &mut [f64],
    base: &[f64],
    t: f64,
    changing: &mut Vec<String>,
) -> Result<(), Error> {
    for d in &sys.model.events.equations {
        let v = evaluate(sys, d.value, base, params, t).ok_or_else(|| {
            Error::from(SolveError {
                model: sys.model.name.clone(),
                t,
                flag: "WHEN".into(),
                message: format!(
                    "the equation of the discrete variable `{}` is not a finite value of \
                     variables, parameters and time",
                    d.name
                ),
            })
        })?;
        if params[d.parameter] != v {
            params[d.parameter] = v;
            changing.push(d.name.clone());
        }
    }
    Ok(())
}

/// The values of the relations and the discrete equations' variables.
fn event_values(sys: &SimplifiedSystem, params: &[f64]) -> Vec<f64> {
    let events = &sys.model.events;
    (events.relations.iter().map(|r| params[r.parameter]))
        .chain(events.equations.iter().map(|d| params[d.parameter]))
        .collect()
}

/// `error` with what the last event switched, where the integration fails at that event
/// (the mode it switched to has no consistent solution).
pub(super) fn in_mode(error: Error, history: &History) -> Error {
    match &history.last_switch {
        Some((t, switched)) if matches!(&error, Error::Solve(e) if (e.t - t).abs() <= same_instant(*t)) => {
            with_switch(error, *t, switched)
        }
        _ => error,
    }
}

/// `error` (of the solver) with what the event at `t` switched, if anything.
fn with_switch(error: Error, t: f64, switched: &[String]) -> Error {
    match error {
        Error::Solve(mut e) if !switched.is_empty() => {
            e.message = format!(
                "{}; the equations have no consistent solution in the mode the event at t = \
                 {t} switched to: {}",
                e.message,
                switched.join(", ")
            );
            Error::Solve(e)
        }
        error => error,
    }
}

/// What differs between `before` (of [`event_values`]) and `params`: each relation as
/// written with its new value, each discrete variable with its new value.
fn switched(sys: &SimplifiedSystem, before: &[f64], params: &[f64]) -> Vec<String> {
    let events = &sys.model.events;
    let now = event_values(sys, params);
    let relations = events.relations.iter().map(|r| r.text.as_str());
    let discrete = events.equations.iter().map(|d| d.name.as_str());
    relations
        .clone()
        .zip(before.iter().zip(&now))
        .filter(|(_, (a, b))| a != b)
        .map(|(text, (_, &b))| format!("`{text}` is now {}", b != 0.0))
        .chain(
            discrete
                .zip(
                    before[relations.len()..]
                        .iter()
                        .zip(&now[events.relations.len()..]),
                )
                .filter(|(_, (a, b))| a != b)
                .map(|(name, (_, b))| format!("`{name}` = {b}")),
        )
        .collect()
}

/// The relations whose values differ among the rounds `cycle` (of [`event_values`]).
fn varying_relations(sys: &SimplifiedSystem, cycle: &[Vec<f64>]) -> Vec<usize> {
    (0..sys.model.events.relations.len())
        .filter(|&k| cycle.iter().any(|v| v[k] != cycle[0][k]))
        .collect()
}

/// The unknowns and their derivatives at a point.
type Point = (Vec<f64>, Vec<f64>);

/// Relations of a cycle searched at most (2^this combinations).
const MAX_SEARCHED_RELATIONS: usize = 10;

/// Searches values of the relations `varying` (fewest true first) whose discrete values
/// and consistent point (from `consistent`) reproduce them: a mixed system that the
/// rounds of the event iteration cycle around (a friction element that sticks, where
/// either sliding direction predicts the other). Leaves `params` at the values found and
/// returns the point, or `None` when no combination is consistent.
fn search_consistent(
    sys: &SimplifiedSystem,
    params: &mut [f64],
    varying: &[usize],
    observer: &mut Observer,
    t: f64,
    mut consistent: impl FnMut(&[f64]) -> Result<Point, Error>,
) -> Result<Option<Point>, Error> {
    if varying.is_empty() || varying.len() > MAX_SEARCHED_RELATIONS {
        return Ok(None);
    }
    let relations = &sys.model.events.relations;
    let mut combinations: Vec<u32> = (0..1u32 << varying.len()).collect();
    combinations.sort_by_key(|m| m.count_ones());
    let start = params.to_vec();
    for m in combinations {
        params.copy_from_slice(&start);
        for (bit, &k) in varying.iter().enumerate() {
            params[relations[k].parameter] = f64::from(u8::from(m & (1 << bit) != 0));
        }
        let mut ignored = Vec::new();
        update_discrete(sys, params, &observer.base.clone(), t, &mut ignored)?;
        let Ok((y, yp)) = consistent(params) else {
            continue;
        };
        if !observer.load(t, &y, &yp, params) {
            continue;
        }
        let reproduced = relations.iter().all(|r| {
            let value = params[r.parameter] != 0.0;
            r.holds(observer.base[r.crossing]) == value
        });
        let mut changed = Vec::new();
        update_discrete(sys, params, &observer.base.clone(), t, &mut changed)?;
        if reproduced && changed.is_empty() {
            return Ok(Some((y, yp)));
        }
    }
    params.copy_from_slice(&start);
    Ok(None)
}

/// `(pre parameter, parameter)` for each `pre(v)` of a discrete variable `v`.
fn pre_of_discrete(model: &crate::simplify::Events) -> Vec<(usize, usize)> {
    model
        .pre
        .iter()
        .filter_map(|&(k, v)| {
            let &(_, p) = model.discrete.iter().find(|&&(d, _)| d == v)?;
            Some((k, p))
        })
        .collect()
}

/// The right limit at a settled event.
pub(super) struct Settled {
    /// The unknowns.
    pub y: Vec<f64>,
    /// Their derivatives.
    pub yp: Vec<f64>,
    /// The message of a `terminate(..)` that ends the simulation here.
    pub terminated: Option<String>,
}
