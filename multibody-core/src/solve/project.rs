//! Consistent outputs: the algebraic unknowns of each reported point solved again from
//! the constraints, with the states and derivatives as reported.
//!
//! IDA stops its Newton iteration when the correction is small against the error
//! weights, and between steps it interpolates; either way a loop-closure equation holds
//! only to about the tolerance times the coordinates. The reported points are what
//! users plot and check, so their algebraic unknowns are polished by a few Newton steps
//! on the purely algebraic residual rows (those without derivatives), which leaves the
//! integration itself untouched.

use nalgebra::{DMatrix, DVector};

use super::ida::DaeFunctions;

/// Newton steps per point.
const MAX_ITERATIONS: usize = 4;

/// Largest number of algebraic unknowns projected (a dense solve per point).
const MAX_ALGEBRAIC: usize = 64;

/// The square system of algebraic rows and unknowns, when there is one.
pub(crate) struct Projection {
    rows: Vec<usize>,
    /// For each residual row, its position in `rows`.
    row_of: Vec<Option<usize>>,
    cols: Vec<usize>,
    /// CSC pattern of the Jacobian.
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    values: Vec<f64>,
    residual: Vec<f64>,
}

impl Projection {
    /// Finds the rows of `f` free of derivatives and the unknowns with mass 0; `None`
    /// when there are none, more than [`MAX_ALGEBRAIC`], or not as many of each.
    pub(crate) fn new(
        f: &mut dyn DaeFunctions,
        mass: &[f64],
        t: f64,
        u: &[f64],
        up: &[f64],
    ) -> Option<Projection> {
        let n = f.len();
        let (col_ptr, row_idx) = f.jacobian_pattern()?;
        if col_ptr.len() != n + 1 {
            return None;
        }
        let cols: Vec<usize> = (0..n).filter(|&i| mass[i] == 0.0).collect();
        if cols.is_empty() || cols.len() > MAX_ALGEBRAIC {
            return None;
        }
        // Rows that depend on a derivative: the Jacobian changes with cj.
        let mut v0 = vec![0.0; row_idx.len()];
        let mut v1 = vec![0.0; row_idx.len()];
        f.jacobian(t, u, up, 0.0, &mut v0).ok()?;
        f.jacobian(t, u, up, 1.0, &mut v1).ok()?;
        let mut dynamic = vec![false; n];
        for k in 0..row_idx.len() {
            if v0[k] != v1[k] {
                dynamic[row_idx[k]] = true;
            }
        }
        let rows: Vec<usize> = (0..n).filter(|&r| !dynamic[r]).collect();
        let mut row_of = vec![None; n];
        for (k, &r) in rows.iter().enumerate() {
            row_of[r] = Some(k);
        }
        (rows.len() == cols.len()).then(|| Projection {
            rows,
            row_of,
            cols,
            values: vec![0.0; row_idx.len()],
            col_ptr,
            row_idx,
            residual: vec![0.0; n],
        })
    }

    /// Polishes the algebraic unknowns of `u` at `t`; keeps them when Newton does not
    /// reduce the residual.
    pub(crate) fn apply(&mut self, f: &mut dyn DaeFunctions, t: f64, u: &mut [f64], up: &[f64]) {
        let m = self.rows.len();
        let norm = |p: &Projection| -> f64 {
            p.rows
                .iter()
                .map(|&r| p.residual[r].abs())
                .fold(0.0, f64::max)
        };
        if f.residual(t, u, up, &mut self.residual).is_err() {
            return;
        }
        let mut best = norm(self);
        for _ in 0..MAX_ITERATIONS {
            if best < 1e-14 {
                return;
            }
            if f.jacobian(t, u, up, 0.0, &mut self.values).is_err() {
                return;
            }
            let mut j = DMatrix::<f64>::zeros(m, m);
            for (jc, &c) in self.cols.iter().enumerate() {
                for k in self.col_ptr[c]..self.col_ptr[c + 1] {
                    if let Some(i) = self.row_of[self.row_idx[k]] {
                        j[(i, jc)] = self.values[k];
                    }
                }
            }
            let b = DVector::from_iterator(m, self.rows.iter().map(|&r| -self.residual[r]));
            let Some(dx) = j.lu().solve(&b) else {
                return;
            };
            let old: Vec<f64> = self.cols.iter().map(|&c| u[c]).collect();
            for (jc, &c) in self.cols.iter().enumerate() {
                u[c] += dx[jc];
            }
            let ok = f.residual(t, u, up, &mut self.residual).is_ok();
            let now = if ok { norm(self) } else { f64::INFINITY };
            if !now.is_finite() || now >= best {
                for (jc, &c) in self.cols.iter().enumerate() {
                    u[c] = old[jc];
                }
                let _ = f.residual(t, u, up, &mut self.residual);
                return;
            }
            best = now;
        }
    }
}
