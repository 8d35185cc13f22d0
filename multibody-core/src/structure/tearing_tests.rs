//! Golden and property tests for [`super::tear`].

use super::*;

fn eq(vars: &[(usize, bool)]) -> TearingEquation {
    TearingEquation {
        vars: vars.to_vec(),
    }
}

/// Panics unless `t` is a valid tearing of the block.
fn check(n_vars: usize, eqs: &[TearingEquation], t: &Tearing) {
    assert_eq!(t.torn_vars.len(), t.residual_eqs.len(), "{t:?}");
    let mut known = vec![false; n_vars];
    let mut eq_used = vec![false; eqs.len()];
    for &v in &t.torn_vars {
        assert!(!known[v], "var {v} torn twice");
        known[v] = true;
    }
    for &e in &t.residual_eqs {
        assert!(!eq_used[e]);
        eq_used[e] = true;
    }
    for &(e, v) in &t.assignments {
        assert!(!eq_used[e], "eq {e} used twice");
        eq_used[e] = true;
        assert!(!known[v], "var {v} assigned twice");
        assert!(
            eqs[e].vars.iter().any(|&(u, s)| u == v && s),
            "eq {e} not solvable for {v}"
        );
        for &(u, _) in &eqs[e].vars {
            assert!(u == v || known[u], "eq {e} uses unknown var {u}");
        }
        known[v] = true;
    }
    assert!(
        known.iter().all(|&k| k),
        "some variable neither torn nor assigned"
    );
    assert!(
        eq_used.iter().all(|&u| u),
        "some equation neither assigned nor residual"
    );
}

#[test]
fn three_equation_loop() {
    // v0 = R*i1, i1 = i2, v0 = R*i2 style: every var in two equations.
    let eqs = [
        eq(&[(0, true), (1, true)]),
        eq(&[(1, true), (2, true)]),
        eq(&[(0, true), (2, true)]),
    ];
    let t = tear(3, &eqs, None);
    assert_eq!(
        t,
        Tearing {
            torn_vars: vec![0],
            residual_eqs: vec![2],
            assignments: vec![(0, 1), (1, 2)],
        }
    );
    check(3, &eqs, &t);
}

#[test]
fn resistor_network_kcl() {
    // i0 = i1 + i2 (KCL), u = R1*i1, u = R2*i2, u = U - R0*i0: vars i0, i1, i2, u.
    let eqs = [
        eq(&[(0, true), (1, true), (2, true)]),
        eq(&[(3, true), (1, true)]),
        eq(&[(3, true), (2, true)]),
        eq(&[(3, true), (0, true)]),
    ];
    let t = tear(4, &eqs, None);
    // u appears in three equations: tear it; i1, i2 follow, then KCL (the lowest
    // ready equation) gives i0 and the source equation is the residual.
    assert_eq!(
        t,
        Tearing {
            torn_vars: vec![3],
            residual_eqs: vec![3],
            assignments: vec![(1, 1), (2, 2), (0, 0)],
        }
    );
    check(4, &eqs, &t);
}

#[test]
fn unsolvable_variable_is_torn() {
    // x0 + x1 = 0, sin(x1) + x0 = 0: x1 cannot be solved from eq 1.
    let eqs = [eq(&[(0, true), (1, true)]), eq(&[(1, false), (0, true)])];
    let t = tear(2, &eqs, None);
    assert_eq!(
        t,
        Tearing {
            torn_vars: vec![1],
            residual_eqs: vec![1],
            assignments: vec![(0, 0)],
        }
    );
    check(2, &eqs, &t);
}

#[test]
fn forbidden_tearing_variable_is_avoided() {
    let eqs = [
        eq(&[(0, true), (1, true)]),
        eq(&[(1, true), (2, true)]),
        eq(&[(0, true), (2, true)]),
    ];
    let t = tear(3, &eqs, Some(&[false, true, true]));
    assert_eq!(
        t,
        Tearing {
            torn_vars: vec![1],
            residual_eqs: vec![2],
            assignments: vec![(0, 0), (1, 2)],
        }
    );
    // nothing tearable: still a valid result
    let t = tear(3, &eqs, Some(&[false, false, false]));
    assert_eq!(t.torn_vars, vec![0]);
    check(3, &eqs, &t);
}

