//! Index reduction on the symbolic system: slots for every variable and derivative, the
//! integer graph for Pantelides, symbolic differentiation of the equations it marks, and
//! dummy-derivative state selection.

use crate::hash::HashMap;

use crate::expr::{Arena, Id, IdIndex, Node, NodeMap};
use crate::model::{EquationText, Variable};
use crate::structure::dummy_derivatives::{
    SelectionError, SelectionLevel, StateRank, dummy_derivatives_with_definitions,
};
use crate::structure::pantelides::{StructurallySingular, pantelides_with_implicit};
use crate::structure::{BipartiteGraph, Rows};

use super::error::SimplifyError;

/// One unknown of the reduced system: a variable or a time derivative of one.
#[derive(Clone, Debug)]
pub struct Slot {
    /// The leaf node (`Var(i)` or `der(...)`) in the system's arena.
    pub leaf: Id,
    /// The flat variable behind it.
    pub var: usize,
    /// How many times `var` is differentiated (0 for the variable itself).
    pub order: usize,
}

impl Slot {
    /// Display name (`j1.phi`, `der(j1.w)`), from the flat variables: made when asked
    /// for, so building the slots of a large model touches no name.
    ///
    /// # Panics
    /// If `variables` is not the flat variable list of the slot's system (too short).
    pub fn name(&self, variables: &[Variable]) -> String {
        derivative_name(&variables[self.var].name, self.order)
    }
}

/// An equation of the reduced system.
#[derive(Clone, Debug)]
pub struct ReducedEquation {
    /// The residual (`= 0`).
    pub residual: Id,
    /// How it reads in messages.
    pub text: EquationText,
}

/// The index-reduced system with its state selection.
#[derive(Clone, Debug)]
pub(crate) struct IndexReduced {
    pub slots: Vec<Slot>,
    /// The slot of each leaf, indexed by the leaf's id.
    pub slot_of: IdIndex,
    pub var_diff: Vec<Option<usize>>,
    pub equations: Vec<ReducedEquation>,
    /// Row `e`: the slots equation `e` contains, as read from its residual (ascending;
    /// Pantelides' own graph over-approximates a differentiated equation's).
    pub incidence: Rows,
    pub states: Vec<usize>,
    pub dummy: Vec<bool>,
    pub n_original: usize,
    pub warnings: Vec<String>,
    /// Groups of candidates whose choice as states depends on the configuration.
    pub dynamic: Vec<DynamicCandidates>,
}

/// Candidates for states whose choice depends on the configuration: the variables (the
/// bottoms of the derivative chains of a level of the selection, those that may be
/// states at all) among which `chosen.len()` are states, and which ones the static
/// selection chose.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct DynamicCandidates {
    /// Flat variables.
    pub candidates: Vec<usize>,
    /// Per candidate: the flat variable that is its derivative (a velocity declared as
    /// `w = der(phi)`), if any.
    pub derivatives: Vec<Option<usize>>,
    /// Per candidate: its state priority.
    pub priorities: Vec<f64>,
    /// Positions in `candidates` of the static choice.
    pub chosen: Vec<usize>,
    /// How often the candidates are differentiated in the level (2 for the joint angles
    /// of a mechanism, whose accelerations the level decides about).
    pub order: usize,
}

/// Applies the derivative aliases to an expression (`der(x) -> v`), with a memo kept
/// across the expressions of one pass.
fn canonical(arena: &mut Arena, e: Id, derivative_map: &HashMap<Id, Id>, memo: &mut NodeMap) -> Id {
    if derivative_map.is_empty() {
        e
    } else {
        arena.substitute_memo(e, derivative_map, memo)
    }
}

/// The canonical time derivative of a leaf.
fn leaf_derivative(arena: &mut Arena, leaf: Id, dmap: &HashMap<Id, Id>) -> Id {
    let d = arena.der(leaf);
    canonical_leaf(arena, d, dmap)
}

