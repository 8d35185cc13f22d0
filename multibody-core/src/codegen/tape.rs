//! The instruction set, the tape and its value evaluation.

use crate::expr::{Cmp, Func1, Func2};
use crate::sparse_lu::{LuError, SparseLu};

use super::EvalError;

/// One instruction. Instruction `i` writes register `i` (static single assignment);
/// operands are registers of earlier instructions. Numeric constants live in the tape's
/// constant pool so that an instruction stays 16 bytes and hashable.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Op {
    /// `consts[k]`
    Const(u32),
    /// `inputs[slot]`
    Input(u32),
    /// `a + b`
    Add(u32, u32),
    /// `a - b`
    Sub(u32, u32),
    /// `a * b`
    Mul(u32, u32),
    /// `a / b`
    Div(u32, u32),
    /// `-a`
    Neg(u32),
    /// `consts[k] * a` as `(k, a)`
    Scale(u32, u32),
    /// `a + consts[k] * b` as `(a, k, b)`
    AddScaled(u32, u32, u32),
    /// `a ^ n`
    PowI(u32, i32),
    /// `a ^ b`
    Pow(u32, u32),
    /// `f(a)`
    F1(Func1, u32),
    /// `f(a, b)`
    F2(Func2, u32, u32),
    /// `a op b` as 1.0 or 0.0
    Cmp(Cmp, u32, u32),
    /// `if c != 0 { a } else { b }` as `(c, a, b)`
    Select(u32, u32, u32),
    /// Linear solve number `s` of the side table; writes registers `i .. i + k`.
    LinearSolve(u32),
    /// A register written by the preceding `LinearSolve`; does nothing itself.
    LsPart,
}

impl Op {
    /// Calls `f` on every register operand (for `LinearSolve`, those of the side table).
    #[inline]
    pub(crate) fn for_each_operand(&self, ls: &[LsInfo], mut f: impl FnMut(u32)) {
        match *self {
            Op::Const(_) | Op::Input(_) | Op::LsPart => {}
            Op::Neg(a) | Op::Scale(_, a) | Op::PowI(a, _) | Op::F1(_, a) => f(a),
            Op::Add(a, b)
            | Op::Sub(a, b)
            | Op::Mul(a, b)
            | Op::Div(a, b)
            | Op::AddScaled(a, _, b)
            | Op::Pow(a, b)
            | Op::F2(_, a, b)
            | Op::Cmp(_, a, b) => {
                f(a);
                f(b)
            }
            Op::Select(c, a, b) => {
                f(c);
                f(a);
                f(b)
            }
            Op::LinearSolve(s) => {
                let info = &ls[s as usize];
                info.a.iter().chain(info.c.iter()).for_each(|&r| f(r));
            }
        }
    }

    /// The operator with every register operand replaced by `map(register)`.
    pub(crate) fn remap(self, map: impl Fn(u32) -> u32) -> Op {
        match self {
            Op::Const(_) | Op::Input(_) | Op::LsPart | Op::LinearSolve(_) => self,
            Op::Add(a, b) => Op::Add(map(a), map(b)),
            Op::Sub(a, b) => Op::Sub(map(a), map(b)),
            Op::Mul(a, b) => Op::Mul(map(a), map(b)),
            Op::Div(a, b) => Op::Div(map(a), map(b)),
            Op::Neg(a) => Op::Neg(map(a)),
            Op::Scale(k, a) => Op::Scale(k, map(a)),
            Op::AddScaled(a, k, b) => Op::AddScaled(map(a), k, map(b)),
            Op::PowI(a, n) => Op::PowI(map(a), n),
            Op::Pow(a, b) => Op::Pow(map(a), map(b)),
            Op::F1(f, a) => Op::F1(f, map(a)),
            Op::F2(f, a, b) => Op::F2(f, map(a), map(b)),
            Op::Cmp(c, a, b) => Op::Cmp(c, map(a), map(b)),
            Op::Select(c, a, b) => Op::Select(map(c), map(a), map(b)),
        }
    }
}

