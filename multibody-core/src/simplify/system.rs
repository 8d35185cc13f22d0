//! The simplified system: unknowns, mass matrix, residuals, observed variables and the
//! compiled functions, with a translation report.

use crate::hash::HashMap;
use std::fmt;

use crate::codegen::Stmt;
use crate::codegen::dae::{CompiledDae, ResidualRow};
use crate::expr::{Arena, Id, NameResolver};
use crate::model::{Parameter, Variable};

use super::causalize::{BlockInfo, BlockKind, Schedule};
use super::reduce::{ReducedEquation, Slot};

/// Times of the phases of model compilation, in seconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PhaseTimes {
    /// Flattening and the balance check.
    pub flatten_s: f64,
    /// Alias elimination, index reduction, state selection, sorting and tearing.
    pub simplify_s: f64,
    /// Building the residual, Jacobian and observed functions.
    pub codegen_s: f64,
}

/// Dymola-style translation statistics.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Statistics {
    /// Scalar equations of the flat model.
    pub flat_equations: usize,
    /// Scalar unknowns of the flat model.
    pub flat_unknowns: usize,
    /// Unknowns removed by alias elimination (`a = ±b`, `a = constant`).
    pub alias_variables: usize,
    /// Variables made the derivative of another (`der(x) = v`).
    pub derivative_aliases: usize,
    /// Equations added by index reduction (time derivatives).
    pub differentiated_equations: usize,
    /// Dummy derivatives chosen by state selection.
    pub dummy_derivatives: usize,
    /// Equations of the sorted system (after index reduction).
    pub sorted_equations: usize,
    /// Continuous states.
    pub states: usize,
    /// Algebraic unknowns of the DAE (iteration variables left to the solver).
    pub algebraic: usize,
    /// Unknowns solved by explicit assignments.
    pub assignments: usize,
    /// Linear blocks solved inside: (size, tearing variables).
    pub linear_inline: Vec<(usize, usize)>,
    /// Linear blocks solved inside by a sparse LU: (size, unknowns left to the LU after
    /// symbolic pre-elimination).
    pub linear_sparse: Vec<(usize, usize)>,
    /// Linear blocks left to the solver: sizes.
    pub linear_solver: Vec<usize>,
    /// Nonlinear blocks: (size, tearing variables).
    pub nonlinear: Vec<(usize, usize)>,
    /// Compilation times.
    pub times: PhaseTimes,
}

impl Statistics {
    pub(crate) fn blocks(&mut self, blocks: &[BlockInfo]) {
        for b in blocks {
            match b.kind {
                BlockKind::Explicit => {}
                BlockKind::LinearInline => self.linear_inline.push((b.size, b.torn)),
                BlockKind::LinearSolver => self.linear_solver.push(b.size),
                BlockKind::LinearSparse => self.linear_sparse.push((b.size, b.torn)),
                BlockKind::Nonlinear => self.nonlinear.push((b.size, b.torn)),
            }
        }
    }
}

fn sizes(v: &[(usize, usize)], after: bool) -> String {
    if v.is_empty() {
        return "none".into();
    }
    let mut s: Vec<usize> = v.iter().map(|p| if after { p.1 } else { p.0 }).collect();
    s.sort_unstable_by(|a, b| b.cmp(a));
    let shown: Vec<String> = s.iter().take(12).map(|x| x.to_string()).collect();
    let more = if s.len() > 12 {
        format!(", ... ({} more)", s.len() - 12)
    } else {
        String::new()
    };
    format!("{{{}{}}}", shown.join(", "), more)
}