#[test]
fn priority_picks_tearing_variable() {
    let eqs = [
        eq(&[(0, true), (1, true)]),
        eq(&[(1, true), (2, true)]),
        eq(&[(0, true), (2, true)]),
    ];
    let t = tear_with_priority(3, &eqs, None, Some(&[0.0, 0.0, 1.0]));
    assert_eq!(
        t,
        Tearing {
            torn_vars: vec![2],
            residual_eqs: vec![2],
            assignments: vec![(1, 1), (0, 0)],
        }
    );
}

#[test]
fn triangular_block_needs_no_tearing() {
    let eqs = [eq(&[(0, true), (1, true)]), eq(&[(1, true)])];
    let t = tear(2, &eqs, None);
    assert_eq!(
        t,
        Tearing {
            torn_vars: vec![],
            residual_eqs: vec![],
            assignments: vec![(1, 1), (0, 0)],
        }
    );
}

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// A random block with a perfect matching (eq i contains var perm[i]).
fn random_block(rng: &mut Rng, n: usize, extra: usize) -> Vec<TearingEquation> {
    let mut perm: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        perm.swap(i, rng.below(i + 1));
    }
    (0..n)
        .map(|i| {
            let mut vars = vec![(perm[i], rng.below(4) != 0)];
            for _ in 0..rng.below(extra + 1) {
                vars.push((rng.below(n), rng.below(3) != 0));
            }
            TearingEquation { vars }
        })
        .collect()
}

#[test]
fn random_blocks_are_valid() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    for _ in 0..2000 {
        let n = 1 + rng.below(12);
        let eqs = random_block(&mut rng, n, 4);
        let tearable: Vec<bool> = (0..n).map(|_| rng.below(5) != 0).collect();
        let t = tear(n, &eqs, Some(&tearable));
        check(n, &eqs, &t);
        assert_eq!(t, tear(n, &eqs, Some(&tearable)));
    }
}

#[test]
fn large_blocks_are_torn_as_their_structure_dictates() {
    // One big cycle, eq i in vars i and i+1 (mod n): every variable is in two
    // equations, so the lowest index is torn; then eq 0 gives var 1, eq 1 var 2, ...,
    // eq n-2 var n-1 (lowest ready equation first), and eq n-1 (vars n-1 and 0) is the
    // one residual. A single tearing variable suffices, and this is the only order.
    let n = 10_000;
    let eqs: Vec<TearingEquation> = (0..n)
        .map(|i| eq(&[(i, true), ((i + 1) % n, true)]))
        .collect();
    let t = tear(n, &eqs, None);
    check(n, &eqs, &t);
    assert_eq!(
        t,
        Tearing {
            torn_vars: vec![0],
            residual_eqs: vec![n - 1],
            assignments: (0..n - 1).map(|i| (i, i + 1)).collect(),
        }
    );

    // A lower-triangular block in disguise: eq i solves var perm[i] and uses only
    // variables solved by earlier equations (any of them, solvable or not), with the
    // equations shuffled. It needs no tearing at all: there is always an equation with
    // one unknown, so nothing may be torn, and every equation is an assignment of its
    // own variable.
    let mut rng = Rng(7);
    let mut perm: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        perm.swap(i, rng.below(i + 1));
    }
    let mut triangular: Vec<(usize, TearingEquation)> = (0..n)
        .map(|i| {
            let mut vars = vec![(perm[i], true)];
            if i > 0 {
                for _ in 0..rng.below(4) {
                    vars.push((perm[rng.below(i)], rng.below(2) == 0));
                }
            }
            (perm[i], TearingEquation { vars })
        })
        .collect();
    for i in (1..n).rev() {
        triangular.swap(i, rng.below(i + 1));
    }
    let (solves, eqs): (Vec<usize>, Vec<TearingEquation>) = triangular.into_iter().unzip();
    let t = tear(n, &eqs, None);
    check(n, &eqs, &t);
    assert!(t.torn_vars.is_empty(), "{} torn", t.torn_vars.len());
    assert!(t.residual_eqs.is_empty());
    assert_eq!(t.assignments.len(), n);
    for &(e, v) in &t.assignments {
        assert_eq!(v, solves[e], "eq {e} solved for the wrong variable");
    }

    // A random block of the same size: still a valid tearing, deterministic.
    let eqs = random_block(&mut rng, n, 3);
    let t = tear(n, &eqs, None);
    check(n, &eqs, &t);
    assert_eq!(t, tear(n, &eqs, None));
}
