//! `structural_simplify`: from a model to states, algebraic unknowns and residuals.
//!
//! The pipeline reads as its stages, each a function here on the algorithm of its own
//! file:
//! 1. flattening, the balance check and folding of evaluated parameters
//!    (`flatten_stage`, on [`crate::model::flatten`] and `evaluate.rs`);
//! 2. alias elimination (`alias_stage`, `alias.rs`);
//! 3. index reduction and state selection (`reduce.rs`, on the integer algorithms of
//!    [`crate::structure`]: Pantelides, dummy derivatives);
//! 4. causalization (`causalize_stage`, [`mod@causalize`]: matching, BLT, tearing, and
//!    where linear blocks are solved);
//! 5. the order of the unknowns and the residual's rows (`order_unknowns`);
//! 6. code generation ([`crate::codegen::dae`]);
//! 7. the translation statistics (`statistics`),
//!
//! assembled into a [`SimplifiedSystem`]. Where the choice of states depends on the
//! configuration, stages 1 to 7 run again with dynamic states (`dynamic_states.rs`).
//!
//! The layering is one way: `structure` (integer algorithms on plain data) and `expr`
//! underneath, then `model`, `codegen`, `simplify` and `solve`; codegen compiles plain
//! statements ([`crate::codegen::Stmt`]) on expressions and knows nothing of models or
//! of how the statements were found.

mod alias;
pub mod causalize;
pub mod dynamic_states;
mod error;
mod evaluate;
pub mod events;
mod inputs;
mod pre_eliminate;
pub(crate) mod reduce;
mod reroot;
mod system;

#[cfg(test)]
mod causalize_reuse_tests;
#[cfg(test)]
mod linear_block_tests;
#[cfg(test)]
mod tests;

use crate::hash::{HashMap, HashSet};
use std::sync::Arc;
use std::time::Instant;

pub use crate::codegen::dae::ResidualRow;
pub use causalize::{BlockKind, LinearBlockLimits};
pub use dynamic_states::DynamicStateGroup;
pub use error::SimplifyError;
pub use events::{DiscreteEquation, EventRelation, EventWhen, Events, Reinit};
pub use reduce::Slot;
use system::{DynamicSelection, ModelData, Reduction, Sorted};
pub use system::{PhaseTimes, SimplifiedSystem, StateCandidates, Statistics};

use crate::Error;
use crate::codegen::Stmt;
use crate::codegen::dae::{DaeSpec, compile_dae};
use crate::expr::Id;
use crate::model::{EquationText, FlatOrigins, System, Variable, check_balance, flatten};
use crate::structure::BipartiteGraph;

use causalize::{Schedule, Temporaries, causalize_graph};
use reduce::{ReduceInput, reduce};

/// Options of [`structural_simplify_with`].
#[derive(Clone, Debug, PartialEq)]
pub struct SimplifyOptions {
    /// Where linear algebraic blocks are solved (default: [`LinearBlockLimits::default`],
    /// blocks up to 400 equations with at most 24 tearing variables inside; a knob of
    /// the benchmarks).
    #[doc(hidden)]
    pub linear_blocks: LinearBlockLimits,
    /// Folds the value of every tunable parameter into the equations, as if all were
    /// declared `evaluate = true` (Dymola's "Evaluate parameters to reduce models"):
    /// smaller, faster code, but changing a parameter then needs a new
    /// `structural_simplify` (default: false; parameters marked `evaluate` are folded
    /// either way).
    pub evaluate_parameters: bool,
    /// What to do with planar kinematic loops (closed loops whose revolute joints have
    /// parallel axes), which the `multibody` crate's `structural_simplify_with` detects
    /// from the mechanism's geometry (default: [`PlanarLoops::Diagnose`]).
    pub planar_loops: PlanarLoops,
    /// Where the choice of states among a group of candidates depends on the
    /// configuration (the joint angles of a kinematic loop): whether the model gets
    /// dynamic states, whose selection the solver changes at run time when the current
    /// one degrades (Mattsson, Olsson and Elmqvist 2000; default:
    /// [`DynamicStates::WhenNeeded`]).
    pub dynamic_state_selection: DynamicStates,
    /// Variables that are the model's inputs, by full path (`"torque.tau"`): each
    /// becomes a parameter of the compiled model (of the same name) whose value a problem
    /// gives, as a constant ([`ProblemBuilder::value`](crate::solve::ProblemBuilder::value))
    /// or as a function of time
    /// ([`ProblemBuilder::input`](crate::solve::ProblemBuilder::input)), without
    /// compiling again; [`linearize`](crate::solve::linearize) takes them as inputs.
    /// Usually signal inputs connected to nothing; any unknown can be one, so long as
    /// index reduction does not need its derivative (default: none).
    pub inputs: Vec<String>,
    /// Makes every signal input connected to nothing an input of the model, as if named
    /// in [`Self::inputs`] (without it such an input leaves the model unbalanced, an
    /// error that names it; default: false).
    pub open_inputs: bool,
}