impl fmt::Display for Statistics {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "Translated model:")?;
        writeln!(
            f,
            "  flat model: {} scalar equations, {} scalar unknowns",
            self.flat_equations, self.flat_unknowns
        )?;
        writeln!(
            f,
            "  alias elimination: {} unknowns removed, {} derivative aliases",
            self.alias_variables, self.derivative_aliases
        )?;
        writeln!(
            f,
            "  index reduction: {} equations differentiated, {} dummy derivatives",
            self.differentiated_equations, self.dummy_derivatives
        )?;
        writeln!(
            f,
            "  sorted system: {} equations; {} continuous states, {} algebraic unknowns, {} explicit assignments",
            self.sorted_equations, self.states, self.algebraic, self.assignments
        )?;
        writeln!(
            f,
            "  linear systems solved inside: sizes {} before and {} after tearing",
            sizes(&self.linear_inline, false),
            sizes(&self.linear_inline, true)
        )?;
        writeln!(
            f,
            "  linear systems solved inside by sparse LU: sizes {} before and {} after pre-elimination",
            sizes(&self.linear_sparse, false),
            sizes(&self.linear_sparse, true)
        )?;
        let solver: Vec<(usize, usize)> = self.linear_solver.iter().map(|&s| (s, s)).collect();
        writeln!(
            f,
            "  linear systems left to the solver: sizes {}",
            sizes(&solver, false)
        )?;
        writeln!(
            f,
            "  nonlinear systems: sizes {} before and {} after tearing",
            sizes(&self.nonlinear, false),
            sizes(&self.nonlinear, true)
        )?;
        write!(
            f,
            "  times: flatten {:.3} ms, simplify {:.3} ms, codegen {:.3} ms",
            self.times.flatten_s * 1e3,
            self.times.simplify_s * 1e3,
            self.times.codegen_s * 1e3
        )
    }
}

/// A group of candidates for states (see [`SimplifiedSystem::state_candidates`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StateCandidates {
    /// The candidates (variables).
    pub candidates: Vec<String>,
    /// Those the static selection chose as states.
    pub chosen: Vec<String>,
}

/// What the model declared, after flattening: its name, variables, parameters and
/// their values, start values and assertions, and the expressions of all of them.
#[derive(Clone, Debug)]
pub(crate) struct ModelData {
    pub(crate) name: String,
    /// The expressions, shared with the problems built on this system (their
    /// initializations extend it without copying it).
    pub(crate) arena: std::sync::Arc<Arena>,
    /// The flat variables (shared with the texts of the equations).
    pub(crate) variables: std::sync::Arc<Vec<Variable>>,
    pub(crate) parameters: Vec<Parameter>,
    /// Per parameter: whether its value was folded in at compile time.
    pub(crate) evaluated_parameters: Vec<bool>,
    /// Conditions on parameters, checked for each problem's values.
    pub(crate) assertions: Vec<crate::model::FlatAssertion>,
    /// Parameter bindings (expressions of other parameters) per parameter.
    pub(crate) parameter_values: Vec<Option<Id>>,
    /// Start values per flat variable (expressions of parameters).
    pub(crate) starts: Vec<Option<Id>>,
    /// Full names of the structural parameters (for messages).
    pub(crate) structural: Vec<String>,
    /// What generates events, and what happens at them.
    pub(crate) events: super::Events,
    /// The parameters that are the model's inputs (see
    /// [`SimplifyOptions::inputs`](super::SimplifyOptions::inputs)).
    pub(crate) inputs: Vec<usize>,
}

impl ModelData {
    /// Per parameter (of `n`): whether its value changes during a run (events change
    /// it, or it is an input).
    pub(crate) fn changing_parameters(&self, n: usize) -> Vec<bool> {
        let mut changing = self.events.parameters(n);
        for &j in &self.inputs {
            if let Some(c) = changing.get_mut(j) {
                *c = true;
            }
        }
        changing
    }
}

/// The index-reduced equations and the variables they are in: what alias elimination,
/// index reduction and state selection made of the model.
#[derive(Clone, Debug)]
pub(crate) struct Reduction {
    /// Per flat variable: its replacement when alias elimination removed it.
    pub(crate) replaced: Vec<Option<Id>>,
    /// The variables and derivatives the reduced equations are in.
    pub(crate) slots: Vec<Slot>,
    /// The slot of each leaf, indexed by the leaf's id.
    pub(crate) slot_of: crate::expr::IdIndex,
    /// Per slot: the slot of its derivative.
    pub(crate) var_diff: Vec<Option<usize>>,
    pub(crate) equations: Vec<ReducedEquation>,
    pub(crate) initial_equations: Vec<(Id, String)>,
    /// Slots that are states.
    pub(crate) states: Vec<usize>,
    /// Leaves that tearing never iterates on (orientation matrix entries), for the
    /// initialization system's tearing too.
    pub(crate) never_tear: crate::hash::HashSet<Id>,
}

