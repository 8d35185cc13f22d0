//! Tests of the parameter prelude (instructions that depend only on invariant inputs are
//! skipped while those keep their values) and of specializing a tape to parameter
//! values.

use crate::expr::{Arena, Func1, Id};

use super::tape::Op;
use super::*;

/// Input slots: parameters `p0, p1, p2` at 0..3 (invariant), variables `x, y` at 3..5.
const N_PARAMS: usize = 3;
const N_INPUTS: usize = 5;

/// The expressions under test: arithmetic mixing parameters and variables, and a 3x3
/// sparse linear solve whose entries involve parameters. Returns the builder's inputs
/// (leaves in slot order), the solve statement and the outputs.
fn model(arena: &mut Arena) -> (Vec<Id>, Stmt, Vec<Id>) {
    let p: Vec<Id> = (0..N_PARAMS as u32).map(|j| arena.param(j)).collect();
    let x = arena.var(0);
    let y = arena.var(1);
    let z: Vec<Id> = (2..5).map(|i| arena.var(i)).collect();
    // A = [[2 + p0 x, p1 x, 0], [p1, 3 + y^2, p2 y], [0, p2, 4 + p0]], c = [x, y, p0 p1].
    let two = arena.constant(2.0);
    let three = arena.constant(3.0);
    let four = arena.constant(4.0);
    let p0x = arena.mul(p[0], x);
    let a00 = arena.add(two, p0x);
    let a01 = arena.mul(p[1], x);
    let y2 = arena.powi(y, 2);
    let a11 = arena.add(three, y2);
    let a12 = arena.mul(p[2], y);
    let a22 = arena.add(four, p[0]);
    let c2 = arena.mul(p[0], p[1]);
    let solve = Stmt::SparseLinearSolve {
        targets: z.clone(),
        entries: vec![
            (0, 0, a00),
            (0, 1, a01),
            (1, 0, p[1]),
            (1, 1, a11),
            (1, 2, a12),
            (2, 1, p[2]),
            (2, 2, a22),
        ],
        c: vec![x, y, c2],
    };
    // Outputs: p0 p1 x + sin(p2) y, (p0 + p1)(p0 - p1) + y, z0 + z1 z2, p2 z2.
    let p0p1 = arena.mul(p[0], p[1]);
    let t1 = arena.mul(p0p1, x);
    let sp2 = arena.f1(Func1::Sin, p[2]);
    let t2 = arena.mul(sp2, y);
    let o0 = arena.add(t1, t2);
    let s = arena.add(p[0], p[1]);
    let d = arena.sub(p[0], p[1]);
    let sd = arena.mul(s, d);
    let o1 = arena.add(sd, y);
    let z12 = arena.mul(z[1], z[2]);
    let o2 = arena.add(z[0], z12);
    let o3 = arena.mul(p[2], z[2]);
    let mut inputs = p;
    inputs.extend([x, y]);
    (inputs, solve, vec![o0, o1, o2, o3])
}

fn tape(arena: &Arena, inputs: &[Id], solve: &Stmt, outputs: &[Id]) -> Tape {
    let mut b = TapeBuilder::new(arena, N_INPUTS);
    b.invariant_inputs(0..N_PARAMS);
    for (slot, &leaf) in inputs.iter().enumerate() {
        b.input(leaf, slot);
    }
    b.stmt(solve).unwrap();
    for &o in outputs {
        b.output(o).unwrap();
    }
    b.build()
}

/// Outputs of `tape` at `inputs` with a fresh workspace (nothing skipped).
fn fresh(tape: &Tape, inputs: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; tape.n_outputs()];
    tape.eval(inputs, &mut tape.workspace(), &mut out).unwrap();
    out
}

fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| (x - y).abs() <= tol * (1.0 + x.abs().max(y.abs())))
}

#[test]
fn the_prelude_holds_what_depends_only_on_parameters() {
    let mut arena = Arena::new();
    let (inputs, solve, outputs) = model(&mut arena);
    let t = tape(&arena, &inputs, &solve, &outputs);
    // p0 p1, sin(p2), p0 + p1, p0 - p1, their product, 4 + p0, the three parameter
    // inputs and the constants: at least 9 instructions, and nothing reading x or y.
    assert!(t.prelude_len() >= 9, "prelude {}", t.prelude_len());
    for op in &t.ops[..t.prelude_len()] {
        match *op {
            Op::Input(s) => assert!((s as usize) < N_PARAMS, "{op:?} in the prelude"),
            Op::LinearSolve(_) | Op::LsPart => panic!("a linear solve in the prelude"),
            _ => {}
        }
    }
    // Without invariant inputs only constants are hoisted.
    let mut b = TapeBuilder::new(&arena, N_INPUTS);
    for (slot, &leaf) in inputs.iter().enumerate() {
        b.input(leaf, slot);
    }
    b.stmt(&solve).unwrap();
    for &o in &outputs {
        b.output(o).unwrap();
    }
    let plain = b.build();
    assert!(
        plain.ops[..plain.prelude_len()]
            .iter()
            .all(|op| matches!(op, Op::Const(_)))
    );
}

