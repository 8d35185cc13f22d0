//! Dynamic state selection (Mattsson, Olsson and Elmqvist, 2000): where the static
//! choice of states among a group of candidates depends on the configuration (the
//! joint angles of a kinematic loop, the coordinates of a pendulum in Cartesian form),
//! the model gets *dynamic states* instead: `x = P q` and `xd = der(x)`, where `q` are
//! the candidates and `P` a matrix of parameters that selects some of them. The
//! candidates become algebraic unknowns, solved from the constraints and `P q = x`, and
//! the solver changes `P` at run time, choosing the candidates that parametrize the
//! constraints best, whenever the current choice degrades (see
//! [`crate::solve::DaeProblem::solve`]).
//!
//! `P` is a tunable parameter of the compiled system, 0 by default, so the compiled code
//! assumes nothing about which of its entries vanish: every selection runs with the same
//! code.

use crate::expr::{Arena, Id};
use crate::model::{FlatEquation, FlatSystem, Origin, Parameter, SharedText, Variable};
use crate::structure::dummy_derivatives::ALWAYS;

use super::reduce::DynamicCandidates;

/// One group of dynamic states in a compiled system.
#[derive(Clone, Debug, PartialEq)]
pub struct DynamicStateGroup {
    /// The candidates `q` (flat variables).
    pub candidates: Vec<usize>,
    /// Per candidate: the flat variable that is its derivative, if any.
    pub derivatives: Vec<Option<usize>>,
    /// Per candidate: its state priority (a higher one is preferred among selections
    /// of about equal quality).
    pub priorities: Vec<f64>,
    /// The dynamic states `x` (flat variables), one per state of the group.
    pub states: Vec<usize>,
    /// Their derivatives `xd` (flat variables).
    pub velocity_states: Vec<usize>,
    /// The parameters `P[j, i]` (row `j` selects state `j`), row-major.
    pub selection: Vec<usize>,
    /// The static choice of the candidates (positions in `candidates`), preferred at
    /// the start.
    pub preferred: Vec<usize>,
    /// Where the solution's observed outputs hold each candidate and its derivative,
    /// and where the unknowns `u` hold each `xd` (set when the system is compiled).
    pub outputs: GroupOutputs,
}

/// A group of candidates whose static choice a compiled system watches at run time (see
/// [`super::DynamicStates::WhenNeeded`]).
#[derive(Clone, Debug, PartialEq)]
pub struct StaticGroup {
    /// The candidates and the static choice.
    pub(crate) candidates: DynamicCandidates,
    /// Where the observed function holds the candidates and their derivatives, and
    /// where the unknowns hold the velocities of the chosen ones (`velocity_state`).
    pub outputs: GroupOutputs,
}

impl StaticGroup {
    /// The static choice (positions among the candidates).
    pub fn chosen(&self) -> &[usize] {
        &self.candidates.chosen
    }

    /// Number of candidates.
    pub fn n_candidates(&self) -> usize {
        self.candidates.candidates.len()
    }
}

/// Positions of a group's quantities in the compiled functions' inputs and outputs.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GroupOutputs {
    /// Observed output of each candidate.
    pub candidate: Vec<usize>,
    /// Observed output of each candidate's derivative.
    pub derivative: Vec<usize>,
    /// Observed output of each candidate's second derivative.
    pub acceleration: Vec<usize>,
    /// Unknown (position in `u`) of each `x`.
    pub state: Vec<usize>,
    /// Unknown of each `xd`.
    pub velocity_state: Vec<usize>,
}

impl DynamicStateGroup {
    /// Number of states of the group.
    pub fn n_states(&self) -> usize {
        self.states.len()
    }

    /// The parameter values of `P` that select the candidates `chosen` (one per state,
    /// positions in `candidates`), written into `params`.
    pub fn select(&self, chosen: &[usize], params: &mut [f64]) {
        let k = self.candidates.len();
        for (j, row) in self.selection.chunks(k).enumerate() {
            for (i, &p) in row.iter().enumerate() {
                params[p] = if chosen.get(j) == Some(&i) { 1.0 } else { 0.0 };
            }
        }
    }

    /// The candidates `params` selects (positions in `candidates`), one per state.
    pub fn selected(&self, params: &[f64]) -> Vec<usize> {
        let k = self.candidates.len();
        self.selection
            .chunks(k)
            .map(|row| {
                row.iter()
                    .position(|&p| params[p] != 0.0)
                    .unwrap_or(usize::MAX)
            })
            .collect()
    }
}

/// A name not yet taken in `flat` (`base`, or `base` with a number).
pub(crate) fn free_name(flat: &FlatSystem, base: &str) -> String {
    let taken = |n: &str| {
        flat.variables.iter().any(|v| v.name.starts_with(n))
            || flat.parameters.iter().any(|p| p.name.starts_with(n))
    };
    if !taken(base) {
        return base.to_string();
    }
    (2..)
        .map(|k| format!("{base}_{k}"))
        .find(|n| !taken(n))
        .expect("a free name")
}

