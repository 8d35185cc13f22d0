//! Sparse LU with refactorization, for IDA's iteration matrices: the pattern never
//! changes during an integration and the values change slowly, so the pivot sequence of
//! one factorization usually serves the next ones.
//!
//! The first factorization of a pattern orders the columns by COLAMD (from faer), again
//! by AMD on the pattern with a maximum transversal on its diagonal (KLU's order), and
//! by COLAMD on [`SHUFFLED_COLAMD_TRIALS`] shuffles of the columns (COLAMD breaks ties
//! by position, and on extended Jacobians its fill varies by up to a factor of two with
//! the input order), and keeps the order whose factorization and expected solves cost
//! the fewest multiply-adds (see [`SparseLu::solves_per_factorization`]; AMD halves
//! them on a 100-link pendulum's acceleration block, COLAMD is better on IDA's extended
//! Jacobians, a shuffle took the 100-link pendulum's iteration matrix from 11 488 to
//! 8 289 factor entries). Each runs a left-looking Gilbert-Peierls LU with threshold
//! partial pivoting (the row a maximum transversal matched to the column is kept when it
//! is within a factor of [`DIAGONAL_PREFERENCE`] of the largest candidate) and records
//! the pivot rows and the patterns of `L` and `U`.
//! A refactorization replays them: no graph search, no pivot search, just the
//! arithmetic. If a replayed pivot has become small compared with the entries below it
//! (growth beyond [`REFACTOR_PIVOT_TOLERANCE`]), the factorization is redone with
//! pivoting.
//!
//! `P A Q = L U`: `L` unit lower triangular with its entries kept by original row index,
//! `U` upper triangular by pivot step.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::SymbolicSparseColMatRef;
use faer::sparse::linalg::colamd;

use crate::structure::BipartiteGraph;
use crate::structure::matching::maximum_matching;

/// A candidate on the structural diagonal is taken as pivot when it is at least this
/// fraction of the largest candidate in magnitude.
pub(crate) const DIAGONAL_PREFERENCE: f64 = 0.1;

/// A replayed pivot smaller than this fraction of the largest entry of its column below
/// it triggers a factorization with fresh pivoting.
pub(crate) const REFACTOR_PIVOT_TOLERANCE: f64 = 1e-3;

/// Why a factorization failed.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum LuError {
    /// The matrix is singular (no non-zero pivot in some column) or not finite.
    Singular(String),
}

/// The LU factors and the work space to recompute them.
#[derive(Default, Debug, Clone)]
pub(crate) struct SparseLu {
    n: usize,
    /// Column order: step k eliminates column `col_order[k]` of `A`.
    col_order: Vec<usize>,
    /// Per column: the row of a maximum transversal (the "diagonal" preferred as pivot).
    preferred_row: Vec<usize>,
    /// Pivot row of each step (original row index).
    pivot_row: Vec<usize>,
    /// Step of each original row (`usize::MAX` while not pivotal).
    row_step: Vec<usize>,
    /// `L` by step: original rows and multipliers (unit diagonal not stored). Indices
    /// are 32-bit: refactorization and solves are bound by memory traffic.
    l_ptr: Vec<usize>,
    l_row: Vec<u32>,
    l_val: Vec<f64>,
    /// `U` by step, strictly upper part: earlier steps in topological order, values.
    u_ptr: Vec<usize>,
    u_step: Vec<u32>,
    /// Pivot row of each `u_step` entry (saves an indirection when refactoring).
    u_row: Vec<u32>,
    u_val: Vec<f64>,
    /// Reciprocals of the pivots (the solve multiplies instead of dividing: a division
    /// on the critical path of the back substitution cost a quarter of its time).
    u_inv_diag: Vec<f64>,
    /// Per `U` entry, the range of the `L` column of its step (saves two indirections
    /// per entry when refactoring).
    u_l_range: Vec<(u32, u32)>,
    /// Whether the factors hold a complete factorization whose patterns can be replayed.
    factored: bool,
    /// Dense work vector by original row (kept zero between columns).
    work: Vec<f64>,
    /// Depth-first search scratch.
    mark: Vec<usize>,
    stack: Vec<(usize, usize)>,
    reach: Vec<usize>,
    /// Entries of the pattern given to `reset`.
    pattern_nnz: usize,
    /// Other column orders (AMD after the transversal, COLAMD of shuffled columns)
    /// tried at the first factorization; the cheapest is kept.
    alternative_orders: Vec<Vec<usize>>,
    /// How many solves are expected per factorization: the first factorization keeps
    /// the order that minimizes refactorization multiply-adds plus this many times the
    /// entries of the factors (the multiply-adds of a solve). Default 0 (only the
    /// refactorization counts): a linear block solved inside a residual is solved once
    /// per residual evaluation, and residual evaluations (each a factorization) far
    /// outnumber the Jacobian passes that solve it once per lane.
    pub(crate) solves_per_factorization: usize,
    /// Number of factorizations with pivoting (for tests and logs).
    pub(crate) pivoting_factorizations: usize,
    /// Number of refactorizations that replayed the pivots.
    pub(crate) refactorizations: usize,
}

