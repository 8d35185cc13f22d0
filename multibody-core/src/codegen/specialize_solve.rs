//! Eliminating unknowns of a sparse linear solve whose pivots became constants when a
//! tape was specialized to parameter values.
//!
//! With tunable parameters, compile-time pre-elimination (`simplify/pre_eliminate.rs`)
//! may only divide by a parameter that is a single term: `m1 + m2` or
//! `I_33 + m r_CM[1]^2` could vanish for other values. Once the values are known those
//! coefficients are plain numbers, so unknowns are eliminated here on the instructions,
//! in Markowitz order, on constant pivots that are not small next to the other
//! constants of their column, and only where that creates no new entry ([`MAX_FILL`]).
//! The eliminated unknowns are computed after the reduced solve by back substitution.
//! Fill is not allowed: the extra instructions and a denser iteration matrix cost more
//! than the smaller factorization saves (measured in `docs/benchmarks.md`).

use std::cmp::Reverse;
use std::collections::{BTreeMap, BTreeSet, BinaryHeap};

use super::compile::TapeBuilder;
use super::tape::{Op, SparsePattern};

/// Entries an elimination may add (see the module documentation for why none).
const MAX_FILL: usize = 0;

/// A constant pivot must be at least this fraction of the largest constant of its
/// column (as at compile time).
const PIVOT_THRESHOLD: f64 = 0.1;

/// The block `A x + c = 0` being reduced: rows as maps column -> register.
struct Block {
    rows: Vec<BTreeMap<usize, u32>>,
    /// Rows with an entry in each column.
    cols: Vec<BTreeSet<usize>>,
    c: Vec<u32>,
    row_alive: Vec<bool>,
    col_alive: Vec<bool>,
}

/// One unknown solved from one row: `x_col = -(c + sum(a_k x_k)) / pivot`.
struct Elimination {
    col: usize,
    pivot: f64,
    others: Vec<(usize, u32)>,
    c: u32,
}

/// Emits the sparse linear solve `A x + c = 0` (CSC `pattern`, entry registers `a`,
/// constant registers `c`) with what constant pivots allow eliminated first; returns
/// the register of each unknown. `names` names the unknowns for error messages.
pub(super) fn emit_reduced_sparse_solve(
    b: &mut TapeBuilder<'_>,
    k: usize,
    pattern: &SparsePattern,
    a: &[u32],
    c: &[u32],
    names: &str,
) -> Vec<u32> {
    let mut block = Block {
        rows: vec![BTreeMap::new(); k],
        cols: vec![BTreeSet::new(); k],
        c: c.to_vec(),
        row_alive: vec![true; k],
        col_alive: vec![true; k],
    };
    for col in 0..k {
        for q in pattern.col_ptr[col]..pattern.col_ptr[col + 1] {
            let row = pattern.row_idx[q];
            block.rows[row].insert(col, a[q]);
            block.cols[col].insert(row);
        }
    }
    // Candidates by Markowitz count, checked again when taken (counts only change
    // through eliminations; a stale count is pushed again with its current value).
    let mut heap: BinaryHeap<Reverse<(usize, usize, usize)>> = BinaryHeap::new();
    for (row, entries) in block.rows.iter().enumerate() {
        for (&col, &reg) in entries {
            if b.const_value(reg).is_some() {
                heap.push(Reverse((markowitz(&block, row, col), col, row)));
            }
        }
    }
    let mut eliminations = Vec::new();
    while let Some(Reverse((cost, col, row))) = heap.pop() {
        if !block.row_alive[row] || !block.col_alive[col] {
            continue;
        }
        let Some(&reg) = block.rows[row].get(&col) else {
            continue;
        };
        let now = markowitz(&block, row, col);
        if now != cost {
            heap.push(Reverse((now, col, row)));
            continue;
        }
        if !acceptable_pivot(b, &block, reg, col) || fill_of(&block, row, col) > MAX_FILL {
            continue;
        }
        let (e, updated) = eliminate(b, &mut block, row, col);
        eliminations.push(e);
        for r in updated {
            for (&j, &reg) in &block.rows[r] {
                if b.const_value(reg).is_some() {
                    heap.push(Reverse((markowitz(&block, r, j), j, r)));
                }
            }
        }
    }
    let mut x = vec![u32::MAX; k];
    let left: Vec<usize> = (0..k).filter(|&j| block.col_alive[j]).collect();
    if !left.is_empty() {
        let rows: Vec<usize> = (0..k).filter(|&i| block.row_alive[i]).collect();
        let mut new_row = vec![usize::MAX; k];
        for (r, &i) in rows.iter().enumerate() {
            new_row[i] = r;
        }
        let kk = left.len();
        let mut col_ptr = vec![0usize; kk + 1];
        let mut row_idx = Vec::new();
        let mut regs = Vec::new();
        for (jj, &j) in left.iter().enumerate() {
            let mut entries: Vec<(usize, u32)> = block.cols[j]
                .iter()
                .map(|&i| (new_row[i], block.rows[i][&j]))
                .collect();
            entries.sort_unstable();
            for (r, reg) in entries {
                row_idx.push(r);
                regs.push(reg);
            }
            col_ptr[jj + 1] = row_idx.len();
        }
        let pattern = SparsePattern::new(kk, col_ptr, row_idx);
        let c = rows.iter().map(|&i| block.c[i]).collect();
        let base = b.push_linear_solve(
            regs,
            Some(std::sync::Arc::new(pattern)),
            c,
            names.to_string(),
        );
        for (jj, &j) in left.iter().enumerate() {
            x[j] = base + jj as u32;
        }
    }
    for e in eliminations.iter().rev() {
        let mut s = e.c;
        for &(j, reg) in &e.others {
            let term = b.emit(Op::Mul(reg, x[j]));
            s = b.emit(Op::Add(s, term));
        }
        let k = b.const_slot(-1.0 / e.pivot);
        x[e.col] = b.emit(Op::Scale(k, s));
    }
    x
}