/// When a model gets dynamic states (see [`SimplifyOptions::dynamic_state_selection`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum DynamicStates {
    /// Never: the static choice of states holds for the whole run.
    Off,
    /// The model is compiled with the static choice of states; a solve that finds it
    /// degrading (or failing) compiles the model once more with dynamic states and
    /// solves that instead (the default).
    #[default]
    WhenNeeded,
    /// The model is compiled with dynamic states from the start.
    Always,
}

impl Default for SimplifyOptions {
    fn default() -> Self {
        SimplifyOptions {
            linear_blocks: LinearBlockLimits::default(),
            evaluate_parameters: false,
            planar_loops: PlanarLoops::default(),
            dynamic_state_selection: DynamicStates::WhenNeeded,
            inputs: Vec::new(),
            open_inputs: false,
        }
    }
}

/// Treatment of planar kinematic loops (see [`SimplifyOptions::planar_loops`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum PlanarLoops {
    /// Report the loop and its joints as an error (the default, as Dymola does).
    #[default]
    Diagnose,
    /// Remove the redundant constraints: one revolute joint of each planar loop becomes
    /// a planar cut (in-plane position and rotation about the axis constrained; the
    /// force along the axis and the torques across it zero). The model's variables all
    /// stay.
    RemoveRedundant,
}

/// Simplifies a model with default options: see [`structural_simplify_with`].
pub fn structural_simplify(model: &System) -> Result<SimplifiedSystem, Error> {
    structural_simplify_with(model, &SimplifyOptions::default())
}

/// Flattens `model`, checks its balance, eliminates aliases, reduces the index,
/// selects states, sorts and tears the equations, and compiles the residual, its
/// Jacobian and the observed variables. Where the choice of states depends on the
/// configuration, the model gets dynamic states and is simplified again with them (see
/// [`SimplifyOptions::dynamic_state_selection`]).
pub fn structural_simplify_with(
    model: &System,
    options: &SimplifyOptions,
) -> Result<SimplifiedSystem, Error> {
    let t0 = Instant::now();
    let flat = flatten_stage(model, options)?;
    let flatten_s = t0.elapsed().as_secs_f64();
    match simplify_flat(flat, options, Vec::new(), flatten_s)? {
        Simplified::Done(mut ssys) => {
            if options.dynamic_state_selection == DynamicStates::WhenNeeded
                && !ssys.dynamic.candidates.is_empty()
            {
                ssys.dynamic.source = Some(Arc::new((model.clone(), options.clone())));
            }
            Ok(*ssys)
        }
        Simplified::NeedsDynamicStates(groups) => {
            simplify_with_dynamic_states(model, options, &groups)
        }
    }
}

/// Simplifies `model` with dynamic states for `groups`.
fn simplify_with_dynamic_states(
    model: &System,
    options: &SimplifyOptions,
    groups: &[reduce::DynamicCandidates],
) -> Result<SimplifiedSystem, Error> {
    let t0 = Instant::now();
    let mut flat = flatten_stage(model, options)?;
    let dynamic = dynamic_states::augment(&mut flat.model, groups);
    let flatten_s = t0.elapsed().as_secs_f64();
    match simplify_flat(flat, options, dynamic, flatten_s)? {
        Simplified::Done(ssys) => Ok(*ssys),
        Simplified::NeedsDynamicStates(_) => {
            unreachable!("a system with dynamic states asks for no more")
        }
    }
}

/// The model simplified again with dynamic states for the groups its static selection
/// found (see [`DynamicStates::WhenNeeded`]).
pub(crate) fn dynamic_variant(ssys: &SimplifiedSystem) -> Option<Result<SimplifiedSystem, Error>> {
    let (model, options) = &**ssys.dynamic.source.as_ref()?;
    let groups: Vec<reduce::DynamicCandidates> = ssys
        .dynamic
        .candidates
        .iter()
        .map(|g| g.candidates.clone())
        .collect();
    Some(simplify_with_dynamic_states(model, options, &groups))
}

/// A flat model ready for simplification: flattened, balanced, parameters evaluated.
struct FlatStage {
    model: crate::model::FlatSystem,
    evaluated_parameters: Vec<bool>,
    events: Events,
    /// The parameters that are the model's inputs.
    inputs: Vec<usize>,
}