/// The pattern of a sparse `A` (compressed columns), with its rows for row-wise access.
#[derive(Clone, Debug)]
pub(crate) struct SparsePattern {
    pub(crate) col_ptr: Vec<usize>,
    pub(crate) row_idx: Vec<usize>,
    /// Row j holds the entries `row_entries[row_ptr[j]..row_ptr[j + 1]]` (indices into
    /// the CSC order).
    pub(crate) row_ptr: Vec<usize>,
    pub(crate) row_entries: Vec<usize>,
}

impl SparsePattern {
    /// The pattern of the `(row, col)` entries (CSC order as given, no duplicates).
    pub(crate) fn new(k: usize, col_ptr: Vec<usize>, row_idx: Vec<usize>) -> SparsePattern {
        let mut row_ptr = vec![0usize; k + 1];
        for &r in &row_idx {
            row_ptr[r + 1] += 1;
        }
        for j in 0..k {
            row_ptr[j + 1] += row_ptr[j];
        }
        let mut fill = row_ptr.clone();
        let mut row_entries = vec![0usize; row_idx.len()];
        for (p, &r) in row_idx.iter().enumerate() {
            row_entries[fill[r]] = p;
            fill[r] += 1;
        }
        SparsePattern {
            col_ptr,
            row_idx,
            row_ptr,
            row_entries,
        }
    }

    /// The column of entry `p` (CSC index).
    pub(crate) fn col_of(&self, p: usize) -> usize {
        self.col_ptr.partition_point(|&q| q <= p) - 1
    }
}

/// A linear system `A x + c = 0` solved inside the tape: dense (LU with partial
/// pivoting) or sparse (the refactorizing sparse LU).
#[derive(Clone, Debug)]
pub(crate) struct LsInfo {
    /// Dimension.
    pub(crate) k: usize,
    /// Registers of `A`: row-major k*k when dense, one per entry in CSC order when
    /// sparse.
    pub(crate) a: Vec<u32>,
    /// The pattern of a sparse `A`; `None` for a dense one.
    pub(crate) sparse: Option<std::sync::Arc<SparsePattern>>,
    /// Registers of `c`.
    pub(crate) c: Vec<u32>,
    /// Offset of this system's LU factors in the workspace (k*k entries).
    pub(crate) lu_off: usize,
    /// Offset of this system's pivots in the workspace (k entries).
    pub(crate) piv_off: usize,
    /// The unknowns solved for, for error messages.
    pub(crate) names: String,
}

/// What a [`Run`] of instructions computes: the common arithmetic kinds get loops of
/// their own, everything else goes through the general dispatch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum RunKind {
    Const,
    Input,
    Add,
    Sub,
    Mul,
    Div,
    Neg,
    Scale,
    AddScaled,
    Other,
}

impl RunKind {
    fn of(op: &Op) -> RunKind {
        match op {
            Op::Const(_) => RunKind::Const,
            Op::Input(_) => RunKind::Input,
            Op::Add(..) => RunKind::Add,
            Op::Sub(..) => RunKind::Sub,
            Op::Mul(..) => RunKind::Mul,
            Op::Div(..) => RunKind::Div,
            Op::Neg(_) => RunKind::Neg,
            Op::Scale(..) => RunKind::Scale,
            Op::AddScaled(..) => RunKind::AddScaled,
            _ => RunKind::Other,
        }
    }
}

/// A maximal range `start..end` of consecutive instructions of one [`RunKind`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct Run {
    pub(crate) kind: RunKind,
    pub(crate) start: u32,
    pub(crate) end: u32,
}

/// The runs of `ops`, in order, with no run crossing `split` (the end of the prelude).
pub(crate) fn runs_of(ops: &[Op], split: usize) -> Vec<Run> {
    let mut runs: Vec<Run> = Vec::new();
    for (i, op) in ops.iter().enumerate() {
        let kind = RunKind::of(op);
        match runs.last_mut() {
            Some(r) if r.kind == kind && i != split => r.end = i as u32 + 1,
            _ => runs.push(Run {
                kind,
                start: i as u32,
                end: i as u32 + 1,
            }),
        }
    }
    runs
}

