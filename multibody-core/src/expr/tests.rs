//! Unit tests of construction-time simplification, display and solving.

use super::*;

fn v(name: &str) -> Expr {
    Expr::var(name)
}

#[test]
fn sums_collect_like_terms_and_fold_constants() {
    let x = v("t_sum.x");
    let y = v("t_sum.y");
    assert_eq!(x + x, 2.0 * x);
    assert_eq!((x + 1.0) - 1.0, x);
    assert_eq!(x - x, Expr::constant(0.0));
    assert_eq!((x + y) + (y - x), 2.0 * y);
    assert_eq!(((x + 2.0) * 3.0).to_string(), "3*t_sum.x + 6");
}

#[test]
fn products_merge_exponents_and_neutral_elements() {
    let x = v("t_prod.x");
    let y = v("t_prod.y");
    assert_eq!(x * x, x.powi(2));
    assert_eq!(x * 1.0, x);
    assert_eq!(x * 0.0, Expr::constant(0.0));
    assert_eq!((x * y) / x, y);
    assert_eq!((2.0 * x) * (3.0 * y), 6.0 * (x * y));
    assert_eq!((x / y).to_string(), "t_prod.x/t_prod.y");
    assert_eq!(Expr::constant(2.0).sin().as_f64(), Some(2f64.sin()));
}

#[test]
fn display_is_readable_infix() {
    // terms are ordered by creation: sin(phi) exists before w here
    let phi = v("pendulum.phi");
    let s = phi.sin();
    let w = v("pendulum.w");
    assert_eq!(
        (s * 2.0 + w).to_string(),
        "2*sin(pendulum.phi) + pendulum.w"
    );
    assert_eq!(
        (w - phi.der()).to_string(),
        "pendulum.w - der(pendulum.phi)"
    );
    let e = (phi + w) * v("pendulum.J");
    assert_eq!(e.to_string(), "(pendulum.phi + pendulum.w)*pendulum.J");
    assert_eq!((-phi).to_string(), "-pendulum.phi");
}

#[test]
fn solve_linear_gives_solution_and_coefficient() {
    let x = v("t_solve.x");
    let y = v("t_solve.y");
    let r = Expr::param("t_solve.R");
    // R*x - y = 0  ->  x = y/R, coefficient R
    let (sol, coef) = (r * x - y).solve_for(x).unwrap();
    assert_eq!(sol, y / r);
    assert_eq!(coef, r);
    // nonlinear in x
    assert!((x * x - y).solve_for(x).is_none());
    assert!((x.sin() - y).solve_for(x).is_none());
    // absent
    assert!((y - 1.0).solve_for(x).is_none());
    // x*y - 1 is linear in x with coefficient y (which may vanish)
    let (_, c) = (x * y - 1.0).solve_for(x).unwrap();
    assert_eq!(c, y);
}

#[test]
fn derivatives_of_known_forms() {
    let x = v("t_diff.x");
    let y = v("t_diff.y");
    assert_eq!((x * y).diff(x), y);
    assert_eq!((x.powi(3)).diff(x), 3.0 * x.powi(2));
    assert_eq!(x.sin().diff(x), x.cos());
    assert_eq!(x.sin().time_derivative(), x.cos() * x.der());
    assert_eq!((x * y).time_derivative(), x * y.der() + y * x.der());
    assert_eq!(x.der().diff(x), Expr::constant(0.0));
    assert_eq!(x.der().diff(x.der()), Expr::constant(1.0));
}

#[test]
fn substitution_re_simplifies() {
    let x = v("t_subst.x");
    let y = v("t_subst.y");
    let e = x * y + x.der();
    let r = e.substitute(&[(x, Expr::constant(2.0) * y)]);
    assert_eq!(r, 2.0 * y.powi(2) + 2.0 * y.der());
}

