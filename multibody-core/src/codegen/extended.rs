//! The extended Jacobian: the DAE iteration matrix bordered by intermediate registers of
//! the residual tape ("cuts"), so that it stays sparse when many rows depend on many
//! unknowns through a few shared intermediates. In a multibody chain the absolute
//! orientation of link k depends on every joint angle before it, so the plain Jacobian
//! `J = dF/du + cj dF/du'` has O(N^2) entries and needs O(N) colours; with the
//! orientation entries as cuts every row has a handful of entries and the colours stay
//! constant in N.
//!
//! For cut registers `c = g(u, u', earlier cuts)` the extended system
//!
//! ```text
//! [ dF/du + cj dF/du'    dF/dc      ] [du]   [b]
//! [ dg/du + cj dg/du'    dg/dc - I  ] [dc] = [0]
//! ```
//!
//! is square (`n + m`), and eliminating `dc` (the lower-right block is unit lower
//! triangular, so always invertible) leaves exactly `J du = b`: solving it is solving
//! with the exact Jacobian. A tape's linear solve `A x + c = 0` makes its solution
//! registers cuts whose rows are the linearized system `A dx + dA x + dc = 0`. Cuts are
//! intermediates of the linear algebra only: they are never unknowns of the DAE nor of
//! its Newton iteration.

use super::EvalError;
use super::elimination_queue::EliminationQueue;
use super::forward::forward_core;
use super::sparsity::{Coloring, MAX_LANES, color_columns, merge_into, rows_to_csc};
use super::tape::{Op, Tape, Workspace, solve_linear};

/// Entries an elimination may add and still be made (default of
/// [`ExtendedJacobian::new`]'s `max_fill`). Fewer cuts make a smaller iteration matrix,
/// whose triangular solves (one per Newton iteration) cost per row as well as per
/// entry; more fill makes its factors denser. On the 100-link pendulum, 16 instead of 8 took the matrix from 785 to 653
/// rows and the solve from 0.53 s to 0.46 s (parameters folded); 32 was slower again.
pub const DEFAULT_MAX_FILL: usize = 16;

const NO_CUT: u32 = u32::MAX;

/// The sparse extended Jacobian of a DAE residual tape (see the module documentation),
/// in CSC form with its column colouring. Rows and columns `0..n` belong to the
/// unknowns (column j merges `u_j` and `u'_j`), rows and columns `n..n + m` to the cuts
/// in tape order.
#[derive(Clone, Debug)]
pub struct ExtendedJacobian {
    /// Number of DAE unknowns.
    pub n: usize,
    /// Column pointers (length `dimension() + 1`).
    pub col_ptr: Vec<usize>,
    /// Row index of each stored entry, sorted within each column.
    pub row_idx: Vec<usize>,
    u_offset: usize,
    yp_offset: usize,
    /// Per register: its cut number, or `NO_CUT`.
    cut_of: Vec<u32>,
    n_cuts: usize,
    coloring: Coloring,
    /// Whether forward passes may skip the tape's prelude: no cut lies in it and the
    /// seeded slots (`u`, `u'`) are not invariant inputs.
    prelude_skippable: bool,
}

/// Scratch memory for [`ExtendedJacobian::eval`].
#[derive(Clone, Debug)]
pub struct ExtendedWorkspace {
    ws: Workspace,
    seeds: Vec<f64>,
    cut_seeds: Vec<f64>,
    cut_rows: Vec<f64>,
    out: Vec<f64>,
    tangents: Vec<f64>,
}

/// Column of input `slot`, if it is an unknown or a derivative.
fn column(slot: usize, n: usize, u_offset: usize, yp_offset: usize) -> Option<u32> {
    if (u_offset..u_offset + n).contains(&slot) {
        Some((slot - u_offset) as u32)
    } else if (yp_offset..yp_offset + n).contains(&slot) {
        Some((slot - yp_offset) as u32)
    } else {
        None
    }
}

/// Registers read by row `j` of linear solve `s` (row j of `A`, then `c_j`).
fn linear_row_operands(tape: &Tape, s: u32, j: usize) -> Vec<u32> {
    let info = &tape.ls[s as usize];
    let k = info.k;
    let mut ops: Vec<u32> = match &info.sparse {
        Some(p) => p.row_entries[p.row_ptr[j]..p.row_ptr[j + 1]]
            .iter()
            .map(|&e| info.a[e])
            .collect(),
        None => info.a[j * k..(j + 1) * k].to_vec(),
    };
    ops.push(info.c[j]);
    ops
}