impl SparseLu {
    /// Forgets the pattern: the next factorization orders and pivots afresh.
    pub(crate) fn reset(&mut self, n: usize, col_ptr: &[usize], row_idx: &[usize]) {
        self.n = n;
        self.pattern_nnz = col_ptr.get(n).copied().unwrap_or(0);
        self.factored = false;
        (self.col_order, self.preferred_row) = ordering(n, col_ptr, row_idx);
        let mut orders: Vec<Vec<usize>> =
            matched_amd_order(n, col_ptr, row_idx, &self.preferred_row)
                .into_iter()
                .collect();
        // COLAMD breaks ties by position: on extended Jacobians its fill varies by a
        // factor of two with the order the columns come in. Shuffled inputs give it
        // other chances (deterministic seeds).
        for seed in 1..=SHUFFLED_COLAMD_TRIALS as u64 {
            orders.push(shuffled_column_order(n, col_ptr, row_idx, seed));
        }
        orders.retain(|o| *o != self.col_order);
        orders.dedup();
        self.alternative_orders = orders;
    }

    /// Factorizes the `n x n` CSC matrix (pattern as given to [`reset`](Self::reset)),
    /// replaying the previous pivots when possible.
    pub(crate) fn factorize(
        &mut self,
        col_ptr: &[usize],
        row_idx: &[usize],
        values: &[f64],
    ) -> Result<(), LuError> {
        self.factorize_with(col_ptr, row_idx, |p| values[p])
    }

    /// [`factorize`](Self::factorize) with entry `p` (CSC order) given by `value(p)`
    /// (read in place, with no copy into a value array).
    pub(crate) fn factorize_with(
        &mut self,
        col_ptr: &[usize],
        row_idx: &[usize],
        value: impl Fn(usize) -> f64 + Copy,
    ) -> Result<(), LuError> {
        let nnz = col_ptr.get(self.n).copied().unwrap_or(0);
        if let Some(k) = (0..nnz).position(|p| !value(p).is_finite()) {
            self.factored = false;
            return Err(LuError::Singular(format!("matrix entry {k} is not finite")));
        }
        if self.factored && self.refactor(col_ptr, row_idx, value) {
            self.refactorizations += 1;
            return Ok(());
        }
        self.pivoting_factorizations += 1;
        let r = self.factor_with_pivoting(col_ptr, row_idx, value);
        self.factored = r.is_ok();
        if r.is_ok() && !self.alternative_orders.is_empty() {
            // First factorization of this pattern: try the other orders too and keep
            // the one whose factorization and expected solves cost the fewest
            // multiply-adds.
            let orders = std::mem::take(&mut self.alternative_orders);
            let mut best = self.clone();
            for order in orders {
                self.col_order = order;
                let ok = self.factor_with_pivoting(col_ptr, row_idx, value).is_ok();
                log::debug!(
                    "sparse LU order (n = {}): {} factor entries and {} refactor multiply-adds against {} and {}",
                    self.n,
                    self.factor_nnz(),
                    self.refactor_flops(),
                    best.factor_nnz(),
                    best.refactor_flops()
                );
                if ok && self.factorization_cost() < best.factorization_cost() {
                    best = self.clone();
                }
            }
            *self = best;
            self.factored = true;
        }
        r
    }

