//! Tests of the tape compiler, evaluation, forward mode and sparse Jacobian.

use std::collections::BTreeSet;

use crate::expr::{Arena, Cmp, Func1, Func2, Id, Node};

use super::tape::Op;
use super::*;

/// A tiny deterministic random generator (64-bit LCG).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// A tape computing `outputs` of variables `0..n_vars` bound to input slots `0..n_vars`.
fn tape_of(arena: &Arena, vars: &[Id], outputs: &[Id]) -> Tape {
    let mut b = TapeBuilder::new(arena, vars.len());
    for (i, &v) in vars.iter().enumerate() {
        b.input(v, i);
    }
    for &o in outputs {
        b.output(o).unwrap();
    }
    b.build()
}

/// Checks the forward tangents of every output against central finite differences of
/// `eval`, in all input directions at once.
fn check_forward(tape: &Tape, x: &[f64], what: &str) {
    let ni = tape.n_inputs();
    let no = tape.n_outputs();
    let mut ws = tape.workspace();
    let mut seeds = vec![0.0; ni * ni];
    for i in 0..ni {
        seeds[i * ni + i] = 1.0;
    }
    let mut out = vec![0.0; no];
    let mut tan = vec![0.0; no * ni];
    tape.forward(x, &seeds, ni, &mut ws, &mut out, &mut tan)
        .unwrap();
    let mut plain = vec![0.0; no];
    tape.eval(x, &mut ws, &mut plain).unwrap();
    assert_eq!(out, plain, "{what}: forward values differ from eval");
    let h = 1e-6;
    let (mut op, mut om) = (vec![0.0; no], vec![0.0; no]);
    for j in 0..ni {
        let mut xp = x.to_vec();
        let mut xm = x.to_vec();
        xp[j] += h;
        xm[j] -= h;
        tape.eval(&xp, &mut ws, &mut op).unwrap();
        tape.eval(&xm, &mut ws, &mut om).unwrap();
        for o in 0..no {
            let fd = (op[o] - om[o]) / (2.0 * h);
            let ad = tan[o * ni + j];
            assert!(
                (fd - ad).abs() <= 1e-6 * (1.0 + ad.abs()),
                "{what}: output {o}, input {j} at {x:?}: forward {ad}, finite difference {fd}"
            );
        }
    }
}

/// Variant names of the instructions of a tape.
fn op_names(tape: &Tape) -> BTreeSet<String> {
    tape.ops
        .iter()
        .map(|op| format!("{op:?}").split('(').next().unwrap().to_string())
        .collect()
}

#[test]
fn op_is_small() {
    assert!(std::mem::size_of::<Op>() <= 16);
}