/// Stage 1: flattening, the balance check, the evaluation of parameters and the
/// relations that generate events.
fn flatten_stage(model: &System, options: &SimplifyOptions) -> Result<FlatStage, Error> {
    let mut flat = flatten(model)?;
    let mut evaluated_parameters =
        evaluate::evaluate_parameters(&mut flat, options.evaluate_parameters);
    let inputs = inputs::augment(&mut flat, options)?;
    let events = events::augment(&mut flat)?;
    check_balance(&flat)?;
    evaluated_parameters.resize(flat.parameters.len(), false);
    Ok(FlatStage {
        model: flat,
        evaluated_parameters,
        events,
        inputs,
    })
}

/// What simplifying a flat model gave.
enum Simplified {
    /// The simplified system.
    Done(Box<SimplifiedSystem>),
    /// The choice of states depends on the configuration: simplify again with dynamic
    /// states for these groups.
    NeedsDynamicStates(Vec<reduce::DynamicCandidates>),
}

/// Stages 2 to 7 on a flat model: alias elimination, index reduction with state
/// selection, causalization, ordering of the unknowns, code generation and the
/// statistics, assembled into the result.
fn simplify_flat(
    stage: FlatStage,
    options: &SimplifyOptions,
    mut dynamic: Vec<dynamic_states::DynamicStateGroup>,
    flatten_s: f64,
) -> Result<Simplified, Error> {
    let FlatStage {
        model: mut flat,
        evaluated_parameters,
        mut events,
        inputs,
    } = stage;
    let t1 = Instant::now();
    let name = flat.name.clone();
    let flat_size = (flat.equations.len(), flat.variables.len());

    let aliased = alias_stage(&mut flat, &inputs);
    // The variables and the equations' origins move into storage shared by the texts of
    // all equations (no copy of an origin or a name per equation).
    let variables: Arc<Vec<Variable>> = Arc::new(std::mem::take(&mut flat.variables));
    let texts = FlatOrigins::new(
        std::mem::take(&mut flat.equations),
        variables.clone(),
        flat.stores.clone(),
    );
    let equations: Vec<(Id, EquationText)> = aliased
        .kept_equations
        .iter()
        .map(|&e| (texts.equations()[e].residual, EquationText::of(&texts, e)))
        .collect();
    let flat_names = crate::model::FlatNames {
        variables: &variables,
        parameters: &flat.parameters,
    };
    let show = |a: &crate::expr::Arena, e: Id| a.display(e, &flat_names);
    let input_names: Vec<(usize, String)> = (inputs.iter())
        .map(|&j| (j, flat.parameters[j].name.to_string()))
        .collect();
    let reduced = reduce(
        ReduceInput {
            arena: &mut flat.arena,
            variables: &variables,
            priority: &aliased.priority,
            kept: &aliased.kept,
            derivative_map: &aliased.aliases.derivative_map,
            equations,
            definitions: aliased.definitions,
            defines_angular_velocity: &aliased.defines_angular_velocity,
            angular_velocity: &aliased.angular_velocity,
            inputs: &input_names,
            show: &show,
        },
        &name,
    )?;
    if options.dynamic_state_selection == DynamicStates::Always
        && dynamic.is_empty()
        && !reduced.dynamic.is_empty()
    {
        return Ok(Simplified::NeedsDynamicStates(reduced.dynamic));
    }

    let mut default_params =
        crate::model::evaluate_bindings(&flat.arena, &flat.parameter_values, &HashMap::default())
            .unwrap_or_else(|_| vec![f64::NAN; flat.parameters.len()]);
    // What events change has no default to rely on: no coefficient of it is safe to
    // divide by (a friction element's `if locked then 0 else 1`).
    // Nor have the inputs, which the problem sets.
    for (p, changes) in events.parameters(default_params.len()).iter().enumerate() {
        if *changes || inputs.contains(&p) {
            default_params[p] = f64::NAN;
        }
    }
    let causal = causalize_stage(
        &mut flat.arena,
        &flat.derivative_rules,
        &default_params,
        &reduced,
        &aliased.priority,
        options,
    )
    .map_err(|s| {
        let name_of =
            |&l: &Id| reduced.slots[reduced.slot_of.get(l).expect("a slot")].name(&variables);
        SimplifyError::singular(
            &name,
            s.over_equations
                .iter()
                .map(|&e| {
                    reduce::with_reduced_form(
                        &reduced.equations[e].text.to_string(),
                        &flat.arena,
                        reduced.equations[e].residual,
                        &show,
                    )
                })
                .collect(),
            s.over_unknowns.iter().map(name_of).collect(),
            s.under_unknowns.iter().map(name_of).collect(),
        )
    })?;
    let order = order_unknowns(&reduced, &causal.schedule);
    let simplify_s = t1.elapsed().as_secs_f64();

    locate_reinits(
        &name,
        &mut events,
        &mut flat.arena,
        &variables,
        &aliased.aliases.replaced,
        &reduced,
        &order,
    )?;

    // Code generation.
    let t2 = Instant::now();
    let (observed, observed_names) = observed_outputs(
        &mut flat.arena,
        &variables,
        &aliased.aliases.replaced,
        &aliased.aliases.derivative,
        &reduced,
    );
    for group in &mut dynamic {
        group.outputs = dynamic_outputs(group, &reduced, &order.index_of, variables.len());
    }
    // Groups whose static choice the solver watches (when the model has no dynamic
    // states of its own).
    let dynamic_candidates: Vec<dynamic_states::StaticGroup> = if dynamic.is_empty() {
        reduced
            .dynamic
            .iter()
            .filter_map(|g| static_group(g, &reduced, &order.index_of, variables.len()))
            .collect()
    } else {
        Vec::new()
    };
    let compiled = compile_dae(
        &mut flat.arena,
        &DaeSpec {
            steps: &causal.schedule.steps,
            unknowns: &order.unknowns,
            derivative_inputs: &order.derivative_inputs,
            rows: &order.rows,
            observed: &observed,
            observed_names,
            n_params: flat.parameters.len(),
            names: &|id| {
                reduced
                    .slot_of
                    .get(id)
                    .map(|s| reduced.slots[s].name(&variables))
                    .unwrap_or_else(|| format!("{id:?}"))
            },
        },
    )
    .map_err(|e| SimplifyError::Codegen {
        model: name.clone(),
        message: e.to_string(),
    })?;
    let times = PhaseTimes {
        flatten_s,
        simplify_s,
        codegen_s: t2.elapsed().as_secs_f64(),
    };

    let statistics = statistics(
        flat_size,
        &aliased.aliases,
        &reduced,
        &causal.schedule,
        &order,
        times,
    );
    log::debug!("{statistics}");
    let mut warnings = reduced.warnings.clone();
    warnings.sort();
    warnings.dedup();
    let states = reduced.states.clone();
    let starts = flat.starts.clone();
    // The flat model's vectors move into the result (no copy of every name).
    let crate::model::FlatSystem {
        parameters,
        parameter_values,
        arena,
        assertions,
        structural,
        ..
    } = flat;
    Ok(Simplified::Done(Box::new(SimplifiedSystem {
        model: ModelData {
            name,
            arena: std::sync::Arc::new(arena),
            variables,
            parameters,
            evaluated_parameters,
            assertions,
            parameter_values,
            starts,
            structural,
            events,
            inputs,
        },
        reduction: Reduction {
            replaced: aliased.aliases.replaced,
            slots: reduced.slots,
            slot_of: reduced.slot_of,
            var_diff: reduced.var_diff,
            equations: reduced.equations,
            initial_equations: aliased.initial_equations,
            states,
            never_tear: causal.never_tear,
        },
        sorted: Sorted {
            unknowns: order.unknowns,
            mass_matrix_diagonal: order.mass,
            schedule: causal.schedule,
            rows: order.rows,
            next_temporary: causal.next_temporary,
        },
        compiled,
        dynamic: DynamicSelection {
            groups: dynamic,
            candidates: dynamic_candidates,
            source: None,
            variant: std::sync::OnceLock::new(),
        },
        parameter_index: std::sync::OnceLock::new(),
        unknown_index: std::sync::OnceLock::new(),
        statistics,
        warnings,
    })))
}

