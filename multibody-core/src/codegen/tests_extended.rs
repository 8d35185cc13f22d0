//! Tests of the extended Jacobian: solving the bordered system gives the solution with
//! the exact Jacobian, while rows and colours stay bounded for chains.

use crate::expr::{Arena, Func1, Id};

use super::*;

/// Dense Gaussian elimination with partial pivoting (test reference).
fn dense_solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for k in 0..n {
        let p = (k..n)
            .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
            .unwrap();
        a.swap(k, p);
        b.swap(k, p);
        assert!(a[k][k].abs() > 1e-14, "singular reference matrix");
        for i in k + 1..n {
            let l = a[i][k] / a[k][k];
            for j in k..n {
                a[i][j] -= l * a[k][j];
            }
            b[i] -= l * b[k];
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        x[k] = (b[k] - (k + 1..n).map(|j| a[k][j] * x[j]).sum::<f64>()) / a[k][k];
    }
    x
}

/// A residual shaped like a pendulum chain: the absolute angle of link k sums the
/// relative angles before it, every row reads the cosine and sine of its link's absolute
/// angle, and a 2x2 linear solve in the middle reads the chain too.
/// Inputs: `[t, u_0..u_n, u'_0..u'_n]`.
fn chain_tape(n: usize, with_solve: bool) -> Tape {
    let mut a = Arena::new();
    let u: Vec<Id> = (0..n as u32).map(|i| a.var(i)).collect();
    let yp: Vec<Id> = u.iter().map(|&v| a.der(v)).collect();
    let t = a.time();
    let mut theta = Vec::new();
    let mut acc = a.zero();
    for &q in &u {
        acc = a.add(acc, q);
        theta.push(acc);
    }
    let xs: Vec<Id> = (1000..1002).map(|i| a.var(i)).collect();
    let solve = if with_solve {
        let m = n / 2;
        let c0 = a.f1(Func1::Cos, theta[m]);
        let s0 = a.f1(Func1::Sin, theta[m]);
        let three = a.constant(3.0);
        let d0 = a.add(three, c0);
        let d1 = a.add(three, s0);
        let minus_t = a.scale(-1.0, t);
        Some(Stmt::LinearSolve {
            targets: xs.clone(),
            a: vec![d0, s0, c0, d1],
            c: vec![yp[m], minus_t],
        })
    } else {
        None
    };
    let mut rows = Vec::new();
    for k in 0..n {
        let c = a.f1(Func1::Cos, theta[k]);
        let s = a.f1(Func1::Sin, theta[k]);
        let term = a.mul(yp[k], c);
        let next = a.mul(s, u[(k + 1) % n]);
        let mut r = a.add(term, next);
        if with_solve && k % 3 == 0 {
            let xx = a.mul(xs[0], xs[1]);
            r = a.add(r, xx);
        }
        rows.push(r);
    }
    let mut b = TapeBuilder::new(&a, 2 * n + 1);
    b.input(t, 0);
    for k in 0..n {
        b.input(u[k], 1 + k);
        b.input(yp[k], 1 + n + k);
    }
    if let Some(s) = &solve {
        b.stmt(s).unwrap();
    }
    for &r in &rows {
        b.output(r).unwrap();
    }
    b.build()
}

/// Dense `J = dF/du + cj dF/du'` by the plain sparse Jacobian.
fn plain_dense(tape: &Tape, n: usize, x: &[f64], cj: f64) -> Vec<Vec<f64>> {
    let jac = DaeJacobian::new(tape, n, 1, 1 + n);
    let mut ws = jac.workspace(tape);
    let mut values = vec![0.0; jac.nnz()];
    jac.eval(tape, x, cj, &mut ws, &mut values).unwrap();
    let mut d = vec![vec![0.0; n]; n];
    for j in 0..n {
        for p in jac.col_ptr[j]..jac.col_ptr[j + 1] {
            d[jac.row_idx[p]][j] = values[p];
        }
    }
    d
}

fn check_solve(n: usize, with_solve: bool) -> ExtendedJacobian {
    check_solve_with(n, with_solve, DEFAULT_MAX_FILL)
}

fn check_solve_with(n: usize, with_solve: bool, max_fill: usize) -> ExtendedJacobian {
    let tape = chain_tape(n, with_solve);
    let ext = ExtendedJacobian::new(&tape, n, 1, 1 + n, max_fill);
    let dim = ext.dimension();
    let mut x = vec![0.3];
    for k in 0..2 * n {
        x.push(((k * 37 % 11) as f64 - 5.0) * 0.13);
    }
    let cj = 7.5;
    let mut ws = ext.workspace(&tape);
    let mut values = vec![f64::NAN; ext.nnz()];
    ext.eval(&tape, &x, cj, &mut ws, &mut values).unwrap();
    let mut big = vec![vec![0.0; dim]; dim];
    for j in 0..dim {
        for p in ext.col_ptr[j]..ext.col_ptr[j + 1] {
            assert!(values[p].is_finite(), "entry ({}, {j})", ext.row_idx[p]);
            big[ext.row_idx[p]][j] = values[p];
        }
    }
    let b: Vec<f64> = (0..n).map(|k| 1.0 + (k % 5) as f64).collect();
    let mut rhs = b.clone();
    rhs.resize(dim, 0.0);
    let du_ext = dense_solve(big, rhs);
    let du = dense_solve(plain_dense(&tape, n, &x, cj), b);
    for k in 0..n {
        assert!(
            (du_ext[k] - du[k]).abs() < 1e-9 * (1.0 + du[k].abs()),
            "n = {n}: unknown {k}: extended {} vs plain {}",
            du_ext[k],
            du[k]
        );
    }
    ext
}

#[test]
fn extended_solve_equals_exact_jacobian_solve() {
    for n in [1, 2, 5, 13] {
        check_solve(n, false);
        check_solve(n, true);
    }
}

#[test]
fn extended_rows_and_colours_stay_bounded_along_a_chain() {
    // Without fill every intermediate of the solve is cut: the colours are the same
    // at any length.
    let small = check_solve_with(20, true, 0);
    let large = check_solve_with(80, true, 0);
    assert_eq!(small.n_colors(), large.n_colors());
    assert!(large.n_colors() <= 8, "{} colours", large.n_colors());
    // Entries grow linearly: per unknown the same budget.
    let per = |e: &ExtendedJacobian| e.nnz() as f64 / e.n as f64;
    assert!(
        per(&large) <= per(&small) * 1.1,
        "{} vs {}",
        per(&large),
        per(&small)
    );
    // With the default fill fewer intermediates are cut; colours and entries per
    // unknown stay bounded all the same.
    let (a, b, c) = (
        check_solve(20, true),
        check_solve(80, true),
        check_solve(320, true),
    );
    for e in [&a, &b, &c] {
        assert!(e.n_colors() <= 12, "{} colours", e.n_colors());
        assert!(e.dimension() < large.dimension() * 4, "{}", e.dimension());
    }
    assert!(
        per(&c) <= per(&b) * 1.1 && per(&b) <= per(&a) * 1.5,
        "{} {} {}",
        per(&a),
        per(&b),
        per(&c)
    );
    // The plain Jacobian of the same chain fills up.
    let tape = chain_tape(80, true);
    let plain = DaeJacobian::new(&tape, 80, 1, 81);
    assert!(plain.nnz() > 3000 && plain.n_colors() >= 80);
}
