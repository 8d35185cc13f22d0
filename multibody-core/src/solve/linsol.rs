//! A sparse LU factorization ([`SparseLu`]: COLAMD order from faer, pivots replayed
//! across refactorizations) wrapped as a SUNDIALS `SUNLinearSolver`.
//!
//! The numerical part ([`IterationLu`]) is safe Rust. The FFI glue at the bottom
//! builds a custom direct linear solver with `SUNLinSolNewEmpty` whose
//! `setup` factorizes the CSC `SUNSparseMatrix` that IDA's Jacobian callback
//! filled, and whose `solve` applies the factorization. The column order and
//! pivot sequence are computed once and reused as long as the sparsity pattern
//! is unchanged and the pivots stay large enough.

use std::ffi::{c_int, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};

use sundials_sys as sys;

use crate::sparse_lu::{LuError, SparseLu};

/// Return code for a recoverable failure (singular or non-finite matrix).
/// Any positive value makes IDA retry with a smaller step.
const RECOVERABLE_FAILURE: c_int = sys::SUNLS_LUFACT_FAIL as c_int;
/// Return code for an unrecoverable failure (internal error, panic).
const FATAL_FAILURE: c_int = -1;

/// Why a factorization or solve did not succeed.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum LuFailure {
    /// Singular or non-finite: IDA may recover by reducing the step size.
    Recoverable(String),
    /// Inconsistent input (bad pattern, missing factorization).
    Fatal(String),
}

/// Newton iterations expected per factorization of IDA's iteration matrix, for the
/// choice of the column order (see `SparseLu::solves_per_factorization`).
const SOLVES_PER_FACTORIZATION: usize = 20;

/// Sparse LU state: the pattern of the last factorized matrix, its symbolic
/// analysis and the numeric factorization.
#[derive(Default)]
pub(crate) struct IterationLu {
    n: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Whether `lu` was set up for the stored pattern.
    analysed: bool,
    lu: SparseLu,
    /// Whether `lu` holds a valid factorization.
    factored: bool,
    scratch: Vec<f64>,
    /// Right-hand side padded to the matrix size (extended Jacobians).
    padded: Vec<f64>,
    /// Number of symbolic analyses performed (for tests and logging).
    pub(crate) symbolic_analyses: usize,
    /// Message of the last failure, if any.
    pub(crate) last_failure: Option<String>,
}

impl IterationLu {
    /// Factorizes the `n x n` CSC matrix given by SUNDIALS' (signed) index
    /// arrays and values. Reuses the symbolic analysis if the pattern equals
    /// the previous one.
    pub(crate) fn factorize(
        &mut self,
        n: usize,
        col_ptr: &[i64],
        row_idx: &[i64],
        values: &[f64],
    ) -> Result<(), LuFailure> {
        self.factored = false;
        if col_ptr.len() != n + 1 || row_idx.len() != values.len() {
            return Err(LuFailure::Fatal(format!(
                "sparse matrix arrays have inconsistent lengths (n = {n}, col_ptr {}, row_idx {}, values {})",
                col_ptr.len(),
                row_idx.len(),
                values.len()
            )));
        }
        let same_pattern = self.analysed
            && self.n == n
            && self.col_ptr.len() == col_ptr.len()
            && self.row_idx.len() == row_idx.len()
            && self
                .col_ptr
                .iter()
                .zip(col_ptr)
                .all(|(&a, &b)| a as i64 == b)
            && self
                .row_idx
                .iter()
                .zip(row_idx)
                .all(|(&a, &b)| a as i64 == b);
        if !same_pattern {
            self.analysed = false;
            self.n = n;
            self.col_ptr.clear();
            self.row_idx.clear();
            for &c in col_ptr {
                self.col_ptr.push(
                    usize::try_from(c)
                        .map_err(|_| LuFailure::Fatal(format!("negative column pointer {c}")))?,
                );
            }
            for &r in row_idx {
                let r = usize::try_from(r)
                    .ok()
                    .filter(|&r| r < n)
                    .ok_or_else(|| LuFailure::Fatal(format!("row index {r} out of range")))?;
                self.row_idx.push(r);
            }
            if !valid_csc(n, &self.col_ptr, &self.row_idx) {
                self.col_ptr.clear();
                self.row_idx.clear();
                return Err(LuFailure::Fatal(
                    "sparse pattern is not a valid CSC pattern with sorted rows".into(),
                ));
            }
            self.lu.reset(n, &self.col_ptr, &self.row_idx);
            // IDA solves with one iteration matrix for many Newton iterations (about
            // 80 per factorization on the 100-link pendulum; 20 is a conservative
            // weight: 20 and 80 picked the same orders there).
            self.lu.solves_per_factorization = SOLVES_PER_FACTORIZATION;
            self.analysed = true;
            self.symbolic_analyses += 1;
            log::debug!(
                "sparse LU: column order #{} (n = {n}, nnz = {})",
                self.symbolic_analyses,
                self.row_idx.len()
            );
        }
        match self.lu.factorize(&self.col_ptr, &self.row_idx, values) {
            Ok(()) => {
                if self.lu.pivoting_factorizations + self.lu.refactorizations == 1 {
                    log::debug!(
                        "sparse LU: n = {n}, {} entries, {} in the factors",
                        self.row_idx.len(),
                        self.lu.factor_nnz()
                    );
                }
                self.factored = true;
                Ok(())
            }
            Err(LuError::Singular(m)) => Err(LuFailure::Recoverable(format!(
                "sparse LU: iteration matrix is singular ({m})"
            ))),
        }
    }