/// The sorted system: the unknowns of the residual, the order of the explicit
/// computations, and the residual's rows.
#[derive(Clone, Debug)]
pub(crate) struct Sorted {
    /// The unknowns: leaves (state slots and iteration variables), in order.
    pub(crate) unknowns: Vec<Id>,
    pub(crate) mass_matrix_diagonal: Vec<f64>,
    pub(crate) schedule: Schedule,
    pub(crate) rows: Vec<ResidualRow>,
    /// First variable index free for temporaries.
    pub(crate) next_temporary: u32,
}

/// Dynamic state selection: the groups of dynamic states this system has, or those
/// whose static choice the solver watches, and the compilation with dynamic states
/// made when that choice degrades.
#[derive(Clone, Debug)]
pub(crate) struct DynamicSelection {
    /// Groups of dynamic states (see [`super::dynamic_states`]).
    pub(crate) groups: Vec<super::dynamic_states::DynamicStateGroup>,
    /// Groups whose static choice of states depends on the configuration (watched by
    /// the solver when the system has no dynamic states).
    pub(crate) candidates: Vec<super::dynamic_states::StaticGroup>,
    /// The model and options to compile again with dynamic states, when the solver
    /// finds the static choice degrading.
    pub(crate) source: Option<std::sync::Arc<(crate::model::System, super::SimplifyOptions)>>,
    /// That compilation, made on first need.
    pub(crate) variant: std::sync::OnceLock<Result<Box<SimplifiedSystem>, String>>,
}

/// A model reduced to unknowns `u` (states and algebraic unknowns), a diagonal mass
/// matrix and residuals `0 = F(t, u, u')`, with every eliminated variable kept as an
/// observed expression and the compiled functions ready for a
/// [`DaeProblem`](crate::solve::DaeProblem).
#[derive(Clone, Debug)]
pub struct SimplifiedSystem {
    /// What the model declared.
    pub(crate) model: ModelData,
    /// The index-reduced equations.
    pub(crate) reduction: Reduction,
    /// The sorted residual.
    pub(crate) sorted: Sorted,
    /// The residual, Jacobian and observed functions.
    pub(crate) compiled: CompiledDae,
    /// Dynamic state selection.
    pub(crate) dynamic: DynamicSelection,
    /// The names of `parameters` with their lookup, built for the first solution and
    /// shared by every later one.
    pub(crate) parameter_index: std::sync::OnceLock<std::sync::Arc<crate::names::NameIndex>>,
    /// The names of the unknowns with their lookup (for `der(x)` in solutions), built
    /// for the first solution and shared likewise.
    pub(crate) unknown_index: std::sync::OnceLock<std::sync::Arc<crate::names::NameIndex>>,
    pub(crate) statistics: Statistics,
    pub(crate) warnings: Vec<String>,
}

impl SimplifiedSystem {
    /// The compiled residual, Jacobian and observed functions (for diagnostics and
    /// benchmarks: tape lengths, Jacobian colours and non-zeros).
    pub fn compiled(&self) -> &CompiledDae {
        &self.compiled
    }

    /// The model's name.
    pub fn name(&self) -> &str {
        &self.model.name
    }

    /// The relations that generate events (see [`super::events`]), in the order of
    /// their crossing variables `events.crossing[k]`.
    pub fn event_relations(&self) -> &[super::EventRelation] {
        &self.model.events.relations
    }