/// [`canonical`] of a leaf (`x`, `der(x)`, `der(der(x))`, ...): what substitution
/// gives, found through the map alone.
fn canonical_leaf(arena: &mut Arena, e: Id, dmap: &HashMap<Id, Id>) -> Id {
    if let Some(&r) = dmap.get(&e) {
        return r;
    }
    match *arena.node(e) {
        Node::Der(x) => {
            let nx = canonical_leaf(arena, x, dmap);
            if nx == x { e } else { arena.der(nx) }
        }
        _ => e,
    }
}

/// Builds slots for the leaves of the equations and for every kept variable.
pub(crate) struct SlotTable<'a> {
    pub arena: &'a mut Arena,
    /// The flat variables (for their names).
    pub variables: &'a [Variable],
    pub slots: Vec<Slot>,
    /// The slot of each leaf, indexed by the leaf's id.
    pub slot_of: IdIndex,
}

impl SlotTable<'_> {
    /// The slot of a leaf (`Var` or `Der`), creating it and its lower-order chain.
    pub fn slot(&mut self, leaf: Id) -> usize {
        if let Some(s) = self.slot_of.get(leaf) {
            return s;
        }
        let (var, order) = match *self.arena.node(leaf) {
            Node::Var(i) => (i as usize, 0),
            Node::Der(inner) => {
                let below = self.slot(inner);
                (self.slots[below].var, self.slots[below].order + 1)
            }
            n => panic!("slot of a non-variable leaf {n:?}"),
        };
        let s = self.slots.len();
        self.slots.push(Slot { leaf, var, order });
        self.slot_of.insert(leaf, s);
        s
    }
}

/// The name of the `order`-th derivative of the variable `name`: `der(der(x))`.
fn derivative_name(name: &str, order: usize) -> String {
    let mut out = String::with_capacity(name.len() + 5 * order);
    for _ in 0..order {
        out.push_str("der(");
    }
    out.push_str(name);
    for _ in 0..order {
        out.push(')');
    }
    out
}

/// Variables of a residual as slots (`Var` and `der` leaves; parameters and time are
/// known).
pub(crate) fn incidence(table: &mut SlotTable<'_>, e: Id) -> Vec<usize> {
    let mut out = Vec::new();
    incidence_into(table, e, &mut Vec::new(), &mut out);
    out
}

/// [`incidence`] into `out` (cleared first; `leaves` is work space), for callers that
/// reuse the buffers.
pub(crate) fn incidence_into(
    table: &mut SlotTable<'_>,
    e: Id,
    leaves: &mut Vec<Id>,
    out: &mut Vec<usize>,
) {
    table.arena.leaves_into(e, leaves);
    out.clear();
    for &l in leaves.iter() {
        if matches!(table.arena.node(l), Node::Var(_) | Node::Der(_)) {
            out.push(table.slot(l));
        }
    }
    out.sort_unstable();
    out.dedup();
}

/// Inputs of the reduction.
pub(crate) struct ReduceInput<'a> {
    pub arena: &'a mut Arena,
    /// The flat variables (for their names).
    pub variables: &'a [Variable],
    /// State priority and whether each flat variable is kept (not eliminated).
    pub priority: &'a [f64],
    pub kept: &'a [bool],
    /// Derivative aliases `der(x) -> v`.
    pub derivative_map: &'a HashMap<Id, Id>,
    /// Equations: residual and text.
    pub equations: Vec<(Id, EquationText)>,
    /// Per equation: whether it defines a variable with a derivative rule.
    pub definitions: Vec<bool>,
    /// Per equation: whether it defines an angular velocity (see
    /// [`dummy_derivatives_with_definitions`]).
    pub defines_angular_velocity: &'a [bool],
    /// Per flat variable: whether it is an angular velocity (a variable that the
    /// derivative rules of orientation entries contain).
    pub angular_velocity: &'a [bool],
    /// The parameters that are the model's inputs, with their names: no equation that
    /// reads one may be differentiated (its derivative is not known).
    pub inputs: &'a [(usize, String)],
    /// Displays an expression (for messages).
    pub show: &'a dyn Fn(&Arena, Id) -> String,
}