    /// Left-looking LU with threshold partial pivoting; records the patterns.
    fn factor_with_pivoting(
        &mut self,
        col_ptr: &[usize],
        row_idx: &[usize],
        value: impl Fn(usize) -> f64,
    ) -> Result<(), LuError> {
        let n = self.n;
        assert!(
            u32::try_from(n).is_ok(),
            "sparse LU of order {n}: rows and steps are stored in 32 bits"
        );
        self.pivot_row.clear();
        self.pivot_row.resize(n, usize::MAX);
        self.row_step.clear();
        self.row_step.resize(n, usize::MAX);
        self.l_ptr.clear();
        self.l_row.clear();
        self.l_val.clear();
        self.u_ptr.clear();
        self.u_step.clear();
        self.u_row.clear();
        self.u_val.clear();
        self.u_inv_diag.clear();
        self.u_inv_diag.resize(n, 0.0);
        self.work.clear();
        self.work.resize(n, 0.0);
        self.mark.clear();
        self.mark.resize(n, usize::MAX);
        self.l_ptr.push(0);
        self.u_ptr.push(0);
        for k in 0..n {
            let col = self.col_order[k];
            let entries = col_ptr[col]..col_ptr[col + 1];
            // Pattern of x = L \ A[:, col]: rows reachable through pivotal rows, in
            // topological order (reverse post-order of the depth-first search).
            self.reach.clear();
            for &r in &row_idx[entries.clone()] {
                if self.mark[r] != k {
                    self.dfs(r, k);
                }
            }
            for p in entries {
                self.work[row_idx[p]] = value(p);
            }
            // Eliminate with the earlier steps, in topological order.
            for idx in (0..self.reach.len()).rev() {
                let r = self.reach[idx];
                let s = self.row_step[r];
                if s == usize::MAX {
                    continue;
                }
                let x = self.work[r];
                self.u_step.push(s as u32);
                self.u_row.push(r as u32);
                self.u_val.push(x);
                if x != 0.0 {
                    for q in self.l_ptr[s]..self.l_ptr[s + 1] {
                        self.work[self.l_row[q] as usize] -= self.l_val[q] * x;
                    }
                }
            }
            // Pivot among the rows that are not pivotal yet.
            let mut best = usize::MAX;
            let mut best_abs = -1.0f64;
            let mut diag_abs = -1.0f64;
            for &r in &self.reach {
                if self.row_step[r] == usize::MAX {
                    let a = self.work[r].abs();
                    if a > best_abs {
                        best_abs = a;
                        best = r;
                    }
                    if r == self.preferred_row[col] {
                        diag_abs = a;
                    }
                }
            }
            if best == usize::MAX || best_abs == 0.0 || !best_abs.is_finite() {
                for &r in &self.reach {
                    self.work[r] = 0.0;
                }
                return Err(LuError::Singular(format!(
                    "no usable pivot in column {col} (step {k} of {n})"
                )));
            }
            if diag_abs >= DIAGONAL_PREFERENCE * best_abs && diag_abs > 0.0 {
                best = self.preferred_row[col];
            }
            let pivot = self.work[best];
            self.pivot_row[k] = best;
            self.row_step[best] = k;
            self.u_inv_diag[k] = 1.0 / pivot;
            for &r in &self.reach {
                if self.row_step[r] == usize::MAX {
                    self.l_row.push(r as u32);
                    self.l_val.push(self.work[r] / pivot);
                }
                self.work[r] = 0.0;
            }
            self.l_ptr.push(self.l_row.len());
            self.u_ptr.push(self.u_step.len());
        }
        let small = |v: usize| u32::try_from(v).expect("sparse LU larger than 2^32 entries");
        self.u_l_range.clear();
        self.u_l_range.extend(self.u_step.iter().map(|&s| {
            let s = s as usize;
            (small(self.l_ptr[s]), small(self.l_ptr[s + 1]))
        }));
        Ok(())
    }

    /// Depth-first search from row `r` through `L`'s columns, appending rows in
    /// post-order to `reach` (marks with `k`).
    fn dfs(&mut self, r: usize, k: usize) {
        self.stack.clear();
        self.mark[r] = k;
        self.stack.push((r, 0));
        while let Some(&mut (row, ref mut next)) = self.stack.last_mut() {
            let s = self.row_step[row];
            let mut pushed = None;
            if s != usize::MAX {
                let (start, end) = (self.l_ptr[s], self.l_ptr[s + 1]);
                while start + *next < end {
                    let child = self.l_row[start + *next] as usize;
                    *next += 1;
                    if self.mark[child] != k {
                        pushed = Some(child);
                        break;
                    }
                }
            }
            match pushed {
                Some(child) => {
                    self.mark[child] = k;
                    self.stack.push((child, 0));
                }
                None => {
                    self.stack.pop();
                    self.reach.push(row);
                }
            }
        }
    }