    /// The groups of candidates for states whose static choice depends on the
    /// configuration (the joint angles of a kinematic loop): per group, the candidates
    /// and those chosen. A solve watches the choice and changes to dynamic states where
    /// it degrades (see [`super::DynamicStates`]).
    pub fn state_candidates(&self) -> Vec<StateCandidates> {
        let name = |v: usize| self.model.variables[v].name.to_string();
        let from = |candidates: &[usize], chosen: &[usize]| StateCandidates {
            candidates: candidates.iter().map(|&v| name(v)).collect(),
            chosen: chosen.iter().map(|&i| name(candidates[i])).collect(),
        };
        if self.dynamic.groups.is_empty() {
            self.dynamic
                .candidates
                .iter()
                .map(|g| from(&g.candidates.candidates, &g.candidates.chosen))
                .collect()
        } else {
            self.dynamic
                .groups
                .iter()
                .map(|g| from(&g.candidates, &g.preferred))
                .collect()
        }
    }

    /// Names of the unknowns `u`, in order: position-level states, algebraic unknowns,
    /// velocity-level states.
    pub fn unknowns(&self) -> Vec<String> {
        self.sorted
            .unknowns
            .iter()
            .map(|&l| self.leaf_name(l))
            .collect()
    }

    /// Names of the continuous states, in the order of [`unknowns`](Self::unknowns).
    pub fn states(&self) -> Vec<String> {
        self.sorted
            .unknowns
            .iter()
            .zip(&self.sorted.mass_matrix_diagonal)
            .filter(|(_, m)| **m == 1.0)
            .map(|(&l, _)| self.leaf_name(l))
            .collect()
    }

    /// The diagonal of the mass matrix: 1 for a differential unknown, 0 for an
    /// algebraic one.
    pub fn mass_matrix_diagonal(&self) -> &[f64] {
        &self.sorted.mass_matrix_diagonal
    }

    /// The residual equations `0 = F(t, u, u')` as text, one per unknown.
    pub fn equations(&self) -> Vec<String> {
        let names = self.resolver();
        // A state's derivative is a leaf computed by the sorted steps: show how.
        let mut computed: HashMap<Id, String> = HashMap::default();
        for step in &self.sorted.schedule.steps {
            match step {
                Stmt::Assign { target, expr, .. } => {
                    computed.insert(*target, self.model.arena.display(*expr, &names));
                }
                Stmt::LinearSolve { targets, .. } | Stmt::SparseLinearSolve { targets, .. } => {
                    let k = targets.len();
                    for &t in targets {
                        computed.insert(t, format!("(solved in a linear system of {k})"));
                    }
                }
            }
        }
        self.sorted
            .rows
            .iter()
            .map(|r| match r {
                ResidualRow::Equation { residual, .. } => {
                    format!("0 = {}", self.model.arena.display(*residual, &names))
                }
                ResidualRow::StateDerivative { state, value } => format!(
                    "der({}) = {}",
                    self.leaf_name(self.sorted.unknowns[*state]),
                    computed
                        .remove(value)
                        .unwrap_or_else(|| self.model.arena.display(*value, &names))
                ),
            })
            .collect()
    }

    /// Every variable of the model that is not an unknown, with the expression or
    /// equation that computes it: `(name, how)`.
    pub fn observed(&self) -> Vec<(String, String)> {
        let names = self.resolver();
        let mut out = Vec::new();
        for (i, v) in self.model.variables.iter().enumerate() {
            if let Some(r) = self.reduction.replaced[i] {
                out.push((v.name.to_string(), self.model.arena.display(r, &names)));
            }
        }
        for step in &self.sorted.schedule.steps {
            match step {
                Stmt::Assign {
                    target,
                    expr,
                    equation,
                } if *equation != usize::MAX => {
                    out.push((
                        self.leaf_name(*target),
                        self.model.arena.display(*expr, &names),
                    ));
                }
                Stmt::LinearSolve { targets, .. } | Stmt::SparseLinearSolve { targets, .. } => {
                    for &t in targets {
                        if self.reduction.slot_of.contains(t) {
                            out.push((self.leaf_name(t), "linear system".into()));
                        }
                    }
                }
                _ => {}
            }
        }
        out
    }