    /// Solves `A x = b` in place (`x` holds `b` on entry).
    pub(crate) fn solve_in_place(&mut self, x: &mut [f64]) -> Result<(), LuFailure> {
        if !self.factored {
            return Err(LuFailure::Fatal(
                "solve called without a factorization".into(),
            ));
        }
        if x.len() != self.n {
            return Err(LuFailure::Fatal(format!(
                "right-hand side has length {} instead of {}",
                x.len(),
                self.n
            )));
        }
        self.lu.solve_in_place(x, &mut self.scratch);
        if x.iter().any(|v| !v.is_finite()) {
            return Err(LuFailure::Recoverable(
                "sparse LU solve produced non-finite values".into(),
            ));
        }
        Ok(())
    }
}

/// Checks CSC invariants: monotone column pointers starting at 0 and ending at
/// `row_idx.len()`, rows strictly increasing within each column.
pub(crate) fn valid_csc(n: usize, col_ptr: &[usize], row_idx: &[usize]) -> bool {
    if col_ptr.len() != n + 1 || col_ptr[0] != 0 || col_ptr[n] != row_idx.len() {
        return false;
    }
    for j in 0..n {
        if col_ptr[j] > col_ptr[j + 1] {
            return false;
        }
        let rows = &row_idx[col_ptr[j]..col_ptr[j + 1]];
        if rows.iter().any(|&r| r >= n) || rows.windows(2).any(|w| w[0] >= w[1]) {
            return false;
        }
    }
    true
}

// ---------------------------------------------------------------------------
// FFI glue: the SUNLinearSolver operations.
// ---------------------------------------------------------------------------

/// Creates a SUNDIALS linear solver backed by [`IterationLu`]. Returns null on
/// allocation failure. The solver owns its content and frees it in its
/// `free` operation (called by `SUNLinSolFree`).
pub(crate) fn new_sparse_lu_solver(ctx: sys::SUNContext) -> sys::SUNLinearSolver {
    // SAFETY: `ctx` is a valid context owned by the caller; the returned
    // solver has freshly allocated, zeroed ops which we fill in.
    unsafe {
        let ls = sys::SUNLinSolNewEmpty(ctx);
        if ls.is_null() {
            return ls;
        }
        let content = Box::into_raw(Box::<IterationLu>::default());
        (*ls).content = content.cast::<c_void>();
        let ops = (*ls).ops;
        (*ops).gettype = Some(ls_gettype);
        (*ops).getid = Some(ls_getid);
        (*ops).setup = Some(ls_setup);
        (*ops).solve = Some(ls_solve);
        (*ops).free = Some(ls_free);
        ls
    }
}