/// The flat model after alias elimination, with what index reduction needs to know
/// about its variables and equations.
struct AliasStage {
    aliases: alias::Aliases,
    /// Per flat variable: whether it is kept (not an alias).
    kept: Vec<bool>,
    /// Per flat variable: its state priority.
    priority: Vec<f64>,
    /// Per flat variable: whether it is an angular velocity (what the derivative rules
    /// contain, under the aliases).
    angular_velocity: Vec<bool>,
    /// The equations alias elimination kept (indices into the flat equations).
    kept_equations: Vec<usize>,
    /// Per kept equation: whether it defines a variable with a derivative rule (an
    /// orientation matrix entry): such an equation is solved for it and never
    /// differentiated.
    definitions: Vec<bool>,
    /// Per kept equation: whether it defines an angular velocity.
    defines_angular_velocity: Vec<bool>,
    /// The initial equations under the same substitutions, with their texts.
    initial_equations: Vec<(Id, String)>,
}

/// Stage 2: alias elimination.
fn alias_stage(flat: &mut crate::model::FlatSystem, inputs: &[usize]) -> AliasStage {
    let aliases = alias::eliminate_aliases(flat, inputs);
    let nv = flat.variables.len();
    let kept: Vec<bool> = aliases.replaced.iter().map(Option::is_none).collect();
    let priority: Vec<f64> = flat.variables.iter().map(|v| v.state_priority).collect();
    let mut has_rule = vec![false; nv];
    for &(x, _) in &flat.derivative_rules {
        has_rule[x as usize] = true;
    }
    let angular_velocity: Vec<bool> = (0..nv)
        .map(|v| aliases.in_rules[v] && !has_rule[v])
        .collect();
    let kept_equations: Vec<usize> = (0..flat.equations.len())
        .filter(|&e| !aliases.removed[e])
        .collect();
    let definitions: Vec<bool> = kept_equations
        .iter()
        .map(|&e| {
            flat.equations[e]
                .lhs_var
                .is_some_and(|v| has_rule[v as usize])
        })
        .collect();
    // An equation whose left-hand side is an angular velocity (or an alias of one)
    // defines it: a joint's propagation of angular velocity.
    let is_angular_velocity = |v: u32| {
        let v = v as usize;
        angular_velocity[v]
            || aliases.replaced[v].is_some_and(|r| match flat.arena.node(r) {
                crate::expr::Node::Var(rep) => angular_velocity[*rep as usize],
                _ => false,
            })
    };
    let defines_angular_velocity: Vec<bool> = kept_equations
        .iter()
        .map(|&e| flat.equations[e].lhs_var.is_some_and(is_angular_velocity))
        .collect();
    // The combined map is built only for a model that has initial equations: it copies
    // every alias.
    let mut initial_equations: Vec<(Id, String)> = Vec::new();
    if !flat.initial_equations.is_empty() {
        let mut full_map = aliases.map.clone();
        for (&k, &v) in &aliases.derivative_map {
            full_map.insert(k, v);
        }
        let mut memo: HashMap<Id, Id> = HashMap::default();
        for eq in &flat.initial_equations {
            let r = flat
                .arena
                .substitute_memo(eq.residual, &full_map, &mut memo);
            initial_equations.push((r, flat.describe(eq)));
        }
    }
    AliasStage {
        aliases,
        kept,
        priority,
        angular_velocity,
        kept_equations,
        definitions,
        defines_angular_velocity,
        initial_equations,
    }
}