#[test]
fn equal_sums_and_products_are_one_node_with_operands_stored_once() {
    let mut a = Arena::new();
    let (x, y, z) = (a.var(0), a.var(1), a.var(2));
    let s = a.linear_combination(1.5, &[(2.0, x), (-1.0, y)]);
    let p = a.product(&[x, y, z]);
    let pools = a.pool_lens();
    let nodes = a.len();
    // The same operands in another order: the same nodes, and nothing new stored.
    assert_eq!(a.linear_combination(1.5, &[(-1.0, y), (2.0, x)]), s);
    assert_eq!(a.product(&[z, x, y]), p);
    assert_eq!((a.len(), a.pool_lens()), (nodes, pools));
    // Different operands are different nodes, read back from the pools.
    let s2 = a.linear_combination(1.5, &[(2.0, x), (1.0, y)]);
    assert_ne!(s2, s);
    let Node::Sum(ts, c) = *a.node(s2) else {
        panic!("a sum")
    };
    assert_eq!(f64::from_bits(c), 1.5);
    let terms: Vec<(f64, Id)> = a
        .terms(ts)
        .iter()
        .map(|&(k, t)| (f64::from_bits(k), t))
        .collect();
    assert_eq!(terms, vec![(2.0, x), (1.0, y)]);
    let Node::Prod(fs) = *a.node(p) else {
        panic!("a product")
    };
    assert_eq!(a.factors(fs), &[(x, 1), (y, 1), (z, 1)]);
    // A clone is independent: what it adds is not in the original.
    let mut b = a.clone();
    b.product(&[x, x, y]);
    assert_eq!(a.len(), nodes + 1);
    assert_eq!(b.len(), nodes + 2);
}

#[test]
fn nodes_sharing_their_newest_operand_are_told_apart_and_found_after_growth() {
    // The table places a node by its newest operand: thousands of nodes built on the
    // same `x` crowd one region, and the table grows many times meanwhile. Every node
    // must still be found again, and distinct ones stay distinct.
    let mut a = Arena::new();
    let (x, y) = (a.var(0), a.var(1));
    let build = |a: &mut Arena| -> Vec<Id> {
        let mut made = Vec::new();
        for k in 1..=3000 {
            let c = a.constant(k as f64);
            made.push(a.powi(x, k));
            made.push(a.linear_combination(0.0, &[(1.0, x), (1.0, c)]));
            made.push(a.f1(Func1::Sin, made[made.len() - 1]));
            made.push(a.linear_combination(k as f64, &[(1.0, x), (2.0, y)]));
        }
        made
    };
    let first = build(&mut a);
    let len = a.len();
    let distinct: std::collections::HashSet<Id> = first.iter().copied().collect();
    assert_eq!(distinct.len(), first.len());
    // Var, param and der leaves never enter the table but are still one node each.
    let (v, p, d) = (a.var(7), a.param(3), a.der(y));
    assert_eq!((a.var(7), a.param(3), a.der(y)), (v, p, d));
    assert_eq!(build(&mut a), first);
    assert_eq!(a.len(), len + 3);
}

#[test]
fn solving_for_a_direct_term_equals_the_general_path() {
    let mut a = Arena::new();
    let (x, y, z) = (a.var(0), a.var(1), a.var(2));
    let p = a.param(0);
    let sin_y = a.f1(Func1::Sin, y);
    let xy = a.mul(x, y);
    let yz = a.mul(y, z);
    let x2 = a.powi(x, 2);
    let cases: Vec<Id> = vec![
        // x a direct term: the shortcut answers.
        a.linear_combination(0.1, &[(3.0, x), (5.0, sin_y), (1.0 / 3.0, yz)]),
        a.linear_combination(0.0, &[(-1.0, x), (1.0, y)]),
        a.linear_combination(2.5, &[(7.0, x)]),
        a.linear_combination(0.0, &[(0.3, x), (1.0, p)]),
        // x also inside another term: the general path decides (linear, nonlinear).
        a.linear_combination(1.0, &[(2.0, x), (1.0, xy)]),
        a.linear_combination(0.0, &[(2.0, x), (1.0, x2)]),
    ];
    for (i, &e) in cases.iter().enumerate() {
        let fast = a.solve_linear(e, x);
        let general = a.solve_linear_general(e, x);
        assert_eq!(fast, general, "case {i}");
        if i < 4 {
            assert!(fast.is_some(), "case {i}");
        }
    }
    assert!(a.solve_linear(cases[5], x).is_none());
}