/// A compiled straight-line program: inputs in, outputs out. Independent of the arena
/// it was compiled from; `Send + Sync` and cheap to share.
#[derive(Clone, Debug)]
pub struct Tape {
    /// A number unique to this tape's structure (workspaces keep sparse factorizations
    /// per tape).
    pub(crate) id: u64,
    pub(crate) ops: Vec<Op>,
    /// `ops` as runs of one kind, evaluated by a loop each.
    pub(crate) runs: Vec<Run>,
    pub(crate) consts: Vec<f64>,
    pub(crate) ls: Vec<LsInfo>,
    pub(crate) outputs: Vec<u32>,
    pub(crate) n_inputs: usize,
    pub(crate) lu_len: usize,
    pub(crate) piv_len: usize,
    pub(crate) max_k: usize,
    /// The prelude: instructions `0..prelude_len` depend only on constants and the
    /// invariant inputs; they are the first `prelude_runs` runs.
    pub(crate) prelude_len: usize,
    pub(crate) prelude_runs: usize,
    /// The input slots that rarely change (parameters), `start..end`.
    pub(crate) invariant_inputs: (usize, usize),
}

/// Scratch memory for evaluating a [`Tape`]: registers, tangents and linear-solve
/// factors. Reusable across calls (and across tapes; it grows when needed), so
/// evaluation does not allocate once the workspace has served the tape. It remembers
/// which tape's parameter prelude its registers hold, for which parameter values.
#[derive(Clone, Debug, Default)]
pub struct Workspace {
    pub(crate) regs: Vec<f64>,
    pub(crate) tan: Vec<f64>,
    pub(crate) lu: Vec<f64>,
    pub(crate) piv: Vec<usize>,
    pub(crate) rhs: Vec<f64>,
    /// Factorizations of the sparse linear solves, by linear-solve index, for the tape
    /// `sparse_for`.
    pub(crate) sparse: SparseSolves,
    /// What the registers of a tape's prelude were last computed from.
    pub(crate) prelude: PreludeCache,
}

/// What the prelude registers in a [`Workspace`] hold: the tape and the values of its
/// invariant inputs they were computed for, and the lanes for which their tangents are
/// known to be zero.
#[derive(Clone, Debug, Default)]
pub(crate) struct PreludeCache {
    /// Id of the tape (0: none).
    tape: u64,
    /// The invariant inputs the prelude values were computed from.
    inputs: Vec<f64>,
    /// Number of lanes whose prelude tangents are all zero (0: unknown).
    zero_tangent_lanes: usize,
}

impl PreludeCache {
    /// Whether the prelude registers hold `tape`'s prelude at `inputs`.
    #[inline]
    fn holds(&self, tape: &Tape, inputs: &[f64]) -> bool {
        let (a, b) = tape.invariant_inputs;
        // Bitwise: -0.0 and 0.0 may give different results (atan2, 1/p).
        self.tape == tape.id
            && self.inputs.len() == b - a
            && self
                .inputs
                .iter()
                .zip(&inputs[a..b])
                .all(|(x, y)| x.to_bits() == y.to_bits())
    }

    /// Forgets what the registers hold (a tape without prelude overwrote them).
    #[inline]
    fn invalidate(&mut self) {
        self.tape = 0;
        self.zero_tangent_lanes = 0;
    }

    /// Records that the prelude registers now hold `tape`'s prelude at `inputs`.
    fn record(&mut self, tape: &Tape, inputs: &[f64]) {
        if self.tape != tape.id {
            // The tangent buffer holds another tape's tangents.
            self.zero_tangent_lanes = 0;
        }
        self.tape = tape.id;
        let (a, b) = tape.invariant_inputs;
        self.inputs.clear();
        self.inputs.extend_from_slice(&inputs[a..b]);
    }

    /// Before a value pass (no tangents) of `tape` at `inputs`: the number of leading
    /// runs to skip, recording the prelude as computed.
    #[inline]
    pub(crate) fn value_pass(&mut self, tape: &Tape, inputs: &[f64]) -> usize {
        if tape.prelude_len == 0 {
            self.invalidate();
            return 0;
        }
        if self.holds(tape, inputs) {
            return tape.prelude_runs;
        }
        self.record(tape, inputs);
        0
    }