/// The sorted and torn equations.
struct CausalStage {
    schedule: Schedule,
    /// First variable index free for temporaries.
    next_temporary: u32,
    /// Leaves tearing never iterates on.
    never_tear: HashSet<Id>,
}

/// Stage 4: causalization. Every slot that is not a state is an unknown; the equations
/// are matched, sorted into blocks (BLT) and torn; a structurally singular system is
/// the equations and unknowns that make it so. The default parameter values decide
/// which coefficients may vanish.
fn causalize_stage(
    arena: &mut crate::expr::Arena,
    derivative_rules: &[(u32, Id)],
    default_params: &[f64],
    reduced: &reduce::IndexReduced,
    priority: &[f64],
    options: &SimplifyOptions,
) -> Result<CausalStage, causalize::Singular> {
    let state_set: HashSet<usize> = reduced.states.iter().copied().collect();
    let mut unknown_leaves: Vec<Id> = Vec::new();
    // The unknown each slot is (`usize::MAX` for states).
    let mut unknown_of_slot = vec![usize::MAX; reduced.slots.len()];
    for (s, slot) in reduced.slots.iter().enumerate() {
        if !state_set.contains(&s) {
            unknown_of_slot[s] = unknown_leaves.len();
            unknown_leaves.push(slot.leaf);
        }
    }
    let residuals: Vec<Id> = reduced.equations.iter().map(|e| e.residual).collect();
    // The incidence in the unknowns, from reduce's in the slots: reading every residual
    // again is a pass over the whole arena.
    let mut incidence = BipartiteGraph::with_capacity(
        unknown_leaves.len(),
        residuals.len(),
        reduced.incidence.n_items(),
    );
    let mut row = Vec::new();
    for slots in reduced.incidence.iter() {
        row.clear();
        row.extend(
            slots
                .iter()
                .map(|&s| unknown_of_slot[s])
                .filter(|&k| k != usize::MAX),
        );
        incidence.add_equation_from(&mut row);
    }
    let never_tear: HashSet<Id> = derivative_rules
        .iter()
        .map(|&(x, _)| arena.var(x))
        .collect();
    // From the priorities read once (not another pass over every variable).
    let tear_priority: HashMap<Id, f64> = priority
        .iter()
        .enumerate()
        .filter(|&(_, &p)| p != 0.0)
        .map(|(i, &p)| (arena.var(i as u32), p))
        .collect();
    let mut temps = Temporaries {
        next: priority.len() as u32,
        params: default_params,
        never_tear: &never_tear,
        tear_priority: &tear_priority,
    };
    let schedule = causalize_graph(
        arena,
        &residuals,
        &unknown_leaves,
        &incidence,
        &[],
        options.linear_blocks,
        &mut temps,
    )?;
    let next_temporary = temps.next;
    Ok(CausalStage {
        schedule,
        next_temporary,
        never_tear,
    })
}

