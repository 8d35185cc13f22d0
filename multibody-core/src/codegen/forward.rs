//! Forward-mode differentiation of a tape in several directions (lanes) at once.

use crate::expr::{Func1, Func2};

use super::EvalError;
use super::tape::{Op, RunKind, Tape, Workspace, lu_solve, sign, solve_linear, value};

/// Derivative of a unary function at `a`, given its value `v = f(a)`.
#[inline]
fn d_f1(f: Func1, a: f64, v: f64) -> f64 {
    match f {
        Func1::Sin => a.cos(),
        Func1::Cos => -a.sin(),
        Func1::Tan => 1.0 + v * v,
        Func1::Asin => 1.0 / (1.0 - a * a).sqrt(),
        Func1::Acos => -1.0 / (1.0 - a * a).sqrt(),
        Func1::Atan => 1.0 / (1.0 + a * a),
        Func1::Exp => v,
        Func1::Log => 1.0 / a,
        Func1::Sqrt => 0.5 / v,
        Func1::Abs => sign(a),
        Func1::Sign => 0.0,
        Func1::Sinh => a.cosh(),
        Func1::Cosh => a.sinh(),
        Func1::Tanh => 1.0 - v * v,
        Func1::NoEvent => 1.0,
        Func1::Pre => 0.0,
    }
}

/// `t[l] = ca * ta[l] + cb * tb[l]`, skipping terms whose tangent is zero (so that an
/// infinite partial derivative times a zero direction stays zero).
#[inline(always)]
fn combine(t: &mut [f64], ca: f64, ta: &[f64], cb: f64, tb: &[f64]) {
    for ((t, &x), &y) in t.iter_mut().zip(ta).zip(tb) {
        let mut s = 0.0;
        if x != 0.0 {
            s += ca * x;
        }
        if y != 0.0 {
            s += cb * y;
        }
        *t = s;
    }
}

/// Tangents of instruction `i` (anything but a linear solve) into `t` (`w` lanes), from
/// the tangents of earlier registers in `done` (`done[r * w + lane]`) and the values in
/// `regs`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn op_tangent(
    op: Op,
    i: usize,
    regs: &[f64],
    consts: &[f64],
    seeds: &[f64],
    done: &[f64],
    t: &mut [f64],
    w: usize,
) {
    let tr = |x: u32| &done[x as usize * w..x as usize * w + w];
    let r = |x: u32| regs[x as usize];
    match op {
        Op::Const(_) => t.fill(0.0),
        Op::Input(s) => t.copy_from_slice(&seeds[s as usize * w..s as usize * w + w]),
        Op::Add(a, b) => {
            for ((t, x), y) in t.iter_mut().zip(tr(a)).zip(tr(b)) {
                *t = x + y;
            }
        }
        Op::Sub(a, b) => {
            for ((t, x), y) in t.iter_mut().zip(tr(a)).zip(tr(b)) {
                *t = x - y;
            }
        }
        Op::Mul(a, b) => {
            let (va, vb) = (r(a), r(b));
            for ((t, x), y) in t.iter_mut().zip(tr(a)).zip(tr(b)) {
                *t = x * vb + va * y;
            }
        }
        Op::Div(a, b) => {
            let (v, vb) = (regs[i], r(b));
            for ((t, x), y) in t.iter_mut().zip(tr(a)).zip(tr(b)) {
                *t = (x - v * y) / vb;
            }
        }
        Op::Neg(a) => {
            for (t, x) in t.iter_mut().zip(tr(a)) {
                *t = -x;
            }
        }
        Op::Scale(k, a) => {
            let k = consts[k as usize];
            for (t, x) in t.iter_mut().zip(tr(a)) {
                *t = k * x;
            }
        }
        Op::AddScaled(a, k, b) => {
            let k = consts[k as usize];
            for ((t, x), y) in t.iter_mut().zip(tr(a)).zip(tr(b)) {
                *t = x + k * y;
            }
        }
        Op::PowI(a, e) => {
            let d = f64::from(e) * r(a).powi(e - 1);
            for (t, x) in t.iter_mut().zip(tr(a)) {
                *t = if *x != 0.0 { d * x } else { 0.0 };
            }
        }
        Op::Pow(a, b) => {
            let (va, vb, v) = (r(a), r(b), regs[i]);
            let ca = vb * va.powf(vb - 1.0);
            let cb = v * va.ln();
            combine(t, ca, tr(a), cb, tr(b));
        }
        Op::F1(f, a) => {
            let d = d_f1(f, r(a), regs[i]);
            for (t, x) in t.iter_mut().zip(tr(a)) {
                *t = if *x != 0.0 { d * x } else { 0.0 };
            }
        }
        Op::F2(f, a, b) => {
            let (va, vb) = (r(a), r(b));
            let (ca, cb) = match f {
                Func2::Atan2 => {
                    let q = va * va + vb * vb;
                    (vb / q, -va / q)
                }
                Func2::Min => {
                    if va <= vb || vb.is_nan() {
                        (1.0, 0.0)
                    } else {
                        (0.0, 1.0)
                    }
                }
                Func2::Max => {
                    if va >= vb || vb.is_nan() {
                        (1.0, 0.0)
                    } else {
                        (0.0, 1.0)
                    }
                }
            };
            combine(t, ca, tr(a), cb, tr(b));
        }
        Op::Cmp(..) => t.fill(0.0),
        Op::Select(c, a, b) => {
            let src = if r(c) != 0.0 { a } else { b };
            t.copy_from_slice(tr(src));
        }
        Op::LinearSolve(_) | Op::LsPart => {}
    }
}