#[test]
fn forward_matches_finite_differences_for_every_op() {
    let mut a = Arena::new();
    let x = a.var(0);
    let y = a.var(1);
    type Build = fn(&mut Arena, Id, Id) -> Id;
    let cases: Vec<(&str, Build)> = vec![
        ("add", |a, x, y| a.add(x, y)),
        ("sub", |a, x, y| a.sub(x, y)),
        ("mul", |a, x, y| a.mul(x, y)),
        ("div", |a, x, y| a.div(x, y)),
        ("neg", |a, x, _| a.neg(x)),
        ("scale", |a, x, _| a.scale(3.5, x)),
        ("affine", |a, x, y| {
            a.linear_combination(2.0, &[(2.5, x), (-0.5, y)])
        }),
        ("sum-neg-first", |a, x, y| {
            a.linear_combination(0.0, &[(-1.0, x), (1.0, y)])
        }),
        ("powi", |a, x, _| a.powi(x, 3)),
        ("powi-neg", |a, x, _| a.powi(x, -2)),
        ("prod-mixed", |a, x, y| {
            let p = a.powi(x, 2);
            let q = a.powi(y, -3);
            a.mul(p, q)
        }),
        ("prod-two-den", |a, x, y| {
            let s = a.add(x, y);
            let d = a.mul(y, s);
            let one = a.one();
            a.div(one, d)
        }),
        ("pow", |a, x, y| a.pow(x, y)),
        ("pow-const", |a, x, _| {
            let e = a.constant(2.5);
            a.pow(x, e)
        }),
        ("sin", |a, x, _| a.f1(Func1::Sin, x)),
        ("cos", |a, x, _| a.f1(Func1::Cos, x)),
        ("tan", |a, x, _| a.f1(Func1::Tan, x)),
        ("asin", |a, x, _| a.f1(Func1::Asin, x)),
        ("acos", |a, x, _| a.f1(Func1::Acos, x)),
        ("atan", |a, x, _| a.f1(Func1::Atan, x)),
        ("exp", |a, x, _| a.f1(Func1::Exp, x)),
        ("log", |a, x, _| a.f1(Func1::Log, x)),
        ("sqrt", |a, x, _| a.f1(Func1::Sqrt, x)),
        ("abs", |a, x, y| {
            let d = a.sub(x, y);
            a.f1(Func1::Abs, d)
        }),
        ("sign", |a, x, y| {
            let d = a.sub(x, y);
            let s = a.f1(Func1::Sign, d);
            a.mul(s, x)
        }),
        ("sinh", |a, x, _| a.f1(Func1::Sinh, x)),
        ("cosh", |a, x, _| a.f1(Func1::Cosh, x)),
        ("tanh", |a, x, _| a.f1(Func1::Tanh, x)),
        ("atan2", |a, x, y| a.f2(Func2::Atan2, x, y)),
        ("atan2-neg", |a, x, y| {
            let m = a.neg(y);
            a.f2(Func2::Atan2, x, m)
        }),
        ("min", |a, x, y| a.f2(Func2::Min, x, y)),
        ("max", |a, x, y| a.f2(Func2::Max, x, y)),
        ("cmp", |a, x, y| a.cmp(Cmp::Lt, x, y)),
        ("select", |a, x, y| {
            let c = a.cmp(Cmp::Gt, x, y);
            let p = a.mul(x, y);
            let s = a.f1(Func1::Sin, y);
            a.ite(c, p, s)
        }),
    ];
    let mut rng = Lcg(12345);
    let mut seen = BTreeSet::new();
    for (name, build) in cases {
        let e = build(&mut a, x, y);
        let tape = tape_of(&a, &[x, y], &[e]);
        seen.extend(op_names(&tape));
        for _ in 0..20 {
            let p = [rng.range(0.2, 0.9), rng.range(0.2, 0.9)];
            if (p[0] - p[1]).abs() < 1e-3 {
                continue; // keep away from the kinks of abs, min, max and comparisons
            }
            let mut ws = tape.workspace();
            let mut out = [0.0];
            tape.eval(&p, &mut ws, &mut out).unwrap();
            let expect = a
                .eval(e, &|n| match n {
                    Node::Var(i) => Some(p[*i as usize]),
                    _ => None,
                })
                .unwrap();
            assert!(
                (out[0] - expect).abs() <= 1e-12 * (1.0 + expect.abs()),
                "{name}: tape {} vs arena {expect}",
                out[0]
            );
            check_forward(&tape, &p, name);
        }
    }
    for op in [
        "Const",
        "Input",
        "Add",
        "Sub",
        "Mul",
        "Div",
        "Neg",
        "Scale",
        "AddScaled",
        "PowI",
        "Pow",
        "F1",
        "F2",
        "Cmp",
        "Select",
    ] {
        assert!(
            seen.contains(op),
            "instruction {op} not exercised: {seen:?}"
        );
    }
}

/// A 3x3 system whose matrix and constants depend on the inputs.
fn linear_system(a: &mut Arena) -> (Vec<Id>, Vec<Id>, Stmt, Vec<Id>) {
    let x = a.var(0);
    let y = a.var(1);
    let z = a.var(2);
    let t: Vec<Id> = (10..13).map(|i| a.var(i)).collect();
    let four = a.constant(4.0);
    let e00 = a.add(four, x);
    let sz = a.f1(Func1::Sin, z);
    let yy = a.mul(y, y);
    let five = a.constant(5.0);
    let e11 = a.add(five, yy);
    let xy = a.mul(x, y);
    let six = a.constant(6.0);
    let e22 = a.add(six, xy);
    let half = a.constant(0.5);
    let one = a.one();
    let m = vec![e00, y, half, sz, e11, x, one, z, e22];
    let c0 = a.linear_combination(-1.0, &[(1.0, x)]);
    let c1 = a.mul(y, z);
    let c2 = a.f1(Func1::Exp, x);
    let c = vec![c0, c1, c2];
    let s = Stmt::LinearSolve {
        targets: t.clone(),
        a: m,
        c,
    };
    let p01 = a.mul(t[0], t[1]);
    let o3 = a.add(p01, z);
    let outs = vec![t[0], t[1], t[2], o3];
    (vec![x, y, z], t, s, outs)
}