    /// Recomputes the factors with the recorded pivots and patterns; `false` if a pivot
    /// became too small (the factors are then invalid).
    fn refactor(
        &mut self,
        col_ptr: &[usize],
        row_idx: &[usize],
        value: impl Fn(usize) -> f64,
    ) -> bool {
        let n = self.n;
        // Local slices: the compiler keeps their pointers in registers.
        let SparseLu {
            col_order,
            pivot_row,
            l_ptr,
            l_val,
            u_ptr,
            u_val,
            u_inv_diag,
            work,
            u_row,
            u_l_range,
            l_row,
            ..
        } = self;
        let (col_order, pivot_row) = (&col_order[..n], &pivot_row[..n]);
        let (l_ptr, u_ptr, u_row, u_l, l_row) = (
            &l_ptr[..],
            &u_ptr[..],
            &u_row[..],
            &u_l_range[..],
            &l_row[..],
        );
        let (l_val, u_val, u_inv_diag, work) = (
            &mut l_val[..],
            &mut u_val[..],
            &mut u_inv_diag[..],
            &mut work[..],
        );
        let mut ok = true;
        for k in 0..n {
            let col = col_order[k];
            for p in col_ptr[col]..col_ptr[col + 1] {
                work[row_idx[p]] = value(p);
            }
            let (u0, u1) = (u_ptr[k], u_ptr[k + 1]);
            for ((&r, &(a, b)), u) in u_row[u0..u1]
                .iter()
                .zip(&u_l[u0..u1])
                .zip(&mut u_val[u0..u1])
            {
                let x = work[r as usize];
                work[r as usize] = 0.0;
                *u = x;
                let (a, b) = (a as usize, b as usize);
                for (&row, &l) in l_row[a..b].iter().zip(&l_val[a..b]) {
                    work[row as usize] -= l * x;
                }
            }
            let pr = pivot_row[k];
            let pivot = work[pr];
            work[pr] = 0.0;
            let inv = 1.0 / pivot;
            u_inv_diag[k] = inv;
            let (a, b) = (l_ptr[k], l_ptr[k + 1]);
            let mut below = 0.0f64;
            for (&row, l) in l_row[a..b].iter().zip(&mut l_val[a..b]) {
                let w = work[row as usize];
                // Entries are finite (checked on entry): a plain comparison.
                let m = w.abs();
                below = if m > below { m } else { below };
                *l = w * inv;
                work[row as usize] = 0.0;
            }
            // A replayed pivot must stay finite and not small next to the entries below.
            ok &=
                pivot.abs() >= REFACTOR_PIVOT_TOLERANCE * below && inv.is_finite() && pivot != 0.0;
        }
        if !ok {
            self.factored = false;
        }
        ok
    }

    /// Solves `A x = b` in place (`x` holds `b` on entry); `scratch` has length n.
    pub(crate) fn solve_in_place(&self, x: &mut [f64], scratch: &mut Vec<f64>) {
        let n = self.n;
        debug_assert!(self.factored && x.len() == n);
        let (pivot_row, l_ptr, l_row, l_val) = (
            &self.pivot_row[..n],
            &self.l_ptr[..],
            &self.l_row[..],
            &self.l_val[..],
        );
        // Forward: L z = P b, in original row indexing.
        for k in 0..n {
            let v = x[pivot_row[k]];
            if v != 0.0 {
                let (a, b) = (l_ptr[k], l_ptr[k + 1]);
                for (&row, &l) in l_row[a..b].iter().zip(&l_val[a..b]) {
                    x[row as usize] -= l * v;
                }
            }
        }
        scratch.clear();
        scratch.extend(pivot_row.iter().map(|&r| x[r]));
        let z = &mut scratch[..n];
        let (u_ptr, u_step, u_val, u_inv_diag) = (
            &self.u_ptr[..],
            &self.u_step[..],
            &self.u_val[..],
            &self.u_inv_diag[..n],
        );
        // Backward: U y = z, by steps (U stored by columns).
        for k in (0..n).rev() {
            let y = z[k] * u_inv_diag[k];
            z[k] = y;
            if y != 0.0 {
                let (a, b) = (u_ptr[k], u_ptr[k + 1]);
                for (&s, &u) in u_step[a..b].iter().zip(&u_val[a..b]) {
                    z[s as usize] -= u * y;
                }
            }
        }
        for (&c, &v) in self.col_order.iter().zip(z.iter()) {
            x[c] = v;
        }
    }

