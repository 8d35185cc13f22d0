//! The instruction set, the tape and its value evaluation.

use crate::expr::{Cmp, Func1, Func2};

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

/// A dense linear system `A x + c = 0` solved inside the tape.
#[derive(Clone, Debug)]
pub(crate) struct LsInfo {
    /// Dimension.
    pub(crate) k: usize,
    /// Registers of `A`, row-major.
    pub(crate) a: Vec<u32>,
    /// Registers of `c`.
    pub(crate) c: Vec<u32>,
    /// Offset of this system's LU factors in the workspace (k*k entries).
    pub(crate) lu_off: usize,
    /// Offset of this system's pivots in the workspace (k entries).
    pub(crate) piv_off: usize,
    /// The unknowns solved for, for error messages.
    pub(crate) names: String,
}

/// A compiled straight-line program: inputs in, outputs out. Independent of the arena
/// it was compiled from; `Send + Sync` and cheap to share.
#[derive(Clone, Debug)]
pub struct Tape {
    pub(crate) ops: Vec<Op>,
    pub(crate) consts: Vec<f64>,
    pub(crate) ls: Vec<LsInfo>,
    pub(crate) outputs: Vec<u32>,
    pub(crate) n_inputs: usize,
    pub(crate) lu_len: usize,
    pub(crate) piv_len: usize,
    pub(crate) max_k: usize,
}

/// Scratch memory for evaluating a [`Tape`]: registers, tangents and linear-solve
/// factors. Reusable across calls (and across tapes; it grows when needed), so
/// evaluation does not allocate.
#[derive(Clone, Debug, Default)]
pub struct Workspace {
    pub(crate) regs: Vec<f64>,
    pub(crate) tan: Vec<f64>,
    pub(crate) lu: Vec<f64>,
    pub(crate) piv: Vec<usize>,
    pub(crate) rhs: Vec<f64>,
}

impl Workspace {
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
    at: usize,
    regs: &mut [f64],
    lu: &mut [f64],
    piv: &mut [usize],
) -> Result<(), EvalError> {
    let k = info.k;
    let err = |what: &str| EvalError {
        message: format!("linear system for [{}] {}", info.names, what),
        recoverable: true,
    };
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
        let Workspace { regs, lu, piv, .. } = ws;
        let regs = &mut regs[..self.ops.len()];
        let consts = &self.consts[..];
        for (i, &op) in self.ops.iter().enumerate() {
            match op {
                Op::LinearSolve(s) => solve_linear(&self.ls[s as usize], i, regs, lu, piv)?,
                Op::LsPart => {}
                _ => regs[i] = value(op, consts, inputs, regs),
            }
        }
        for (o, &r) in out.iter_mut().zip(&self.outputs) {
            *o = regs[r as usize];
        }
        Ok(())
    }
}