/// The tape of [`linear_system`] with `more` outputs after its own, and the statement.
fn linear_system_tape(a: &mut Arena, more: impl Fn(&mut Arena, &[Id]) -> Vec<Id>) -> (Tape, Stmt) {
    let (vars, _targets, s, mut outs) = linear_system(a);
    outs.extend(more(a, &vars));
    let mut b = TapeBuilder::new(a, 3);
    for (i, &v) in vars.iter().enumerate() {
        b.input(v, i);
    }
    b.stmt(&s).unwrap();
    for &o in &outs {
        b.output(o).unwrap();
    }
    (b.build(), s)
}

#[test]
fn linear_solve_values_and_tangents() {
    let mut a = Arena::new();
    let (tape, s) = linear_system_tape(&mut a, |_, _| Vec::new());
    assert!(op_names(&tape).contains("LinearSolve"));
    let Stmt::LinearSolve { a: am, c: cv, .. } = &s else {
        unreachable!()
    };
    let mut rng = Lcg(7);
    for _ in 0..10 {
        let p = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        let mut ws = tape.workspace();
        let mut out = [0.0; 4];
        tape.eval(&p, &mut ws, &mut out).unwrap();
        let leaf = |n: &Node| match n {
            Node::Var(i) => Some(p[*i as usize]),
            _ => None,
        };
        for row in 0..3 {
            let mut r = a.eval(cv[row], &leaf).unwrap();
            for col in 0..3 {
                r += a.eval(am[row * 3 + col], &leaf).unwrap() * out[col];
            }
            assert!(r.abs() < 1e-12, "residual {r} in row {row}");
        }
        assert!((out[3] - (out[0] * out[1] + p[2])).abs() < 1e-12);
        check_forward(&tape, &p, "linear solve 3x3");
    }
}

#[test]
fn linear_solve_scalar_and_singular() {
    let mut a = Arena::new();
    let x = a.var(0);
    let y = a.var(1);
    let v = a.var(5);
    let w = a.var(6);
    let sv = a.f1(Func1::Sin, v);
    let x2 = a.scale(2.0, x);
    let y2 = a.scale(2.0, y);
    let one = a.one();
    let vw = a.add(v, w);
    // Scalar: x * v + y = 0.
    let mut b = TapeBuilder::new(&a, 2);
    b.input(x, 0);
    b.input(y, 1);
    b.stmt(&Stmt::LinearSolve {
        targets: vec![v],
        a: vec![x],
        c: vec![y],
    })
    .unwrap();
    b.output(sv).unwrap();
    let tape = b.build();
    let mut ws = tape.workspace();
    let mut out = [0.0];
    tape.eval(&[2.0, 3.0], &mut ws, &mut out).unwrap();
    assert!((out[0] - (-1.5f64).sin()).abs() < 1e-15);
    check_forward(&tape, &[2.0, 3.0], "scalar solve");
    let e = tape.eval(&[0.0, 3.0], &mut ws, &mut out).unwrap_err();
    assert!(e.recoverable);
    // Singular 2x2: rows proportional.
    let mut b = TapeBuilder::new(&a, 2);
    b.input(x, 0);
    b.input(y, 1);
    b.stmt(&Stmt::LinearSolve {
        targets: vec![v, w],
        a: vec![x, y, x2, y2],
        c: vec![one, one],
    })
    .unwrap();
    b.output(vw).unwrap();
    let tape = b.build();
    let mut ws = tape.workspace();
    let e = tape.eval(&[1.0, 2.0], &mut ws, &mut out).unwrap_err();
    assert!(e.recoverable);
    assert!(e.message.contains("singular"), "{}", e.message);
    // Malformed dimensions.
    let mut b = TapeBuilder::new(&a, 2);
    b.input(x, 0);
    let err = b.stmt(&Stmt::LinearSolve {
        targets: vec![v, w],
        a: vec![x],
        c: vec![x, x],
    });
    assert!(matches!(err, Err(CodegenError::BadLinearSolve(_))));
}

