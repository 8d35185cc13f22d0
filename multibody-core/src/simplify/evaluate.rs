//! Evaluation of parameters at compile time (MSL `Evaluate=true`): the values of
//! parameters marked [`evaluate`](crate::model::Parameter::evaluate), or of every
//! parameter with [`SimplifyOptions::evaluate_parameters`](super::SimplifyOptions), are
//! substituted into the flat equations before alias elimination, so that zero offsets,
//! unit axes and switches fold away ("Evaluate parameters to reduce models" in Dymola).
//! Parameters computed at initialization (`fixed = false`), and those whose bindings
//! depend on them, stay symbolic.

use crate::expr::Node;
use crate::hash::HashMap;
use crate::model::{FlatSystem, evaluate_bindings};

/// Substitutes the values of the parameters to evaluate (`all`, or those marked) into
/// `flat`; returns, per parameter, whether it was evaluated.
pub(crate) fn evaluate_parameters(flat: &mut FlatSystem, all: bool) -> Vec<bool> {
    let np = flat.parameters.len();
    let mut evaluated: Vec<bool> = flat
        .parameters
        .iter()
        .map(|p| p.fixed && (all || p.evaluate))
        .collect();
    if !evaluated.iter().any(|&e| e) {
        return evaluated;
    }
    // A binding that reads a parameter that is not evaluated keeps its parameter
    // symbolic too.
    let reads: Vec<Vec<usize>> = flat
        .parameter_values
        .iter()
        .map(|b| match b {
            Some(e) => flat
                .arena
                .leaves(*e)
                .into_iter()
                .filter_map(|l| match flat.arena.node(l) {
                    Node::Param(j) => Some(*j as usize),
                    _ => None,
                })
                .collect(),
            None => Vec::new(),
        })
        .collect();
    loop {
        let mut changed = false;
        for j in 0..np {
            if evaluated[j] && reads[j].iter().any(|&k| !evaluated[k]) {
                evaluated[j] = false;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let Ok(values) = evaluate_bindings(&flat.arena, &flat.parameter_values, &HashMap::default())
    else {
        // Cyclic bindings: left to the problem, which reports them by name.
        return vec![false; np];
    };
    let mut map = HashMap::default();
    for j in (0..np).filter(|&j| evaluated[j]) {
        let leaf = flat.arena.param(j as u32);
        let value = flat.arena.constant(values[j]);
        map.insert(leaf, value);
    }
    let mut memo = HashMap::default();
    let arena = &mut flat.arena;
    for eq in flat
        .equations
        .iter_mut()
        .chain(flat.initial_equations.iter_mut())
    {
        eq.residual = arena.substitute_leaves_memo(eq.residual, &map, &mut memo);
    }
    for e in flat.starts.iter_mut().flatten() {
        *e = arena.substitute_leaves_memo(*e, &map, &mut memo);
    }
    for (j, b) in flat.parameter_values.iter_mut().enumerate() {
        if evaluated[j] {
            *b = Some(arena.constant(values[j]));
        } else if let Some(e) = b {
            *e = arena.substitute_leaves_memo(*e, &map, &mut memo);
        }
    }
    for (_, d) in flat.derivative_rules.iter_mut() {
        *d = arena.substitute_leaves_memo(*d, &map, &mut memo);
    }
    evaluated
}
