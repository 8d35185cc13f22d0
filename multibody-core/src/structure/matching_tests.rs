//! Golden and property tests for [`super::maximum_matching`].

use super::*;

fn check_valid(g: &BipartiteGraph, m: &Matching) {
    for (e, v) in m.eq_to_var.iter().enumerate() {
        if let Some(v) = *v {
            assert_eq!(m.var_to_eq[v], Some(e));
            assert!(g.eq_vars[e].binary_search(&v).is_ok());
        }
    }
    for (v, e) in m.var_to_eq.iter().enumerate() {
        if let Some(e) = *e {
            assert_eq!(m.eq_to_var[e], Some(v));
        }
    }
}

/// Simple Kuhn algorithm (recursion-free) used as a reference on small graphs.
fn reference_size(g: &BipartiteGraph) -> usize {
    let mut var_to_eq = vec![None::<usize>; g.n_vars];
    let mut size = 0;
    for root in 0..g.n_eqs() {
        let mut seen = vec![false; g.n_vars];
        // stack of (eq, next position, var chosen to reach it)
        let mut stack: Vec<(usize, usize)> = vec![(root, 0)];
        let mut via: Vec<usize> = Vec::new();
        let mut ok = false;
        while let Some(top) = stack.last_mut() {
            let e = top.0;
            if top.1 >= g.eq_vars[e].len() {
                stack.pop();
                via.pop();
                continue;
            }
            let v = g.eq_vars[e][top.1];
            top.1 += 1;
            if seen[v] {
                continue;
            }
            seen[v] = true;
            via.push(v);
            match var_to_eq[v] {
                None => {
                    ok = true;
                    break;
                }
                Some(w) => stack.push((w, 0)),
            }
        }
        if ok {
            for (i, &(e, _)) in stack.iter().enumerate() {
                var_to_eq[via[i]] = Some(e);
            }
            size += 1;
        }
    }
    size
}

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
}

#[test]
fn long_chain_is_perfect() {
    let n = 100_000;
    let mut g = BipartiteGraph::new(n);
    for i in 0..n - 1 {
        g.add_equation(vec![i, i + 1]);
    }
    g.add_equation(vec![n - 1]);
    let m = maximum_matching(&g, None, None);
    assert!(m.is_perfect());
    assert_eq!(m.size(), n);
    // the unique perfect matching: eq i <-> var i
    assert!(m.eq_to_var.iter().enumerate().all(|(e, v)| *v == Some(e)));
}

#[test]
fn tridiagonal_with_random_preferences_is_perfect() {
    let n = 200_000;
    let mut g = BipartiteGraph::new(n);
    for i in 0..n {
        g.add_equation(vec![i.saturating_sub(1), i, (i + 1).min(n - 1)]);
    }
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let pref: Vec<f64> = (0..n).map(|_| (rng.next() % 1000) as f64).collect();
    let m = maximum_matching(&g, None, Some(&pref));
    check_valid(&g, &m);
    assert!(m.is_perfect());
    assert_eq!(m, maximum_matching(&g, None, Some(&pref)));
}

#[test]
fn structurally_singular() {
    let mut g = BipartiteGraph::new(2);
    g.add_equation(vec![0]);
    g.add_equation(vec![0]);
    let m = maximum_matching(&g, None, None);
    assert_eq!(m.size(), 1);
    assert_eq!(m.eq_to_var, vec![Some(0), None]);
    assert_eq!(m.var_to_eq, vec![Some(0), None]);
    assert!(!m.is_perfect());
}

#[test]
fn underdetermined() {
    let mut g = BipartiteGraph::new(3);
    g.add_equation(vec![0, 1]);
    g.add_equation(vec![1, 2]);
    let m = maximum_matching(&g, None, None);
    assert_eq!(m.size(), 2);
    assert_eq!(m.eq_to_var, vec![Some(0), Some(2)]);
    assert_eq!(m.var_to_eq, vec![Some(0), None, Some(1)]);
}

#[test]
fn var_allowed_excludes_known_variables() {
    let mut g = BipartiteGraph::new(3);
    g.add_equation(vec![0, 1]);
    g.add_equation(vec![1, 2]);
    let allowed = [true, false, true];
    let m = maximum_matching(&g, Some(&allowed), None);
    assert_eq!(m.eq_to_var, vec![Some(0), Some(2)]);
    assert_eq!(m.var_to_eq, vec![Some(0), None, Some(1)]);
    let allowed = [false, false, true];
    let m = maximum_matching(&g, Some(&allowed), None);
    assert_eq!(m.eq_to_var, vec![None, Some(2)]);
}

