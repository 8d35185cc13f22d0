//! Tests of [`Arena::linear_form`] and [`Arena::linear_coefficients`]: the coefficients are the partial derivatives that
//! [`Arena::diff`] gives (the same nodes), the rest is the expression with the unknowns
//! at zero, and what is not linear in the unknowns is refused.

use super::{Arena, Cmp, Func1, Id, LinearForm, Node};

/// Value of `e` with variable `i` equal to `x[i]`, parameter `j` equal to `p[j]`.
fn value(arena: &Arena, e: Id, x: &[f64], p: &[f64]) -> f64 {
    arena
        .eval(e, &|n: &Node| match n {
            Node::Var(i) => x.get(*i as usize).copied(),
            Node::Param(j) => p.get(*j as usize).copied(),
            _ => None,
        })
        .expect("every leaf has a value")
}

/// Unknowns: variables 0 and 1 (indices 0 and 1); variable 2 and the parameters are
/// known.
fn unknown(arena: &Arena) -> impl Fn(Id) -> Option<usize> + '_ {
    move |l| match arena.node(l) {
        Node::Var(i) if *i < 2 => Some(*i as usize),
        _ => None,
    }
}

fn form(arena: &mut Arena, e: Id) -> Option<LinearForm> {
    let copy = arena.clone();
    arena.linear_form(e, &unknown(&copy))
}

/// `3 x cos(p) + (a + b) y - 2 x + sin(q) + c (x + y)`: coefficients `3 cos(p) - 2 + c`
/// and `a + b + c`, rest `sin(q)`; they are the very nodes `diff` builds, and the form
/// evaluates to the expression at a random point.
#[test]
fn coefficients_are_the_partial_derivatives_and_the_rest_is_what_is_left() {
    let mut a = Arena::new();
    let (x, y, q) = (a.var(0), a.var(1), a.var(2));
    let (p, pa, pb, pc) = (a.param(0), a.param(1), a.param(2), a.param(3));
    let cos_p = a.f1(Func1::Cos, p);
    let three = a.constant(3.0);
    let t1 = a.product(&[three, x, cos_p]);
    let ab = a.add(pa, pb);
    let t2 = a.mul(ab, y);
    let two = a.constant(2.0);
    let t3 = a.mul(two, x);
    let sin_q = a.f1(Func1::Sin, q);
    let xy = a.add(x, y);
    let t5 = a.mul(pc, xy);
    let s = a.add(t1, t2);
    let s = a.sub(s, t3);
    let s = a.add(s, sin_q);
    let e = a.add(s, t5);
    let f = form(&mut a, e).expect("linear in x and y");
    assert_eq!(f.coefficients.len(), 2, "{f:?}");
    for &(j, coef) in &f.coefficients {
        let leaf = [x, y][j];
        assert_eq!(coef, a.diff(e, leaf), "coefficient of unknown {j}");
    }
    assert_eq!(f.rest, sin_q);
    let (xv, pv) = ([0.3, -1.7, 0.9], [0.4, 1.1, -2.5, 0.6]);
    let mut sum = value(&a, f.rest, &xv, &pv);
    for &(j, coef) in &f.coefficients {
        sum += value(&a, coef, &xv, &pv) * xv[j];
    }
    let want = value(&a, e, &xv, &pv);
    assert!(
        (sum - want).abs() < 1e-12 * want.abs().max(1.0),
        "{sum} vs {want}"
    );
}

/// Coefficients of several expressions share their subexpressions' work and agree with
/// the forms taken one at a time, and `der(x)` is a leaf of its own.
#[test]
fn shared_coefficients_agree_with_single_forms() {
    let mut a = Arena::new();
    let (x, y, q) = (a.var(0), a.var(1), a.var(2));
    let cos_q = a.f1(Func1::Cos, q);
    let common = a.mul(cos_q, y);
    let dx = a.der(x);
    let e1 = a.add(common, dx);
    let e2 = a.sub(common, x);
    let copy = a.clone();
    let both = a.linear_coefficients(&[e1, e2], &unknown(&copy));
    let singles = [form(&mut a, e1), form(&mut a, e2)];
    for (shared, single) in both.iter().zip(&singles) {
        assert_eq!(shared.as_ref(), single.as_ref().map(|f| &f.coefficients));
    }
    let f1 = singles[0].clone().expect("linear");
    assert_eq!(f1.coefficients, vec![(1, cos_q)]);
    assert_eq!(f1.rest, dx, "der(x) is not x");
}

/// The arena does not distribute `c (x + y) - c x`: the coefficient of `x` cancels to
/// nothing and that of `y` is `c`, the rest 0. When every unknown of a sum cancels
/// (`c (x + y) - c x - c y`), the node still holds them, so it is not called free of
/// them: no form, and neither has a product of it with an unknown.
#[test]
fn cancelled_unknowns_are_absent_or_refuse_the_form() {
    let mut a = Arena::new();
    let (x, y, c) = (a.var(0), a.var(1), a.param(0));
    let xy = a.add(x, y);
    let c_xy = a.mul(c, xy);
    let cx = a.mul(c, x);
    let partial = a.sub(c_xy, cx);
    assert_ne!(
        partial,
        a.mul(c, y),
        "the arena distributed: the test needs another case"
    );
    let f = form(&mut a, partial).expect("linear in y");
    assert_eq!(f.coefficients, vec![(1, c)]);
    assert_eq!(f.rest, a.zero());
    let cy = a.mul(c, y);
    let all = a.sub(partial, cy);
    assert_ne!(
        all,
        a.zero(),
        "the arena cancelled: the test needs another case"
    );
    assert_eq!(form(&mut a, all), None);
    let y_all = a.mul(y, all);
    assert_eq!(form(&mut a, y_all), None);
    // A power of a parameter times a sum: p^-1 (x + 2 y).
    let p = a.param(1);
    let inv_p = a.powi(p, -1);
    let two = a.constant(2.0);
    let two_y = a.mul(two, y);
    let x_2y = a.add(x, two_y);
    let e = a.mul(inv_p, x_2y);
    let f = form(&mut a, e).expect("linear");
    for &(j, coef) in &f.coefficients {
        assert_eq!(coef, a.diff(e, [x, y][j]));
    }
    assert_eq!(f.coefficients.len(), 2);
}

/// Products of unknowns, powers, functions and conditions of them are not linear;
/// functions of known leaves are.
#[test]
fn nonlinear_uses_of_the_unknowns_are_refused() {
    let mut a = Arena::new();
    let (x, y, q) = (a.var(0), a.var(1), a.var(2));
    let xy = a.mul(x, y);
    let x2 = a.powi(x, 2);
    let sin_x = a.f1(Func1::Sin, x);
    let zero = a.zero();
    let positive = a.cmp(Cmp::Gt, x, zero);
    let branch = a.ite(positive, y, q);
    for e in [xy, x2, sin_x, branch] {
        assert_eq!(form(&mut a, e), None, "{e:?}");
    }
    let sin_q = a.f1(Func1::Sin, q);
    let e = a.mul(sin_q, x);
    assert_eq!(form(&mut a, e).unwrap().coefficients, vec![(0, sin_q)]);
}