    /// Entries of `L` and `U` (diagonal included), for logs.
    pub(crate) fn factor_nnz(&self) -> usize {
        if self.factored {
            self.l_row.len() + self.u_step.len() + self.n
        } else {
            0
        }
    }

    /// Multiply-adds of one refactorization with the recorded patterns (0 before a
    /// factorization).
    pub(crate) fn refactor_flops(&self) -> usize {
        if !self.factored {
            return 0;
        }
        (0..self.n)
            .map(|k| {
                (self.u_ptr[k]..self.u_ptr[k + 1])
                    .map(|q| {
                        let s = self.u_step[q] as usize;
                        self.l_ptr[s + 1] - self.l_ptr[s]
                    })
                    .sum::<usize>()
                    + (self.l_ptr[k + 1] - self.l_ptr[k])
            })
            .sum()
    }

    /// What one factorization and its expected solves cost in multiply-adds (see
    /// [`solves_per_factorization`](Self::solves_per_factorization)).
    fn factorization_cost(&self) -> usize {
        self.refactor_flops() + self.solves_per_factorization * self.factor_nnz()
    }

    /// Order of the matrix.
    pub(crate) fn size(&self) -> usize {
        self.n
    }

    /// Entries of the matrix pattern (as given to [`reset`](Self::reset)).
    pub(crate) fn pattern_nnz(&self) -> usize {
        self.pattern_nnz
    }
}

/// Fill-reducing order: COLAMD (from faer) orders the columns; a maximum transversal
/// names the preferred pivot row of each column (its "diagonal"), kept when it is large
/// enough, so that pivots stay where the structure put them. (AMD on the symmetrized
/// pattern without the transversal filled ten times more on multibody Jacobians; with
/// it, see [`matched_amd_order`].)
fn ordering(n: usize, col_ptr: &[usize], row_idx: &[usize]) -> (Vec<usize>, Vec<usize>) {
    let mut g = BipartiteGraph::new(n);
    let mut rows: Vec<Vec<usize>> = vec![Vec::new(); n];
    for c in 0..n {
        for &r in &row_idx[col_ptr[c]..col_ptr[c + 1]] {
            rows[r].push(c);
        }
    }
    for r in rows {
        g.add_equation(r);
    }
    let m = maximum_matching(&g, None, None);
    let preferred: Vec<usize> = (0..n).map(|c| m.var_to_eq[c].unwrap_or(c)).collect();
    (column_order(n, col_ptr, row_idx), preferred)
}

/// AMD on `B + B^T`, where `B` is the pattern with each column's preferred row moved to
/// the diagonal (KLU's ordering after its transversal); `None` when the transversal is
/// not complete or faer cannot allocate.
fn matched_amd_order(
    n: usize,
    col_ptr: &[usize],
    row_idx: &[usize],
    preferred: &[usize],
) -> Option<Vec<usize>> {
    if n == 0 {
        return Some(Vec::new());
    }
    // Row r of A becomes row `col_of_row[r]` of B.
    let mut col_of_row = vec![usize::MAX; n];
    for (c, &r) in preferred.iter().enumerate() {
        if col_of_row[r] != usize::MAX {
            return None;
        }
        col_of_row[r] = c;
    }
    let mut b_ptr = Vec::with_capacity(n + 1);
    let mut b_idx = Vec::with_capacity(row_idx.len());
    b_ptr.push(0usize);
    for c in 0..n {
        let start = b_idx.len();
        b_idx.extend(
            row_idx[col_ptr[c]..col_ptr[c + 1]]
                .iter()
                .map(|&r| col_of_row[r]),
        );
        b_idx[start..].sort_unstable();
        b_ptr.push(b_idx.len());
    }
    let sym = SymbolicSparseColMatRef::new_checked(n, n, &b_ptr, None, &b_idx);
    let req = faer::sparse::linalg::amd::order_scratch::<usize>(n, b_idx.len());
    let mut mem = MemBuffer::try_new(req).ok()?;
    let stack = MemStack::new(&mut mem);
    let mut perm = vec![0usize; n];
    let mut perm_inv = vec![0usize; n];
    faer::sparse::linalg::amd::order(&mut perm, &mut perm_inv, sym, Default::default(), stack)
        .ok()?;
    Some(perm)
}