/// Columns of row `j` of linear solve `s` (all of them for a dense one).
fn linear_row_columns(tape: &Tape, s: u32, j: usize) -> Vec<usize> {
    let info = &tape.ls[s as usize];
    match &info.sparse {
        Some(p) => {
            let mut cols: Vec<usize> = p.row_entries[p.row_ptr[j]..p.row_ptr[j + 1]]
                .iter()
                .map(|&e| p.col_of(e))
                .collect();
            cols.sort_unstable();
            cols
        }
        None => (0..info.k).collect(),
    }
}

/// Chooses the cut registers by vertex elimination on the tape's dependency graph
/// (Markowitz order): registers that depend on unknowns are vertices between the
/// unknown columns and the residual rows; eliminating a vertex with p predecessors and
/// s successors connects each predecessor to each successor. Vertices are eliminated
/// cheapest first while that does not add entries (`p * s <= p + s + max_fill`); the
/// rest are cuts. Solutions of linear solves are always cuts.
fn choose_cuts(
    tape: &Tape,
    n: usize,
    u_offset: usize,
    yp_offset: usize,
    max_fill: usize,
) -> Vec<bool> {
    let nregs = tape.ops.len();
    // Vertex ids: registers 0..nregs, columns nregs..nregs + n, output rows after.
    let col = |j: u32| nregs as u32 + j;
    let nv = nregs + n + tape.outputs.len();
    let mut preds: Vec<Vec<u32>> = vec![Vec::new(); nv];
    let mut succs: Vec<Vec<u32>> = vec![Vec::new(); nv];
    let mut live = vec![false; nv];
    let mut fixed = vec![false; nv]; // never eliminated
    let mut operands = Vec::new();
    for (i, &op) in tape.ops.iter().enumerate() {
        let mut ps: Vec<u32> = Vec::new();
        match op {
            Op::Const(_) | Op::LsPart => continue,
            Op::Input(s) => {
                if let Some(c) = column(s as usize, n, u_offset, yp_offset) {
                    ps.push(col(c));
                }
            }
            Op::LinearSolve(s) => {
                let k = tape.ls[s as usize].k;
                for j in 0..k {
                    let mut ps: Vec<u32> = linear_row_operands(tape, s, j)
                        .into_iter()
                        .filter(|&r| live[r as usize])
                        .collect();
                    ps.extend(
                        linear_row_columns(tape, s, j)
                            .into_iter()
                            .filter(|&c| c != j)
                            .map(|c| (i + c) as u32),
                    );
                    ps.sort_unstable();
                    ps.dedup();
                    preds[i + j] = ps;
                    live[i + j] = true;
                    fixed[i + j] = true;
                }
                continue;
            }
            _ => {
                operands.clear();
                op.for_each_operand(&tape.ls, |r| operands.push(r));
                ps.extend(operands.iter().copied().filter(|&r| live[r as usize]));
            }
        }
        ps.sort_unstable();
        ps.dedup();
        if !ps.is_empty() {
            live[i] = true;
            preds[i] = ps;
        }
    }
    for j in 0..n {
        live[nregs + j] = true;
        fixed[nregs + j] = true;
    }
    for (o, &r) in tape.outputs.iter().enumerate() {
        let v = nregs + n + o;
        fixed[v] = true;
        live[v] = true;
        if live[r as usize] {
            preds[v] = vec![r];
        }
    }
    for v in 0..nv {
        if !live[v] {
            continue;
        }
        for k in 0..preds[v].len() {
            let p = preds[v][k];
            succs[p as usize].push(v as u32);
        }
    }
    for s in succs.iter_mut() {
        s.sort_unstable();
        s.dedup();
    }
    let cost = |p: usize, s: usize| -> i64 { (p * s) as i64 - (p + s) as i64 };
    // Only costs up to `max_fill` are ever eliminated: a vertex costing more enters the
    // queue when an elimination next to it lowers its cost.
    let mut queue = EliminationQueue::up_to(max_fill as i64);
    for v in 0..nregs {
        if live[v] && !fixed[v] {
            queue.push_ascending(cost(preds[v].len(), succs[v].len()), v as u32);
        }
    }
    let mut eliminated = vec![false; nv];
    // Merges land here and swap into the list: allocations circulate.
    let mut merged = Vec::new();
    while let Some((c, v)) = queue.pop() {
        let vu = v as usize;
        if eliminated[vu] {
            continue;
        }
        let now = cost(preds[vu].len(), succs[vu].len());
        if now != c {
            queue.push(now, v);
            continue;
        }
        eliminated[vu] = true;
        let ps = std::mem::take(&mut preds[vu]);
        let ss = std::mem::take(&mut succs[vu]);
        for &p in &ps {
            let list = &mut succs[p as usize];
            list.retain(|&x| x != v);
            merge_into(list, &ss, &mut merged);
            std::mem::swap(list, &mut merged);
        }
        for &s in &ss {
            let list = &mut preds[s as usize];
            list.retain(|&x| x != v);
            merge_into(list, &ps, &mut merged);
            std::mem::swap(list, &mut merged);
        }
        for &x in ps.iter().chain(&ss) {
            let xu = x as usize;
            if xu < nregs && !fixed[xu] && !eliminated[xu] {
                queue.push(cost(preds[xu].len(), succs[xu].len()), x);
            }
        }
    }
    (0..nregs).map(|r| live[r] && !eliminated[r]).collect()
}