/// The unknowns of the residual in order, with their mass-matrix diagonal and the rows.
struct Ordering {
    /// Position-level states, algebraic unknowns, velocity-level states.
    unknowns: Vec<Id>,
    mass: Vec<f64>,
    /// The index of each unknown.
    index_of: HashMap<Id, usize>,
    rows: Vec<ResidualRow>,
    /// Derivatives of states that the iteration solves for: read from `u'`.
    derivative_inputs: Vec<(Id, usize)>,
    n_states: usize,
    n_algebraic: usize,
}

/// The unknown each `reinit` of `events` sets: a differential state of the simplified
/// system, or an error naming the variable.
fn locate_reinits(
    model: &str,
    events: &mut Events,
    arena: &mut crate::expr::Arena,
    variables: &[Variable],
    replaced: &[Option<Id>],
    reduced: &reduce::IndexReduced,
    order: &Ordering,
) -> Result<(), SimplifyError> {
    for w in &mut events.whens {
        for r in &mut w.reinits {
            let name = &variables[r.variable].name;
            let leaf = arena.var(r.variable as u32);
            let unknown = replaced[r.variable]
                .is_none()
                .then(|| reduced.slot_of.get(leaf))
                .flatten()
                .and_then(|s| order.index_of.get(&reduced.slots[s].leaf).copied())
                .filter(|&i| order.mass[i] == 1.0);
            r.unknown = unknown.ok_or_else(|| SimplifyError::StateSelection {
                model: model.to_string(),
                message: format!(
                    "reinit({name}, ..) in the when clause `{}`: `{name}` is not a state of the \
                     simplified model (raise its state_priority, or reinit the state it \
                     follows from)",
                    w.text
                ),
            })?;
        }
    }
    Ok(())
}

/// Stage 5: the order of the unknowns (position-level states, algebraic unknowns,
/// velocity-level states) and the rows of the residual (the iteration's residuals, then
/// `u' - value` for each state whose derivative is computed explicitly).
fn order_unknowns(reduced: &reduce::IndexReduced, schedule: &Schedule) -> Ordering {
    let state_set: HashSet<usize> = reduced.states.iter().copied().collect();
    let iteration: HashSet<Id> = schedule.iteration.iter().copied().collect();
    let derivative_leaf = |s: usize| reduced.slots[reduced.var_diff[s].expect("a state")].leaf;
    let (position, velocity): (Vec<usize>, Vec<usize>) = reduced
        .states
        .iter()
        .partition(|&&s| state_set.contains(&reduced.var_diff[s].expect("a state")));
    let state_derivatives: HashSet<Id> =
        reduced.states.iter().map(|&s| derivative_leaf(s)).collect();
    let algebraic: Vec<Id> = schedule
        .iteration
        .iter()
        .copied()
        .filter(|l| !state_derivatives.contains(l))
        .collect();
    let mut unknowns: Vec<Id> = Vec::new();
    let mut mass = Vec::new();
    for &s in &position {
        unknowns.push(reduced.slots[s].leaf);
        mass.push(1.0);
    }
    for &l in &algebraic {
        unknowns.push(l);
        mass.push(0.0);
    }
    for &s in &velocity {
        unknowns.push(reduced.slots[s].leaf);
        mass.push(1.0);
    }
    let index_of: HashMap<Id, usize> = unknowns.iter().enumerate().map(|(k, &l)| (l, k)).collect();
    let mut rows: Vec<ResidualRow> = schedule
        .residuals
        .iter()
        .map(|&(residual, equation)| ResidualRow::Equation { residual, equation })
        .collect();
    let mut derivative_inputs = Vec::new();
    for &s in position.iter().chain(&velocity) {
        let k = index_of[&reduced.slots[s].leaf];
        let d = derivative_leaf(s);
        if iteration.contains(&d) {
            derivative_inputs.push((d, k));
        } else {
            rows.push(ResidualRow::StateDerivative { state: k, value: d });
        }
    }
    debug_assert_eq!(rows.len(), unknowns.len());
    Ordering {
        unknowns,
        mass,
        index_of,
        rows,
        derivative_inputs,
        n_states: position.len() + velocity.len(),
        n_algebraic: algebraic.len(),
    }
}