#[test]
fn tridiagonal_jacobian_is_exact_with_three_colours() {
    let n = 1000;
    let mut a = Arena::new();
    let u: Vec<Id> = (0..n as u32).map(|i| a.var(i)).collect();
    let yp: Vec<Id> = u.iter().map(|&v| a.der(v)).collect();
    let t = a.time();
    let mut rows = Vec::new();
    for i in 0..n {
        let mut terms = vec![(-2.0, u[i])];
        if i > 0 {
            terms.push((1.0, u[i - 1]));
        }
        if i + 1 < n {
            terms.push((1.0, u[i + 1]));
        }
        let lap = a.linear_combination(0.0, &terms);
        let r = a.sub(yp[i], lap);
        rows.push((lap, r));
    }
    let mut b = TapeBuilder::new(&a, 2 * n + 1);
    b.input(t, 0);
    for i in 0..n {
        b.input(u[i], 1 + i);
        b.input(yp[i], 1 + n + i);
    }
    for (i, &(lap, r)) in rows.iter().enumerate() {
        if i % 2 == 0 {
            b.output_input_minus(1 + n + i, lap).unwrap();
        } else {
            b.output(r).unwrap();
        }
    }
    let tape = b.build();
    let jac = DaeJacobian::new(&tape, n, 1, 1 + n);
    assert_eq!(jac.n_colors(), 3);
    assert_eq!(jac.nnz(), 3 * n - 2);
    let mut rng = Lcg(99);
    let inputs: Vec<f64> = (0..2 * n + 1).map(|_| rng.range(-1.0, 1.0)).collect();
    let mut ws = jac.workspace(&tape);
    let mut values = vec![f64::NAN; jac.nnz()];
    let cj = 0.5;
    jac.eval(&tape, &inputs, cj, &mut ws, &mut values).unwrap();
    for j in 0..n {
        let rows: Vec<usize> = jac.row_idx[jac.col_ptr[j]..jac.col_ptr[j + 1]].to_vec();
        let expect: Vec<usize> = (j.saturating_sub(1)..(j + 2).min(n)).collect();
        assert_eq!(rows, expect, "column {j}");
        let range = jac.col_ptr[j]..jac.col_ptr[j + 1];
        for (&r, &v) in jac.row_idx[range.clone()].iter().zip(&values[range]) {
            let want = if r == j { cj + 2.0 } else { -1.0 };
            assert_eq!(v, want, "entry ({r}, {j})");
        }
    }
}

#[test]
fn jacobian_with_many_colours_matches_dense_forward() {
    // Rows depending on many columns (40 colours) force several passes of 24 lanes.
    let n = 40;
    let mut a = Arena::new();
    let u: Vec<Id> = (0..n as u32).map(|i| a.var(i)).collect();
    let yp: Vec<Id> = u.iter().map(|&v| a.der(v)).collect();
    let total = a.sum(&u);
    let mut rows = Vec::new();
    for i in 0..n {
        let s = a.f1(Func1::Sin, u[i]);
        let p = a.mul(s, total);
        let q = a.mul(yp[i], u[(i + 1) % n]);
        rows.push(a.add(p, q));
    }
    let mut b = TapeBuilder::new(&a, 2 * n);
    for i in 0..n {
        b.input(u[i], i);
        b.input(yp[i], n + i);
    }
    for &r in &rows {
        b.output(r).unwrap();
    }
    let tape = b.build();
    let jac = DaeJacobian::new(&tape, n, 0, n);
    assert_eq!(jac.n_colors(), n);
    let mut rng = Lcg(3);
    let x: Vec<f64> = (0..2 * n).map(|_| rng.range(-1.0, 1.0)).collect();
    let mut ws = jac.workspace(&tape);
    let mut values = vec![0.0; jac.nnz()];
    let cj = 3.0;
    jac.eval(&tape, &x, cj, &mut ws, &mut values).unwrap();
    // Reference: one dense forward pass over all 2n inputs.
    let mut seeds = vec![0.0; 4 * n * n];
    for i in 0..2 * n {
        seeds[i * 2 * n + i] = 1.0;
    }
    let mut tws = tape.workspace();
    let mut out = vec![0.0; n];
    let mut tan = vec![0.0; n * 2 * n];
    tape.forward(&x, &seeds, 2 * n, &mut tws, &mut out, &mut tan)
        .unwrap();
    for j in 0..n {
        let range = jac.col_ptr[j]..jac.col_ptr[j + 1];
        for (&r, &v) in jac.row_idx[range.clone()].iter().zip(&values[range]) {
            let want = tan[r * 2 * n + j] + cj * tan[r * 2 * n + n + j];
            assert!((v - want).abs() < 1e-12, "({r}, {j})");
        }
    }
}