    /// The translation statistics.
    pub fn statistics(&self) -> &Statistics {
        &self.statistics
    }

    /// Warnings found while simplifying (for example about state selection).
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// Names of the model's inputs (see
    /// [`SimplifyOptions::inputs`](super::SimplifyOptions::inputs)), parameters whose
    /// values a problem gives, constant or as functions of time.
    pub fn inputs(&self) -> Vec<String> {
        (self.model.inputs.iter())
            .map(|&j| self.model.parameters[j].name.to_string())
            .collect()
    }

    /// Names of the tunable parameters.
    pub fn parameters(&self) -> Vec<String> {
        self.model
            .parameters
            .iter()
            .map(|p| p.name.to_string())
            .collect()
    }

    /// The names of the tunable parameters with their lookup (built once, shared).
    pub(crate) fn parameter_index(&self) -> std::sync::Arc<crate::names::NameIndex> {
        self.parameter_index
            .get_or_init(|| {
                let names = self
                    .model
                    .parameters
                    .iter()
                    .map(|p| p.name.clone())
                    .collect();
                std::sync::Arc::new(crate::names::NameIndex::new(names))
            })
            .clone()
    }

    /// The names of the unknowns with their lookup (built once, shared).
    pub(crate) fn unknown_index(&self) -> std::sync::Arc<crate::names::NameIndex> {
        self.unknown_index
            .get_or_init(|| {
                let names = self.unknowns().into_iter().map(Into::into).collect();
                std::sync::Arc::new(crate::names::NameIndex::new(names))
            })
            .clone()
    }

    /// Names of the parameters whose values were folded into the equations at compile
    /// time (marked `evaluate`, or all with
    /// [`SimplifyOptions::evaluate_parameters`](super::SimplifyOptions)); a problem
    /// cannot change them.
    pub fn evaluated_parameters(&self) -> Vec<String> {
        self.model
            .parameters
            .iter()
            .zip(&self.model.evaluated_parameters)
            .filter(|(_, e)| **e)
            .map(|(p, _)| p.name.to_string())
            .collect()
    }

    /// Names of every variable that a solution can return: the model's variables and
    /// the derivatives that the reduced system contains, and those that are another
    /// variable (`der(j1.phi)`, which is `j1.w`).
    pub fn variable_names(&self) -> Vec<String> {
        self.compiled
            .observed_names
            .names()
            .iter()
            .map(|n| n.to_string())
            .collect()
    }

    /// A readable name for a leaf: its slot's name, or how it displays.
    pub(crate) fn leaf_name(&self, leaf: Id) -> String {
        self.leaf_name_in(&self.model.arena, leaf)
    }

    /// [`Self::leaf_name`] for a leaf of `arena`, an extension of this system's arena
    /// (the initialization adds its own temporaries).
    pub(crate) fn leaf_name_in(&self, arena: &Arena, leaf: Id) -> String {
        match self.reduction.slot_of.get(leaf) {
            Some(s) => self.reduction.slots[s].name(&self.model.variables),
            None => arena.display(leaf, &self.resolver()),
        }
    }

    pub(crate) fn resolver(&self) -> SystemNames<'_> {
        SystemNames {
            variables: &self.model.variables,
            parameters: &self.model.parameters,
        }
    }
}

/// Names of the leaves of a simplified system.
pub(crate) struct SystemNames<'a> {
    variables: &'a [Variable],
    parameters: &'a [Parameter],
}

impl NameResolver for SystemNames<'_> {
    fn var(&self, i: u32) -> String {
        match self.variables.get(i as usize) {
            Some(v) => v.name.to_string(),
            None => format!("_tmp{i}"),
        }
    }
    fn param(&self, i: u32) -> String {
        match self.parameters.get(i as usize) {
            Some(p) => p.name.to_string(),
            None => format!("_start{}", i as usize - self.parameters.len()),
        }
    }
}