/// Stage 7: the translation statistics.
fn statistics(
    (flat_equations, flat_unknowns): (usize, usize),
    aliases: &alias::Aliases,
    reduced: &reduce::IndexReduced,
    schedule: &Schedule,
    order: &Ordering,
    times: PhaseTimes,
) -> Statistics {
    let mut statistics = Statistics {
        flat_equations,
        flat_unknowns,
        alias_variables: aliases.replaced.iter().filter(|r| r.is_some()).count(),
        derivative_aliases: aliases.derivative.iter().filter(|d| d.is_some()).count(),
        differentiated_equations: reduced.equations.len() - reduced.n_original,
        dummy_derivatives: reduced.dummy.iter().filter(|&&d| d).count(),
        sorted_equations: reduced.equations.len(),
        states: order.n_states,
        algebraic: order.n_algebraic,
        assignments: schedule
            .steps
            .iter()
            .filter(|s| matches!(s, Stmt::Assign { equation, .. } if *equation != usize::MAX))
            .count(),
        times,
        ..Statistics::default()
    };
    statistics.blocks(&schedule.blocks);
    statistics
}

/// `r = ±x + offset` for one variable `x` and an offset of parameters and constants:
/// the sign and `x` (an alias's replacement whose derivative is `±der(x)`).
fn offset_alias(arena: &crate::expr::Arena, r: Id) -> Option<(f64, u32)> {
    use crate::expr::Node;
    match *arena.node(r) {
        Node::Var(x) => Some((1.0, x)),
        Node::Sum(ts, _) => {
            let mut found = None;
            for &(k, t) in arena.terms(ts) {
                match *arena.node(t) {
                    Node::Var(x) if found.is_none() => {
                        let k = f64::from_bits(k);
                        if k.abs() != 1.0 {
                            return None;
                        }
                        found = Some((k, x));
                    }
                    Node::Param(_) => {}
                    _ => return None,
                }
            }
            found
        }
        _ => None,
    }
}

/// Observed outputs of slots: the flat variables, then the derivative slots in slot
/// order.
struct OutputIndex<'r> {
    reduced: &'r reduce::IndexReduced,
    derivative_output: Vec<usize>,
}

impl<'r> OutputIndex<'r> {
    fn new(reduced: &'r reduce::IndexReduced, n_variables: usize) -> Self {
        let mut derivative_output = vec![usize::MAX; reduced.slots.len()];
        let mut next = n_variables;
        for (k, s) in reduced.slots.iter().enumerate() {
            if s.order > 0 {
                derivative_output[k] = next;
                next += 1;
            }
        }
        OutputIndex {
            reduced,
            derivative_output,
        }
    }

    /// The observed output of a slot.
    fn output(&self, slot: usize) -> usize {
        let s = &self.reduced.slots[slot];
        if s.order == 0 {
            s.var
        } else {
            self.derivative_output[slot]
        }
    }

    /// The slot of a kept variable.
    fn slot_of_var(&self, v: usize) -> usize {
        self.reduced
            .slots
            .iter()
            .position(|s| s.var == v && s.order == 0)
            .expect("a kept variable has a slot")
    }

    /// Observed outputs of candidates, their derivatives and second derivatives
    /// (`usize::MAX` where there is none).
    fn candidates(&self, candidates: &[usize]) -> (Vec<usize>, Vec<usize>, Vec<usize>) {
        let derivative_slots: Vec<Option<usize>> = candidates
            .iter()
            .map(|&q| self.reduced.var_diff[self.slot_of_var(q)])
            .collect();
        let derivative = derivative_slots
            .iter()
            .map(|d| d.map_or(usize::MAX, |d| self.output(d)))
            .collect();
        let acceleration = derivative_slots
            .iter()
            .map(|d| {
                d.and_then(|d| self.reduced.var_diff[d])
                    .map_or(usize::MAX, |a| self.output(a))
            })
            .collect();
        (candidates.to_vec(), derivative, acceleration)
    }
}

/// Where the compiled functions hold the quantities of a group of dynamic states.
fn dynamic_outputs(
    group: &dynamic_states::DynamicStateGroup,
    reduced: &reduce::IndexReduced,
    index_of: &HashMap<Id, usize>,
    n_variables: usize,
) -> dynamic_states::GroupOutputs {
    let outputs = OutputIndex::new(reduced, n_variables);
    let (candidate, derivative, acceleration) = outputs.candidates(&group.candidates);
    let unknown = |v: usize| index_of[&reduced.slots[outputs.slot_of_var(v)].leaf];
    dynamic_states::GroupOutputs {
        candidate,
        derivative,
        acceleration,
        state: group.states.iter().map(|&v| unknown(v)).collect(),
        velocity_state: group.velocity_states.iter().map(|&v| unknown(v)).collect(),
    }
}

