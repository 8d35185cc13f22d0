//! Structural dependencies of tape outputs on inputs, and the sparse DAE Jacobian by
//! column colouring and compressed forward mode.

use super::EvalError;
use super::tape::{Op, Tape, Workspace};

/// Merges two sorted, duplicate-free vectors into `out` (cleared first), for callers
/// that reuse it.
pub(crate) fn merge_into(a: &[u32], b: &[u32], out: &mut Vec<u32>) {
    out.clear();
    if a.is_empty() || a == b {
        out.extend_from_slice(b);
        return;
    }
    if b.is_empty() {
        out.extend_from_slice(a);
        return;
    }
    out.reserve(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].cmp(&b[j]) {
            std::cmp::Ordering::Less => {
                out.push(a[i]);
                i += 1;
            }
            std::cmp::Ordering::Greater => {
                out.push(b[j]);
                j += 1;
            }
            std::cmp::Ordering::Equal => {
                out.push(a[i]);
                i += 1;
                j += 1;
            }
        }
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
}

impl Tape {
    /// For each output, the sorted input slots it structurally depends on (through any
    /// operand, conditions and comparisons included). Linear in the tape length times
    /// the size of the dependency sets; sets are freed after their last use.
    pub fn dependencies(&self) -> Vec<Vec<usize>> {
        self.dependency_sets(self.outputs.len(), Some, usize::MAX)
            .into_iter()
            .map(|set| set.into_iter().map(|s| s as usize).collect())
            .collect()
    }

    /// Whether some output among the first `n` depends on at least `k` distinct columns
    /// of the DAE Jacobian (`u_j` at input slot `u_offset + j` and `u'_j` at
    /// `yp_offset + j` are column `j`). The sets are cut at `k` columns, so this costs
    /// the tape length times `k` where [`dependencies`](Tape::dependencies) can cost
    /// its square (a chain's acceleration block depends on every coordinate).
    pub fn column_degree_reaches(
        &self,
        n: usize,
        u_offset: usize,
        yp_offset: usize,
        k: usize,
    ) -> bool {
        if k == 0 {
            return true;
        }
        let column = |s: u32| -> Option<u32> {
            let s = s as usize;
            if s >= u_offset && s < u_offset + n {
                Some((s - u_offset) as u32)
            } else if s >= yp_offset && s < yp_offset + n {
                Some((s - yp_offset) as u32)
            } else {
                None
            }
        };
        self.dependency_sets(n, column, k)
            .iter()
            .any(|set| set.len() >= k)
    }

    /// The sorted dependency sets of the first `n_outputs` outputs: input slot `s`
    /// counts as `map(s)` (left out when `None`), and every set is cut to its `cap`
    /// smallest members. Sets are freed after their last use.
    fn dependency_sets(
        &self,
        n_outputs: usize,
        map: impl Fn(u32) -> Option<u32>,
        cap: usize,
    ) -> Vec<Vec<u32>> {
        let len = self.ops.len();
        const KEEP: u32 = u32::MAX;
        let mut last_use = vec![0u32; len];
        for (i, op) in self.ops.iter().enumerate() {
            op.for_each_operand(&self.ls, |r| last_use[r as usize] = i as u32);
        }
        for &o in self.outputs.iter().take(n_outputs) {
            last_use[o as usize] = KEEP;
        }
        // The union of the operands' sets, merged in two work buffers and copied out
        // once (one allocation per node, none for an empty set).
        let (mut acc, mut next): (Vec<u32>, Vec<u32>) = (Vec::new(), Vec::new());
        let mut union = |sets: &[Vec<u32>], operands: &[u32]| -> Vec<u32> {
            acc.clear();
            for &r in operands {
                merge_into(&acc, &sets[r as usize], &mut next);
                next.truncate(cap);
                std::mem::swap(&mut acc, &mut next);
            }
            acc.clone()
        };
        let mut sets: Vec<Vec<u32>> = vec![Vec::new(); len];
        let mut operands: Vec<u32> = Vec::new();
        for (i, &op) in self.ops.iter().enumerate() {
            operands.clear();
            op.for_each_operand(&self.ls, |r| operands.push(r));
            match op {
                Op::Const(_) | Op::LsPart => {}
                Op::Input(s) => sets[i] = map(s).into_iter().collect(),
                Op::LinearSolve(s) => {
                    // Many operands: one sort instead of a merge per operand.
                    let mut all: Vec<u32> = operands
                        .iter()
                        .flat_map(|&r| sets[r as usize].iter().copied())
                        .collect();
                    all.sort_unstable();
                    all.dedup();
                    all.truncate(cap);
                    for j in 1..self.ls[s as usize].k {
                        sets[i + j] = all.clone();
                    }
                    sets[i] = all;
                }
                _ => sets[i] = union(&sets, &operands),
            }
            for &r in &operands {
                if last_use[r as usize] == i as u32 {
                    sets[r as usize] = Vec::new();
                }
            }
        }
        self.outputs
            .iter()
            .take(n_outputs)
            .map(|&o| sets[o as usize].clone())
            .collect()
    }
}

