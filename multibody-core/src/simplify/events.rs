//! Relations that generate events, with Modelica's semantics (specification, chapter 8):
//! every `<`, `<=`, `>` or `>=` of the model's equations whose operands depend on a
//! variable or on time, outside `noEvent`, holds its value between events.
//!
//! Each such relation `a op b` becomes
//! - a *relation parameter* (`events.relation[k]`, 1 when the relation holds, 0 when
//!   not) that replaces it in the equations, so that the compiled functions see a
//!   constant between events and the integrator never steps across a switch;
//! - a *crossing variable* (`events.crossing[k] = a - b`), whose zero the integrator
//!   locates (root finding). There the relation takes its new value, the model is
//!   re-initialized with it and the integration restarts.
//!
//! Relations of parameters alone are evaluated as they are; `==` and `!=` never
//! generate events (as in Modelica, where they are not allowed on reals outside
//! functions). Initial equations keep their relations: they are evaluated once.
//!
//! `when` clauses: the conditions' relations generate events like the equations'.
//! Each variable a clause assigns (a *discrete variable*) becomes a parameter
//! (`events.discrete[k]`) that the equation `v = events.discrete[k]` gives to `v`,
//! changed only at events; `pre(x)` in a clause reads a parameter (`events.pre[k]`)
//! that holds `x` just before the event, and is `x` itself in the equations.
//!
//! A variable declared discrete that no clause assigns is defined by its equation
//! `v = expr` (a friction element's `mode`, `locked`): the equation becomes a
//! [`DiscreteEquation`], evaluated at every round of every event's iteration with
//! `pre(x)` the value of the round before, and `v` is held by a parameter in between.
//! Such equations and the continuous ones that depend on them form a mixed system that
//! the event iteration solves by alternating the two until nothing changes.

use crate::expr::{Cmp, Func1, Id, Node, NodeMap};
use crate::hash::HashSet;
use crate::model::{FlatEquation, FlatSystem, ModelError, Origin, Parameter, SharedText, Variable};

/// What generates events in a model, and what happens at them.
#[derive(Clone, Debug, Default)]
pub struct Events {
    /// The relations that generate events.
    pub relations: Vec<EventRelation>,
    /// The `when` clauses.
    pub whens: Vec<EventWhen>,
    /// `(parameter, variable)`: the parameters that hold `pre(variable)` at an event.
    pub pre: Vec<(usize, usize)>,
    /// The parameters of `initial()`: 1 at the initial event, 0 elsewhere.
    pub initial: Vec<usize>,
    /// The parameters of `terminal()`: 1 at the terminal event, 0 elsewhere.
    pub terminal: Vec<usize>,
    /// The discrete variables defined by equations, in the order they are evaluated
    /// (each after those it reads).
    pub equations: Vec<DiscreteEquation>,
    /// `(variable, parameter)`: every discrete variable and the parameter that holds it.
    pub discrete: Vec<(usize, usize)>,
}

/// The equation `v = value` of a discrete variable that no `when` clause assigns: its
/// parameter takes `value` at every round of an event's iteration.
#[derive(Clone, Debug)]
pub struct DiscreteEquation {
    /// The variable's full name.
    pub name: String,
    /// The parameter that holds it.
    pub parameter: usize,
    /// Its value: relations by their parameters, `pre(x)` by the parameters of
    /// [`Events::pre`], discrete variables by their parameters.
    pub value: Id,
}

impl Events {
    /// Whether the model has neither relations that generate events nor `when`
    /// clauses.
    pub fn is_empty(&self) -> bool {
        self.relations.is_empty() && self.whens.is_empty() && self.equations.is_empty()
    }

    /// Per parameter (of `n`): whether events change it (a relation's value, a
    /// discrete variable, a `pre` value).
    pub fn parameters(&self, n: usize) -> Vec<bool> {
        let mut changing = vec![false; n];
        let indices = self
            .relations
            .iter()
            .map(|r| r.parameter)
            .chain(self.pre.iter().map(|&(p, _)| p))
            .chain(self.initial.iter().copied())
            .chain(self.terminal.iter().copied())
            .chain(self.equations.iter().map(|d| d.parameter))
            .chain(
                self.whens
                    .iter()
                    .flat_map(|w| w.assignments.iter().map(|&(p, _)| p)),
            );
        for p in indices {
            if let Some(c) = changing.get_mut(p) {
                *c = true;
            }
        }
        changing
    }
}

