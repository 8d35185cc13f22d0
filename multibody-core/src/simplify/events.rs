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

use crate::expr::{Cmp, Func1, Id, Node, NodeMap};
use crate::hash::HashSet;
use crate::model::{FlatEquation, FlatSystem, Origin, Parameter, SharedText, Variable};

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
}

impl EventRelation {
    /// Whether the relation holds where its crossing function is `g`.
    pub fn holds(&self, g: f64) -> bool {
        self.op.apply(g, 0.0) != 0.0
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
        .chain(flat.derivative_rules.iter().map(|&(_, d)| d));
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

/// Turns the relations of `flat`'s equations that generate events into relation
/// parameters and crossing variables (see the module documentation); returns them.
pub(crate) fn augment(flat: &mut FlatSystem) -> Vec<EventRelation> {
    let relations = find_relations(flat);
    if relations.is_empty() {
        return Vec::new();
    }
    let base = free_name(flat, "events");
    let mut map = NodeMap::default();
    let mut out = Vec::with_capacity(relations.len());
    for (k, &c) in relations.iter().enumerate() {
        let Node::Cmp(op, a, b) = *flat.arena.node(c) else {
            unreachable!("a relation")
        };
        let text = flat.show(c);
        let parameter = flat.parameters.len();
        flat.parameters.push(Parameter {
            name: SharedText::from(format!("{base}.relation[{}]", k + 1)),
            value: None,
            fixed: true,
            description: SharedText::from(format!("1 while {text} holds (changes at events)")),
            unit: SharedText::default(),
            evaluate: false,
            min: f64::NEG_INFINITY,
            max: f64::INFINITY,
            symbol: None,
        });
        let zero = flat.arena.zero();
        flat.parameter_values.push(Some(zero));
        let crossing = flat.variables.len();
        flat.variables.push(
            Variable::new(format!("{base}.crossing[{}]", k + 1))
                .description(format!("crossing function of {text}")),
        );
        flat.starts.push(None);
        let p = flat.arena.param(parameter as u32);
        map.insert(c, p);
        let g = flat.arena.sub(a, b);
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
    out
}