    /// Before a forward pass of `tape` at `inputs` with `lanes` tangent lanes: the
    /// number of leading runs to skip. `may_skip` says that no parameter slot is
    /// seeded and no hook needs to see the prelude's instructions. When the prelude is
    /// skipped, its tangents in `tan` are exactly zero (filled here when they may not
    /// be).
    pub(crate) fn forward_pass(
        &mut self,
        tape: &Tape,
        inputs: &[f64],
        lanes: usize,
        tan: &mut [f64],
        may_skip: bool,
    ) -> usize {
        if tape.prelude_len == 0 {
            self.invalidate();
            return 0;
        }
        if may_skip && self.holds(tape, inputs) {
            if self.zero_tangent_lanes != lanes {
                tan[..tape.prelude_len * lanes].fill(0.0);
                self.zero_tangent_lanes = lanes;
            }
            return tape.prelude_runs;
        }
        self.record(tape, inputs);
        // The full pass computes the prelude tangents from the seeds (and may leave
        // NaN where a prelude value is not finite, or a hook may set them): the next
        // skipping pass zeros them first.
        self.zero_tangent_lanes = 0;
        0
    }
}

/// The sparse LU factorizations of a tape's sparse linear solves (kept between calls so
/// that pivots are replayed).
#[derive(Clone, Debug, Default)]
pub(crate) struct SparseSolves {
    /// Id of the tape these belong to (0: none).
    pub(crate) tape: u64,
    pub(crate) lu: Vec<SparseLu>,
    pub(crate) scratch: Vec<f64>,
}

impl Workspace {
    /// For each sparse linear solve of the last evaluated tape: its size, the entries
    /// of its matrix, the entries of its LU factors (diagonal included) and the
    /// multiply-adds of one refactorization (0 before the first evaluation). For logs
    /// and benchmarks.
    pub fn sparse_factor_sizes(&self) -> Vec<(usize, usize, usize, usize)> {
        self.sparse
            .lu
            .iter()
            .filter(|lu| lu.size() > 0)
            .map(|lu| {
                (
                    lu.size(),
                    lu.pattern_nnz(),
                    lu.factor_nnz(),
                    lu.refactor_flops(),
                )
            })
            .collect()
    }

    /// Makes sure the buffers fit `tape` with `lanes` tangent directions.
    pub(crate) fn fit(&mut self, tape: &Tape, lanes: usize) {
        let n = tape.ops.len();
        if self.regs.len() < n {
            self.regs.resize(n, 0.0);
        }
        if self.tan.len() < n * lanes {
            self.tan.resize(n * lanes, 0.0);
        }
        if self.lu.len() < tape.lu_len {
            self.lu.resize(tape.lu_len, 0.0);
        }
        if self.piv.len() < tape.piv_len {
            self.piv.resize(tape.piv_len, 0);
        }
        if self.rhs.len() < tape.max_k {
            self.rhs.resize(tape.max_k, 0.0);
        }
        if self.sparse.tape != tape.id {
            self.sparse.tape = tape.id;
            self.sparse.lu = tape
                .ls
                .iter()
                .map(|info| {
                    let mut lu = SparseLu::default();
                    if let Some(p) = &info.sparse {
                        lu.reset(info.k, &p.col_ptr, &p.row_idx);
                    }
                    lu
                })
                .collect();
        }
    }
}

/// Relative pivot size below which a linear system counts as singular.
const PIVOT_TOL: f64 = 1e-13;

/// `sign(x)` as -1, 0 or 1.
#[inline]
pub(crate) fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// Value of a non-linear-solve instruction.
#[inline(always)]
pub(crate) fn value(op: Op, consts: &[f64], inputs: &[f64], regs: &[f64]) -> f64 {
    let r = |x: u32| regs[x as usize];
    match op {
        Op::Const(k) => consts[k as usize],
        Op::Input(s) => inputs[s as usize],
        Op::Add(a, b) => r(a) + r(b),
        Op::Sub(a, b) => r(a) - r(b),
        Op::Mul(a, b) => r(a) * r(b),
        Op::Div(a, b) => r(a) / r(b),
        Op::Neg(a) => -r(a),
        Op::Scale(k, a) => consts[k as usize] * r(a),
        Op::AddScaled(a, k, b) => r(a) + consts[k as usize] * r(b),
        Op::PowI(a, n) => r(a).powi(n),
        Op::Pow(a, b) => r(a).powf(r(b)),
        Op::F1(f, a) => f.apply(r(a)),
        Op::F2(f, a, b) => f.apply(r(a), r(b)),
        Op::Cmp(c, a, b) => c.apply(r(a), r(b)),
        Op::Select(c, a, b) => {
            if r(c) != 0.0 {
                r(a)
            } else {
                r(b)
            }
        }
        // Handled by the callers; never reached.
        Op::LinearSolve(_) | Op::LsPart => f64::NAN,
    }
}

