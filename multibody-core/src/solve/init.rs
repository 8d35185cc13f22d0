//! Consistent initialization: a problem of its own at the initial time.
//!
//! Its unknowns are every slot of the reduced system (variables, states, derivatives,
//! dummy derivatives) and the parameters computed at initialization (`fixed = false`).
//! Its equations are the model's (including the differentiated ones: velocity and
//! acceleration constraints hold at t0 too), the initial equations and the fixed start
//! values. When they leave degrees of freedom open, the start values of states are
//! assumed fixed (reported, like Dymola's translation log), chosen by augmenting paths
//! so that the system stays structurally regular. The system is then sorted and torn
//! like the DAE, and its iteration variables solved by damped Newton with the exact
//! sparse Jacobian; other start values serve as guesses.

use std::sync::Arc;

use crate::hash::HashMap;
use crate::model::EquationText;

use crate::codegen::dae::{DaeSpec, ResidualRow, compile_dae};
use crate::expr::{Id, IdIndex, Node};
use crate::simplify::SimplifiedSystem;
use crate::simplify::causalize::{
    LinearBlockLimits, Temporaries, causalize_graph, incidence_graph,
};
use crate::structure::dm::dulmage_mendelsohn;
use crate::structure::matching::{Augmenter, maximum_matching};

use super::error::InitError;
use super::newton::{NewtonOptions, newton};

/// What an equation of the initialization system is, shown in its error messages
/// (written out only then; an assumed start carries its slot's name, which the report
/// of assumed values needs anyway).
enum InitText<'a> {
    /// An equation of the simplified model.
    Model(&'a EquationText),
    /// An initial equation, as written.
    Initial(&'a str),
    /// The fixed start value of a variable.
    FixedStart(&'a str),
    /// A start value assumed to complete the initial conditions (the slot's name).
    AssumedStart(String),
}

impl std::fmt::Display for InitText<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            InitText::Model(text) => write!(f, "{text}"),
            InitText::Initial(text) => write!(f, "initial equation {text}"),
            InitText::FixedStart(name) => write!(f, "fixed start value of {name}"),
            InitText::AssumedStart(name) => write!(f, "assumed start value of {name}"),
        }
    }
}

/// Numeric inputs of an initialization.
pub(crate) struct InitInput<'a> {
    pub sys: &'a SimplifiedSystem,
    pub t0: f64,
    /// All parameter values (those computed at initialization hold their guesses).
    pub params: Vec<f64>,
    /// Start values per flat variable.
    pub starts: Vec<Option<f64>>,
    /// Whether each flat variable's start value is fixed.
    pub fixed: Vec<bool>,
    /// Iteration guesses per flat variable (override the start value as a guess).
    pub guesses: Vec<Option<f64>>,
}

/// The consistent values at the initial time.
#[derive(Clone, Debug)]
pub(crate) struct InitResult {
    /// Value of each slot.
    pub slot_values: Vec<f64>,
    /// All parameter values, the computed ones included.
    pub params: Vec<f64>,
    /// Start values assumed fixed to complete the initial conditions.
    pub assumed: Vec<(String, f64)>,
    /// Newton iterations.
    pub iterations: usize,
    /// Names of the iteration variables.
    pub iteration_variables: Vec<String>,
}

