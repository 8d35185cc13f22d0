//! The balance check: as many equations as unknowns, with a message that says which
//! unknowns are left undetermined or which equations over-determine.

use crate::expr::{Arena, Id, Node};
use crate::structure::{BipartiteGraph, dm::dulmage_mendelsohn, matching::maximum_matching};

use super::error::ModelError;
use super::flatten::FlatSystem;

/// The variables (by index) occurring in `e`, where `der(x)` counts as `x`.
pub fn variables_in(arena: &Arena, e: Id) -> Vec<usize> {
    let mut out: Vec<usize> = arena
        .leaves(e)
        .into_iter()
        .filter_map(|l| base_variable(arena, l))
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// The variable under a leaf: `x` for `x`, `der(x)`, `der(der(x))`.
pub fn base_variable(arena: &Arena, mut leaf: Id) -> Option<usize> {
    loop {
        match arena.node(leaf) {
            Node::Var(i) => return Some(*i as usize),
            Node::Der(x) => leaf = *x,
            _ => return None,
        }
    }
}

/// Checks that the flat model has as many equations as unknowns. When it does not,
/// a maximum matching and the Dulmage-Mendelsohn decomposition name the unknowns no
/// equation can determine and the equations with nothing left to determine.
pub fn check_balance(flat: &FlatSystem) -> Result<(), ModelError> {
    let (ne, nv) = (flat.equations.len(), flat.variables.len());
    if ne == nv {
        return Ok(());
    }
    let mut g = BipartiteGraph::new(nv);
    for eq in &flat.equations {
        g.add_equation(variables_in(&flat.arena, eq.residual));
    }
    let m = maximum_matching(&g, None, None);
    let dm = dulmage_mendelsohn(&g, &m, None);
    let undetermined = dm
        .under_vars
        .iter()
        .map(|&v| flat.variables[v].name.to_string())
        .collect();
    let overdetermined = dm
        .over_eqs
        .iter()
        .map(|&e| flat.describe(&flat.equations[e]))
        .collect();
    Err(ModelError::Unbalanced {
        model: flat.name.clone(),
        equations: ne,
        unknowns: nv,
        undetermined,
        overdetermined,
        unconnected_inputs: if ne < nv {
            unconnected_inputs(flat)
        } else {
            Vec::new()
        },
    })
}

/// Input signals that nothing outside their component sets: in no connection and in no
/// equation of another component (their component only reads them).
fn unconnected_inputs(flat: &FlatSystem) -> Vec<String> {
    unconnected_input_variables(flat)
        .into_iter()
        .map(|v| flat.variables[v].name.to_string())
        .collect()
}

/// The indices of the input signals that nothing outside their component sets (see
/// [`unconnected_inputs`]), in declaration order.
pub(crate) fn unconnected_input_variables(flat: &FlatSystem) -> Vec<usize> {
    use super::flatten::Origin;
    use super::variable::VarKind;
    /// The component that owns a connector variable: its path without the connector
    /// (`force.force[1]` -> `force`).
    fn owner(name: &str) -> &str {
        let name = name.split('[').next().unwrap_or(name);
        name.rsplit_once('.').map_or("", |(o, _)| o)
    }
    let inputs: Vec<usize> = (0..flat.variables.len())
        .filter(|&v| flat.variables[v].kind == VarKind::Input)
        .collect();
    if inputs.is_empty() {
        return Vec::new();
    }
    let mut set = vec![false; flat.variables.len()];
    for eq in &flat.equations {
        let from_outside = |v: usize| match &eq.origin {
            Origin::Component { path, .. } => path.as_str() != owner(&flat.variables[v].name),
            _ => true,
        };
        for v in variables_in(&flat.arena, eq.residual) {
            if flat.variables[v].kind == VarKind::Input && from_outside(v) {
                set[v] = true;
            }
        }
    }
    inputs.into_iter().filter(|&v| !set[v]).collect()
}

/// Evaluates parameter bindings (expressions of other parameters) in dependency order;
/// `overrides` replace bindings. A parameter without a binding is 0 (a guess for one
/// computed at initialization). Fails with the parameters whose bindings depend on each
/// other or on variables.
pub fn evaluate_bindings(
    arena: &Arena,
    bindings: &[Option<Id>],
    overrides: &crate::hash::HashMap<usize, f64>,
) -> Result<Vec<f64>, Vec<usize>> {
    let np = bindings.len();
    let mut values: Vec<Option<f64>> = vec![None; np];
    for (&j, &v) in overrides {
        values[j] = Some(v);
    }
    loop {
        let mut progress = false;
        let mut missing = Vec::new();
        for j in 0..np {
            if values[j].is_some() {
                continue;
            }
            let Some(e) = bindings[j] else {
                values[j] = Some(0.0);
                progress = true;
                continue;
            };
            let v = arena.eval(e, &|n: &Node| match n {
                Node::Param(k) => values.get(*k as usize).copied().flatten(),
                _ => None,
            });
            match v {
                Some(v) => {
                    values[j] = Some(v);
                    progress = true;
                }
                None => missing.push(j),
            }
        }
        if missing.is_empty() {
            break;
        }
        if !progress {
            return Err(missing);
        }
    }
    Ok(values.into_iter().map(|v| v.unwrap_or(0.0)).collect())
}