impl ExtendedJacobian {
    /// The extended pattern of `tape`'s first `n` outputs, with `u_j` in input slot
    /// `u_offset + j` and `u'_j` in `yp_offset + j`; intermediates are eliminated
    /// cheapest first while an elimination adds at most `max_fill` entries, the others
    /// are cuts.
    ///
    /// # Panics
    /// If the tape has fewer than `n` outputs.
    pub fn new(
        tape: &Tape,
        n: usize,
        u_offset: usize,
        yp_offset: usize,
        max_fill: usize,
    ) -> ExtendedJacobian {
        assert!(
            tape.n_outputs() >= n,
            "ExtendedJacobian::new: the tape has fewer than {n} outputs"
        );
        let is_cut = choose_cuts(tape, n, u_offset, yp_offset, max_fill);
        let nregs = tape.ops.len();
        let mut cut_of = vec![NO_CUT; nregs];
        let mut n_cuts = 0usize;
        for (r, &c) in is_cut.iter().enumerate() {
            if c {
                cut_of[r] = n_cuts as u32;
                n_cuts += 1;
            }
        }
        let dim = n + n_cuts;
        // The prelude may be skipped unless a cut lies in it (cuts must pass through the
        // forward hook) or the seeded slots overlap the invariant inputs.
        let (lo, hi) = tape.invariant_inputs;
        let seeded_outside = |start: usize| start + n <= lo || start >= hi;
        let prelude_skippable = !is_cut[..tape.prelude_len].iter().any(|&c| c)
            && seeded_outside(u_offset)
            && seeded_outside(yp_offset);
        // Dependencies with the final cuts (a cut register reads as its own column).
        let mut deps: Vec<Vec<u32>> = vec![Vec::new(); nregs];
        let mut rows: Vec<Vec<usize>> = vec![Vec::new(); dim];
        // A cut register reads as its own column, any other as its dependencies.
        let cut_column = |r: u32| match cut_of[r as usize] {
            NO_CUT => None,
            c => Some((n + c as usize) as u32),
        };
        // `acc` merged with register `r`'s columns, through the work buffer `next`.
        let merge_leaf = |acc: &mut Vec<u32>, next: &mut Vec<u32>, r: u32, deps: &[Vec<u32>]| {
            match cut_column(r) {
                Some(c) => merge_into(acc, &[c], next),
                None => merge_into(acc, &deps[r as usize], next),
            }
            std::mem::swap(acc, next);
        };
        let (mut acc, mut next): (Vec<u32>, Vec<u32>) = (Vec::new(), Vec::new());
        let mut operands = Vec::new();
        for (i, &op) in tape.ops.iter().enumerate() {
            match op {
                Op::Const(_) | Op::LsPart => {}
                Op::Input(s) => {
                    if let Some(c) = column(s as usize, n, u_offset, yp_offset) {
                        deps[i] = vec![c];
                    }
                }
                Op::LinearSolve(s) => {
                    let k = tape.ls[s as usize].k;
                    for j in 0..k {
                        acc.clear();
                        acc.extend(
                            linear_row_columns(tape, s, j)
                                .into_iter()
                                .map(|c| (n + cut_of[i + c] as usize) as u32),
                        );
                        acc.sort_unstable();
                        for r in linear_row_operands(tape, s, j) {
                            merge_leaf(&mut acc, &mut next, r, &deps);
                        }
                        rows[n + cut_of[i + j] as usize] =
                            acc.iter().map(|&c| c as usize).collect();
                    }
                }
                _ => {
                    operands.clear();
                    op.for_each_operand(&tape.ls, |r| operands.push(r));
                    acc.clear();
                    for &r in &operands {
                        merge_leaf(&mut acc, &mut next, r, &deps);
                    }
                    if let Some(own) = cut_column(i as u32) {
                        merge_into(&acc, &[own], &mut next);
                        rows[own as usize] = next.iter().map(|&c| c as usize).collect();
                    }
                    deps[i] = acc.clone();
                }
            }
        }
        for (o, &r) in tape.outputs.iter().take(n).enumerate() {
            rows[o] = match cut_column(r) {
                Some(c) => vec![c as usize],
                None => deps[r as usize].iter().map(|&c| c as usize).collect(),
            };
        }
        let (col_ptr, row_idx) = rows_to_csc(&rows, dim);
        let coloring = color_columns(&col_ptr, &row_idx, &rows);
        ExtendedJacobian {
            n,
            col_ptr,
            row_idx,
            u_offset,
            yp_offset,
            cut_of,
            n_cuts,
            coloring,
            prelude_skippable,
        }
    }