/// `r` with each derivative `der(x)` that the reduced model does not contain replaced by
/// `-(b / a) der(y)`, where an equation of the reduced model reads `a x + b y = 0` and
/// `der(y)` is in it (`index`): an initial equation on the derivative of a variable that
/// alias elimination left as an alias of a state's (two speeds of one flange).
fn derivatives_through_aliases(
    sys: &SimplifiedSystem,
    arena: &mut crate::expr::Arena,
    r: Id,
    index: &IdIndex,
) -> Id {
    let mut map = crate::hash::HashMap::default();
    for l in arena.leaves(r) {
        let Node::Der(x) = *arena.node(l) else {
            continue;
        };
        if index.contains(l) || !matches!(arena.node(x), Node::Var(_)) {
            continue;
        }
        let found = sys.reduction.equations.iter().find_map(|e| {
            let Node::Sum(ts, c) = *arena.node(e.residual) else {
                return None;
            };
            let terms = arena.terms(ts);
            if f64::from_bits(c) != 0.0 || terms.len() != 2 {
                return None;
            }
            let (a, b) = match (terms[0], terms[1]) {
                ((ka, ta), (kb, tb)) if ta == x => ((ka, ta), (kb, tb)),
                ((kb, tb), (ka, ta)) if ta == x => ((ka, ta), (kb, tb)),
                _ => return None,
            };
            let y = b.1;
            let slot = sys.reduction.slot_of.get(y)?;
            let d = sys.reduction.var_diff[slot]?;
            let dy = sys.reduction.slots[d].leaf;
            index
                .contains(dy)
                .then(|| (-f64::from_bits(b.0) / f64::from_bits(a.0), dy))
        });
        if let Some((k, dy)) = found {
            let value = arena.scale(k, dy);
            map.insert(l, value);
        }
    }
    if map.is_empty() {
        r
    } else {
        arena.substitute_leaves(r, &map)
    }
}

