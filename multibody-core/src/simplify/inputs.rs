//! The model's inputs: the variables named in [`SimplifyOptions::inputs`] (and, with
//! [`SimplifyOptions::open_inputs`], every signal input connected to nothing) become
//! parameters of the compiled model, of the same names, through an equation
//! `input = parameter` that alias elimination removes. A problem gives their values, as
//! constants or as functions of time, without compiling again; events and
//! specialization treat them as changing, and index reduction refuses to differentiate
//! them.

use crate::hash::HashSet;
use crate::model::{FlatEquation, FlatSystem, ModelError, Origin, VarKind};
use crate::names::closest;

use super::SimplifyOptions;
use super::events::add_parameter;

/// Turns the inputs that `options` names into parameters of `flat`; returns their
/// indices among `flat.parameters`, in the order given (named, then open).
pub(crate) fn augment(
    flat: &mut FlatSystem,
    options: &SimplifyOptions,
) -> Result<Vec<usize>, ModelError> {
    let variables = input_variables(flat, options)?;
    let mut params = Vec::with_capacity(variables.len());
    for v in variables {
        let (name, unit) = (
            flat.variables[v].name.clone(),
            flat.variables[v].unit.clone(),
        );
        // The value until a problem gives one: the variable's start value, else 0.
        let start = flat.starts[v];
        let j = add_parameter(
            flat,
            name.to_string(),
            "an input of the model".into(),
            start,
        );
        flat.parameters[j].unit = unit;
        let (x, u) = (flat.arena.var(v as u32), flat.arena.param(j as u32));
        let residual = flat.arena.sub(x, u);
        flat.equations.push(FlatEquation {
            residual,
            origin: Origin::Input {
                variable: name.to_string(),
            },
            lhs_var: Some(v as u32),
        });
        params.push(j);
    }
    Ok(params)
}

/// The flat variables that `options` makes inputs: those named (each must be an unknown
/// of the model, named once), then the open signal inputs not named.
fn input_variables(flat: &FlatSystem, options: &SimplifyOptions) -> Result<Vec<usize>, ModelError> {
    let mut out: Vec<usize> = Vec::new();
    let mut seen = HashSet::default();
    if !options.inputs.is_empty() {
        let index: crate::hash::HashMap<&str, usize> = (flat.variables.iter().enumerate())
            .map(|(i, v)| (&*v.name, i))
            .collect();
        for name in &options.inputs {
            let Some(&v) = index.get(name.as_str()) else {
                let names = flat.variables.iter().map(|v| &*v.name);
                return Err(ModelError::UnknownName {
                    what: "input variable",
                    name: name.clone(),
                    place: "SimplifyOptions::inputs".into(),
                    suggestions: closest(name, names, 3),
                });
            };
            if flat.variables[v].discrete {
                return Err(ModelError::InvalidInput {
                    name: name.clone(),
                    message: "is a discrete variable".into(),
                });
            }
            if !seen.insert(v) {
                return Err(ModelError::InvalidInput {
                    name: name.clone(),
                    message: "is named twice in SimplifyOptions::inputs".into(),
                });
            }
            out.push(v);
        }
    }
    if options.open_inputs {
        for v in crate::model::unconnected_input_variables(flat) {
            debug_assert_eq!(flat.variables[v].kind, VarKind::Input);
            if seen.insert(v) {
                out.push(v);
            }
        }
    }
    Ok(out)
}