/// The name of the first of the model's `inputs` that `residual` reads.
fn input_in<'i>(arena: &Arena, residual: Id, inputs: &'i [(usize, String)]) -> Option<&'i str> {
    if inputs.is_empty() {
        return None;
    }
    let leaves = arena.leaves(residual);
    inputs
        .iter()
        .find(|(j, _)| {
            leaves
                .iter()
                .any(|&l| matches!(arena.node(l), crate::expr::Node::Param(k) if *k as usize == *j))
        })
        .map(|(_, name)| name.as_str())
}

/// An equation as written, followed by what it became after alias elimination, for
/// messages about structural singularities.
pub(crate) fn with_reduced_form(
    text: &str,
    arena: &Arena,
    residual: Id,
    show: &dyn Fn(&Arena, Id) -> String,
) -> String {
    let reduced = show(arena, residual);
    let no_unknowns = arena
        .leaves(residual)
        .iter()
        .all(|&l| !matches!(arena.node(l), Node::Var(_) | Node::Der(_)));
    if no_unknowns {
        format!("{text}   [reduces to 0 = {reduced}: no unknown is left in it]")
    } else {
        format!("{text}   [reduces to 0 = {reduced}]")
    }
}

/// Runs index reduction and state selection.
pub(crate) fn reduce(input: ReduceInput<'_>, model: &str) -> Result<IndexReduced, SimplifyError> {
    let ReduceInput {
        arena,
        variables,
        priority,
        kept,
        derivative_map,
        equations,
        definitions,
        defines_angular_velocity,
        angular_velocity,
        inputs,
        show,
    } = input;
    let mut table = SlotTable {
        arena,
        variables,
        slots: Vec::new(),
        slot_of: IdIndex::default(),
    };
    for (i, &k) in kept.iter().enumerate() {
        if k {
            let leaf = table.arena.var(i as u32);
            table.slot(leaf);
        }
    }
    let mut eqs: Vec<ReducedEquation> = equations
        .into_iter()
        .map(|(residual, text)| ReducedEquation { residual, text })
        .collect();
    let mut graph = BipartiteGraph::new(0);
    let (mut leaves, mut inc) = (Vec::new(), Vec::new());
    for eq in &eqs {
        incidence_into(&mut table, eq.residual, &mut leaves, &mut inc);
        graph.add_equation_from(&mut inc);
    }
    let (mut var_diff, mut implicit) = derivative_links(&mut table, derivative_map);
    // (Derivative rules may mention variables no equation does: they got slots too.)
    let n_slots = table.slots.len();
    var_diff.resize(n_slots, None);
    implicit.resize(n_slots, Vec::new());
    graph.n_vars = n_slots;
    let red = match pantelides_with_implicit(&graph, &var_diff, &implicit, &definitions) {
        Ok(r) => r,
        Err(StructurallySingular {
            equations,
            overdetermined,
            undetermined,
        }) => {
            let names = |vs: &[usize]| -> Vec<String> {
                vs.iter()
                    .map(|&v| table.slots[v].name(table.variables))
                    .collect()
            };
            return Err(SimplifyError::singular(
                model,
                equations
                    .iter()
                    .map(|&e| {
                        with_reduced_form(
                            &eqs[e].text.to_string(),
                            table.arena,
                            eqs[e].residual,
                            show,
                        )
                    })
                    .collect(),
                names(&overdetermined),
                names(&undetermined),
            ));
        }
    };
    // New derivative slots.
    let anti = red.antiderivative_var();
    for s in n_slots..red.var_diff.len() {
        let a = anti[s].expect("a new slot is a derivative");
        let leaf = leaf_derivative(table.arena, table.slots[a].leaf, derivative_map);
        let got = table.slot(leaf);
        debug_assert_eq!(got, s, "derivative slots are created in order");
    }
    // Differentiate the marked equations.
    let n_original = eqs.len();
    let anti_eq = red.antiderivative_eq();
    let mut warnings = Vec::new();
    let mut memo = NodeMap::new();
    for e in n_original..red.graph.n_eqs() {
        let src = anti_eq[e].expect("a new equation is a derivative");
        if let Some(input) = input_in(table.arena, eqs[src].residual, inputs) {
            return Err(SimplifyError::DifferentiatedInput {
                model: model.to_string(),
                input: input.to_string(),
                equation: eqs[src].text.to_string(),
            });
        }
        let d = table.arena.time_derivative(eqs[src].residual);
        let d = canonical(table.arena, d, derivative_map, &mut memo);
        let text = eqs[src].text.derivative();
        let before = table.slots.len();
        incidence_into(&mut table, d, &mut leaves, &mut inc);
        graph.add_equation_from(&mut inc);
        if table.slots.len() != before {
            warnings.push(format!(
                "index reduction: differentiating `{}` introduced unexpected derivatives",
                eqs[src].text
            ));
        }
        eqs.push(ReducedEquation { residual: d, text });
    }
    let mut var_diff = red.var_diff.clone();
    var_diff.resize(table.slots.len(), None);
    // State selection.
    let rank: Vec<StateRank> = table
        .slots
        .iter()
        .map(|s| StateRank {
            priority: priority[s.var],
            declaration: s.var,
        })
        .collect();
    let mut red = red;
    red.var_diff = var_diff.clone();
    red.graph.n_vars = table.slots.len();
    // The angular velocities (orientation entries aside): intermediates of state
    // selection.
    let intermediates: Vec<bool> = table
        .slots
        .iter()
        .map(|s| s.order == 0 && angular_velocity.get(s.var).copied().unwrap_or(false))
        .collect();
    let selection = match dummy_derivatives_with_definitions(
        &red,
        n_original,
        &rank,
        &intermediates,
        defines_angular_velocity,
    ) {
        Ok(s) => s,
        Err(SelectionError::Singular {
            equations,
            candidates,
        }) => {
            return Err(SimplifyError::singular(
                model,
                equations.iter().map(|&e| eqs[e].text.to_string()).collect(),
                candidates
                    .iter()
                    .map(|&v| table.slots[v].name(table.variables))
                    .collect(),
                Vec::new(),
            ));
        }
        Err(SelectionError::AlwaysViolated(slots)) => {
            return Err(SimplifyError::StateSelection {
                model: model.to_string(),
                message: format!(
                    "{} must be states (state_select = always), but the constraints of the \
                     model leave fewer degrees of freedom",
                    slots
                        .iter()
                        .map(|&v| format!("`{}`", table.slots[v].name(table.variables)))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            });
        }
    };
    let dynamic = dynamic_candidates(
        table.arena,
        &table.slots,
        &var_diff,
        &eqs,
        &selection.levels,
        priority,
    );
    let mut dummy = selection.dummy.clone();
    dummy.resize(table.slots.len(), false);
    Ok(IndexReduced {
        slot_of: table.slot_of,
        slots: table.slots,
        var_diff,
        equations: eqs,
        incidence: graph.eq_vars,
        states: selection.states,
        dummy,
        n_original,
        warnings,
        dynamic,
    })
}

/// `var_diff` from the leaves: a slot's derivative is the slot of its canonical time
/// derivative, when that exists. A slot whose derivative is an expression (a derivative
/// rule) gets the slots of that expression as its implicit derivative instead.
fn derivative_links(
    table: &mut SlotTable<'_>,
    dmap: &HashMap<Id, Id>,
) -> (Vec<Option<usize>>, Vec<Vec<usize>>) {
    let n = table.slots.len();
    let mut var_diff = vec![None; n];
    let mut implicit = vec![Vec::new(); n];
    for s in 0..n {
        let d = leaf_derivative(table.arena, table.slots[s].leaf, dmap);
        if let Some(ds) = table.slot_of.get(d) {
            var_diff[s] = Some(ds);
        } else if !matches!(table.arena.node(d), Node::Der(_)) {
            implicit[s] = incidence(table, d);
        }
    }
    (var_diff, implicit)
}

/// Whether the Jacobian of a selection level's equations with respect to its dummies can
/// become singular (see the call site).
/// The groups of [`DynamicCandidates`]: for every level of the selection whose choice
/// depends on the configuration and that has more candidates than equations, the
/// variables at the bottom of the candidates' derivative chains whose priority lets
/// them be states (not below 0, not `always`), and those the static selection kept.
fn dynamic_candidates(
    arena: &mut Arena,
    slots: &[Slot],
    var_diff: &[Option<usize>],
    eqs: &[ReducedEquation],
    levels: &[SelectionLevel],
    priority: &[f64],
) -> Vec<DynamicCandidates> {
    use crate::structure::dummy_derivatives::ALWAYS;
    let mut anti = vec![None; var_diff.len()];
    for (v, d) in var_diff.iter().enumerate() {
        if let Some(d) = *d {
            anti[d] = Some(v);
        }
    }
    let base = |mut v: usize| {
        while let Some(a) = anti[v] {
            v = a;
        }
        v
    };
    let mut groups = Vec::new();
    for level in levels {
        if level.candidates.len() <= level.equations.len()
            || !configuration_dependent(arena, slots, eqs, level)
        {
            continue;
        }
        let depth = |mut w: usize| {
            let mut d = 0;
            while let Some(a) = anti[w] {
                d += 1;
                w = a;
            }
            d
        };
        // The order of the states the level decides about: that of the candidates the
        // static selection kept.
        let Some(order) = level
            .candidates
            .iter()
            .filter(|v| !level.dummies.contains(v))
            .map(|&v| depth(v))
            .max()
        else {
            continue;
        };
        let mut group = DynamicCandidates {
            candidates: Vec::new(),
            derivatives: Vec::new(),
            priorities: Vec::new(),
            chosen: Vec::new(),
            order,
        };
        for &v in &level.candidates {
            let b = base(v);
            let var = slots[b].var;
            if depth(v) != order
                || !(0.0..ALWAYS).contains(&priority[var])
                || group.candidates.contains(&var)
            {
                continue;
            }
            if !level.dummies.contains(&v) {
                group.chosen.push(group.candidates.len());
            }
            group.candidates.push(var);
            group.priorities.push(priority[var]);
            group.derivatives.push(
                var_diff[b]
                    .filter(|&d| slots[d].order == 0)
                    .map(|d| slots[d].var),
            );
        }
        if !group.chosen.is_empty() && group.candidates.len() > group.chosen.len() {
            log::debug!(
                "dynamic state selection: {} states among {} candidates",
                group.chosen.len(),
                group.candidates.len()
            );
            groups.push(group);
        }
    }
    groups
}

fn configuration_dependent(
    arena: &mut Arena,
    slots: &[Slot],
    eqs: &[ReducedEquation],
    level: &SelectionLevel,
) -> bool {
    use crate::structure::blt::blt_flat;
    use crate::structure::matching::maximum_matching;
    let local: HashMap<Id, usize> = level
        .dummies
        .iter()
        .enumerate()
        .map(|(k, &v)| (slots[v].leaf, k))
        .collect();
    let mut g = BipartiteGraph::new(level.dummies.len());
    let (mut leaves, mut vars) = (Vec::new(), Vec::new());
    for &e in &level.equations {
        arena.leaves_into(eqs[e].residual, &mut leaves);
        vars.clear();
        vars.extend(leaves.iter().filter_map(|l| local.get(l).copied()));
        g.add_equation_from(&mut vars);
    }
    let m = maximum_matching(&g, None, None);
    if !m.is_perfect() {
        return true;
    }
    blt_flat(&g, &m).iter().any(|block| {
        if block.eqs.len() > 1 {
            return true;
        }
        let r = eqs[level.equations[block.eqs[0]]].residual;
        let c = arena.diff(r, slots[level.dummies[block.vars[0]]].leaf);
        arena.as_const(c) == Some(0.0)
            || arena
                .leaves(c)
                .iter()
                .any(|&l| matches!(arena.node(l), Node::Var(_) | Node::Der(_)))
    })
}