/// Directions evaluated per forward pass of [`DaeJacobian::eval`] and of the extended
/// Jacobian. Each pass also computes the values (and factors the tape's linear solves)
/// again; 24 lanes take the 19 to 21 colours of the pendulum chains' extended Jacobians
/// in one pass (16 needed two: the 100-link chain's solve took 5 % longer).
pub(crate) const MAX_LANES: usize = 24;

/// A column colouring: columns of one colour share no row.
#[derive(Clone, Debug)]
pub(crate) struct Coloring {
    /// Colour of each column (`usize::MAX` for an empty column).
    pub(crate) colors: Vec<usize>,
    pub(crate) n_colors: usize,
    /// Columns of colour c are `by_color[color_ptr[c]..color_ptr[c + 1]]`.
    pub(crate) color_ptr: Vec<usize>,
    pub(crate) by_color: Vec<usize>,
}

/// Greedy distance-2 colouring of the columns of a CSC pattern (`rows[r]` lists the
/// columns of row r): columns sharing a row get different colours.
pub(crate) fn color_columns(col_ptr: &[usize], row_idx: &[usize], rows: &[Vec<usize>]) -> Coloring {
    let n_cols = col_ptr.len() - 1;
    let mut colors = vec![usize::MAX; n_cols];
    let mut forbidden: Vec<usize> = Vec::new(); // forbidden[c] == j: colour c taken for column j
    let mut n_colors = 0;
    // A row that touches every non-empty column makes all of them conflict: one colour
    // each, found in O(nnz) instead of the greedy's O(sum of squared row lengths) (the
    // dense Jacobian of a long chain's accelerations).
    let nonempty = (0..n_cols).filter(|&j| col_ptr[j] < col_ptr[j + 1]).count();
    let full_row = rows.iter().any(|r| r.len() == nonempty && nonempty > 0);
    for j in 0..n_cols {
        if full_row {
            if col_ptr[j] < col_ptr[j + 1] {
                colors[j] = n_colors;
                n_colors += 1;
            }
            continue;
        }
        if col_ptr[j] == col_ptr[j + 1] {
            continue; // empty column: no colour needed
        }
        for &r in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
            for &k in &rows[r] {
                let c = colors[k];
                if c != usize::MAX {
                    forbidden[c] = j;
                }
            }
        }
        let c = (0..n_colors)
            .find(|&c| forbidden[c] != j)
            .unwrap_or(n_colors);
        if c == n_colors {
            n_colors += 1;
            forbidden.push(usize::MAX);
        }
        colors[j] = c;
    }
    let mut color_ptr = vec![0usize; n_colors + 1];
    for &c in colors.iter().filter(|&&c| c != usize::MAX) {
        color_ptr[c + 1] += 1;
    }
    for c in 0..n_colors {
        color_ptr[c + 1] += color_ptr[c];
    }
    let mut fill = color_ptr.clone();
    let mut by_color = vec![0usize; color_ptr[n_colors]];
    for (j, &c) in colors.iter().enumerate() {
        if c != usize::MAX {
            by_color[fill[c]] = j;
            fill[c] += 1;
        }
    }
    Coloring {
        colors,
        n_colors,
        color_ptr,
        by_color,
    }
}