#[test]
fn a_skipped_prelude_gives_what_a_fresh_evaluation_gives() {
    let mut arena = Arena::new();
    let (inputs, solve, outputs) = model(&mut arena);
    let t = tape(&arena, &inputs, &solve, &outputs);
    // Another tape sharing the workspace overwrites its registers.
    let other = {
        let x = arena.var(0);
        let s = arena.f1(Func1::Cos, x);
        let mut b = TapeBuilder::new(&arena, 1);
        b.input(x, 0);
        b.output(s).unwrap();
        b.build()
    };
    let mut ws = t.workspace();
    let mut out = vec![0.0; 4];
    let params = [
        [1.5, 0.5, 0.25],
        [1.5, 0.5, 0.25],
        [0.7, -0.2, 0.9],
        [0.7, -0.2, 0.9],
    ];
    for (k, p) in params.iter().enumerate() {
        for (x, y) in [(0.3, -0.4), (1.1, 0.6)] {
            let inputs = [p[0], p[1], p[2], x, y];
            t.eval(&inputs, &mut ws, &mut out).unwrap();
            assert_eq!(out, fresh(&t, &inputs), "parameter set {k}, x = {x}");
        }
        // After either parameter set's first evaluation (the next one reuses the
        // values, so only the cache can notice).
        if k == 0 || k == 2 {
            let mut o = [0.0];
            other.eval(&[0.2], &mut ws, &mut o).unwrap();
            let (mut oo, mut ot) = ([0.0], [0.0]);
            other
                .forward(&[0.2], &[1.0], 1, &mut ws, &mut oo, &mut ot)
                .unwrap();
        }
    }
}

#[test]
fn forward_mode_after_a_skipped_prelude_matches_a_fresh_one() {
    let mut arena = Arena::new();
    let (inputs, solve, outputs) = model(&mut arena);
    let t = tape(&arena, &inputs, &solve, &outputs);
    let x = [1.2, 0.4, -0.3, 0.5, 0.8];
    let lanes = 2;
    // Seeds on x and y only, then on p0 and x: the second pass must not skip.
    let seeds_xy = {
        let mut s = vec![0.0; N_INPUTS * lanes];
        s[3 * lanes] = 1.0;
        s[4 * lanes + 1] = 1.0;
        s
    };
    let seeds_px = {
        let mut s = vec![0.0; N_INPUTS * lanes];
        s[0] = 1.0;
        s[3 * lanes + 1] = 1.0;
        s
    };
    let run = |ws: &mut Workspace, seeds: &[f64]| {
        let mut out = vec![0.0; 4];
        let mut tan = vec![0.0; 4 * lanes];
        t.forward(&x, seeds, lanes, ws, &mut out, &mut tan).unwrap();
        (out, tan)
    };
    let mut ws = t.workspace();
    for seeds in [&seeds_xy, &seeds_xy, &seeds_px, &seeds_xy, &seeds_px] {
        let got = run(&mut ws, seeds);
        let want = run(&mut t.workspace(), seeds);
        assert_eq!(got, want);
    }
    // A value pass in between keeps the prelude and its zero tangents valid.
    let mut out = vec![0.0; 4];
    t.eval(&x, &mut ws, &mut out).unwrap();
    assert_eq!(run(&mut ws, &seeds_xy), run(&mut t.workspace(), &seeds_xy));
}

