//! Iterating on coordinates: moving an iteration variable along a chain of explicit
//! assignments to a variable of higher state priority.
//!
//! A nonlinear equation that closes a loop analytically (a rod length) contains
//! positions, not the joint coordinate that determines them; sorting makes one of those
//! positions its iteration variable and computes the coordinate from it afterwards
//! (`s := (x - 1.2)`). When every step of that chain is linear in its input with a
//! coefficient that cannot vanish, the chain can run the other way: the coordinate
//! becomes the iteration variable, the positions are computed from it, and Newton
//! starts from the coordinate's start value (what Modelica tools do).

use crate::expr::{Arena, Id};
use crate::hash::{HashMap, HashSet};

use super::causalize::{Schedule, Step, safe_coefficient};

/// How far a chain is followed.
const MAX_CHAIN: usize = 8;

/// Position of each assignment's target in `steps`.
fn positions(steps: &[Step]) -> HashMap<Id, usize> {
    let mut at = HashMap::default();
    for (k, s) in steps.iter().enumerate() {
        match s {
            Step::Assign { target, .. } => {
                at.insert(*target, k);
            }
            Step::LinearSolve { targets, .. } | Step::SparseLinearSolve { targets, .. } => {
                for t in targets {
                    at.insert(*t, k);
                }
            }
        }
    }
    at
}

/// The chain of assignments from `x` to a variable of higher priority: `(step, input)`
/// pairs, first step first.
fn find_chain(
    arena: &mut Arena,
    steps: &[Step],
    x: Id,
    priority: &HashMap<Id, f64>,
    params: &[f64],
) -> Option<Vec<(usize, Id)>> {
    let px = priority.get(&x).copied().unwrap_or(0.0);
    let mut chain = Vec::new();
    let mut current = x;
    let mut used: HashSet<usize> = HashSet::default();
    for _ in 0..MAX_CHAIN {
        // The first assignment that uses `current` and can be solved back for it.
        let next = steps.iter().enumerate().find_map(|(k, s)| match s {
            Step::Assign { target, expr, .. }
                if !used.contains(&k) && arena.contains(*expr, current) =>
            {
                let residual = arena.sub(*target, *expr);
                let back = arena.solve_linear(residual, current)?;
                safe_coefficient(arena, back.coefficient, params).then_some((k, *target))
            }
            _ => None,
        });
        let (k, target) = next?;
        used.insert(k);
        chain.push((k, current));
        if priority.get(&target).copied().unwrap_or(0.0) > px {
            return Some(chain);
        }
        current = target;
    }
    None
}

/// Moves each iteration variable of `schedule` to a variable of higher priority reached
/// through invertible assignments, when the reversed chain can be evaluated where the
/// first of its steps stood. Returns how many iteration variables moved.
pub(crate) fn reroot_iteration_variables(
    arena: &mut Arena,
    schedule: &mut Schedule,
    priority: &HashMap<Id, f64>,
    params: &[f64],
) -> usize {
    let mut moved = 0;
    for i in 0..schedule.iteration.len() {
        let x = schedule.iteration[i];
        let Some(chain) = find_chain(arena, &schedule.steps, x, priority, params) else {
            continue;
        };
        let steps = &schedule.steps;
        let at = positions(steps);
        let in_chain: HashSet<usize> = chain.iter().map(|&(k, _)| k).collect();
        let chain_vars: HashSet<Id> = chain.iter().map(|&(_, v)| v).collect();
        // The reversed steps go where the first chain step was; everything else they
        // read must be computed before that, and nothing before it may read the chain.
        let insert_at = chain
            .iter()
            .map(|&(k, _)| k)
            .min()
            .expect("a chain has steps");
        let mut valid = true;
        for &(k, input) in &chain {
            let Step::Assign { expr, .. } = &steps[k] else {
                unreachable!("chains are made of assignments")
            };
            for leaf in arena.leaves(*expr) {
                if leaf != input
                    && at
                        .get(&leaf)
                        .is_some_and(|&p| p >= insert_at && !in_chain.contains(&p))
                {
                    valid = false;
                }
            }
        }
        let targets: HashSet<Id> = chain
            .iter()
            .map(|&(k, _)| match &steps[k] {
                Step::Assign { target, .. } => *target,
                _ => unreachable!("chains are made of assignments"),
            })
            .collect();
        for (k, s) in steps.iter().enumerate().take(insert_at) {
            let reads = match s {
                Step::Assign { expr, .. } => arena.leaves(*expr),
                _ => Vec::new(),
            };
            if !in_chain.contains(&k)
                && reads
                    .iter()
                    .any(|l| chain_vars.contains(l) || targets.contains(l))
            {
                valid = false;
            }
        }
        if !valid {
            continue;
        }
        // Reverse: the last target is the new iteration variable; each step, solved
        // for its input, computes the previous variable.
        let mut reversed = Vec::new();
        for &(k, input) in chain.iter().rev() {
            let Step::Assign {
                target,
                expr,
                equation,
            } = schedule.steps[k].clone()
            else {
                unreachable!("chains are made of assignments")
            };
            let residual = arena.sub(target, expr);
            let back = arena
                .solve_linear(residual, input)
                .expect("checked invertible");
            reversed.push(Step::Assign {
                target: input,
                expr: back.solution,
                equation,
            });
        }
        let new_iteration = match &schedule.steps[chain.last().expect("non-empty").0] {
            Step::Assign { target, .. } => *target,
            _ => unreachable!("chains are made of assignments"),
        };
        let mut steps: Vec<Step> = Vec::with_capacity(schedule.steps.len());
        for (k, s) in schedule.steps.drain(..).enumerate() {
            if k == insert_at {
                steps.extend(reversed.iter().cloned());
            }
            if !in_chain.contains(&k) {
                steps.push(s);
            }
        }
        schedule.steps = steps;
        schedule.iteration[i] = new_iteration;
        moved += 1;
    }
    moved
}