/// Transposes row lists (`rows[r]` sorted column indices) into a CSC pattern with
/// `n_cols` columns and sorted row indices.
pub(crate) fn rows_to_csc(rows: &[Vec<usize>], n_cols: usize) -> (Vec<usize>, Vec<usize>) {
    let mut col_ptr = vec![0usize; n_cols + 1];
    for cols in rows {
        for &c in cols {
            col_ptr[c + 1] += 1;
        }
    }
    for j in 0..n_cols {
        col_ptr[j + 1] += col_ptr[j];
    }
    let mut next = col_ptr.clone();
    let mut row_idx = vec![0usize; col_ptr[n_cols]];
    for (r, cols) in rows.iter().enumerate() {
        for &c in cols {
            row_idx[next[c]] = r;
            next[c] += 1;
        }
    }
    (col_ptr, row_idx)
}

/// Sparse Jacobian `J = dF/du + cj dF/du'` of a DAE residual tape whose inputs hold
/// `u` (n values from `u_offset`) and `u'` (n values from `yp_offset`) among others;
/// rows are the first n outputs, column j merges `u_j` with `u'_j`. The pattern is in
/// compressed sparse column form (row indices sorted within each column); values are
/// computed by compressed forward mode over a greedy distance-2 colouring of the
/// columns, one lane per colour, at most 24 lanes per pass.
#[derive(Clone, Debug)]
pub struct DaeJacobian {
    /// Number of rows and columns.
    pub n: usize,
    /// Column pointers (length n + 1).
    pub col_ptr: Vec<usize>,
    /// Row index of each stored entry, sorted within each column.
    pub row_idx: Vec<usize>,
    u_offset: usize,
    yp_offset: usize,
    /// Colour of each column.
    colors: Vec<usize>,
    n_colors: usize,
    /// Columns grouped by colour: those of colour c are
    /// `by_color[color_ptr[c]..color_ptr[c + 1]]`.
    color_ptr: Vec<usize>,
    by_color: Vec<usize>,
}

/// Scratch memory for [`DaeJacobian::eval`].
#[derive(Clone, Debug)]
pub struct JacobianWorkspace {
    ws: Workspace,
    seeds: Vec<f64>,
    out: Vec<f64>,
    tangents: Vec<f64>,
}

impl DaeJacobian {
    /// The pattern and column colouring from the residual tape's dependencies: rows are
    /// its first `n` outputs; `u_j` is input slot `u_offset + j` and `u'_j` is
    /// `yp_offset + j`.
    ///
    /// # Panics
    /// If the tape has fewer than `n` outputs or the slot ranges exceed its inputs.
    pub fn new(tape: &Tape, n: usize, u_offset: usize, yp_offset: usize) -> DaeJacobian {
        assert!(
            tape.n_outputs() >= n,
            "DaeJacobian::new: the tape has fewer than {n} outputs"
        );
        assert!(
            u_offset + n <= tape.n_inputs() && yp_offset + n <= tape.n_inputs(),
            "DaeJacobian::new: unknowns or derivatives outside the tape's inputs"
        );
        let deps = tape.dependencies();
        // Rows: sorted column lists.
        let mut rows: Vec<Vec<usize>> = Vec::with_capacity(n);
        for d in deps.iter().take(n) {
            let mut cols: Vec<usize> = d
                .iter()
                .filter_map(|&s| {
                    if s >= u_offset && s < u_offset + n {
                        Some(s - u_offset)
                    } else if s >= yp_offset && s < yp_offset + n {
                        Some(s - yp_offset)
                    } else {
                        None
                    }
                })
                .collect();
            cols.sort_unstable();
            cols.dedup();
            rows.push(cols);
        }
        let (col_ptr, row_idx) = rows_to_csc(&rows, n);
        let Coloring {
            colors,
            n_colors,
            color_ptr,
            by_color,
        } = color_columns(&col_ptr, &row_idx, &rows);
        DaeJacobian {
            n,
            col_ptr,
            row_idx,
            u_offset,
            yp_offset,
            colors,
            n_colors,
            color_ptr,
            by_color,
        }
    }

