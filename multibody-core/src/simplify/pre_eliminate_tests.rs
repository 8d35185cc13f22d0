//! Golden tests of symbolic pre-elimination on plain linear rows.

use super::*;

/// Rows of numbers: `(entries, c)`.
fn rows(arena: &mut Arena, spec: &[(&[(usize, f64)], f64)]) -> Vec<LinearRow> {
    spec.iter()
        .map(|(entries, c)| LinearRow {
            entries: entries
                .iter()
                .map(|&(k, a)| (k, arena.constant(a)))
                .collect(),
            c: arena.constant(*c),
        })
        .collect()
}

/// Solves the reduced system densely and back-substitutes, returning every unknown.
fn solve_reduced(arena: &mut Arena, r: &PreEliminated, n: usize) -> Vec<f64> {
    let m = r.vars.len();
    let mut a = vec![vec![0.0; m + 1]; m];
    for (row, (_, lr)) in r.rows.iter().enumerate() {
        for &(j, coef) in &lr.entries {
            let col = r.vars.iter().position(|&v| v == j).unwrap();
            a[row][col] = arena.as_const(coef).unwrap();
        }
        a[row][m] = -arena.as_const(lr.c).unwrap();
    }
    // Gaussian elimination with partial pivoting.
    for k in 0..m {
        let p = (k..m)
            .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
            .unwrap();
        a.swap(k, p);
        for i in k + 1..m {
            let f = a[i][k] / a[k][k];
            for j in k..=m {
                a[i][j] -= f * a[k][j];
            }
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..m).rev() {
        let s: f64 = (k + 1..m).map(|j| a[k][j] * x[r.vars[j]]).sum();
        x[r.vars[k]] = (a[k][m] - s) / a[k][k];
    }
    for e in r.eliminations.iter().rev() {
        let s: f64 = e
            .others
            .iter()
            .map(|&(k, a)| arena.as_const(a).unwrap() * x[k])
            .sum::<f64>()
            + arena.as_const(e.c).unwrap();
        x[e.var] = -s / arena.as_const(e.pivot).unwrap();
    }
    x
}

/// A chain `x0 - x1 = 1, x1 - x2 = 2, x2 + x0 = 3` with a variable-free
/// coefficient everywhere: the first elimination (cost 1) makes the rest cheaper, and
/// everything goes; the values are those of the dense solution.
#[test]
fn a_cycle_of_unit_coefficients_is_eliminated_completely() {
    let mut arena = Arena::new();
    let spec: [(&[(usize, f64)], f64); 3] = [
        (&[(0, 1.0), (1, -1.0)], -1.0),
        (&[(1, 1.0), (2, -1.0)], -2.0),
        (&[(2, 1.0), (0, 1.0)], -3.0),
    ];
    let rs = rows(&mut arena, &spec);
    let r = pre_eliminate(&mut arena, rs, 3, &[], 1, &mut |_, e| e);
    assert_eq!(r.eliminations.len(), 3);
    assert!(r.vars.is_empty() && r.rows.is_empty());
    let x = solve_reduced(&mut arena, &r, 3);
    // x0 = x1 + 1, x1 = x2 + 2, x2 = 3 - x0 => x0 = 6 - x0 => x0 = 3.
    assert_eq!(x, vec![3.0, 2.0, 0.0]);
}

/// An arrow matrix: a hub unknown `x0` in every row. Eliminating a spoke costs nothing
/// (its column has one row), so the spokes go and `x0` is left alone; with
/// `max_fill = 0` eliminations that would add an entry are refused.
#[test]
fn fill_limit_is_respected_and_values_are_exact() {
    let mut arena = Arena::new();
    // Row i (1..=4): x0 + 2 x_i = i;  row 0: x0 + x1 + x2 + x3 + x4 = 10.
    let mut spec: Vec<(Vec<(usize, f64)>, f64)> = vec![((0..5).map(|k| (k, 1.0)).collect(), -10.0)];
    for i in 1..5 {
        spec.push((vec![(0, 1.0), (i, 2.0)], -(i as f64)));
    }
    let spec_ref: Vec<(&[(usize, f64)], f64)> =
        spec.iter().map(|(e, c)| (e.as_slice(), *c)).collect();
    let exact = {
        // x_i = (i - x0) / 2; x0 + sum (i - x0)/2 = 10 => x0 (1 - 2) + 5 = 10 => x0 = -5.
        let x0 = -5.0;
        let mut v = vec![x0];
        v.extend((1..5).map(|i| (i as f64 - x0) / 2.0));
        v
    };
    for fill in [0usize, 1, 4] {
        let rs = rows(&mut arena, &spec_ref);
        let r = pre_eliminate(&mut arena, rs, 5, &[], fill, &mut |_, e| e);
        let x = solve_reduced(&mut arena, &r, 5);
        for (k, (&got, &want)) in x.iter().zip(&exact).enumerate() {
            assert!(
                (got - want).abs() < 1e-12,
                "fill {fill}: x{k} = {got}, want {want}"
            );
        }
        // Spokes: column count 2 (row 0 and their own row), own row has 2 entries:
        // cost (2 - 1) (2 - 1) = 1. With fill 0 nothing is eliminated at first ...
        if fill == 0 {
            assert!(r.eliminations.is_empty(), "{:?}", r.eliminations);
        } else {
            assert!(r.vars.len() <= 1, "fill {fill}: left {:?}", r.vars);
        }
    }
}

/// A coefficient that may vanish (a variable, or a parameter whose default is zero) is
/// never a pivot.
#[test]
fn unsafe_coefficients_are_not_pivots() {
    let mut arena = Arena::new();
    let q = arena.var(7);
    let p0 = arena.param(0);
    let one = arena.one();
    let rows = vec![
        LinearRow {
            entries: vec![(0, q)],
            c: one,
        },
        LinearRow {
            entries: vec![(1, p0)],
            c: one,
        },
    ];
    let r = pre_eliminate(&mut arena, rows, 2, &[0.0], 4, &mut |_, e| e);
    assert!(r.eliminations.is_empty());
    assert_eq!(r.vars, vec![0, 1]);
}

/// A constant that cancels to rounding noise (0.3 - 3 * 0.1) is removed rather than
/// kept as a tiny pivot candidate, and a pivot made by elimination from parameters
/// (`p - 1`) is refused even though it is nonzero for the default `p = 3`.
#[test]
fn cancellations_and_made_parameter_differences_are_no_pivots() {
    let mut arena = Arena::new();
    // Row 0: x0 + x1 = 1; row 1: 3 x0 + 0.3 x1 + x2 = 2; row 2: x2 = 5.
    // Eliminating x0 from row 0 leaves 0.3 - 3 * 0.1... here 0.3 - 3 = -2.7 for x1,
    // so use coefficients that cancel: row 1 is 0.1 x0 + 0.1 x1 + x2 = 2 after scaling.
    let spec: [(&[(usize, f64)], f64); 3] = [
        (&[(0, 1.0), (1, 1.0)], -1.0),
        (&[(0, 0.1), (1, 0.3 - 0.2), (2, 1.0)], -2.0),
        (&[(2, 1.0)], -5.0),
    ];
    let rs = rows(&mut arena, &spec);
    let r = pre_eliminate(&mut arena, rs, 3, &[], 8, &mut |_, e| e);
    // 0.3 - 0.2 - 0.1 is 2.8e-17, not zero: it must not survive as an entry of x1.
    for (_, row) in &r.rows {
        for &(j, a) in &row.entries {
            let v = arena.as_const(a).unwrap();
            assert!(v.abs() > 1e-12, "entry of x{j} kept at {v:e}");
        }
    }
    // Parameter pivots: p x0 + x1 = 0, x0 + x1 = 1 (p = 3 by default). x1 goes from
    // the second row, leaving (p - 1) x0, a difference elimination made.
    let mut arena = Arena::new();
    let p = arena.param(0);
    let one = arena.one();
    let zero = arena.zero();
    let minus_one = arena.constant(-1.0);
    let rows2 = vec![
        LinearRow {
            entries: vec![(0, p), (1, one)],
            c: zero,
        },
        LinearRow {
            entries: vec![(0, one), (1, one)],
            c: minus_one,
        },
    ];
    let r = pre_eliminate(&mut arena, rows2, 2, &[3.0], 8, &mut |_, e| e);
    assert_eq!(r.eliminations.len(), 1, "{:?}", r.eliminations);
    assert_eq!(r.vars.len(), 1);
}

/// An entry that vanishes at the default parameter values whatever the variables are
/// (`p q` with `p = 0` by default, as an offset `r_CM[3]` times a direction cosine) does
/// not count as fill: with `max_fill = 0`, `x0` is eliminated from `x0 + x1 = 1`
/// although `p q x0 + 2 x1 = 3` also holds `x0`; with `p = 1` by default it is not. The
/// entry is kept symbolically, so the reduced system is exact for any `p`.
#[test]
fn entries_zero_at_the_defaults_do_not_count_as_fill() {
    for (default_p, eliminated) in [(0.0, 1), (1.0, 0)] {
        let mut arena = Arena::new();
        let p = arena.param(0);
        let q = arena.var(7);
        let pq = arena.mul(p, q);
        let (one, two) = (arena.one(), arena.constant(2.0));
        let (minus_one, minus_three) = (arena.constant(-1.0), arena.constant(-3.0));
        let rows = vec![
            LinearRow {
                entries: vec![(0, one), (1, one)],
                c: minus_one,
            },
            LinearRow {
                entries: vec![(0, pq), (1, two)],
                c: minus_three,
            },
        ];
        let r = pre_eliminate(&mut arena, rows, 2, &[default_p], 0, &mut |_, e| e);
        assert_eq!(r.eliminations.len(), eliminated, "p = {default_p}");
        if eliminated == 0 {
            continue;
        }
        assert_eq!(r.eliminations[0].var, 0);
        assert_eq!(r.vars, vec![1]);
        // At p = 0.5, q = 2 (so p q = 1): x0 + x1 = 1, x0 + 2 x1 = 3 => x1 = 2, x0 = -1.
        let at = |arena: &Arena, e: Id| {
            arena
                .eval(e, &|n: &Node| match n {
                    Node::Param(0) => Some(0.5),
                    Node::Var(7) => Some(2.0),
                    _ => None,
                })
                .unwrap()
        };
        let (_, row) = &r.rows[0];
        let x1 = -at(&arena, row.c) / at(&arena, row.entries[0].1);
        let e = &r.eliminations[0];
        let x0 = -(at(&arena, e.c) + at(&arena, e.others[0].1) * x1) / at(&arena, e.pivot);
        assert!(
            (x1 - 2.0).abs() < 1e-14 && (x0 + 1.0).abs() < 1e-14,
            "{x0} {x1}"
        );
    }
}