/// Borrows the [`IterationLu`] content of a solver created by
/// [`new_sparse_lu_solver`].
///
/// # Safety
/// `ls` must be such a solver, not yet freed, and no other reference to its
/// content may be live.
unsafe fn content<'a>(ls: sys::SUNLinearSolver) -> Option<&'a mut IterationLu> {
    // SAFETY: guaranteed by the caller.
    unsafe {
        if ls.is_null() || (*ls).content.is_null() {
            None
        } else {
            Some(&mut *((*ls).content.cast::<IterationLu>()))
        }
    }
}

unsafe extern "C" fn ls_gettype(_ls: sys::SUNLinearSolver) -> sys::SUNLinearSolver_Type {
    sys::SUNLinearSolver_Type_SUNLINEARSOLVER_DIRECT
}

unsafe extern "C" fn ls_getid(_ls: sys::SUNLinearSolver) -> sys::SUNLinearSolver_ID {
    sys::SUNLinearSolver_ID_SUNLINEARSOLVER_CUSTOM
}

fn failure_code(lu: &mut IterationLu, r: Result<(), LuFailure>) -> c_int {
    match r {
        Ok(()) => {
            lu.last_failure = None;
            0
        }
        Err(LuFailure::Recoverable(m)) => {
            log::debug!("sparse LU (recoverable): {m}");
            lu.last_failure = Some(m);
            RECOVERABLE_FAILURE
        }
        Err(LuFailure::Fatal(m)) => {
            log::warn!("sparse LU: {m}");
            lu.last_failure = Some(m);
            FATAL_FAILURE
        }
    }
}

unsafe extern "C" fn ls_setup(ls: sys::SUNLinearSolver, a: sys::SUNMatrix) -> c_int {
    catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: IDA passes the solver it owns and the CSC SUNSparseMatrix
        // attached to it; index arrays have n + 1 and nnz entries.
        unsafe {
            let Some(lu) = content(ls) else {
                return FATAL_FAILURE;
            };
            if a.is_null() {
                return failure_code(lu, Err(LuFailure::Fatal("no matrix".into())));
            }
            let n = usize::try_from(sys::SUNSparseMatrix_Columns(a)).unwrap_or(0);
            let ptrs = sys::SUNSparseMatrix_IndexPointers(a);
            let vals = sys::SUNSparseMatrix_IndexValues(a);
            let data = sys::SUNSparseMatrix_Data(a);
            let cap = usize::try_from(sys::SUNSparseMatrix_NNZ(a)).unwrap_or(0);
            if ptrs.is_null() || vals.is_null() || data.is_null() {
                return failure_code(lu, Err(LuFailure::Fatal("matrix has no data".into())));
            }
            let col_ptr = std::slice::from_raw_parts(ptrs, n + 1);
            let nnz = usize::try_from(col_ptr[n]).unwrap_or(usize::MAX);
            if nnz > cap {
                return failure_code(
                    lu,
                    Err(LuFailure::Fatal(format!(
                        "nnz {nnz} exceeds capacity {cap}"
                    ))),
                );
            }
            let row_idx = std::slice::from_raw_parts(vals, nnz);
            let values = std::slice::from_raw_parts(data, nnz);
            let r = lu.factorize(n, col_ptr, row_idx, values);
            failure_code(lu, r)
        }
    }))
    .unwrap_or(FATAL_FAILURE)
}

unsafe extern "C" fn ls_solve(
    ls: sys::SUNLinearSolver,
    _a: sys::SUNMatrix,
    x: sys::N_Vector,
    b: sys::N_Vector,
    _tol: sys::sunrealtype,
) -> c_int {
    catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: x and b are serial vectors of length n (possibly the same
        // vector); we copy with `ptr::copy`, which allows overlap.
        unsafe {
            let Some(lu) = content(ls) else {
                return FATAL_FAILURE;
            };
            let n = usize::try_from(sys::N_VGetLength(x)).unwrap_or(0);
            let xp = sys::N_VGetArrayPointer(x);
            let bp = sys::N_VGetArrayPointer(b);
            if xp.is_null() || bp.is_null() {
                return failure_code(lu, Err(LuFailure::Fatal("vector has no data".into())));
            }
            if n > lu.n {
                return failure_code(
                    lu,
                    Err(LuFailure::Fatal(format!(
                        "vector of length {n} for a matrix of size {}",
                        lu.n
                    ))),
                );
            }
            if xp != bp {
                std::ptr::copy(bp, xp, n);
            }
            let xs = std::slice::from_raw_parts_mut(xp, n);
            let r = if n == lu.n {
                lu.solve_in_place(xs)
            } else {
                // Extended Jacobian: the bordering rows have zero right-hand sides.
                let mut padded = std::mem::take(&mut lu.padded);
                padded.clear();
                padded.extend_from_slice(xs);
                padded.resize(lu.n, 0.0);
                let r = lu.solve_in_place(&mut padded);
                xs.copy_from_slice(&padded[..n]);
                lu.padded = padded;
                r
            };
            failure_code(lu, r)
        }
    }))
    .unwrap_or(FATAL_FAILURE)
}