#[test]
fn common_subexpressions_are_compiled_once() {
    let mut a = Arena::new();
    let x = a.var(0);
    let y = a.var(1);
    let xy = a.mul(x, y);
    let s = a.f1(Func1::Sin, xy);
    let c = a.f1(Func1::Cos, xy);
    let e2 = a.add(c, xy);
    let once = tape_of(&a, &[x, y], &[s, e2]);
    let twice = tape_of(&a, &[x, y], &[s, e2, s, e2]);
    assert_eq!(once.len(), twice.len());
    assert_eq!(twice.n_outputs(), 4);
    let muls = once
        .ops
        .iter()
        .filter(|op| matches!(op, Op::Mul(..)))
        .count();
    assert_eq!(muls, 1);
    // Inputs, x*y, sin, cos, +.
    assert_eq!(once.len(), 6);
    // Instruction-level numbering shares prefixes of products.
    let z = a.var(2);
    let xyz = a.product(&[x, y, z]);
    let t = tape_of(&a, &[x, y, z], &[xy, xyz]);
    assert_eq!(t.len(), 5);
}

#[test]
fn dead_code_is_removed() {
    let mut a = Arena::new();
    let x = a.var(0);
    let y = a.var(1);
    let v = a.var(2);
    let w = a.var(3);
    let ex = a.f1(Func1::Exp, x);
    let big = a.mul(ex, y);
    let sy = a.f1(Func1::Sin, y);
    let w2 = a.scale(2.0, w);
    let o = a.add(w2, x);
    let mut b = TapeBuilder::new(&a, 2);
    b.input(x, 0);
    b.input(y, 1);
    b.stmt(&Stmt::Assign {
        target: v,
        expr: big,
        equation: usize::MAX,
    })
    .unwrap();
    b.stmt(&Stmt::Assign {
        target: w,
        expr: sy,
        equation: usize::MAX,
    })
    .unwrap();
    b.output(o).unwrap();
    let tape = b.build();
    // x, y, sin y, 2 sin y + x as Scale + Add (or AddScaled): nothing of exp(x) * y.
    assert!(tape.len() <= 5, "{:?}", tape.ops);
    assert!(
        !tape
            .ops
            .iter()
            .any(|op| matches!(op, Op::F1(Func1::Exp, _)))
    );
    let mut ws = tape.workspace();
    let mut out = [0.0];
    tape.eval(&[0.3, 0.7], &mut ws, &mut out).unwrap();
    assert!((out[0] - (2.0 * 0.7f64.sin() + 0.3)).abs() < 1e-15);
    // A dead linear solve disappears too.
    let (vars, _t, s, _outs) = linear_system(&mut a);
    let mut b = TapeBuilder::new(&a, 3);
    for (i, &v) in vars.iter().enumerate() {
        b.input(v, i);
    }
    b.stmt(&s).unwrap();
    b.output(vars[0]).unwrap();
    let tape = b.build();
    assert_eq!(tape.len(), 1);
    assert_eq!(tape.dependencies(), vec![vec![0]]);
}

#[test]
fn undefined_leaf_is_an_error() {
    let mut a = Arena::new();
    let x = a.var(0);
    let y = a.var(7);
    let e = a.add(x, y);
    let mut b = TapeBuilder::new(&a, 1);
    b.input(x, 0);
    match b.output(e) {
        Err(CodegenError::UndefinedLeaf(s)) => assert!(s.contains("Var(7)"), "{s}"),
        other => panic!("expected an undefined leaf, got {other:?}"),
    }
    let dy = a.der(x);
    let mut b = TapeBuilder::new(&a, 1);
    b.input(x, 0);
    let r = b.stmt(&Stmt::Assign {
        target: y,
        expr: dy,
        equation: usize::MAX,
    });
    assert!(matches!(r, Err(CodegenError::UndefinedLeaf(_))));
    let r = b.stmt(&Stmt::Assign {
        target: e,
        expr: x,
        equation: usize::MAX,
    });
    assert!(matches!(r, Err(CodegenError::NotALeaf(_))));
    assert!(matches!(
        b.output_input_minus(3, x),
        Err(CodegenError::SlotOutOfRange {
            slot: 3,
            n_inputs: 1
        })
    ));
}