/// Factors and solves the linear system of `info`, whose solution goes to
/// `regs[at .. at + k]`. The LU factors and pivots stay in `lu` / `piv` for tangents.
pub(crate) fn solve_linear(
    info: &LsInfo,
    s: usize,
    at: usize,
    regs: &mut [f64],
    lu: &mut [f64],
    piv: &mut [usize],
    sparse: &mut SparseSolves,
) -> Result<(), EvalError> {
    let k = info.k;
    let err = |what: &str| EvalError {
        message: format!("linear system for [{}] {}", info.names, what),
        recoverable: true,
    };
    if let Some(pattern) = &info.sparse {
        let SparseSolves {
            lu: lus, scratch, ..
        } = sparse;
        let a = &info.a[..];
        let regs_ro: &[f64] = regs;
        if let Err(LuError::Singular(m)) =
            lus[s].factorize_with(&pattern.col_ptr, &pattern.row_idx, |p| {
                regs_ro[a[p] as usize]
            })
        {
            return Err(err(&format!("is singular ({m})")));
        }
        let (before, after) = regs.split_at_mut(at);
        let x = &mut after[..k];
        for (xi, &ci) in x.iter_mut().zip(&info.c) {
            *xi = -before[ci as usize];
        }
        lus[s].solve_in_place(x, scratch);
        if x.iter().any(|v| !v.is_finite()) {
            return Err(err("has a non-finite solution"));
        }
        return Ok(());
    }
    if k == 1 {
        let a = regs[info.a[0] as usize];
        let c = regs[info.c[0] as usize];
        let x = -c / a;
        if a == 0.0 || !x.is_finite() {
            return Err(err(&format!("is singular or ill-posed (a = {a}, c = {c})")));
        }
        lu[info.lu_off] = a;
        piv[info.piv_off] = 0;
        regs[at] = x;
        return Ok(());
    }
    let m = &mut lu[info.lu_off..info.lu_off + k * k];
    let p = &mut piv[info.piv_off..info.piv_off + k];
    let mut scale = 0.0f64;
    for (dst, &src) in m.iter_mut().zip(&info.a) {
        *dst = regs[src as usize];
        scale = scale.max(dst.abs());
    }
    if !scale.is_finite() {
        return Err(err("has a non-finite matrix entry"));
    }
    let tol = scale * PIVOT_TOL;
    for col in 0..k {
        let mut best = col;
        let mut best_abs = m[col * k + col].abs();
        for row in col + 1..k {
            let v = m[row * k + col].abs();
            if v > best_abs {
                best = row;
                best_abs = v;
            }
        }
        if best_abs <= tol || best_abs == 0.0 {
            return Err(err(&format!(
                "is singular (pivot {best_abs:e} in column {col}, matrix scale {scale:e})"
            )));
        }
        p[col] = best;
        if best != col {
            for j in 0..k {
                m.swap(col * k + j, best * k + j);
            }
        }
        let d = m[col * k + col];
        for row in col + 1..k {
            let f = m[row * k + col] / d;
            m[row * k + col] = f;
            if f != 0.0 {
                for j in col + 1..k {
                    m[row * k + j] -= f * m[col * k + j];
                }
            }
        }
    }
    let (before, after) = regs.split_at_mut(at);
    let x = &mut after[..k];
    for (xi, &ci) in x.iter_mut().zip(&info.c) {
        *xi = -before[ci as usize];
    }
    lu_solve(m, p, x);
    if x.iter().any(|v| !v.is_finite()) {
        return Err(err("has a non-finite solution"));
    }
    Ok(())
}