unsafe extern "C" fn ls_free(ls: sys::SUNLinearSolver) -> sys::SUNErrCode {
    if ls.is_null() {
        return 0;
    }
    // SAFETY: the content was created by `Box::into_raw` in
    // `new_sparse_lu_solver` and is freed exactly once here.
    unsafe {
        let content = (*ls).content;
        (*ls).content = std::ptr::null_mut();
        if !content.is_null() {
            let boxed = Box::from_raw(content.cast::<IterationLu>());
            // Dropping the factors does not panic in practice; never unwind into C.
            let _ = catch_unwind(AssertUnwindSafe(move || drop(boxed)));
        }
        sys::SUNLinSolFreeEmpty(ls);
    }
    0
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;

    fn to_i64(v: &[usize]) -> Vec<i64> {
        v.iter().map(|&x| x as i64).collect()
    }

    #[test]
    fn solve_small_sparse_system_and_reuse_symbolic() {
        // [[4, 1, 0], [1, 3, 0], [0, 2, 5]] in CSC.
        let col_ptr = [0usize, 2, 5, 6];
        let row_idx = [0usize, 1, 0, 1, 2, 2];
        let (cp, ri) = (to_i64(&col_ptr), to_i64(&row_idx));
        let mut lu = IterationLu::default();
        let vals = [4.0, 1.0, 1.0, 3.0, 2.0, 5.0];
        lu.factorize(3, &cp, &ri, &vals).unwrap();
        let a = [[4.0, 1.0, 0.0], [1.0, 3.0, 0.0], [0.0, 2.0, 5.0]];
        let x_true = [1.0, -2.0, 0.5];
        let mut b: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|j| a[i][j] * x_true[j]).sum())
            .collect();
        lu.solve_in_place(&mut b).unwrap();
        for i in 0..3 {
            assert!((b[i] - x_true[i]).abs() < 1e-12, "{b:?}");
        }
        lu.factorize(3, &cp, &ri, &[8.0, 2.0, 2.0, 6.0, 4.0, 10.0])
            .unwrap();
        assert_eq!(lu.symbolic_analyses, 1);
    }

    #[test]
    fn singular_and_nonfinite_are_recoverable() {
        let cp = [0i64, 1, 2];
        let ri = [0i64, 1];
        let mut lu = IterationLu::default();
        assert!(matches!(
            lu.factorize(2, &cp, &ri, &[1.0, 0.0]),
            Err(LuFailure::Recoverable(_))
        ));
        assert!(matches!(
            lu.factorize(2, &cp, &ri, &[1.0, f64::NAN]),
            Err(LuFailure::Recoverable(_))
        ));
        lu.factorize(2, &cp, &ri, &[1.0, 2.0]).unwrap();
        // structurally singular (empty column)
        let cp2 = [0i64, 1, 1];
        let ri2 = [0i64];
        assert!(lu.factorize(2, &cp2, &ri2, &[1.0]).is_err());
    }

    #[test]
    fn invalid_pattern_is_fatal() {
        let mut lu = IterationLu::default();
        let cp = [0i64, 2, 2];
        let ri = [1i64, 0];
        assert!(matches!(
            lu.factorize(2, &cp, &ri, &[1.0, 1.0]),
            Err(LuFailure::Fatal(_))
        ));
    }
}