/// The statically selected group `g` as the solver watches it: where the velocities of
/// its chosen candidates are unknowns (`None` when one is not).
fn static_group(
    g: &reduce::DynamicCandidates,
    reduced: &reduce::IndexReduced,
    index_of: &HashMap<Id, usize>,
    n_variables: usize,
) -> Option<dynamic_states::StaticGroup> {
    let outputs = OutputIndex::new(reduced, n_variables);
    let (candidate, derivative, acceleration) = outputs.candidates(&g.candidates);
    if derivative.contains(&usize::MAX) {
        return None;
    }
    let velocity_state = g
        .chosen
        .iter()
        .map(|&i| {
            let d = reduced.var_diff[outputs.slot_of_var(g.candidates[i])]?;
            index_of.get(&reduced.slots[d].leaf).copied()
        })
        .collect::<Option<Vec<usize>>>()?;
    Some(dynamic_states::StaticGroup {
        candidates: g.clone(),
        outputs: dynamic_states::GroupOutputs {
            candidate,
            derivative,
            acceleration,
            state: Vec::new(),
            velocity_state,
        },
    })
}

/// Every variable of the model (replaced ones by their expression) and every
/// derivative slot, as observed outputs, with their names: made when first asked for
/// (compiling a large model would otherwise touch every variable's name once more).
fn observed_outputs(
    arena: &mut crate::expr::Arena,
    variables: &Arc<Vec<Variable>>,
    replaced: &[Option<Id>],
    derivative: &[Option<u32>],
    reduced: &reduce::IndexReduced,
) -> (Vec<Id>, Arc<crate::names::NameIndex>) {
    let mut out = Vec::with_capacity(variables.len() + reduced.slots.len());
    let mut var_leaf: Vec<Option<Id>> = vec![None; variables.len()];
    for s in &reduced.slots {
        if s.order == 0 {
            var_leaf[s.var] = Some(s.leaf);
        }
    }
    debug_assert_eq!(replaced.len(), variables.len());
    for (i, r) in replaced.iter().enumerate() {
        out.push(r.unwrap_or_else(|| var_leaf[i].expect("every kept variable has a slot")));
    }
    let derivatives: Vec<reduce::Slot> = reduced
        .slots
        .iter()
        .filter(|s| s.order > 0)
        .cloned()
        .collect();
    out.extend(derivatives.iter().map(|s| s.leaf));
    // `der(x)` for a variable x whose derivative is another variable v (`w = der(phi)`):
    // v's value, under x's derivative's name.
    let derivative_aliases: Vec<(usize, usize)> = derivative
        .iter()
        .enumerate()
        .filter_map(|(x, v)| v.map(|v| (x, v as usize)))
        .collect();
    let alias_leaves: Vec<Id> = derivative_aliases.iter().map(|&(_, v)| out[v]).collect();
    out.extend(alias_leaves);
    // The derivative of each kept variable that has one: its derivative slot, or the
    // variable its derivative is an alias of.
    let mut derivative_of_var: Vec<Option<Id>> = vec![None; variables.len()];
    for s in reduced.slots.iter().filter(|s| s.order == 1) {
        derivative_of_var[s.var] = Some(s.leaf);
    }
    for &(x, v) in &derivative_aliases {
        derivative_of_var[x] = Some(out[v]);
    }
    // `der(a)` for an alias `a = ±x` of a variable with a derivative: `±der(x)`.
    let mut alias_derivatives: Vec<(usize, Id)> = Vec::new();
    for (a, r) in replaced.iter().enumerate() {
        let Some(r) = *r else { continue };
        if derivative[a].is_some() {
            continue; // named above
        }
        let Some((sign, x)) = offset_alias(arena, r) else {
            continue;
        };
        if let Some(d) = derivative_of_var.get(x as usize).copied().flatten() {
            let value = if sign < 0.0 { arena.neg(d) } else { d };
            alias_derivatives.push((a, value));
        }
    }
    out.extend(alias_derivatives.iter().map(|&(_, d)| d));
    let variables = variables.clone();
    let names = crate::names::NameIndex::lazy(move || {
        let mut names: Vec<crate::model::SharedText> = Vec::with_capacity(
            variables.len()
                + derivatives.len()
                + derivative_aliases.len()
                + alias_derivatives.len(),
        );
        names.extend(variables.iter().map(|v| v.name.clone()));
        names.extend(derivatives.iter().map(|s| s.name(&variables).into()));
        names.extend(
            derivative_aliases
                .iter()
                .map(|&(x, _)| format!("der({})", variables[x].name).into()),
        );
        names.extend(
            alias_derivatives
                .iter()
                .map(|&(a, _)| format!("der({})", variables[a].name).into()),
        );
        names
    });
    (out, Arc::new(names))
}