/// Solves `A x = b` in place from the LU factors of `A` (row swaps `p`, unit lower `L`
/// and upper `U` stored together row-major in `m`).
#[inline]
pub(crate) fn lu_solve(m: &[f64], p: &[usize], b: &mut [f64]) {
    let k = b.len();
    if k == 1 {
        b[0] /= m[0];
        return;
    }
    for (col, &pc) in p.iter().enumerate() {
        b.swap(col, pc);
    }
    for i in 1..k {
        let row = &m[i * k..i * k + i];
        let s: f64 = row.iter().zip(&b[..i]).map(|(l, x)| l * x).sum();
        b[i] -= s;
    }
    for i in (0..k).rev() {
        let row = &m[i * k + i + 1..(i + 1) * k];
        let s: f64 = row.iter().zip(&b[i + 1..]).map(|(u, x)| u * x).sum();
        b[i] = (b[i] - s) / m[i * k + i];
    }
}

impl Tape {
    /// Whether output `k < n` is `inputs[first + k]` minus a register that depends on
    /// none of the inputs `first..first + n` (or that input alone), and no further
    /// output reads them: the residual of an explicit ODE when those inputs are the
    /// derivatives of the unknowns.
    pub fn is_explicit_in(&self, n: usize, first: usize) -> bool {
        if self.outputs.len() < n {
            return false;
        }
        let dep = self.dependence(first..first + n);
        let is_input = |r: u32, k: usize| self.ops[r as usize] == Op::Input((first + k) as u32);
        self.outputs.iter().enumerate().all(|(k, &o)| {
            if k >= n {
                return !dep[o as usize];
            }
            match self.ops[o as usize] {
                Op::Sub(a, b) => is_input(a, k) && !dep[b as usize],
                _ => is_input(o, k),
            }
        })
    }

    /// Per register: whether it depends on one of the input slots `slots`.
    fn dependence(&self, slots: std::ops::Range<usize>) -> Vec<bool> {
        let mut dep = vec![false; self.ops.len()];
        for (i, op) in self.ops.iter().enumerate() {
            dep[i] = match *op {
                Op::Input(s) => slots.contains(&(s as usize)),
                Op::LsPart => dep[i - 1],
                _ => {
                    let mut any = false;
                    op.for_each_operand(&self.ls, |r| any |= dep[r as usize]);
                    any
                }
            };
        }
        dep
    }

    /// Whether one of the outputs `outputs` depends on one of the input slots `slots`.
    ///
    /// # Panics
    /// If an output index is out of range.
    pub fn outputs_read(&self, outputs: &[usize], slots: std::ops::Range<usize>) -> bool {
        let dep = self.dependence(slots);
        outputs.iter().any(|&k| dep[self.outputs[k] as usize])
    }

    /// Number of input slots.
    pub fn n_inputs(&self) -> usize {
        self.n_inputs
    }

    /// Number of outputs.
    pub fn n_outputs(&self) -> usize {
        self.outputs.len()
    }

    /// Number of instructions (equal to the number of registers).
    pub fn len(&self) -> usize {
        self.ops.len()
    }

    /// Number of instructions of each kind (`"add"`, `"sin"`, ...), sorted by name: a
    /// profile of what evaluating the tape costs.
    pub fn op_counts(&self) -> Vec<(String, usize)> {
        let mut counts: std::collections::BTreeMap<String, usize> = Default::default();
        for op in &self.ops {
            let name = match op {
                Op::Const(_) => "const".to_string(),
                Op::Input(_) => "input".to_string(),
                Op::Add(..) => "add".to_string(),
                Op::Sub(..) => "sub".to_string(),
                Op::Mul(..) => "mul".to_string(),
                Op::Div(..) => "div".to_string(),
                Op::Neg(_) => "neg".to_string(),
                Op::Scale(..) => "scale".to_string(),
                Op::AddScaled(..) => "add_scaled".to_string(),
                Op::PowI(..) => "powi".to_string(),
                Op::Pow(..) => "pow".to_string(),
                Op::F1(f, _) => format!("{f:?}").to_lowercase(),
                Op::F2(f, ..) => format!("{f:?}").to_lowercase(),
                Op::Cmp(..) => "cmp".to_string(),
                Op::Select(..) => "select".to_string(),
                Op::LinearSolve(_) => "linear_solve".to_string(),
                Op::LsPart => "linear_solve_part".to_string(),
            };
            *counts.entry(name).or_default() += 1;
        }
        counts.into_iter().collect()
    }