#[test]
fn assignments_and_rebinding() {
    let mut a = Arena::new();
    let x = a.var(0);
    let y = a.var(1);
    let v = a.var(2);
    let e = a.scale(3.0, v);
    let mut b = TapeBuilder::new(&a, 2);
    b.input(x, 0);
    b.input(y, 1);
    b.stmt(&Stmt::Assign {
        target: v,
        expr: x,
        equation: usize::MAX,
    })
    .unwrap();
    b.output(e).unwrap();
    b.stmt(&Stmt::Assign {
        target: v,
        expr: y,
        equation: usize::MAX,
    })
    .unwrap();
    b.output(e).unwrap();
    let tape = b.build();
    let mut ws = tape.workspace();
    let mut out = [0.0; 2];
    tape.eval(&[1.0, 2.0], &mut ws, &mut out).unwrap();
    assert_eq!(out, [3.0, 6.0]);
    assert_eq!(tape.dependencies(), vec![vec![0], vec![1]]);
}

#[test]
fn inputs_are_emitted_once_at_first_use_and_rebinding_holds() {
    let mut a = Arena::new();
    let x = a.var(0);
    let y = a.var(1);
    let xy = a.mul(x, y);
    let s = a.f1(Func1::Sin, xy);
    let e = a.scale(3.0, x);
    let inputs = |tape: &Tape| {
        tape.ops
            .iter()
            .filter(|op| matches!(op, Op::Input(_)))
            .count()
    };
    // A non-leaf bound to an input stands for the whole expression: sin reads slot 2
    // and neither x nor y is read.
    let mut b = TapeBuilder::new(&a, 4);
    b.input(x, 0);
    b.input(y, 1);
    b.input(xy, 2);
    b.output(s).unwrap();
    // Rebinding x to slot 3 affects only what is compiled afterwards.
    b.output(e).unwrap();
    b.input(x, 3);
    b.output(e).unwrap();
    let tape = b.build();
    assert_eq!(tape.dependencies(), vec![vec![2], vec![0], vec![3]]);
    assert_eq!(inputs(&tape), 3);
    let mut ws = tape.workspace();
    let mut out = [0.0; 3];
    tape.eval(&[1.0, 5.0, 0.5, 2.0], &mut ws, &mut out).unwrap();
    assert_eq!(out, [0.5f64.sin(), 3.0, 6.0]);
    // Two leaves bound to one slot read one instruction, so their product is a square.
    let mut b = TapeBuilder::new(&a, 1);
    b.input(x, 0);
    b.input(y, 0);
    b.output(xy).unwrap();
    let tape = b.build();
    assert_eq!(inputs(&tape), 1);
    assert_eq!(tape.len(), 2, "{:?}", tape.ops);
}