/// A `when` clause, its expressions in the system's arena (relations of the condition
/// replaced by their parameters, `pre(x)` by the parameters of [`Events::pre`]).
#[derive(Clone, Debug)]
pub struct EventWhen {
    /// The condition as written (`ball.h < 0`).
    pub text: String,
    /// The condition.
    pub condition: Id,
    /// `(parameter, value)`: the discrete variables' parameters it sets.
    pub assignments: Vec<(usize, Id)>,
    /// Its `reinit`s.
    pub reinits: Vec<Reinit>,
    /// The message of its `terminate(..)` (with the component's path), which ends the
    /// simulation at its event.
    pub terminate: Option<String>,
    /// Whether it is an `elsewhen` of the clause before it: skipped at an event where
    /// a clause before it in its chain fires.
    pub elsewhen: bool,
}

/// `reinit(x, value)` of a `when` clause.
#[derive(Clone, Debug)]
pub struct Reinit {
    /// The state's flat variable.
    pub variable: usize,
    /// Its new value.
    pub value: Id,
    /// Its position among the unknowns of the simplified system (set once they are
    /// ordered).
    pub unknown: usize,
}

use super::dynamic_states::free_name;

/// A relation that generates events.
#[derive(Clone, Debug, PartialEq)]
pub struct EventRelation {
    /// The comparison (`Lt`, `Le`, `Gt` or `Ge`) of the crossing function with 0.
    pub op: Cmp,
    /// Its relation parameter (an index into the system's parameters).
    pub parameter: usize,
    /// Its crossing variable `lhs - rhs` (an index into the flat variables).
    pub crossing: usize,
    /// The relation as written in the model (`ball.h < 0`).
    pub text: String,
    /// Whether it is the condition of a `sample(..)`: false at the initialization,
    /// and true from an event at the initial time when the first instant is not
    /// later.
    pub sample: bool,
    /// For a relation of time, `time - c` with `c` an expression of parameters (a time
    /// event: the integration stops at `c` exactly, without root finding): `c`.
    pub time_event: Option<Id>,
    /// Whether only discrete equations read it (not the continuous equations, not a
    /// `when` clause): where it changes without changing a discrete variable, nothing
    /// else changes either (a stuck friction element's speed, at zero up to rounding).
    pub only_discrete: bool,
}

impl EventRelation {
    /// Whether the relation holds where its crossing function is `g`.
    pub fn holds(&self, g: f64) -> bool {
        self.op.apply(g, 0.0) != 0.0
    }

    /// The shift of the crossing function `g` that makes the relation, now `value`,
    /// change only once `g` is `band` beyond zero on the other side (hysteresis: a
    /// crossing function that stays at zero, as a stuck friction element's relative
    /// speed, does not chatter).
    pub fn hysteresis(&self, value: bool, band: f64) -> f64 {
        let positive_side = matches!(self.op, Cmp::Gt | Cmp::Ge) == value;
        if positive_side { band } else { -band }
    }

    /// Whether the relation holds just after its crossing function passed through 0,
    /// rising (`true`) or falling.
    pub fn holds_after_crossing(&self, rising: bool) -> bool {
        match self.op {
            Cmp::Gt | Cmp::Ge => rising,
            _ => !rising,
        }
    }
}

/// Whether a relation of this kind generates events.
fn generates_events(op: Cmp) -> bool {
    matches!(op, Cmp::Lt | Cmp::Le | Cmp::Gt | Cmp::Ge)
}

/// The relations of `flat`'s equations that generate events, in the order first met.
fn find_relations(flat: &FlatSystem) -> Vec<Id> {
    let arena = &flat.arena;
    if !arena.has_comparison() {
        return Vec::new();
    }
    let mut seen = HashSet::default();
    let mut found = Vec::new();
    let roots = flat
        .equations
        .iter()
        .map(|e| e.residual)
        .chain(flat.derivative_rules.iter().map(|&(_, d)| d))
        .chain(flat.whens.iter().map(|w| w.condition));
    for root in roots {
        arena.walk(root, &mut |x, node| match *node {
            Node::F1(Func1::NoEvent, _) => false,
            Node::Cmp(op, _, _) => {
                if generates_events(op) && seen.insert(x) {
                    found.push(x);
                }
                true
            }
            Node::Const(_) | Node::Var(_) | Node::Param(_) | Node::Time | Node::Der(_) => false,
            _ => true,
        });
    }
    found.retain(|&c| {
        arena
            .leaves(c)
            .iter()
            .any(|&l| !matches!(arena.node(l), Node::Param(_)))
    });
    found
}