    /// Number of colours (forward directions needed for the whole Jacobian).
    pub fn n_colors(&self) -> usize {
        self.n_colors
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// The colour of each column (`usize::MAX` for an empty column).
    pub fn column_colors(&self) -> &[usize] {
        &self.colors
    }

    /// Scratch memory for [`eval`](Self::eval) with `tape`.
    pub fn workspace(&self, tape: &Tape) -> JacobianWorkspace {
        let lanes = self.n_colors.clamp(1, MAX_LANES);
        let mut ws = tape.workspace();
        ws.fit(tape, lanes);
        JacobianWorkspace {
            ws,
            seeds: vec![0.0; tape.n_inputs() * lanes],
            out: vec![0.0; tape.n_outputs()],
            tangents: vec![0.0; tape.n_outputs() * lanes],
        }
    }

    /// Values of `J = dF/du + cj dF/du'` in CSC order (`values.len() == nnz()`), at the
    /// full input vector `inputs` of `tape`, by compressed forward mode.
    ///
    /// # Panics
    /// If `values` is shorter than [`nnz`](Self::nnz).
    pub fn eval(
        &self,
        tape: &Tape,
        inputs: &[f64],
        cj: f64,
        ws: &mut JacobianWorkspace,
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        assert!(
            values.len() >= self.nnz(),
            "DaeJacobian::eval: value buffer too short"
        );
        let ni = tape.n_inputs();
        let no = tape.n_outputs();
        let mut c0 = 0;
        while c0 < self.n_colors {
            let lanes = (self.n_colors - c0).min(MAX_LANES);
            let JacobianWorkspace {
                ws: tws,
                seeds,
                out,
                tangents,
            } = ws;
            if seeds.len() < ni * lanes {
                seeds.resize(ni * lanes, 0.0);
            }
            if tangents.len() < no * lanes {
                tangents.resize(no * lanes, 0.0);
            }
            if out.len() < no {
                out.resize(no, 0.0);
            }
            let seeds = &mut seeds[..ni * lanes];
            seeds.fill(0.0);
            let cols = &self.by_color[self.color_ptr[c0]..self.color_ptr[c0 + lanes]];
            for &j in cols {
                let l = self.colors[j] - c0;
                seeds[(self.u_offset + j) * lanes + l] += 1.0;
                seeds[(self.yp_offset + j) * lanes + l] += cj;
            }
            tape.forward(inputs, seeds, lanes, tws, out, tangents)?;
            for &j in cols {
                let l = self.colors[j] - c0;
                for p in self.col_ptr[j]..self.col_ptr[j + 1] {
                    values[p] = tangents[self.row_idx[p] * lanes + l];
                }
            }
            c0 += lanes;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::merge_into;

    #[test]
    fn merging_keeps_sets_sorted_without_duplicates_and_reuses_the_buffer() {
        let mut out = vec![99, 98];
        merge_into(&[1, 3, 5], &[2, 3, 6], &mut out);
        assert_eq!(out, [1, 2, 3, 5, 6]);
        merge_into(&[], &[4, 7], &mut out);
        assert_eq!(out, [4, 7]);
        merge_into(&[4, 7], &[], &mut out);
        assert_eq!(out, [4, 7]);
        merge_into(&[4, 7], &[4, 7], &mut out);
        assert_eq!(out, [4, 7]);
        merge_into(&[8], &[1, 2], &mut out);
        assert_eq!(out, [1, 2, 8]);
    }
}
