//! Symbolic pre-elimination of a sparse linear block: before the block goes to the
//! sparse LU at run time, unknowns whose equation has a coefficient that cannot vanish
//! (a nonzero constant, or an expression of parameters that is nonzero for their
//! defaults, as tearing requires) are eliminated at compile time, in Markowitz order and
//! only where the elimination creates at most `max_fill` new entries.
//!
//! On a chain of bodies most unknowns of the acceleration block (cut forces and torques,
//! body accelerations) are eliminated this way without fill: the LU then factorizes a
//! block a few times smaller, and the eliminated unknowns are computed afterwards by
//! plain assignments (back substitution), compiled with their constant coefficients
//! folded.
//!
//! Costs count the entries that are nonzero at the default parameter values: an entry
//! such as `r_CM[3] * cos(q)` is kept symbolically (the block stays exact for any
//! values) but orders the eliminations as if it were absent, because with the defaults
//! that the problems are usually solved with, specializing the tape to the values
//! (`codegen/specialize.rs`) removes it. This is what lets tunable parameters reach the
//! structure of a model compiled with its parameters folded.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use crate::expr::{Arena, Id, Node};

use super::causalize::safe_coefficient;

/// A linear equation `sum(coefficient * x_var) + c = 0` of the block.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct LinearRow {
    /// `(unknown index, coefficient)`, coefficients free of the block's unknowns.
    pub entries: Vec<(usize, Id)>,
    /// The part free of the block's unknowns.
    pub c: Id,
}

/// One unknown solved from one row: `x_var = -(c + sum(coefficient * x_k)) / pivot`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Elimination {
    /// The unknown.
    pub var: usize,
    /// The row it was solved from (index into the block's rows).
    pub row: usize,
    /// The pivot coefficient.
    pub pivot: Id,
    /// The row's other entries at the time of elimination.
    pub others: Vec<(usize, Id)>,
    /// The row's constant part at that time.
    pub c: Id,
}

/// What remains after pre-elimination.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct PreEliminated {
    /// Eliminations in order; back substitution runs them in reverse.
    pub eliminations: Vec<Elimination>,
    /// Rows left for the LU (indices into the block's rows), with their updated forms.
    pub rows: Vec<(usize, LinearRow)>,
    /// Unknowns left for the LU (indices into the block's unknowns), increasing.
    pub vars: Vec<usize>,
}

/// Whether `a` may serve as a pivot: a constant that is not small next to the other
/// constant entries of its column (threshold pivoting at compile time), or an
/// expression of parameters that is nonzero for their defaults and a single term (an
/// original coefficient such as a mass, not a difference that elimination made and that
/// could vanish for other parameter values).
fn acceptable_pivot(arena: &Arena, a: Id, column_max: f64, params: &[f64]) -> bool {
    if let Some(v) = arena.as_const(a) {
        return v.is_finite() && v.abs() >= PIVOT_THRESHOLD * column_max && v != 0.0;
    }
    let single_term = match arena.node(a) {
        Node::Sum(ts, c) => ts.len() == 1 && f64::from_bits(*c) == 0.0,
        _ => true,
    };
    single_term && safe_coefficient(arena, a, params)
}

/// Whether the coefficient `a` is zero at the default parameter values `params` whatever
/// the values of its other leaves (checked at two generic points, so a coefficient that
/// only vanishes at special values of the variables does not count): `r_CM[3] * cos(q)`
/// with `r_CM = {0.5, 0, 0}` by default. A wrong answer only changes the elimination
/// order, never a result.
fn zero_at_defaults(arena: &Arena, a: Id, params: &[f64]) -> bool {
    if arena.as_const(a).is_some() {
        return false;
    }
    (0..2u64).all(|salt| {
        let v = arena.eval(a, &|n: &Node| match n {
            Node::Param(j) => params.get(*j as usize).copied(),
            Node::Var(v) => Some(generic(*v as u64, salt)),
            Node::Time => Some(generic(u64::MAX, salt)),
            Node::Der(d) => Some(generic(d.0 as u64 ^ 0x5555_0000, salt)),
            _ => None,
        });
        v == Some(0.0)
    })
}

/// The entries `(row, unknown)` that vanish at the default parameter values, by row
/// (rows hold few of them).
struct DefaultZero(Vec<Vec<usize>>);

impl DefaultZero {
    fn contains(&self, row: usize, var: usize) -> bool {
        self.0[row].contains(&var)
    }

    fn insert(&mut self, row: usize, var: usize) {
        if !self.contains(row, var) {
            self.0[row].push(var);
        }
    }