#[test]
fn preference_chooses_among_alternatives() {
    let mut g = BipartiteGraph::new(2);
    g.add_equation(vec![0, 1]);
    let m = maximum_matching(&g, None, None);
    assert_eq!(m.eq_to_var, vec![Some(0)]);
    let m = maximum_matching(&g, None, Some(&[0.0, 5.0]));
    assert_eq!(m.eq_to_var, vec![Some(1)]);
}

#[test]
fn augmentation_repairs_greedy_choice() {
    let mut g = BipartiteGraph::new(2);
    g.add_equation(vec![0, 1]);
    g.add_equation(vec![1, 0]);
    g.add_equation(vec![]);
    let m = maximum_matching(&g, None, Some(&[0.0, 1.0]));
    assert_eq!(m.size(), 2);
    // eq 2 is empty, so all vars but not all eqs are matched
    assert!(!m.is_perfect());
    // greedy: eq0 -> var1 (preferred), eq1 -> var2, eq2 left free;
    // the augmenting path eq2 - var1 - eq0 - var0 repairs it.
    let mut g = BipartiteGraph::new(3);
    g.add_equation(vec![0, 1]);
    g.add_equation(vec![1, 2]);
    g.add_equation(vec![1, 2]);
    let m = maximum_matching(&g, None, Some(&[0.0, 2.0, 1.0]));
    check_valid(&g, &m);
    assert_eq!(m.eq_to_var, vec![Some(0), Some(2), Some(1)]);
}

#[test]
fn random_graphs_match_reference() {
    let mut rng = Rng(12345);
    for _ in 0..500 {
        let n_eqs = (rng.next() % 12) as usize;
        let n_vars = (rng.next() % 12) as usize + 1;
        let mut g = BipartiteGraph::new(n_vars);
        for _ in 0..n_eqs {
            let k = (rng.next() % 4) as usize;
            g.add_equation((0..k).map(|_| (rng.next() as usize) % n_vars).collect());
        }
        let pref: Vec<f64> = (0..n_vars).map(|_| (rng.next() % 3) as f64).collect();
        let m = maximum_matching(&g, None, Some(&pref));
        check_valid(&g, &m);
        assert_eq!(m.size(), reference_size(&g));
    }
}

#[test]
fn large_random_planted_perfect_matching() {
    let n = 100_000;
    let mut rng = Rng(0xdead_beef_1234_5678);
    let mut perm: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        perm.swap(i, (rng.next() as usize) % (i + 1));
    }
    let mut g = BipartiteGraph::new(n);
    for &p in &perm {
        let a = (rng.next() as usize) % n;
        let b = (rng.next() as usize) % n;
        g.add_equation(vec![p, a, b]);
    }
    let pref: Vec<f64> = (0..n).map(|_| (rng.next() % 7) as f64).collect();
    let m = maximum_matching(&g, None, Some(&pref));
    check_valid(&g, &m);
    assert!(m.is_perfect());
}

#[test]
fn incremental_augmenting_reaches_a_maximum_matching() {
    // Equations added one at a time, each matched by an augmenting path when one
    // exists: the final matching is maximum (against the reference) and valid, and
    // the work space carries no marks from one search into the next.
    let mut rng = Rng(777);
    for _ in 0..200 {
        let n_vars = 1 + (rng.next() % 10) as usize;
        let n_eqs = (rng.next() % 12) as usize;
        let mut g = BipartiteGraph::new(n_vars);
        let mut m = Matching {
            eq_to_var: Vec::new(),
            var_to_eq: vec![None; n_vars],
        };
        let mut search = Augmenter::new(n_vars, 0);
        for _ in 0..n_eqs {
            let k = (rng.next() % 4) as usize;
            let e = g.add_equation((0..k).map(|_| (rng.next() as usize) % n_vars).collect());
            m.eq_to_var.push(None);
            search.augment(&g.eq_vars, e, &mut m.var_to_eq, &mut m.eq_to_var);
        }
        check_valid(&g, &m);
        assert_eq!(m.size(), reference_size(&g));
    }
}