    /// Number of runs: maximal sequences of instructions that evaluation dispatches once
    /// (see the instruction scheduling in `schedule.rs`).
    pub fn runs(&self) -> usize {
        self.runs.len()
    }

    /// Number of instructions in the prelude: those that depend only on constants and
    /// the invariant inputs (see [`TapeBuilder::invariant_inputs`]), evaluated once per
    /// workspace and value of those inputs.
    ///
    /// [`TapeBuilder::invariant_inputs`]: super::TapeBuilder::invariant_inputs
    pub fn prelude_len(&self) -> usize {
        self.prelude_len
    }

    /// Whether the tape has no instruction.
    pub fn is_empty(&self) -> bool {
        self.ops.is_empty()
    }

    /// A workspace sized for this tape (registers, linear-solve factors), reusable
    /// across calls.
    pub fn workspace(&self) -> Workspace {
        let mut ws = Workspace::default();
        ws.fit(self, 0);
        ws
    }

    /// Evaluates the tape: `inputs` holds at least [`n_inputs`](Self::n_inputs) values,
    /// the outputs are written to `out` (length [`n_outputs`](Self::n_outputs)).
    /// Non-finite values propagate to the outputs; only a failing linear solve (singular
    /// matrix or non-finite solution) is an error, and a recoverable one.
    ///
    /// # Panics
    /// If `inputs` or `out` is too short.
    pub fn eval(
        &self,
        inputs: &[f64],
        ws: &mut Workspace,
        out: &mut [f64],
    ) -> Result<(), EvalError> {
        assert!(
            inputs.len() >= self.n_inputs,
            "Tape::eval: {} inputs given, {} needed",
            inputs.len(),
            self.n_inputs
        );
        assert!(
            out.len() >= self.outputs.len(),
            "Tape::eval: output buffer too short"
        );
        ws.fit(self, 0);
        let skip = ws.prelude.value_pass(self, inputs);
        let Workspace {
            regs,
            lu,
            piv,
            sparse,
            ..
        } = ws;
        let regs = &mut regs[..self.ops.len()];
        let consts = &self.consts[..];
        let ops = &self.ops[..];
        macro_rules! each {
            ($run:expr, $pat:pat => $value:expr) => {
                for i in $run.start as usize..$run.end as usize {
                    if let $pat = ops[i] {
                        regs[i] = $value;
                    }
                }
            };
        }
        for run in &self.runs[skip..] {
            match run.kind {
                RunKind::Const => each!(run, Op::Const(k) => consts[k as usize]),
                RunKind::Input => each!(run, Op::Input(s) => inputs[s as usize]),
                RunKind::Add => each!(run, Op::Add(a, b) => regs[a as usize] + regs[b as usize]),
                RunKind::Sub => each!(run, Op::Sub(a, b) => regs[a as usize] - regs[b as usize]),
                RunKind::Mul => each!(run, Op::Mul(a, b) => regs[a as usize] * regs[b as usize]),
                RunKind::Div => each!(run, Op::Div(a, b) => regs[a as usize] / regs[b as usize]),
                RunKind::Neg => each!(run, Op::Neg(a) => -regs[a as usize]),
                RunKind::Scale => {
                    each!(run, Op::Scale(k, a) => consts[k as usize] * regs[a as usize])
                }
                RunKind::AddScaled => each!(
                    run,
                    Op::AddScaled(a, k, b) => regs[a as usize] + consts[k as usize] * regs[b as usize]
                ),
                RunKind::Other => {
                    for i in run.start as usize..run.end as usize {
                        match ops[i] {
                            Op::LinearSolve(s) => solve_linear(
                                &self.ls[s as usize],
                                s as usize,
                                i,
                                regs,
                                lu,
                                piv,
                                sparse,
                            )?,
                            Op::LsPart => {}
                            op => regs[i] = value(op, consts, inputs, regs),
                        }
                    }
                }
            }
        }
        for (o, &r) in out.iter_mut().zip(&self.outputs) {
            *o = regs[r as usize];
        }
        Ok(())
    }
}