impl Tape {
    /// Forward mode with `lanes` directions at once. `seeds` is the dense input-major
    /// matrix of input tangents (`seeds[slot * lanes + lane]`, length
    /// `n_inputs * lanes`); the output tangents go to `out_tangents`
    /// (`out_tangents[output * lanes + lane]`, length `n_outputs * lanes`) and the
    /// values to `out`. Linear solves are differentiated exactly
    /// (`dx = -A^{-1} (dA x + dc)` with the factors of the value pass); `Select` takes
    /// the tangent of the chosen branch, comparisons and `sign` have zero tangent.
    ///
    /// # Panics
    /// If a slice is too short.
    pub fn forward(
        &self,
        inputs: &[f64],
        seeds: &[f64],
        lanes: usize,
        ws: &mut Workspace,
        out: &mut [f64],
        out_tangents: &mut [f64],
    ) -> Result<(), EvalError> {
        let n = self.ops.len();
        assert!(
            inputs.len() >= self.n_inputs,
            "Tape::forward: too few inputs"
        );
        assert!(
            seeds.len() >= self.n_inputs * lanes,
            "Tape::forward: too few seeds"
        );
        assert!(
            out.len() >= self.outputs.len(),
            "Tape::forward: output buffer too short"
        );
        assert!(
            out_tangents.len() >= self.outputs.len() * lanes,
            "Tape::forward: tangent buffer too short"
        );
        ws.fit(self, lanes);
        let Workspace {
            regs,
            tan,
            lu,
            piv,
            rhs,
            sparse,
            prelude,
        } = ws;
        let regs = &mut regs[..n];
        let tan = &mut tan[..n * lanes];
        let w = lanes;
        let (a, b) = self.invariant_inputs;
        let params_unseeded = seeds[a * w..b * w].iter().all(|&s| s == 0.0);
        let skip = prelude.forward_pass(self, inputs, w, tan, params_unseeded);
        forward_core(
            self,
            inputs,
            seeds,
            w,
            regs,
            tan,
            skip,
            |i, s, regs, done, rest| {
                // A x + c = 0  =>  A dx = -(dA x + dc).
                let info = &self.ls[s as usize];
                solve_linear(info, s as usize, i, regs, lu, piv, sparse)?;
                let k = info.k;
                let x = &regs[i..i + k];
                let rhs = &mut rhs[..k];
                let t = &mut rest[..k * w];
                for l in 0..w {
                    for (row, b) in rhs.iter_mut().enumerate() {
                        *b = -done[info.c[row] as usize * w + l];
                    }
                    match &info.sparse {
                        Some(pattern) => {
                            for col in 0..k {
                                for p in pattern.col_ptr[col]..pattern.col_ptr[col + 1] {
                                    rhs[pattern.row_idx[p]] -=
                                        done[info.a[p] as usize * w + l] * x[col];
                                }
                            }
                            sparse.lu[s as usize].solve_in_place(rhs, &mut sparse.scratch);
                        }
                        None => {
                            for (row, b) in rhs.iter_mut().enumerate() {
                                for (col, &xc) in x.iter().enumerate() {
                                    *b -= done[info.a[row * k + col] as usize * w + l] * xc;
                                }
                            }
                            let m = &lu[info.lu_off..info.lu_off + k * k];
                            let p = &piv[info.piv_off..info.piv_off + k];
                            lu_solve(m, p, rhs);
                        }
                    }
                    for (j, &v) in rhs.iter().enumerate() {
                        t[j * w + l] = v;
                    }
                }
                Ok(())
            },
            |_, _| {},
        )?;
        for (o, &r) in self.outputs.iter().enumerate() {
            out[o] = regs[r as usize];
            out_tangents[o * w..o * w + w]
                .copy_from_slice(&tan[r as usize * w..r as usize * w + w]);
        }
        Ok(())
    }
}

