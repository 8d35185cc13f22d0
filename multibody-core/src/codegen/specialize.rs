//! Specializing a tape to the values of its invariant inputs (the parameters of one
//! problem).
//!
//! Tunable parameters stay symbolic at compile time, so a tape computes `m * r_CM[2]`
//! even when `r_CM[2]` is 0 in every problem anyone solves. Once a problem fixes the
//! parameter values, the tape is recompiled with each parameter input replaced by its
//! value: constants fold, `x * 0` and `x + 0` vanish with everything only they used, and
//! the entries of a sparse linear solve that became zero leave its pattern (fewer
//! refactorization multiply-adds), and its unknowns whose pivots became constants are
//! eliminated (`specialize_solve.rs`). Compile-time pre-elimination orders its
//! eliminations for this (entries that vanish at the default values do not count as
//! fill). A problem with other values needs a new specialization, not a new
//! compilation. What this saves is measured in `docs/benchmarks.md`.
//!
//! Values and derivatives are those of the original tape at the same parameter values,
//! up to rounding and with the exceptions the tape compiler's folding always makes (as
//! the symbolic simplifier does): `0 * x` and `0 / x` are 0 even where `x` is not finite
//! or zero, `x / k` becomes `(1/k) x`, and `0 - x` becomes `-x` (the sign of a zero
//! result may differ). Eliminating linear-solve unknowns on constant pivots changes
//! the rounding by the conditioning of those eliminations; pivots are chosen by
//! threshold among the constants of their column, as compile-time pre-elimination
//! chooses them.

use crate::expr::Arena;

use super::compile::TapeBuilder;
use super::specialize_solve::emit_reduced_sparse_solve;
use super::tape::{LsInfo, Op, SparsePattern, Tape};

impl Tape {
    /// This tape with its invariant inputs (the slots given to
    /// [`TapeBuilder::invariant_inputs`]) replaced by `values` (one per invariant slot, in
    /// order) and everything that folds as a result folded. The result has the same
    /// inputs and outputs; it ignores the invariant slots.
    ///
    /// # Panics
    /// If `values` does not have one value per invariant slot.
    pub fn specialize(&self, values: &[f64]) -> Tape {
        let values: Vec<Option<f64>> = values.iter().copied().map(Some).collect();
        self.specialize_partly(&values)
    }

    /// [`Self::specialize`] for the invariant inputs with a value (`Some`); those
    /// without one (`None`, such as the parameters that events change) stay inputs of
    /// the result.
    ///
    /// # Panics
    /// If `values` does not have one entry per invariant slot.
    pub fn specialize_partly(&self, values: &[Option<f64>]) -> Tape {
        let (lo, hi) = self.invariant_inputs;
        assert_eq!(
            values.len(),
            hi - lo,
            "Tape::specialize: {} values for {} invariant inputs",
            values.len(),
            hi - lo
        );
        let arena = Arena::default();
        let mut b = TapeBuilder::new(&arena, self.n_inputs);
        let mut map = vec![u32::MAX; self.ops.len()];
        let mut i = 0;
        while i < self.ops.len() {
            let m = |r: u32| map[r as usize];
            map[i] = match self.ops[i] {
                Op::Const(k) => b.constant(self.consts[k as usize]),
                Op::Input(s)
                    if (lo..hi).contains(&(s as usize)) && values[s as usize - lo].is_some() =>
                {
                    b.constant(values[s as usize - lo].unwrap_or_default())
                }
                Op::Scale(k, a) => {
                    let k = b.const_slot(self.consts[k as usize]);
                    b.emit(Op::Scale(k, m(a)))
                }
                Op::AddScaled(a, k, c) => {
                    let k = b.const_slot(self.consts[k as usize]);
                    b.emit(Op::AddScaled(m(a), k, m(c)))
                }
                Op::LinearSolve(s) => {
                    let k = self.ls[s as usize].k;
                    let x = emit_linear_solve(&mut b, &self.ls[s as usize], &map);
                    map[i..i + k].copy_from_slice(&x);
                    i += k;
                    continue;
                }
                Op::LsPart => unreachable!("linear-solve parts follow their solve"),
                op => b.emit(op.remap(m)),
            };
            i += 1;
        }
        b.outputs = self.outputs.iter().map(|&r| map[r as usize]).collect();
        b.build()
    }
}

/// Emits the linear solve `info` with its operands mapped by `map`; returns the
/// register of each unknown. A sparse one loses the entries that are now the constant 0
/// (unless that leaves a row or column empty: the matrix is then singular at these
/// values and stays as it was, to fail as it would have), and its unknowns whose pivots
/// became constants are eliminated first (see `specialize_solve.rs`).
fn emit_linear_solve(b: &mut TapeBuilder<'_>, info: &LsInfo, map: &[u32]) -> Vec<u32> {
    let k = info.k;
    let a: Vec<u32> = info.a.iter().map(|&r| map[r as usize]).collect();
    let c: Vec<u32> = info.c.iter().map(|&r| map[r as usize]).collect();
    if let Some(p) = &info.sparse {
        let keep: Vec<bool> = a.iter().map(|&r| b.const_value(r) != Some(0.0)).collect();
        let mut rows_seen = vec![false; k];
        let mut col_ptr = vec![0usize; k + 1];
        let mut row_idx = Vec::with_capacity(a.len());
        let mut kept = Vec::with_capacity(a.len());
        for col in 0..k {
            for q in p.col_ptr[col]..p.col_ptr[col + 1] {
                if keep[q] {
                    row_idx.push(p.row_idx[q]);
                    kept.push(a[q]);
                    rows_seen[p.row_idx[q]] = true;
                }
            }
            col_ptr[col + 1] = row_idx.len();
        }
        let complete = rows_seen.iter().all(|&s| s) && (0..k).all(|j| col_ptr[j + 1] > col_ptr[j]);
        if complete {
            let pattern = SparsePattern::new(k, col_ptr, row_idx);
            return emit_reduced_sparse_solve(b, k, &pattern, &kept, &c, &info.names);
        }
    }
    let base = b.push_linear_solve(a, info.sparse.clone(), c, info.names.clone());
    (0..k as u32).map(|j| base + j).collect()
}