/// The nodes `pre(x)` in `roots`.
fn find_pre(flat: &FlatSystem, roots: impl Iterator<Item = Id>) -> Vec<Id> {
    let arena = &flat.arena;
    let mut seen = HashSet::default();
    let mut found = Vec::new();
    for root in roots {
        arena.walk(root, &mut |x, node| match *node {
            Node::F1(Func1::Pre, _) => {
                if seen.insert(x) {
                    found.push(x);
                }
                false
            }
            Node::Const(_) | Node::Var(_) | Node::Param(_) | Node::Time | Node::Der(_) => false,
            _ => true,
        });
    }
    found
}

/// A new parameter of `flat` with value `value` (0 when `None`); its index.
pub(super) fn add_parameter(
    flat: &mut FlatSystem,
    name: String,
    description: String,
    value: Option<Id>,
) -> usize {
    let k = flat.parameters.len();
    flat.parameters.push(Parameter {
        name: SharedText::from(name),
        value: None,
        fixed: true,
        description: SharedText::from(description),
        unit: SharedText::default(),
        evaluate: false,
        min: f64::NEG_INFINITY,
        max: f64::INFINITY,
        symbol: None,
    });
    let value = value.unwrap_or_else(|| flat.arena.zero());
    flat.parameter_values.push(Some(value));
    k
}

/// Turns the relations of `flat`'s equations and `when` conditions that generate
/// events into relation parameters and crossing variables, and the discrete variables
/// and `pre` values of its `when` clauses into parameters (see the module
/// documentation); returns what the solver needs of them.
pub(crate) fn augment(flat: &mut FlatSystem) -> Result<Events, ModelError> {
    let mut relations = relations(flat);
    let defined = discrete_equations(flat)?;
    let (whens, pre, discrete, equations) = whens(flat, &relations, defined);
    time_events(flat, &mut relations, &discrete);
    if !equations.is_empty() {
        mark_only_discrete(flat, &mut relations.relations, &whens);
    }
    Ok(Events {
        relations: relations.relations,
        whens,
        pre,
        initial: flat.initials.clone(),
        terminal: flat.terminals.clone(),
        equations,
        discrete: discrete.iter().map(|&(v, p)| (v as usize, p)).collect(),
    })
}

/// Marks the relations that neither the equations nor the `when` clauses read.
fn mark_only_discrete(flat: &FlatSystem, relations: &mut [EventRelation], whens: &[EventWhen]) {
    let mut read = HashSet::default();
    let roots = (flat.equations.iter().map(|e| e.residual))
        .chain(flat.derivative_rules.iter().map(|&(_, d)| d))
        .chain(whens.iter().flat_map(|w| {
            std::iter::once(w.condition)
                .chain(w.assignments.iter().map(|&(_, e)| e))
                .chain(w.reinits.iter().map(|r| r.value))
        }));
    for root in roots {
        for &l in &flat.arena.leaves(root) {
            if let Node::Param(j) = *flat.arena.node(l) {
                read.insert(j as usize);
            }
        }
    }
    for r in relations {
        r.only_discrete = !read.contains(&r.parameter);
    }
}

