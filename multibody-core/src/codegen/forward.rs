//! Forward-mode differentiation of a tape in several directions (lanes) at once.

use crate::expr::{Func1, Func2};

use super::EvalError;
use super::tape::{Op, Tape, Workspace, lu_solve, sign, solve_linear, value};

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
        } = ws;
        let regs = &mut regs[..n];
        let tan = &mut tan[..n * lanes];
        let consts = &self.consts[..];
        let w = lanes;
        for (i, &op) in self.ops.iter().enumerate() {
            // Values.
            match op {
                Op::LinearSolve(s) => solve_linear(&self.ls[s as usize], i, regs, lu, piv)?,
                Op::LsPart => continue,
                _ => regs[i] = value(op, consts, inputs, regs),
            }
            // Tangents.
            let (done, rest) = tan.split_at_mut(i * w);
            let t = &mut rest[..w];
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
                Op::LinearSolve(s) => {
                    // A x + c = 0  =>  A dx = -(dA x + dc).
                    let info = &self.ls[s as usize];
                    let k = info.k;
                    let x = &regs[i..i + k];
                    let m = &lu[info.lu_off..info.lu_off + k * k];
                    let p = &piv[info.piv_off..info.piv_off + k];
                    let rhs = &mut rhs[..k];
                    let t = &mut rest[..k * w];
                    for l in 0..w {
                        for (row, b) in rhs.iter_mut().enumerate() {
                            let mut s = done[info.c[row] as usize * w + l];
                            for (col, &xc) in x.iter().enumerate() {
                                s += done[info.a[row * k + col] as usize * w + l] * xc;
                            }
                            *b = -s;
                        }
                        lu_solve(m, p, rhs);
                        for (j, &v) in rhs.iter().enumerate() {
                            t[j * w + l] = v;
                        }
                    }
                }
                Op::LsPart => {}
            }
        }
        for (o, &r) in self.outputs.iter().enumerate() {
            out[o] = regs[r as usize];
            out_tangents[o * w..o * w + w]
                .copy_from_slice(&tan[r as usize * w..r as usize * w + w]);
        }
        Ok(())
    }
}