    /// Entries of row `row` (its `entries`) that count: those not vanishing at the
    /// defaults.
    fn counted(&self, row: usize, entries: &[(usize, Id)]) -> usize {
        entries.iter().filter(|e| !self.contains(row, e.0)).count()
    }

    /// Removes the entry; whether it was there.
    fn remove(&mut self, row: usize, var: usize) -> bool {
        let vars = &mut self.0[row];
        match vars.iter().position(|&v| v == var) {
            Some(k) => {
                vars.swap_remove(k);
                true
            }
            None => false,
        }
    }
}

/// A pseudo-random value in [0.3, 1.3) for leaf `k` at evaluation point `salt`.
fn generic(k: u64, salt: u64) -> f64 {
    let h = (k ^ (salt << 40)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    0.3 + ((h >> 11) as f64) / ((1u64 << 53) as f64)
}

/// A constant pivot must be at least this fraction of the largest constant entry of its
/// column.
const PIVOT_THRESHOLD: f64 = 0.1;

/// An updated constant entry this small next to the terms it came from is a
/// cancellation: it is removed, not kept as a tiny entry.
fn cancels(v: f64, a: f64, b: f64) -> bool {
    v.abs() <= 64.0 * f64::EPSILON * a.abs().max(b.abs())
}

/// Eliminates what it can from `rows` (over `n_vars` unknowns). `params` are the default
/// parameter values that decide whether a coefficient may vanish. `compact` may replace
/// the coefficients and the constant part of a pivot row by leaves computed beforehand
/// (temporaries): scaling a sum by a constant distributes over its terms, so without
/// it the constant parts would grow along a chain of eliminations.
pub(crate) fn pre_eliminate(
    arena: &mut Arena,
    rows: Vec<LinearRow>,
    n_vars: usize,
    params: &[f64],
    max_fill: usize,
    compact: &mut dyn FnMut(&mut Arena, Id) -> Id,
) -> PreEliminated {
    let mut rows = rows;
    let mut row_alive = vec![true; rows.len()];
    let mut var_alive = vec![true; n_vars];
    // Rows that contain each unknown (may hold stale rows; checked on use).
    let mut col_rows: Vec<Vec<usize>> = vec![Vec::new(); n_vars];
    let mut col_count = vec![0usize; n_vars];
    // Entries `(row, unknown)` that vanish at the default parameter values: they do not
    // count in the Markowitz costs (see the module documentation).
    let mut default_zero = DefaultZero(vec![Vec::new(); rows.len()]);
    for (i, r) in rows.iter().enumerate() {
        for &(k, a) in &r.entries {
            col_rows[k].push(i);
            if zero_at_defaults(arena, a, params) {
                default_zero.insert(i, k);
            } else {
                col_count[k] += 1;
            }
        }
    }
    let coefficient = |row: &LinearRow, var: usize| {
        row.entries
            .iter()
            .find(|&&(k, _)| k == var)
            .map(|&(_, a)| a)
    };
    // Largest constant entry of a column among the live rows.
    let column_max = |rows: &[LinearRow],
                      col_rows: &[Vec<usize>],
                      row_alive: &[bool],
                      arena: &Arena,
                      j: usize| {
        col_rows[j]
            .iter()
            .filter(|&&r| row_alive[r])
            .filter_map(|&r| rows[r].entries.iter().find(|e| e.0 == j))
            .filter_map(|e| arena.as_const(e.1))
            .fold(0.0f64, |m, v| m.max(v.abs()))
    };
    let mut eliminations = Vec::new();
    loop {
        // Candidates by Markowitz cost (fill an elimination can create).
        let mut heap = BinaryHeap::new();
        for (i, r) in rows.iter().enumerate() {
            if !row_alive[i] {
                continue;
            }
            let len = default_zero.counted(i, &r.entries);
            for &(j, a) in &r.entries {
                if default_zero.contains(i, j) {
                    continue;
                }
                let cost = (len - 1) * (col_count[j] - 1);
                if cost <= max_fill
                    && acceptable_pivot(
                        arena,
                        a,
                        column_max(&rows, &col_rows, &row_alive, arena, j),
                        params,
                    )
                {
                    heap.push(Reverse((cost, i, j)));
                }
            }
        }
        let before = eliminations.len();
        while let Some(Reverse((cost, i, j))) = heap.pop() {
            if !row_alive[i] || !var_alive[j] {
                continue;
            }
            let Some(p) = coefficient(&rows[i], j) else {
                continue;
            };
            // An entry cancelled and made again by elimination may now vanish at the
            // defaults: no pivot then (and it would not count in its row or column).
            if default_zero.contains(i, j) {
                continue;
            }
            let len = default_zero.counted(i, &rows[i].entries);
            let now = (len - 1) * (col_count[j] - 1);
            if now > max_fill
                || !acceptable_pivot(
                    arena,
                    p,
                    column_max(&rows, &col_rows, &row_alive, arena, j),
                    params,
                )
            {
                continue;
            }
            if now > cost {
                heap.push(Reverse((now, i, j)));
                continue;
            }
            let mut pivot_row = rows[i].clone();
            pivot_row.c = compact(arena, pivot_row.c);
            for e in pivot_row.entries.iter_mut() {
                if e.0 != j {
                    e.1 = compact(arena, e.1);
                }
            }
            let others: Vec<(usize, Id)> = pivot_row
                .entries
                .iter()
                .copied()
                .filter(|&(k, _)| k != j)
                .collect();
            let one = arena.one();
            let inv = arena.div(one, p);
            let targets: Vec<usize> = col_rows[j]
                .iter()
                .copied()
                .filter(|&r| r != i && row_alive[r])
                .collect();
            for r in targets {
                let Some(pos) = rows[r].entries.iter().position(|&(k, _)| k == j) else {
                    continue;
                };
                let (_, a_rj) = rows[r].entries.remove(pos);
                let f_default_zero = default_zero.remove(r, j);
                if !f_default_zero {
                    col_count[j] -= 1;
                }
                let a_rj = compact(arena, a_rj);
                let f = arena.mul(a_rj, inv);
                for &(k, a_ik) in &others {
                    let delta_default_zero = f_default_zero || default_zero.contains(i, k);
                    let delta = arena.mul(f, a_ik);
                    match rows[r].entries.iter().position(|&(kk, _)| kk == k) {
                        Some(q) => {
                            let old = rows[r].entries[q].1;
                            let v = arena.sub(old, delta);
                            let cancelled = match (
                                arena.as_const(v),
                                arena.as_const(old),
                                arena.as_const(delta),
                            ) {
                                (Some(v), Some(a), Some(b)) => cancels(v, a, b),
                                (Some(v), _, _) => v == 0.0,
                                _ => false,
                            };
                            let was_counted = !default_zero.contains(r, k);
                            if cancelled {
                                rows[r].entries.remove(q);
                                default_zero.remove(r, k);
                                if was_counted {
                                    col_count[k] -= 1;
                                }
                            } else {
                                rows[r].entries[q].1 = v;
                                if !was_counted && !delta_default_zero {
                                    default_zero.remove(r, k);
                                    col_count[k] += 1;
                                }
                            }
                        }
                        None => {
                            let v = arena.neg(delta);
                            rows[r].entries.push((k, v));
                            col_rows[k].push(r);
                            if delta_default_zero {
                                default_zero.insert(r, k);
                            } else {
                                col_count[k] += 1;
                            }
                        }
                    }
                }
                let fc = arena.mul(f, pivot_row.c);
                rows[r].c = arena.sub(rows[r].c, fc);
            }
            row_alive[i] = false;
            var_alive[j] = false;
            for &(k, _) in &pivot_row.entries {
                if !default_zero.remove(i, k) {
                    col_count[k] -= 1;
                }
            }
            eliminations.push(Elimination {
                var: j,
                row: i,
                pivot: p,
                others,
                c: pivot_row.c,
            });
        }
        if eliminations.len() == before {
            break;
        }
    }
    let rows_left = rows
        .into_iter()
        .enumerate()
        .filter(|&(i, _)| row_alive[i])
        .collect();
    let vars = (0..n_vars).filter(|&j| var_alive[j]).collect();
    PreEliminated {
        eliminations,
        rows: rows_left,
        vars,
    }
}

/// The value of an eliminated unknown: `-(c + sum(coefficient * x_k)) / pivot`, with
/// `x` the leaves of the block's unknowns.
pub(crate) fn back_substitution(arena: &mut Arena, e: &Elimination, x: &[Id]) -> Id {
    let mut terms: Vec<(f64, Id)> = Vec::with_capacity(e.others.len() + 1);
    terms.push((1.0, e.c));
    for &(k, a) in &e.others {
        let t = arena.mul(a, x[k]);
        terms.push((1.0, t));
    }
    let sum = arena.linear_combination(0.0, &terms);
    let one = arena.one();
    let inv = arena.div(one, e.pivot);
    let v = arena.mul(sum, inv);
    arena.neg(v)
}

#[cfg(test)]
#[path = "pre_eliminate_tests.rs"]
mod tests;