#[test]
fn a_specialized_tape_computes_the_same_values_and_tangents() {
    let mut arena = Arena::new();
    let (inputs, solve, outputs) = model(&mut arena);
    let t = tape(&arena, &inputs, &solve, &outputs);
    let mut rng = 7u64;
    let mut next = || {
        rng = rng
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (rng >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    for p in [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, -1.0],
        [0.0, 1.0, 2.5],
        [0.3, -0.7, 1.9],
    ] {
        let s = t.specialize(&p);
        if p.contains(&0.0) {
            assert!(s.len() < t.len(), "{p:?}: {} >= {}", s.len(), t.len());
        }
        // Constant pivots (p1, p2, 4 + p0) leave at most the two unknowns whose
        // diagonals depend on x and y to the sparse LU.
        let unknowns: usize = s.ls.iter().map(|l| l.k).sum();
        assert!(unknowns <= 2, "{p:?}: {unknowns} unknowns left");
        for _ in 0..5 {
            // The parameter slots of the specialized tape are ignored.
            let (x, y) = (next(), next());
            let full = [p[0], p[1], p[2], x, y];
            let ignored = [f64::NAN, f64::NAN, f64::NAN, x, y];
            let want = fresh(&t, &full);
            let got = fresh(&s, &ignored);
            assert!(close(&got, &want, 1e-13), "{p:?}: {got:?} vs {want:?}");
            // Tangents along x and y.
            let lanes = 2;
            let mut seeds = vec![0.0; N_INPUTS * lanes];
            seeds[3 * lanes] = 1.0;
            seeds[4 * lanes + 1] = 1.0;
            let (mut o1, mut d1) = (vec![0.0; 4], vec![0.0; 8]);
            let (mut o2, mut d2) = (vec![0.0; 4], vec![0.0; 8]);
            t.forward(&full, &seeds, lanes, &mut t.workspace(), &mut o1, &mut d1)
                .unwrap();
            s.forward(
                &ignored,
                &seeds,
                lanes,
                &mut s.workspace(),
                &mut o2,
                &mut d2,
            )
            .unwrap();
            assert!(close(&d2, &d1, 1e-12), "{p:?}: {d2:?} vs {d1:?}");
        }
    }
}

#[test]
fn specializing_drops_the_zero_entries_of_a_sparse_solve() {
    let mut arena = Arena::new();
    let (inputs, solve, outputs) = model(&mut arena);
    let t = tape(&arena, &inputs, &solve, &outputs);
    let nnz = |t: &Tape| {
        t.ls[0]
            .sparse
            .as_ref()
            .expect("a sparse solve")
            .row_idx
            .len()
    };
    assert_eq!(nnz(&t), 7);
    // p1 = 0 removes (0, 1) and (1, 0), p2 = 0 removes (1, 2) and (2, 1): the diagonal
    // remains, and its constant 4 + p0 is eliminated, leaving the two entries that
    // depend on x and y.
    let s = t.specialize(&[0.5, 0.0, 0.0]);
    assert_eq!((s.ls[0].k, nnz(&s)), (2, 2));
    let x = [0.5, 0.0, 0.0, 0.8, -0.6];
    assert!(close(&fresh(&s, &x), &fresh(&t, &x), 1e-14));
}

#[test]
fn a_pattern_that_zeros_would_make_singular_is_kept() {
    // A = [[p0, 1], [p1, x]], c = [x, 1].
    let mut arena = Arena::new();
    let p0 = arena.param(0);
    let p1 = arena.param(1);
    let x = arena.var(0);
    let z0 = arena.var(1);
    let z1 = arena.var(2);
    let one = arena.constant(1.0);
    let solve = Stmt::SparseLinearSolve {
        targets: vec![z0, z1],
        entries: vec![(0, 0, p0), (1, 0, p1), (0, 1, one), (1, 1, x)],
        c: vec![x, one],
    };
    let sum = arena.add(z0, z1);
    let mut b = TapeBuilder::new(&arena, 3);
    b.invariant_inputs(0..2);
    b.input(p0, 0);
    b.input(p1, 1);
    b.input(x, 2);
    b.stmt(&solve).unwrap();
    b.output(sum).unwrap();
    let t = b.build();
    let nnz = |t: &Tape| t.ls[0].sparse.as_ref().unwrap().row_idx.len();
    // p0 = 0 alone: (0, 0) goes; every row and column keeps an entry, and the constant
    // pivots 2 and 1 then solve both unknowns without a factorization.
    let s = t.specialize(&[0.0, 2.0]);
    assert!(s.ls.is_empty());
    let inputs = [0.0, 2.0, 1.5];
    assert!(close(&fresh(&s, &inputs), &fresh(&t, &inputs), 1e-14));
    // Both zero would leave column 0 empty: the pattern stays whole, and the singular
    // matrix is reported as it was.
    let s = t.specialize(&[0.0, 0.0]);
    assert_eq!(nnz(&s), 4);
    let inputs = [0.0, 0.0, 1.5];
    let mut out = [0.0];
    let a = t.eval(&inputs, &mut t.workspace(), &mut out).unwrap_err();
    let b = s.eval(&inputs, &mut s.workspace(), &mut out).unwrap_err();
    assert!(a.message.contains("singular") && b.message.contains("singular"));
    assert_eq!(a.recoverable, b.recoverable);
}