/// The discrete variables that no `when` clause assigns, with the right-hand sides of
/// their equations `v = expr`, which leave the equations.
fn discrete_equations(flat: &mut FlatSystem) -> Result<Vec<(u32, Id)>, ModelError> {
    let assigned: HashSet<u32> = flat
        .whens
        .iter()
        .flat_map(|w| w.assignments.iter().map(|&(v, _)| v))
        .collect();
    let wanted: Vec<u32> = (0..flat.variables.len() as u32)
        .filter(|v| flat.variables[*v as usize].discrete && !assigned.contains(v))
        .collect();
    if wanted.is_empty() {
        return Ok(Vec::new());
    }
    let mut taken = HashSet::default();
    let mut out = Vec::with_capacity(wanted.len());
    for v in wanted {
        let x = flat.arena.var(v);
        let found = flat.equations.iter().enumerate().find_map(|(k, e)| {
            if e.lhs_var != Some(v) || taken.contains(&k) {
                return None;
            }
            // The residual is `v - value` (`pre(v)` in the value is no occurrence of v).
            let value = flat.arena.sub(x, e.residual);
            let mut occurs = false;
            flat.arena.walk(value, &mut |l, node| match *node {
                Node::F1(Func1::Pre, _) => false,
                _ => {
                    occurs |= l == x;
                    !occurs
                }
            });
            (!occurs).then_some((k, value))
        });
        let Some((k, value)) = found else {
            let name = flat.variables[v as usize].name.to_string();
            let (component, short) = name.rsplit_once('.').unwrap_or(("", &name));
            return Err(ModelError::InvalidWhen {
                component: component.to_string(),
                message: format!(
                    "the discrete variable `{short}` needs an equation `{short} = ...` or a \
                     when clause that assigns it"
                ),
            });
        };
        taken.insert(k);
        out.push((v, value));
    }
    let mut k = 0;
    flat.equations.retain(|_| {
        k += 1;
        !taken.contains(&(k - 1))
    });
    Ok(out)
}

/// Marks the relations of time alone, `time - c` with `c` of parameters and discrete
/// variables (held by the parameters `discrete`), as time events.
fn time_events(flat: &mut FlatSystem, relations: &mut Relations, discrete: &[(u32, usize)]) {
    let mut map = NodeMap::default();
    for &(v, p) in discrete {
        let (x, held) = (flat.arena.var(v), flat.arena.param(p as u32));
        map.insert(x, held);
    }
    let mut memo = NodeMap::default();
    let time = flat.arena.time();
    for (r, &g) in relations.relations.iter_mut().zip(&relations.crossings) {
        let g = flat.arena.substitute_memo(g, &map, &mut memo);
        let c = flat.arena.sub(time, g);
        let of_parameters = flat
            .arena
            .leaves(c)
            .iter()
            .all(|&l| matches!(flat.arena.node(l), Node::Param(_)));
        if of_parameters {
            r.time_event = Some(c);
        }
    }
}

/// The relations of [`augment`], with the map from each relation to its parameter
/// and each one's crossing function `lhs - rhs`.
struct Relations {
    relations: Vec<EventRelation>,
    map: NodeMap,
    crossings: Vec<Id>,
}

fn relations(flat: &mut FlatSystem) -> Relations {
    let relations = find_relations(flat);
    let mut map = NodeMap::default();
    if relations.is_empty() {
        return Relations {
            relations: Vec::new(),
            map,
            crossings: Vec::new(),
        };
    }
    let base = free_name(flat, "events");
    let mut out = Vec::with_capacity(relations.len());
    let mut crossings = Vec::with_capacity(relations.len());
    for (k, &c) in relations.iter().enumerate() {
        let Node::Cmp(op, a, b) = *flat.arena.node(c) else {
            unreachable!("a relation")
        };
        let text = flat.show(c);
        let parameter = add_parameter(
            flat,
            format!("{base}.relation[{}]", k + 1),
            format!("1 while {text} holds (changes at events)"),
            None,
        );
        let crossing = flat.variables.len();
        flat.variables.push(
            Variable::new(format!("{base}.crossing[{}]", k + 1))
                .description(format!("crossing function of {text}")),
        );
        flat.starts.push(None);
        let p = flat.arena.param(parameter as u32);
        map.insert(c, p);
        let g = flat.arena.sub(a, b);
        crossings.push(g);
        let v = flat.arena.var(crossing as u32);
        let residual = flat.arena.sub(v, g);
        flat.equations.push(FlatEquation {
            residual,
            origin: Origin::Crossing {
                relation: text.clone(),
            },
            lhs_var: Some(crossing as u32),
        });
        out.push(EventRelation {
            op,
            parameter,
            crossing,
            text,
            sample: flat.samples.contains(&c),
            time_event: None,
            only_discrete: false,
        });
    }
    // The relations held: every equation sees the relation parameters (the crossing
    // functions too, where one relation is inside another's operands).
    let mut memo = NodeMap::default();
    for e in &mut flat.equations {
        e.residual = flat.arena.substitute_memo(e.residual, &map, &mut memo);
    }
    for (_, d) in &mut flat.derivative_rules {
        *d = flat.arena.substitute_memo(*d, &map, &mut memo);
    }
    Relations {
        relations: out,
        map,
        crossings,
    }
}