/// `sum_i P[j, i] * value_i` for the given row of parameters (values `None` count 0).
fn selected_sum(arena: &mut Arena, row: &[usize], values: &[Option<Id>]) -> Id {
    let terms: Vec<Id> = row
        .iter()
        .zip(values)
        .filter_map(|(&p, v)| {
            let v = (*v)?;
            let p = arena.param(p as u32);
            Some(arena.mul(p, v))
        })
        .collect();
    arena.sum(&terms)
}

/// Adds the dynamic states of `groups` to `flat`: per group, the states `x` and `xd`
/// (priority `always`), the selection parameters `P` (0), and the equations
/// `x = P q` and `der(x) = xd`. Start values: `x = P q_start`, `xd = P der(q)_start`.
pub(crate) fn augment(
    flat: &mut FlatSystem,
    groups: &[DynamicCandidates],
) -> Vec<DynamicStateGroup> {
    let mut out = Vec::with_capacity(groups.len());
    for (g, group) in groups.iter().enumerate() {
        let base = free_name(flat, &format!("dynamic_states{}", g + 1));
        let (k, s) = (group.candidates.len(), group.chosen.len());
        // Parameters P[j, i].
        let mut selection = Vec::with_capacity(s * k);
        for j in 0..s {
            for i in 0..k {
                selection.push(flat.parameters.len());
                flat.parameters.push(Parameter {
                    name: SharedText::from(format!("{base}.P[{},{}]", j + 1, i + 1)),
                    value: None,
                    fixed: true,
                    description: SharedText::from(
                        "1 where the dynamic state is this candidate, 0 elsewhere",
                    ),
                    unit: SharedText::default(),
                    evaluate: false,
                    min: f64::NEG_INFINITY,
                    max: f64::INFINITY,
                    symbol: None,
                });
                let zero = flat.arena.zero();
                flat.parameter_values.push(Some(zero));
            }
        }
        let q_starts: Vec<Option<Id>> = group.candidates.iter().map(|&q| flat.starts[q]).collect();
        let v_starts: Vec<Option<Id>> = group
            .derivatives
            .iter()
            .map(|d| d.and_then(|d| flat.starts[d]))
            .collect();
        let mut states = Vec::with_capacity(s);
        let mut velocity_states = Vec::with_capacity(s);
        for j in 0..s {
            let row = &selection[j * k..(j + 1) * k];
            for (list, name, starts) in [
                (&mut states, format!("{base}.x[{}]", j + 1), &q_starts),
                (
                    &mut velocity_states,
                    format!("{base}.xd[{}]", j + 1),
                    &v_starts,
                ),
            ] {
                let start = selected_sum(&mut flat.arena, row, starts);
                list.push(flat.variables.len());
                flat.variables.push(
                    Variable::new(name)
                        .state_priority(ALWAYS)
                        .description("dynamic state: the candidate that P selects"),
                );
                flat.starts.push(Some(start));
            }
            // x = P q
            let x = flat.arena.var(states[j] as u32);
            let q: Vec<Option<Id>> = group
                .candidates
                .iter()
                .map(|&c| Some(flat.arena.var(c as u32)))
                .collect();
            let pq = selected_sum(&mut flat.arena, row, &q);
            let residual = flat.arena.sub(x, pq);
            flat.equations.push(FlatEquation {
                residual,
                origin: Origin::DynamicStates {
                    text: format!("{base}.x[{}] = P[{}, :] * candidates", j + 1, j + 1),
                },
                lhs_var: Some(states[j] as u32),
            });
            // der(x) = xd, and for candidates whose accelerations the selection decides,
            // der(xd) = xdd (so that index reduction differentiates x = P q twice).
            let dx = flat.arena.der(x);
            let xd = flat.arena.var(velocity_states[j] as u32);
            let residual = flat.arena.sub(dx, xd);
            flat.equations.push(FlatEquation {
                residual,
                origin: Origin::DynamicStates {
                    text: format!("der({base}.x[{}]) = {base}.xd[{}]", j + 1, j + 1),
                },
                lhs_var: None,
            });
            if group.order >= 2 {
                let xdd_var = flat.variables.len();
                flat.variables.push(
                    Variable::new(format!("{base}.xdd[{}]", j + 1))
                        .description("derivative of a dynamic state's velocity"),
                );
                flat.starts.push(None);
                let dxd = flat.arena.der(xd);
                let xdd = flat.arena.var(xdd_var as u32);
                let residual = flat.arena.sub(dxd, xdd);
                flat.equations.push(FlatEquation {
                    residual,
                    origin: Origin::DynamicStates {
                        text: format!("der({base}.xd[{}]) = {base}.xdd[{}]", j + 1, j + 1),
                    },
                    lhs_var: None,
                });
            }
        }
        out.push(DynamicStateGroup {
            candidates: group.candidates.clone(),
            derivatives: group.derivatives.clone(),
            priorities: group.priorities.clone(),
            states,
            velocity_states,
            selection,
            preferred: group.chosen.clone(),
            outputs: GroupOutputs::default(),
        });
    }
    out
}