    /// Number of rows and columns: unknowns plus cuts.
    pub fn dimension(&self) -> usize {
        self.n + self.n_cuts
    }

    /// Number of cut registers.
    pub fn n_cuts(&self) -> usize {
        self.n_cuts
    }

    /// Number of colours (forward directions for the whole matrix).
    pub fn n_colors(&self) -> usize {
        self.coloring.n_colors
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Scratch memory for [`eval`](Self::eval) with `tape`.
    pub fn workspace(&self, tape: &Tape) -> ExtendedWorkspace {
        let lanes = self.coloring.n_colors.clamp(1, MAX_LANES);
        let mut ws = tape.workspace();
        ws.fit(tape, lanes);
        ExtendedWorkspace {
            ws,
            seeds: vec![0.0; tape.n_inputs() * lanes],
            cut_seeds: vec![0.0; self.n_cuts * lanes],
            cut_rows: vec![0.0; self.n_cuts * lanes],
            out: vec![0.0; tape.n_outputs()],
            tangents: vec![0.0; tape.n_outputs() * lanes],
        }
    }

    /// Values of the extended matrix in CSC order (`values.len() >= nnz()`) at the
    /// full input vector `inputs` of `tape`, by compressed forward mode.
    ///
    /// # Panics
    /// If `values` is shorter than [`nnz`](Self::nnz) or the workspace was made for
    /// another tape.
    pub fn eval(
        &self,
        tape: &Tape,
        inputs: &[f64],
        cj: f64,
        ws: &mut ExtendedWorkspace,
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        assert!(
            values.len() >= self.nnz(),
            "ExtendedJacobian::eval: value buffer too short"
        );
        let n = self.n;
        let ni = tape.n_inputs();
        let no = tape.n_outputs();
        let nc = self.coloring.n_colors;
        let mut c0 = 0;
        while c0 < nc {
            let w = (nc - c0).min(MAX_LANES);
            let ExtendedWorkspace {
                ws: tws,
                seeds,
                cut_seeds,
                cut_rows,
                out,
                tangents,
            } = ws;
            seeds.resize(ni * w.max(1), 0.0);
            cut_seeds.resize(self.n_cuts * w, 0.0);
            cut_rows.resize(self.n_cuts * w, 0.0);
            tangents.resize(no * w, 0.0);
            out.resize(no, 0.0);
            let seeds = &mut seeds[..ni * w];
            let cut_seeds = &mut cut_seeds[..self.n_cuts * w];
            seeds.fill(0.0);
            cut_seeds.fill(0.0);
            let c = &self.coloring;
            let cols = &c.by_color[c.color_ptr[c0]..c.color_ptr[c0 + w]];
            for &j in cols {
                let l = c.colors[j] - c0;
                if j < n {
                    seeds[(self.u_offset + j) * w + l] += 1.0;
                    seeds[(self.yp_offset + j) * w + l] += cj;
                } else {
                    cut_seeds[(j - n) * w + l] = 1.0;
                }
            }
            self.forward(
                tape,
                inputs,
                seeds,
                cut_seeds,
                w,
                tws,
                &mut cut_rows[..self.n_cuts * w],
                out,
                &mut tangents[..no * w],
            )?;
            for &j in cols {
                let l = c.colors[j] - c0;
                for p in self.col_ptr[j]..self.col_ptr[j + 1] {
                    let r = self.row_idx[p];
                    values[p] = if r < n {
                        tangents[r * w + l]
                    } else {
                        cut_rows[(r - n) * w + l]
                    };
                }
            }
            c0 += w;
        }
        Ok(())
    }

    /// Forward mode in which cut registers read their seeds (`cut_seeds`) instead of
    /// their computed tangents; what the instruction computed, minus the seed, is the
    /// cut's row (`cut_rows`).
    #[allow(clippy::too_many_arguments)]
    fn forward(
        &self,
        tape: &Tape,
        inputs: &[f64],
        seeds: &[f64],
        cut_seeds: &[f64],
        w: usize,
        ws: &mut Workspace,
        cut_rows: &mut [f64],
        out: &mut [f64],
        out_tangents: &mut [f64],
    ) -> Result<(), EvalError> {
        let nregs = tape.ops.len();
        ws.fit(tape, w);
        let Workspace {
            regs,
            tan,
            lu,
            piv,
            sparse,
            prelude,
            ..
        } = ws;
        let regs = &mut regs[..nregs];
        let tan = &mut tan[..nregs * w];
        let cut_of = &self.cut_of[..];
        let skip = prelude.forward_pass(tape, inputs, w, tan, self.prelude_skippable);
        // Borrowed by both hooks; they never run at the same time.
        let cut_rows = std::cell::RefCell::new(cut_rows);
        forward_core(
            tape,
            inputs,
            seeds,
            w,
            regs,
            tan,
            skip,
            |i, s, regs, done, rest| {
                let info = &tape.ls[s as usize];
                solve_linear(info, s as usize, i, regs, lu, piv, sparse)?;
                // Row j: A_j. dx + dA_j. x + dc_j, with dx the seeds of the solution cuts.
                let mut cut_rows = cut_rows.borrow_mut();
                let k = info.k;
                for j in 0..k {
                    let cut = cut_of[i + j] as usize;
                    let cr = info.c[j] as usize;
                    cut_rows[cut * w..cut * w + w].copy_from_slice(&done[cr * w..cr * w + w]);
                }
                let mut add_entry = |row: usize, col: usize, ar: usize| {
                    let cut = cut_of[i + row] as usize;
                    let (a, x) = (regs[ar], regs[i + col]);
                    let xcut = cut_of[i + col] as usize;
                    let da = &done[ar * w..ar * w + w];
                    let dx = &cut_seeds[xcut * w..xcut * w + w];
                    let target = &mut cut_rows[cut * w..cut * w + w];
                    for ((t, &da), &dx) in target.iter_mut().zip(da).zip(dx) {
                        *t += da * x + a * dx;
                    }
                };
                match &info.sparse {
                    Some(pattern) => {
                        for col in 0..k {
                            for p in pattern.col_ptr[col]..pattern.col_ptr[col + 1] {
                                add_entry(pattern.row_idx[p], col, info.a[p] as usize);
                            }
                        }
                    }
                    None => {
                        for row in 0..k {
                            for col in 0..k {
                                add_entry(row, col, info.a[row * k + col] as usize);
                            }
                        }
                    }
                }
                for j in 0..k {
                    let cut = cut_of[i + j] as usize;
                    rest[j * w..j * w + w].copy_from_slice(&cut_seeds[cut * w..cut * w + w]);
                }
                Ok(())
            },
            |i, t| {
                let cut = cut_of[i];
                if cut != NO_CUT {
                    let cut = cut as usize;
                    let seed = &cut_seeds[cut * w..cut * w + w];
                    let mut cut_rows = cut_rows.borrow_mut();
                    let row = &mut cut_rows[cut * w..cut * w + w];
                    for ((r, t), &s) in row.iter_mut().zip(t.iter_mut()).zip(seed) {
                        *r = *t - s;
                        *t = s;
                    }
                }
            },
        )?;
        for (o, &r) in tape.outputs.iter().enumerate() {
            out[o] = regs[r as usize];
            out_tangents[o * w..o * w + w]
                .copy_from_slice(&tan[r as usize * w..r as usize * w + w]);
        }
        Ok(())
    }
}