#[test]
fn one_builder_gives_tapes_of_chosen_outputs() {
    let mut a = Arena::new();
    let x = a.var(0);
    let y = a.var(1);
    let v = a.var(2);
    let xy = a.mul(x, y);
    let sv = a.f1(Func1::Sin, v);
    let e2 = a.scale(2.0, v);
    let ex = a.f1(Func1::Exp, x);
    let mut b = TapeBuilder::new(&a, 2);
    b.input(x, 0);
    b.input(y, 1);
    // A statement both tapes need, compiled once.
    b.stmt(&Stmt::Assign {
        target: v,
        expr: xy,
        equation: usize::MAX,
    })
    .unwrap();
    assert_eq!(b.output(sv).unwrap(), 0);
    assert_eq!(b.output(e2).unwrap(), 1);
    assert_eq!(b.output(ex).unwrap(), 2);
    let first = b.build_outputs(0..1);
    let rest = b.build_outputs(1..3);
    let whole = b.build();
    let eval = |t: &Tape, k: usize| {
        let mut ws = t.workspace();
        let mut out = vec![0.0; k];
        t.eval(&[0.5, 3.0], &mut ws, &mut out).unwrap();
        out
    };
    assert_eq!(eval(&first, 1), [1.5f64.sin()]);
    assert_eq!(eval(&rest, 2), [3.0, 0.5f64.exp()]);
    assert_eq!(eval(&whole, 3), [1.5f64.sin(), 3.0, 0.5f64.exp()]);
    // Each tape keeps only what its outputs need: no sine in the second, no exponential
    // in the first.
    assert!(
        !rest
            .ops
            .iter()
            .any(|op| matches!(op, Op::F1(Func1::Sin, _)))
    );
    assert!(
        !first
            .ops
            .iter()
            .any(|op| matches!(op, Op::F1(Func1::Exp, _)))
    );
    assert_eq!(first.dependencies(), vec![vec![0, 1]]);
    assert_eq!(rest.dependencies(), vec![vec![0, 1], vec![0]]);
}

#[test]
fn deep_expressions_compile_without_recursion() {
    let mut a = Arena::new();
    let x = a.var(0);
    let mut e = x;
    for _ in 0..50_000 {
        let s = a.f1(Func1::Sin, e);
        e = a.add(s, x);
    }
    let tape = tape_of(&a, &[x], &[e]);
    assert_eq!(tape.len(), 1 + 2 * 50_000);
    assert_eq!(tape.dependencies(), vec![vec![0]]);
    let mut ws = tape.workspace();
    let mut out = [0.0];
    tape.eval(&[0.1], &mut ws, &mut out).unwrap();
    assert!(out[0].is_finite());
}

#[test]
fn dependencies_follow_the_data() {
    let mut a = Arena::new();
    let v: Vec<Id> = (0..5).map(|i| a.var(i)).collect();
    let p = a.param(0);
    let e0 = a.mul(v[3], v[1]);
    let c = a.cmp(Cmp::Gt, v[4], p);
    let e1 = a.ite(c, v[0], e0);
    let k = a.constant(2.0);
    let mut b = TapeBuilder::new(&a, 6);
    for (i, &x) in v.iter().enumerate() {
        b.input(x, i);
    }
    b.input(p, 5);
    b.output(e0).unwrap();
    b.output(e1).unwrap();
    b.output(k).unwrap();
    let tape = b.build();
    assert_eq!(
        tape.dependencies(),
        vec![vec![1, 3], vec![0, 1, 3, 4, 5], vec![]]
    );
}

#[test]
fn tape_is_send_and_sync() {
    fn check<T: Send + Sync + Clone>() {}
    check::<Tape>();
    check::<DaeJacobian>();
    fn shared<T: Send + Sync>() {}
    shared::<crate::names::NameIndex>();
    shared::<super::dae::CompiledDae>();
}

/// Whether no two columns that share a row have the same colour.
fn coloring_is_valid(rows: &[Vec<usize>], colors: &[usize]) -> bool {
    rows.iter().all(|r| {
        let mut seen = BTreeSet::new();
        r.iter().all(|&c| seen.insert(colors[c]))
    })
}

#[test]
fn column_colouring_is_valid_with_and_without_a_full_row() {
    use super::sparsity::{color_columns, rows_to_csc};
    // A tridiagonal pattern: 3 colours.
    let n: usize = 9;
    let tri: Vec<Vec<usize>> = (0..n)
        .map(|i| (i.saturating_sub(1)..(i + 2).min(n)).collect())
        .collect();
    let (cp, ri) = rows_to_csc(&tri, n);
    let c = color_columns(&cp, &ri, &tri);
    assert_eq!(c.n_colors, 3);
    assert!(coloring_is_valid(&tri, &c.colors));
    // The same with one full row (and an empty column 4 left out of the pattern): every
    // non-empty column conflicts with every other one.
    let mut full: Vec<Vec<usize>> = tri
        .iter()
        .map(|r| r.iter().copied().filter(|&c| c != 4).collect())
        .collect();
    full[0] = (0..n).filter(|&c| c != 4).collect();
    let (cp, ri) = rows_to_csc(&full, n);
    let c = color_columns(&cp, &ri, &full);
    assert_eq!(c.n_colors, n - 1);
    assert_eq!(c.colors[4], usize::MAX);
    assert!(coloring_is_valid(&full, &c.colors));
}