/// Fill-in bound of pivoting on `(row, col)`: (row entries - 1) (column entries - 1).
fn markowitz(block: &Block, row: usize, col: usize) -> usize {
    (block.rows[row].len() - 1) * (block.cols[col].len() - 1)
}

/// Whether the entry `reg` of column `col` may be a pivot: a finite nonzero constant
/// not small next to the other constants of its column.
fn acceptable_pivot(b: &TapeBuilder<'_>, block: &Block, reg: u32, col: usize) -> bool {
    let Some(v) = b.const_value(reg) else {
        return false;
    };
    let column_max = block.cols[col]
        .iter()
        .filter_map(|&i| b.const_value(block.rows[i][&col]))
        .fold(0.0f64, |m, v| m.max(v.abs()));
    v != 0.0 && v.is_finite() && v.abs() >= PIVOT_THRESHOLD * column_max
}

/// New entries eliminating `col` with `row` would create.
fn fill_of(block: &Block, row: usize, col: usize) -> usize {
    let mut fill = 0;
    for &r in block.cols[col].iter() {
        if r == row {
            continue;
        }
        fill += block.rows[row]
            .keys()
            .filter(|&&j| j != col && !block.rows[r].contains_key(&j))
            .count();
    }
    fill
}

/// Eliminates unknown `col` with row `row`: every other row with an entry in `col`
/// subtracts `a_r,col / pivot` times row `row`. Returns the elimination and the rows it updated.
fn eliminate(
    b: &mut TapeBuilder<'_>,
    block: &mut Block,
    row: usize,
    col: usize,
) -> (Elimination, Vec<usize>) {
    let pivot_reg = block.rows[row][&col];
    let pivot = b.const_value(pivot_reg).expect("constant pivot");
    let others: Vec<(usize, u32)> = block.rows[row]
        .iter()
        .filter(|&(&j, _)| j != col)
        .map(|(&j, &reg)| (j, reg))
        .collect();
    let c_row = block.c[row];
    let inv = b.const_slot(1.0 / pivot);
    let targets: Vec<usize> = block.cols[col]
        .iter()
        .copied()
        .filter(|&r| r != row)
        .collect();
    for &r in &targets {
        let a_rc = block.rows[r].remove(&col).expect("entry of the column");
        let f = b.emit(Op::Scale(inv, a_rc));
        for &(j, a_ij) in &others {
            let update = b.emit(Op::Mul(f, a_ij));
            let new = match block.rows[r].get(&j) {
                Some(&old) => b.emit(Op::Sub(old, update)),
                None => b.emit(Op::Neg(update)),
            };
            if b.const_value(new) == Some(0.0) {
                block.rows[r].remove(&j);
                block.cols[j].remove(&r);
            } else {
                block.rows[r].insert(j, new);
                block.cols[j].insert(r);
            }
        }
        let update = b.emit(Op::Mul(f, c_row));
        block.c[r] = b.emit(Op::Sub(block.c[r], update));
    }
    for &(j, _) in &others {
        block.cols[j].remove(&row);
    }
    block.cols[col].clear();
    block.rows[row].clear();
    block.row_alive[row] = false;
    block.col_alive[col] = false;
    (
        Elimination {
            col,
            pivot,
            others,
            c: c_row,
        },
        targets,
    )
}