/// The clauses, the `pre` parameters, the discrete variables with their parameters and
/// the discrete equations.
type Whens = (
    Vec<EventWhen>,
    Vec<(usize, usize)>,
    Vec<(u32, usize)>,
    Vec<DiscreteEquation>,
);

/// The `when` clauses of [`augment`], its `pre` parameters, its discrete variables and
/// the discrete equations from `defined` (variables and right-hand sides); `pre(x)` in
/// the equations becomes `x`.
fn whens(flat: &mut FlatSystem, relations: &Relations, defined: Vec<(u32, Id)>) -> Whens {
    let in_equations = if flat.arena.has_pre() {
        find_pre(
            flat,
            flat.equations
                .iter()
                .chain(&flat.initial_equations)
                .map(|e| e.residual)
                .chain(flat.derivative_rules.iter().map(|&(_, d)| d)),
        )
    } else {
        Vec::new()
    };
    if !in_equations.is_empty() {
        let mut map = NodeMap::default();
        for &p in &in_equations {
            let Node::F1(_, a) = *flat.arena.node(p) else {
                unreachable!("a pre node")
            };
            map.insert(p, a);
        }
        let mut memo = NodeMap::default();
        for e in flat.equations.iter_mut().chain(&mut flat.initial_equations) {
            e.residual = flat.arena.substitute_memo(e.residual, &map, &mut memo);
        }
        for (_, d) in &mut flat.derivative_rules {
            *d = flat.arena.substitute_memo(*d, &map, &mut memo);
        }
    }
    if flat.whens.is_empty() && defined.is_empty() {
        return (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    }
    let base = free_name(flat, "events");
    // The discrete variables, each held by a parameter.
    let mut discrete: Vec<(u32, usize)> = Vec::new();
    let assigned: Vec<u32> = flat
        .whens
        .iter()
        .flat_map(|w| w.assignments.iter().map(|&(v, _)| v))
        .chain(defined.iter().map(|&(v, _)| v))
        .collect();
    for v in assigned {
        if discrete.iter().any(|&(d, _)| d == v) {
            continue;
        }
        let name = flat.variables[v as usize].name.to_string();
        let start = flat.starts[v as usize];
        let p = add_parameter(
            flat,
            format!("{base}.discrete[{}]", discrete.len() + 1),
            format!("{name} between events"),
            start,
        );
        let (x, held) = (flat.arena.var(v), flat.arena.param(p as u32));
        let residual = flat.arena.sub(x, held);
        flat.equations.push(FlatEquation {
            residual,
            origin: Origin::Discrete { variable: name },
            lhs_var: Some(v),
        });
        discrete.push((v, p));
    }
    // pre(x) in the clauses: a parameter that holds x before the event.
    let clause_roots: Vec<Id> = flat
        .whens
        .iter()
        .flat_map(|w| {
            std::iter::once(w.condition)
                .chain(w.assignments.iter().map(|&(_, e)| e))
                .chain(w.reinits.iter().map(|&(_, e)| e))
        })
        .chain(defined.iter().map(|&(_, e)| e))
        .collect();
    let mut map = relations.map.clone();
    let mut pre = Vec::new();
    for p in find_pre(flat, clause_roots.into_iter()) {
        let Node::F1(_, a) = *flat.arena.node(p) else {
            unreachable!("a pre node")
        };
        let image = match *flat.arena.node(a) {
            Node::Var(v) => {
                let name = flat.variables[v as usize].name.to_string();
                let start = flat.starts[v as usize];
                let k = add_parameter(
                    flat,
                    format!("{base}.pre[{}]", pre.len() + 1),
                    format!("{name} just before the event"),
                    start,
                );
                pre.push((k, v as usize));
                flat.arena.param(k as u32)
            }
            // pre of anything else is the value now.
            _ => a,
        };
        map.insert(p, image);
    }
    let mut memo = NodeMap::default();
    let whens = std::mem::take(&mut flat.whens);
    let mut out = Vec::with_capacity(whens.len());
    // In the assignments, the discrete variables are read from their parameters, so
    // that each sees the values assigned before it at the same event.
    let mut held_map = map.clone();
    for &(v, p) in &discrete {
        let (x, held) = (flat.arena.var(v), flat.arena.param(p as u32));
        held_map.insert(x, held);
    }
    let mut held_memo = NodeMap::default();
    for w in &whens {
        let text = flat.show(w.condition);
        let condition = flat.arena.substitute_memo(w.condition, &map, &mut memo);
        let assignments: Vec<(usize, Id)> = w
            .assignments
            .iter()
            .map(|&(v, e)| {
                let p = discrete.iter().find(|&&(d, _)| d == v).expect("declared").1;
                (p, flat.arena.substitute_memo(e, &held_map, &mut held_memo))
            })
            .collect();
        let assignments = dependency_order(flat, assignments);
        let reinits = w
            .reinits
            .iter()
            .map(|&(v, e)| Reinit {
                variable: v as usize,
                value: flat.arena.substitute_memo(e, &map, &mut memo),
                unknown: usize::MAX,
            })
            .collect();
        out.push(EventWhen {
            text,
            condition,
            assignments,
            reinits,
            terminate: w.terminate.clone(),
            elsewhen: w.elsewhen,
        });
    }
    flat.whens = whens;
    let equations = ordered_equations(flat, &defined, &discrete, &map);
    (out, pre, discrete, equations)
}

/// The discrete equations of `defined`, with `map` applied and the discrete variables
/// read from their parameters, each after the others it reads (as written where they
/// read each other in a cycle, which the event iteration then settles).
fn ordered_equations(
    flat: &mut FlatSystem,
    defined: &[(u32, Id)],
    discrete: &[(u32, usize)],
    map: &NodeMap,
) -> Vec<DiscreteEquation> {
    let mut map = map.clone();
    for &(v, p) in discrete {
        let (x, held) = (flat.arena.var(v), flat.arena.param(p as u32));
        map.insert(x, held);
    }
    let mut memo = NodeMap::default();
    let parameter_of = |v: u32| discrete.iter().find(|&&(d, _)| d == v).expect("held").1;
    let equations: Vec<DiscreteEquation> = defined
        .iter()
        .map(|&(v, e)| DiscreteEquation {
            name: flat.variables[v as usize].name.to_string(),
            parameter: parameter_of(v),
            value: flat.arena.substitute_memo(e, &map, &mut memo),
        })
        .collect();
    let pairs = equations.iter().map(|d| (d.parameter, d.value)).collect();
    dependency_order(flat, pairs)
        .into_iter()
        .map(|(p, _)| {
            equations
                .iter()
                .find(|d| d.parameter == p)
                .expect("one equation per parameter")
                .clone()
        })
        .collect()
}

/// `(parameter, value)` pairs, each after the others whose parameters its value reads
/// (depth first; as given where they read each other in a cycle).
fn dependency_order(flat: &FlatSystem, pairs: Vec<(usize, Id)>) -> Vec<(usize, Id)> {
    let position: crate::hash::HashMap<usize, usize> = pairs
        .iter()
        .enumerate()
        .map(|(k, &(p, _))| (p, k))
        .collect();
    let reads: Vec<Vec<usize>> = pairs
        .iter()
        .map(|&(_, value)| {
            flat.arena
                .leaves(value)
                .iter()
                .filter_map(|&l| match *flat.arena.node(l) {
                    Node::Param(j) => position.get(&(j as usize)).copied(),
                    _ => None,
                })
                .collect()
        })
        .collect();
    let mut state = vec![0u8; pairs.len()];
    let mut order = Vec::with_capacity(pairs.len());
    fn visit(k: usize, reads: &[Vec<usize>], state: &mut [u8], order: &mut Vec<usize>) {
        if state[k] != 0 {
            return;
        }
        state[k] = 1;
        for &j in &reads[k] {
            visit(j, reads, state, order);
        }
        state[k] = 2;
        order.push(k);
    }
    for k in 0..pairs.len() {
        visit(k, &reads, &mut state, &mut order);
    }
    order.into_iter().map(|k| pairs[k]).collect()
}