#[test]
fn an_extending_arena_finds_its_base_nodes_and_adds_its_own_after_them() {
    let mut base = Arena::new();
    let (x, y) = (base.var(0), base.var(1));
    let (dx, q) = (base.der(x), base.param(3));
    let s = base.linear_combination(1.5, &[(2.0, x), (-1.0, y)]);
    let p = base.product(&[x, y]);
    let sin_s = base.f1(Func1::Sin, s);
    let base_len = base.len();
    let base = std::sync::Arc::new(base);
    let mut a = Arena::extending(base.clone());
    assert_eq!(a.len(), base_len);
    // Rebuilt in any order, the base's nodes are found under their ids, nothing added.
    assert_eq!(a.linear_combination(1.5, &[(-1.0, y), (2.0, x)]), s);
    assert_eq!(a.product(&[y, x]), p);
    assert_eq!(a.f1(Func1::Sin, s), sin_s);
    assert_eq!((a.var(0), a.var(1), a.der(x), a.param(3)), (x, y, dx, q));
    assert_eq!(a.len(), base_len);
    // The operands of a candidate found in the base are given back.
    assert_eq!(a.pool_lens(), (0, 0));
    // New nodes come after the base's, and their operands read back from the pools.
    let s2 = a.linear_combination(0.5, &[(1.0, p), (3.0, sin_s)]);
    let p2 = a.product(&[s, s2]);
    let z = a.var(2);
    assert!(s2.index() >= base_len && p2.index() >= base_len && z.index() >= base_len);
    let Node::Sum(ts, c) = *a.node(s2) else {
        panic!("a sum")
    };
    assert_eq!(f64::from_bits(c), 0.5);
    assert_eq!(a.terms(ts).len(), 2);
    let Node::Prod(fs) = *a.node(p2) else {
        panic!("a product")
    };
    assert_eq!(a.factors(fs), &[(s, 1), (s2, 1)]);
    let Node::Sum(base_ts, _) = *a.node(s) else {
        panic!("a sum")
    };
    assert_eq!(a.terms(base_ts), base.terms(base_ts));
    // The base is untouched; rebuilding finds the new nodes again.
    assert_eq!(base.len(), base_len);
    let (len, pools) = (a.len(), a.pool_lens());
    assert_eq!(a.linear_combination(0.5, &[(3.0, sin_s), (1.0, p)]), s2);
    assert_eq!(a.product(&[s2, s]), p2);
    assert_eq!((a.len(), a.pool_lens()), (len, pools));
    // An arena extending an extending one keeps every id (its base is made standalone).
    let mut b = Arena::extending(std::sync::Arc::new(a.clone()));
    assert_eq!(b.len(), len);
    assert_eq!(b.product(&[s2, s]), p2);
    assert_eq!(b.linear_combination(1.5, &[(2.0, x), (-1.0, y)]), s);
    assert_eq!(b.var(2), z);
    assert_eq!(b.node(s2), a.node(s2));
    assert_eq!(b.len(), len);
}

#[test]
fn containing_marks_exactly_the_nodes_that_reach_a_key() {
    let mut a = Arena::new();
    let (x, y, z) = (a.var(0), a.var(1), a.var(2));
    let dx = a.der(x);
    let sum = a.add(dx, y);
    let sin_sum = a.f1(Func1::Sin, sum);
    let prod = a.mul(y, z);
    let top = a.add(sin_sum, prod);
    let mark = a.containing([dx].into_iter());
    for (id, expected) in [
        (dx, true),
        (sum, true),
        (sin_sum, true),
        (top, true),
        (x, false),
        (y, false),
        (z, false),
        (prod, false),
    ] {
        assert_eq!(mark[id.index()], expected, "node {id:?}");
    }
    assert!(a.containing(std::iter::empty()).iter().all(|&m| !m));
}