/// Finds consistent initial values.
#[allow(clippy::result_large_err)] // built once per problem, reported to the user
pub(crate) fn initialize(input: InitInput<'_>) -> Result<InitResult, InitError> {
    let sys = input.sys;
    let model = sys.model.name.clone();
    // The model's expressions are shared, not copied: the initialization's own nodes
    // go on top of them.
    let mut arena = crate::expr::Arena::extending(sys.model.arena.clone());
    let np = sys.model.parameters.len();
    let nv = sys.model.variables.len();
    // Its equations (derivatives, start values, tearing) add about half as many nodes
    // again, and a parameter per start value.
    arena.reserve(np + nv, sys.model.arena.len() / 2);
    let start_leaf: Vec<Id> = (0..nv).map(|i| arena.param((np + i) as u32)).collect();

    // Unknowns: slots, then parameters computed at initialization.
    let free_params: Vec<usize> = (0..np)
        .filter(|&j| !sys.model.parameters[j].fixed)
        .collect();
    let mut unknowns: Vec<Id> = Vec::with_capacity(sys.reduction.slots.len() + free_params.len());
    unknowns.extend(sys.reduction.slots.iter().map(|s| s.leaf));
    for &j in &free_params {
        unknowns.push(arena.param(j as u32));
    }
    let index = IdIndex::new(&unknowns);

    // Mandatory equations (as many as unknowns in the end, once completed).
    let mut eqs: Vec<(Id, InitText<'_>)> = Vec::with_capacity(unknowns.len());
    eqs.extend(
        sys.reduction
            .equations
            .iter()
            .map(|e| (e.residual, InitText::Model(&e.text))),
    );
    for (r, text) in &sys.reduction.initial_equations {
        let r = &derivatives_through_aliases(sys, &mut arena, *r, &index);
        for l in arena.leaves(*r) {
            if matches!(arena.node(l), Node::Var(_) | Node::Der(_)) && !index.contains(l) {
                return Err(InitError::BadValue {
                    model,
                    message: format!(
                        "the initial equation `{text}` uses `{}`, which the reduced model does \
                         not contain",
                        arena.display(l, &sys.resolver())
                    ),
                });
            }
        }
        eqs.push((*r, InitText::Initial(text)));
    }
    let mut implied: Vec<(usize, Id)> = Vec::new();
    for i in 0..nv {
        if !input.fixed[i] {
            continue;
        }
        let value = match sys.reduction.replaced[i] {
            Some(r) => r,
            None => arena.var(i as u32),
        };
        let has_unknown = arena.leaves(value).iter().any(|&l| index.contains(l));
        if !has_unknown {
            implied.push((i, value));
            continue;
        }
        let r = arena.sub(value, start_leaf[i]);
        eqs.push((r, InitText::FixedStart(&sys.model.variables[i].name)));
    }

    // Structure: mandatory equations must be matchable.
    let mut graph = incidence_graph(&arena, eqs.iter().map(|e| e.0), &index, unknowns.len());
    let m = maximum_matching(&graph, None, None);
    if m.size() < eqs.len() {
        let dm = dulmage_mendelsohn(&graph, &m, None);
        let list = if dm.over_eqs.is_empty() {
            dm.unmatched_eqs
        } else {
            dm.over_eqs
        };
        return Err(InitError::OverDetermined {
            model,
            equations: list.iter().map(|&e| eqs[e].1.to_string()).collect(),
        });
    }
    let mut var_to_eq = m.var_to_eq.clone();
    let mut eq_to_var = m.eq_to_var.clone();

    // Complete with start values, by augmenting paths: first states that have a start
    // value, then other variables that have one, then the remaining states (at 0).
    let mut assumed = Vec::new();
    let is_state: Vec<bool> = {
        let mut v = vec![false; sys.reduction.slots.len()];
        for &s in &sys.reduction.states {
            v[s] = true;
        }
        v
    };
    let has_start = |s: usize| {
        let slot = &sys.reduction.slots[s];
        slot.order == 0 && input.starts[slot.var].is_some()
    };
    let class = |s: usize| match (is_state[s], has_start(s)) {
        (true, true) => 0,
        (false, true) => 1,
        _ => 2,
    };
    // Other variables qualify only if they could have been states (they have a
    // derivative): never orientation matrix entries and the like.
    let candidates: Vec<usize> = (0..sys.reduction.slots.len())
        .filter(|&s| is_state[s] || (has_start(s) && sys.reduction.var_diff[s].is_some()))
        .collect();
    // Sort keys first: comparing through the slots and variables would jump around
    // memory at every comparison.
    let key = |s: usize| {
        (
            class(s),
            -sys.model.variables[sys.reduction.slots[s].var].state_priority,
        )
    };
    let mut keyed: Vec<((u8, f64), usize)> = candidates.iter().map(|&s| (key(s), s)).collect();
    keyed.sort_by(|(ka, a), (kb, b)| ka.0.cmp(&kb.0).then(ka.1.total_cmp(&kb.1)).then(a.cmp(b)));
    let candidates: Vec<usize> = keyed.into_iter().map(|(_, s)| s).collect();
    let mut deficiency = unknowns.len() - eqs.len();
    let mut augmenter = Augmenter::new(unknowns.len(), unknowns.len());
    for s in candidates {
        if deficiency == 0 {
            break;
        }
        let slot = &sys.reduction.slots[s];
        let k = index.get(slot.leaf).expect("a slot is an unknown");
        graph.eq_vars.push(&[k]);
        let e_new = graph.eq_vars.len() - 1;
        eq_to_var.push(None);
        if augmenter.augment(&graph.eq_vars, e_new, &mut var_to_eq, &mut eq_to_var) {
            let value = if slot.order == 0 {
                input.starts[slot.var].unwrap_or(0.0)
            } else {
                0.0
            };
            let r = if slot.order == 0 {
                arena.sub(slot.leaf, start_leaf[slot.var])
            } else {
                slot.leaf
            };
            let name = slot.name(&sys.model.variables);
            eqs.push((r, InitText::AssumedStart(name.clone())));
            assumed.push((name, value));
            deficiency -= 1;
        } else {
            eq_to_var.pop();
            graph.eq_vars.pop();
        }
    }
    if deficiency > 0 {
        let m = maximum_matching(&graph, None, None);
        let dm = dulmage_mendelsohn(&graph, &m, None);
        return Err(InitError::UnderDetermined {
            model,
            variables: dm
                .unmatched_vars
                .iter()
                .map(|&k| sys.leaf_name_in(&arena, unknowns[k]))
                .collect(),
        });
    }
    for (name, value) in &assumed {
        log::info!("initialization of `{model}`: assuming the start value {name} = {value}");
    }

    // Sort, tear and compile the initialization system.
    let residuals: Vec<Id> = eqs.iter().map(|e| e.0).collect();
    let mut known: Vec<f64> = input.params.clone();
    known.extend(input.starts.iter().map(|s| s.unwrap_or(0.0)));
    // Orientation entries are computed from the joint coordinates, never iterated on
    // (as in the DAE's own tearing).
    let never_tear = &sys.reduction.never_tear;
    // Slots (the variables themselves, not their derivatives) rank as tearing and
    // iteration variables by their state priority.
    let tear_priority: HashMap<Id, f64> = sys
        .reduction
        .slots
        .iter()
        .filter(|s| s.order == 0 && sys.model.variables[s.var].state_priority != 0.0)
        .map(|s| (s.leaf, sys.model.variables[s.var].state_priority))
        .collect();
    let mut temps = Temporaries {
        next: sys.sorted.next_temporary,
        params: &known,
        never_tear,
        tear_priority: &tear_priority,
    };
    // The incidence built above (with a row for every assumed start) is exactly what
    // causalizing would read from the residuals again.
    let schedule = causalize_graph(
        &mut arena,
        &residuals,
        &unknowns,
        &graph,
        // The model's equations come first, as the model's schedule numbers them.
        &sys.sorted.schedule.solved_for,
        LinearBlockLimits::default(),
        &mut temps,
    )
    .map_err(|s| InitError::OverDetermined {
        model: model.clone(),
        equations: s
            .over_equations
            .iter()
            .map(|&e| eqs[e].1.to_string())
            .collect(),
    })?;
    let rows: Vec<ResidualRow> = schedule
        .residuals
        .iter()
        .map(|&(residual, equation)| ResidualRow::Equation { residual, equation })
        .collect();
    let n_unknowns = unknowns.len();
    let observed_names = Arc::new(crate::names::NameIndex::lazy(move || {
        vec![crate::model::SharedText::default(); n_unknowns]
    }));
    let compiled = compile_dae(
        &mut arena,
        &DaeSpec {
            steps: &schedule.steps,
            unknowns: &schedule.iteration,
            derivative_inputs: &[],
            rows: &rows,
            observed: &unknowns,
            observed_names,
            n_params: np + nv,
            names: &|id| {
                sys.reduction
                    .slot_of
                    .get(id)
                    .map(|s| sys.reduction.slots[s].name(&sys.model.variables))
                    .unwrap_or_else(|| format!("{id:?}"))
            },
        },
    )
    .map_err(|e| InitError::BadValue {
        model: model.clone(),
        message: format!("compiling the initialization failed: {e}"),
    })?;
    let layout = compiled.layout;
    let mut inputs = vec![0.0; layout.len()];
    inputs[crate::codegen::dae::InputLayout::TIME] = input.t0;
    for j in 0..np {
        inputs[layout.param(j)] = input.params[j];
    }
    for i in 0..nv {
        inputs[layout.param(np + i)] = input.starts[i].unwrap_or(0.0);
    }
    for (k, &l) in schedule.iteration.iter().enumerate() {
        inputs[layout.u(k)] = guess(sys, &input, &arena, l);
    }
    let iteration_variables: Vec<String> = schedule
        .iteration
        .iter()
        .map(|&l| sys.leaf_name_in(&arena, l))
        .collect();
    let outcome = newton(
        &compiled.residual,
        compiled.jacobian(),
        &mut inputs,
        layout.u(0),
        NewtonOptions::default(),
    );
    if !outcome.converged {
        let mut worst: Vec<(usize, f64)> = outcome.residuals.iter().copied().enumerate().collect();
        worst.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
        let residuals = worst
            .iter()
            .take(6)
            .map(|&(k, r)| (eqs[schedule.residuals[k].1].1.to_string(), r.abs()))
            .collect();
        let variables = schedule
            .iteration
            .iter()
            .enumerate()
            .take(16)
            .map(|(k, &l)| (sys.leaf_name_in(&arena, l), inputs[layout.u(k)]))
            .collect();
        log::debug!("initialization of `{model}` failed: {}", outcome.reason);
        let mut conditions: Vec<(String, f64)> = (0..nv)
            .filter(|&i| input.fixed[i])
            .map(|i| {
                (
                    sys.model.variables[i].name.to_string(),
                    input.starts[i].unwrap_or(0.0),
                )
            })
            .collect();
        conditions.extend(assumed.iter().cloned());
        return Err(InitError::NotConverged {
            model,
            iterations: outcome.iterations,
            reason: outcome.reason,
            residuals,
            variables,
            conditions,
        });
    }
    nearest_turns(&compiled, &mut inputs, layout, &schedule.iteration, |l| {
        sys.reduction
            .slot_of
            .get(l)
            .filter(|&s| sys.reduction.slots[s].order == 0)
            .and_then(|s| {
                let v = sys.reduction.slots[s].var;
                input.guesses[v].or(input.starts[v])
            })
    });
    let mut values = vec![0.0; unknowns.len()];
    let mut ws = compiled.observed.workspace();
    compiled
        .observed
        .eval(&inputs, &mut ws, &mut values)
        .map_err(|e| InitError::BadValue {
            model: model.clone(),
            message: format!("evaluating the initial values failed: {}", e.message),
        })?;
    let n_slots = sys.reduction.slots.len();
    let mut params = input.params.clone();
    for (k, &j) in free_params.iter().enumerate() {
        params[j] = values[n_slots + k];
    }
    // Fixed start values of variables the model determines without unknowns.
    for (i, value) in implied {
        let v = arena.eval(value, &|n: &Node| match n {
            Node::Param(j) => params.get(*j as usize).copied(),
            _ => None,
        });
        let start = input.starts[i].unwrap_or(0.0);
        if let Some(v) = v
            && (v - start).abs() > 1e-8 * (1.0 + v.abs())
        {
            return Err(InitError::Inconsistent {
                model,
                variable: sys.model.variables[i].name.to_string(),
                start,
                value: v,
            });
        }
    }
    values.truncate(n_slots);
    Ok(InitResult {
        slot_values: values,
        params,
        assumed,
        iterations: outcome.iterations,
        iteration_variables,
    })
}

/// Iteration variables that converged whole turns (2 pi) away from their guess or start
/// value (a joint angle that Newton's first steps carried round) are brought back by
/// those turns where the system is as well solved there: the solution nearest the
/// start, as a user who gave it expects.
fn nearest_turns(
    compiled: &crate::codegen::dae::CompiledDae,
    inputs: &mut [f64],
    layout: crate::codegen::dae::InputLayout,
    iteration: &[Id],
    start: impl Fn(Id) -> Option<f64>,
) {
    use std::f64::consts::{PI, TAU};
    let residual = &compiled.residual;
    let mut ws = residual.workspace();
    let mut out = vec![0.0; residual.n_outputs()];
    let mut worst = |inputs: &[f64], ws: &mut crate::codegen::Workspace| -> f64 {
        match residual.eval(inputs, ws, &mut out) {
            Ok(()) => out.iter().fold(0.0f64, |m, v| m.max(v.abs())),
            Err(_) => f64::INFINITY,
        }
    };
    let mut converged = None;
    for (k, &l) in iteration.iter().enumerate() {
        let Some(s) = start(l) else { continue };
        let slot = layout.u(k);
        let x = inputs[slot];
        let off = (x - s).abs();
        if off.is_nan() || off <= PI {
            continue;
        }
        let converged = *converged.get_or_insert_with(|| worst(inputs, &mut ws));
        inputs[slot] = x + TAU * ((s - x) / TAU).round();
        let there = worst(inputs, &mut ws);
        if there.is_nan() || there > 10.0 * converged + 1e-12 {
            inputs[slot] = x;
        }
    }
}

/// The first guess of an iteration variable: its guess, its start value, or 0.
fn guess(sys: &SimplifiedSystem, input: &InitInput<'_>, arena: &crate::expr::Arena, l: Id) -> f64 {
    if let Some(s) = sys.reduction.slot_of.get(l) {
        let slot = &sys.reduction.slots[s];
        if slot.order == 0 {
            return input.guesses[slot.var]
                .or(input.starts[slot.var])
                .unwrap_or(0.0);
        }
        return 0.0;
    }
    if let Node::Param(j) = arena.node(l) {
        return input.params.get(*j as usize).copied().unwrap_or(0.0);
    }
    0.0
}
