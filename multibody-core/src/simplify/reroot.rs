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

use super::causalize::{Schedule, safe_coefficient};
use crate::codegen::Stmt;

/// How far a chain is followed.
const MAX_CHAIN: usize = 8;

/// Position of each assignment's target in `steps`.
fn positions(steps: &[Stmt]) -> HashMap<Id, usize> {
    let mut at = HashMap::default();
    for (k, s) in steps.iter().enumerate() {
        match s {
            Stmt::Assign { target, .. } => {
                at.insert(*target, k);
            }
            Stmt::LinearSolve { targets, .. } | Stmt::SparseLinearSolve { targets, .. } => {
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
    steps: &[Stmt],
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
            Stmt::Assign { target, expr, .. }
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
            let Stmt::Assign { expr, .. } = &steps[k] else {
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
                Stmt::Assign { target, .. } => *target,
                _ => unreachable!("chains are made of assignments"),
            })
            .collect();
        for (k, s) in steps.iter().enumerate().take(insert_at) {
            let reads = match s {
                Stmt::Assign { expr, .. } => arena.leaves(*expr),
                Stmt::LinearSolve { a, c, .. } => {
                    a.iter().chain(c).flat_map(|&e| arena.leaves(e)).collect()
                }
                Stmt::SparseLinearSolve { entries, c, .. } => entries
                    .iter()
                    .map(|e| e.2)
                    .chain(c.iter().copied())
                    .flat_map(|e| arena.leaves(e))
                    .collect(),
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
            let Stmt::Assign {
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
            reversed.push(Stmt::Assign {
                target: input,
                expr: back.solution,
                equation,
            });
        }
        let new_iteration = match &schedule.steps[chain.last().expect("non-empty").0] {
            Stmt::Assign { target, .. } => *target,
            _ => unreachable!("chains are made of assignments"),
        };
        let mut steps: Vec<Stmt> = Vec::with_capacity(schedule.steps.len());
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::Node;

    /// `0 = x^2 - 4` iterated on x, then `y := x - 1`, `s := 2 y`: with s preferred, the
    /// chain runs backwards (`y := s / 2`, `x := y + 1`) and s is iterated.
    #[test]
    fn iteration_moves_to_the_preferred_coordinate() {
        let mut a = Arena::new();
        let (x, y, s) = (a.var(0), a.var(1), a.var(2));
        let one = a.constant(1.0);
        let two = a.constant(2.0);
        let four = a.constant(4.0);
        let x2 = a.powi(x, 2);
        let residual = a.sub(x2, four);
        let y_of_x = a.sub(x, one);
        let s_of_y = a.mul(two, y);
        let mut schedule = Schedule {
            steps: vec![
                Stmt::Assign {
                    target: y,
                    expr: y_of_x,
                    equation: 1,
                },
                Stmt::Assign {
                    target: s,
                    expr: s_of_y,
                    equation: 2,
                },
            ],
            iteration: vec![x],
            residuals: vec![(residual, 0)],
            blocks: Vec::new(),
            solved_for: Vec::new(),
        };
        let priority: HashMap<Id, f64> = [(s, 3.0)].into_iter().collect();
        assert_eq!(
            reroot_iteration_variables(&mut a, &mut schedule, &priority, &[]),
            1
        );
        assert_eq!(schedule.iteration, vec![s]);
        // Evaluate the new steps at s = 2: y = 1, x = 2, and the residual vanishes.
        let index = |a: &Arena, leaf: Id| match a.node(leaf) {
            Node::Var(i) => *i,
            _ => panic!("a variable"),
        };
        let mut values: HashMap<u32, f64> = [(2, 2.0)].into_iter().collect();
        for step in &schedule.steps {
            let Stmt::Assign { target, expr, .. } = step else {
                panic!("only assignments")
            };
            let v = a
                .eval(*expr, &|n: &Node| match n {
                    Node::Var(i) => values.get(i).copied(),
                    _ => None,
                })
                .expect("computable");
            values.insert(index(&a, *target), v);
        }
        assert_eq!(values[&1], 1.0);
        assert_eq!(values[&0], 2.0);
        let r = a.eval(residual, &|n: &Node| match n {
            Node::Var(i) => values.get(i).copied(),
            _ => None,
        });
        assert_eq!(r, Some(0.0));
        // A chain that ends in nothing preferred is left alone.
        let mut plain = schedule.clone();
        plain.iteration = vec![s];
        assert_eq!(
            reroot_iteration_variables(&mut a, &mut plain, &HashMap::default(), &[]),
            0
        );
    }
}