/// Number of COLAMD orders of shuffled columns tried at a pattern's first factorization
/// besides COLAMD's own and AMD's.
const SHUFFLED_COLAMD_TRIALS: usize = 6;

/// COLAMD's order for the pattern with its columns shuffled (a fixed permutation per
/// `seed`), mapped back to the original columns.
fn shuffled_column_order(n: usize, col_ptr: &[usize], row_idx: &[usize], seed: u64) -> Vec<usize> {
    let mut perm: Vec<usize> = (0..n).collect();
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    for i in (1..n).rev() {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let j = ((state >> 33) as usize) % (i + 1);
        perm.swap(i, j);
    }
    let mut s_ptr = Vec::with_capacity(n + 1);
    let mut s_idx = Vec::with_capacity(row_idx.len());
    s_ptr.push(0);
    for &c in &perm {
        s_idx.extend_from_slice(&row_idx[col_ptr[c]..col_ptr[c + 1]]);
        s_ptr.push(s_idx.len());
    }
    column_order(n, &s_ptr, &s_idx)
        .into_iter()
        .map(|k| perm[k])
        .collect()
}

/// COLAMD column order of the pattern (identity if faer cannot allocate its scratch).
fn column_order(n: usize, col_ptr: &[usize], row_idx: &[usize]) -> Vec<usize> {
    let identity = || (0..n).collect::<Vec<_>>();
    if n == 0 {
        return Vec::new();
    }
    let sym = SymbolicSparseColMatRef::new_checked(n, n, col_ptr, None, row_idx);
    let req = colamd::order_scratch::<usize>(n, n, row_idx.len());
    let Ok(mut mem) = MemBuffer::try_new(req) else {
        return identity();
    };
    let stack = MemStack::new(&mut mem);
    let mut perm = vec![0usize; n];
    let mut perm_inv = vec![0usize; n];
    match colamd::order(&mut perm, &mut perm_inv, sym, Default::default(), stack) {
        Ok(()) => perm,
        Err(_) => identity(),
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;

    /// Dense matrix to CSC.
    fn csc(a: &[Vec<f64>]) -> (Vec<usize>, Vec<usize>, Vec<f64>) {
        let n = a.len();
        let (mut cp, mut ri, mut v) = (vec![0], Vec::new(), Vec::new());
        for j in 0..n {
            for i in 0..n {
                if a[i][j] != 0.0 {
                    ri.push(i);
                    v.push(a[i][j]);
                }
            }
            cp.push(ri.len());
        }
        (cp, ri, v)
    }

    fn lcg(state: &mut u64) -> f64 {
        *state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    fn residual(a: &[Vec<f64>], x: &[f64], b: &[f64]) -> f64 {
        let n = a.len();
        (0..n)
            .map(|i| ((0..n).map(|j| a[i][j] * x[j]).sum::<f64>() - b[i]).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn random_sparse_systems_refactor_and_repivot() {
        let mut s = 11u64;
        for n in [1usize, 2, 7, 40, 150] {
            // Random pattern with a full diagonal of possibly tiny values.
            let mut a = vec![vec![0.0; n]; n];
            for i in 0..n {
                a[i][i] = 1.0 + lcg(&mut s);
                for _ in 0..3 {
                    let j = (lcg(&mut s) * n as f64) as usize % n;
                    a[i][j] = lcg(&mut s) - 0.5;
                }
            }
            let (cp, ri, v) = csc(&a);
            let mut lu = SparseLu::default();
            lu.reset(n, &cp, &ri);
            lu.factorize(&cp, &ri, &v).unwrap();
            let b: Vec<f64> = (0..n).map(|i| (i % 7) as f64 - 3.0).collect();
            let mut x = b.clone();
            let mut scratch = Vec::new();
            lu.solve_in_place(&mut x, &mut scratch);
            assert!(residual(&a, &x, &b) < 1e-10, "n = {n}");
            // Slightly changed values: replayed pivots.
            let v2: Vec<f64> = v.iter().map(|x| x * 1.01).collect();
            lu.factorize(&cp, &ri, &v2).unwrap();
            assert_eq!(lu.pivoting_factorizations, 1);
            assert_eq!(lu.refactorizations, 1);
            let mut x = b.clone();
            lu.solve_in_place(&mut x, &mut scratch);
            let a2: Vec<Vec<f64>> = a
                .iter()
                .map(|r| r.iter().map(|x| x * 1.01).collect())
                .collect();
            assert!(residual(&a2, &x, &b) < 1e-10, "n = {n} refactored");
        }
    }

    /// The first factorization tries COLAMD and the transversal's AMD order and keeps
    /// the one with fewer refactorization multiply-adds: never more than either alone.
    /// An arrow matrix permuted at random (a dense last row and column) is the case
    /// where the order matters most.
    #[test]
    fn the_cheaper_of_two_orders_is_kept() {
        let mut s = 5u64;
        for n in [10usize, 60, 200] {
            let mut a = vec![vec![0.0; n]; n];
            let mut perm: Vec<usize> = (0..n).collect();
            for i in (1..n).rev() {
                let j = (lcg(&mut s) * (i + 1) as f64) as usize % (i + 1);
                perm.swap(i, j);
            }
            for i in 0..n {
                a[perm[i]][i] = 4.0 + lcg(&mut s);
                a[perm[n - 1]][i] = 0.5 + lcg(&mut s) * 0.1;
                a[perm[i]][n - 1] = 0.5 + lcg(&mut s) * 0.1;
                if i + 1 < n {
                    a[perm[i]][i + 1] = lcg(&mut s) - 0.5;
                }
            }
            let (cp, ri, v) = csc(&a);
            let flops_with = |order: Vec<usize>| {
                let mut lu = SparseLu::default();
                lu.reset(n, &cp, &ri);
                lu.alternative_orders.clear();
                lu.col_order = order;
                lu.factorize(&cp, &ri, &v).unwrap();
                lu.refactor_flops()
            };
            let colamd = flops_with(column_order(n, &cp, &ri));
            let mut lu = SparseLu::default();
            lu.reset(n, &cp, &ri);
            let amd = matched_amd_order(n, &cp, &ri, &lu.preferred_row).map(flops_with);
            lu.factorize(&cp, &ri, &v).unwrap();
            let kept = lu.refactor_flops();
            assert!(kept <= colamd, "n = {n}: {kept} > COLAMD {colamd}");
            if let Some(amd) = amd {
                assert!(kept <= amd, "n = {n}: {kept} > AMD {amd}");
            }
            assert!(lu.alternative_orders.is_empty());
            let b: Vec<f64> = (0..n).map(|i| (i % 5) as f64 - 2.0).collect();
            let mut x = b.clone();
            lu.solve_in_place(&mut x, &mut Vec::new());
            assert!(residual(&a, &x, &b) < 1e-10, "n = {n}");
        }
    }

    #[test]
    fn a_vanishing_pivot_makes_it_pivot_again() {
        // [[e, 1], [1, 1]]: with e = 2 the diagonal pivots; with e = 0 the replayed
        // pivot vanishes and rows must swap.
        let (cp, ri) = (vec![0, 2, 4], vec![0, 1, 0, 1]);
        let mut lu = SparseLu::default();
        lu.reset(2, &cp, &ri);
        lu.factorize(&cp, &ri, &[2.0, 1.0, 1.0, 1.0]).unwrap();
        lu.factorize(&cp, &ri, &[0.0, 1.0, 1.0, 1.0]).unwrap();
        assert_eq!(lu.pivoting_factorizations, 2);
        let mut x = vec![1.0, 2.0];
        lu.solve_in_place(&mut x, &mut Vec::new());
        // 0 x0 + x1 = 1, x0 + x1 = 2.
        assert!(
            (x[0] - 1.0).abs() < 1e-14 && (x[1] - 1.0).abs() < 1e-14,
            "{x:?}"
        );
    }

    #[test]
    fn singular_and_non_finite_are_reported() {
        let (cp, ri) = (vec![0, 2, 4], vec![0, 1, 0, 1]);
        let mut lu = SparseLu::default();
        lu.reset(2, &cp, &ri);
        assert!(lu.factorize(&cp, &ri, &[1.0, 2.0, 2.0, 4.0]).is_err());
        assert!(lu.factorize(&cp, &ri, &[1.0, f64::NAN, 2.0, 4.0]).is_err());
        lu.factorize(&cp, &ri, &[1.0, 2.0, 2.0, 5.0]).unwrap();
        // Structurally singular: an empty column.
        let (cp2, ri2) = (vec![0, 1, 1], vec![0]);
        lu.reset(2, &cp2, &ri2);
        assert!(lu.factorize(&cp2, &ri2, &[1.0]).is_err());
    }
}