/// A tape over `vars` (the unknowns `u` in slots 0 and 1, their derivatives in 2 and 3,
/// a parameter in 4) with outputs `u_k' - value` (`Ok(value)`, as the compiler writes a
/// state's derivative) or an expression (`Err(expr)`).
fn residual_tape(a: &Arena, vars: &[Id; 5], rows: &[(usize, Result<Id, Id>)]) -> Tape {
    let mut b = TapeBuilder::new(a, 5);
    for (i, &x) in vars.iter().enumerate() {
        b.input(x, i);
    }
    for &(k, row) in rows {
        match row {
            Ok(value) => b.output_input_minus(2 + k, value).unwrap(),
            Err(expr) => b.output(expr).unwrap(),
        };
    }
    b.build()
}

#[test]
fn explicit_residuals_are_derivatives_minus_what_the_states_give() {
    let mut a = Arena::new();
    let vars = [a.var(0), a.var(1), a.var(2), a.var(3), a.var(4)];
    let [u0, u1, up0, up1, p] = vars;
    // u0' = u1, u1' = -sin(u0) p: explicit.
    let s = a.f1(Func1::Sin, u0);
    let g1 = a.mul(s, p);
    let g1 = a.neg(g1);
    let explicit = [(0, Ok(u1)), (1, Ok(g1))];
    assert!(residual_tape(&a, &vars, &explicit).is_explicit_in(2, 2));
    // u1' alone (g = 0).
    assert!(residual_tape(&a, &vars, &[(0, Ok(u1)), (1, Err(up1))]).is_explicit_in(2, 2));
    // 2 u0' - u1: not the derivative itself.
    let twice = a.scale(2.0, up0);
    let bad = a.sub(twice, u1);
    assert!(!residual_tape(&a, &vars, &[(0, Err(bad)), (1, Ok(g1))]).is_explicit_in(2, 2));
    // u0' - u1': the other derivative in the value.
    assert!(!residual_tape(&a, &vars, &[(0, Ok(up1)), (1, Ok(g1))]).is_explicit_in(2, 2));
    // Rows in the wrong order: u1' first.
    assert!(!residual_tape(&a, &vars, &[(1, Ok(g1)), (0, Ok(u1))]).is_explicit_in(2, 2));
    // A derivative read through a linear solve: v solves u0 v = u1', then u0' - v.
    let v = a.var(7);
    let mut b = TapeBuilder::new(&a, 5);
    for (i, &x) in vars.iter().enumerate() {
        b.input(x, i);
    }
    b.stmt(&Stmt::LinearSolve {
        targets: vec![v],
        a: vec![u0],
        c: vec![up1],
    })
    .unwrap();
    b.output_input_minus(2, v).unwrap();
    b.output_input_minus(3, g1).unwrap();
    assert!(!b.build().is_explicit_in(2, 2));
    // A further output (an observed value) that reads a derivative.
    let mut b = TapeBuilder::new(&a, 5);
    for (i, &x) in vars.iter().enumerate() {
        b.input(x, i);
    }
    b.output_input_minus(2, u1).unwrap();
    b.output_input_minus(3, g1).unwrap();
    b.output(up0).unwrap();
    assert!(!b.build().is_explicit_in(2, 2));
}

#[test]
fn outputs_read_the_inputs_they_depend_on_through_linear_solves() {
    let mut a = Arena::new();
    // Inputs x, y, z in slots 0, 1, 2; a fifth output reads x alone.
    let (tape, _) = linear_system_tape(&mut a, |a, vars| vec![a.f1(Func1::Sin, vars[0])]);
    // The solution reads every input (the matrix reads y and z, the constants x).
    for slot in 0..3 {
        assert!(
            tape.outputs_read(&[0], slot..slot + 1),
            "solution and slot {slot}"
        );
    }
    // sin x reads x only.
    assert!(tape.outputs_read(&[4], 0..1));
    assert!(!tape.outputs_read(&[4], 1..3));
    assert!(tape.outputs_read(&[4, 3], 2..3));
    assert!(!tape.outputs_read(&[], 0..3));
}