/// The forward sweep shared by [`Tape::forward`] and the extended Jacobian: values and
/// `w`-lane tangents of every instruction, run by run (a loop per kind of run).
/// `linear_solve(i, s, regs, done, rest)` computes the values and tangents of linear
/// solve `s` at register `i` (tangents of earlier registers in `done`, its own from the
/// start of `rest`); `after(i, t)` may rewrite the tangent of instruction `i` (not
/// called for linear solves). The first `skip` runs (at most the prelude, whose values
/// and tangents the caller knows) are not evaluated.
#[inline(always)]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub(crate) fn forward_core(
    tape: &Tape,
    inputs: &[f64],
    seeds: &[f64],
    w: usize,
    regs: &mut [f64],
    tan: &mut [f64],
    skip: usize,
    mut linear_solve: impl FnMut(usize, u32, &mut [f64], &[f64], &mut [f64]) -> Result<(), EvalError>,
    mut after: impl FnMut(usize, &mut [f64]),
) -> Result<(), EvalError> {
    let ops = &tape.ops[..];
    let consts = &tape.consts[..];
    // `$pat` binds the operands; `$val` computes the value; `$tan(t, regs, tr)` the
    // tangent lanes from the operands' tangents (`tr(register)`).
    macro_rules! each {
        ($run:expr, $pat:pat => $val:expr, |$t:ident, $v:ident, $tr:ident| $body:block) => {
            for i in $run.start as usize..$run.end as usize {
                if let $pat = ops[i] {
                    let value = $val;
                    regs[i] = value;
                    let (done, rest) = tan.split_at_mut(i * w);
                    let $t = &mut rest[..w];
                    let $v = value;
                    let $tr = |x: u32| &done[x as usize * w..x as usize * w + w];
                    $body
                    after(i, $t);
                }
            }
        };
    }
    for run in &tape.runs[skip..] {
        match run.kind {
            RunKind::Const => each!(run, Op::Const(k) => consts[k as usize], |t, _v, _tr| {
                t.fill(0.0);
            }),
            RunKind::Input => each!(run, Op::Input(s) => inputs[s as usize], |t, _v, _tr| {
                t.copy_from_slice(&seeds[s as usize * w..s as usize * w + w]);
            }),
            RunKind::Add => {
                each!(run, Op::Add(a, b) => regs[a as usize] + regs[b as usize], |t, _v, tr| {
                    for ((t, x), y) in t.iter_mut().zip(tr(a)).zip(tr(b)) {
                        *t = x + y;
                    }
                })
            }
            RunKind::Sub => {
                each!(run, Op::Sub(a, b) => regs[a as usize] - regs[b as usize], |t, _v, tr| {
                    for ((t, x), y) in t.iter_mut().zip(tr(a)).zip(tr(b)) {
                        *t = x - y;
                    }
                })
            }
            RunKind::Mul => {
                each!(run, Op::Mul(a, b) => regs[a as usize] * regs[b as usize], |t, _v, tr| {
                    let (va, vb) = (regs[a as usize], regs[b as usize]);
                    for ((t, x), y) in t.iter_mut().zip(tr(a)).zip(tr(b)) {
                        *t = x * vb + va * y;
                    }
                })
            }
            RunKind::Div => {
                each!(run, Op::Div(a, b) => regs[a as usize] / regs[b as usize], |t, v, tr| {
                    let vb = regs[b as usize];
                    for ((t, x), y) in t.iter_mut().zip(tr(a)).zip(tr(b)) {
                        *t = (x - v * y) / vb;
                    }
                })
            }
            RunKind::Neg => each!(run, Op::Neg(a) => -regs[a as usize], |t, _v, tr| {
                for (t, x) in t.iter_mut().zip(tr(a)) {
                    *t = -x;
                }
            }),
            RunKind::Scale => {
                each!(run, Op::Scale(k, a) => consts[k as usize] * regs[a as usize], |t, _v, tr| {
                    let k = consts[k as usize];
                    for (t, x) in t.iter_mut().zip(tr(a)) {
                        *t = k * x;
                    }
                })
            }
            RunKind::AddScaled => each!(
                run,
                Op::AddScaled(a, k, b) => regs[a as usize] + consts[k as usize] * regs[b as usize],
                |t, _v, tr| {
                    let k = consts[k as usize];
                    for ((t, x), y) in t.iter_mut().zip(tr(a)).zip(tr(b)) {
                        *t = x + k * y;
                    }
                }
            ),
            RunKind::Other => {
                for i in run.start as usize..run.end as usize {
                    match ops[i] {
                        Op::LsPart => {}
                        Op::LinearSolve(s) => {
                            let (done, rest) = tan.split_at_mut(i * w);
                            linear_solve(i, s, regs, done, rest)?;
                        }
                        op => {
                            regs[i] = value(op, consts, inputs, regs);
                            let (done, rest) = tan.split_at_mut(i * w);
                            let t = &mut rest[..w];
                            op_tangent(op, i, regs, consts, seeds, done, t, w);
                            after(i, t);
                        }
                    }
                }
            }
        }
    }
    Ok(())
}
