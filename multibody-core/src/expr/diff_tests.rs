//! Property tests of symbolic differentiation: every derivative rule of
//! [`Arena::diff`] and [`Arena::time_derivative`] against central finite differences
//! of the numeric evaluation at random points where the function is smooth.

use proptest::prelude::*;
use proptest::test_runner::TestCaseError;

use super::{Arena, Cmp, Func1, Func2, Id, Node};

/// Relative tolerance of the comparison with a central difference of step
/// `FD_STEP * max(1, |x|)` (truncation ~h^2, round-off ~eps/h: both far below).
const FD_TOL: f64 = 1e-6;
const FD_STEP: f64 = 1e-6;

/// Value of `e` with variable `i` equal to `x[i]`, `der(var i)` equal to `xdot[i]`,
/// `der(der(var i))` equal to `xddot[i]`, parameter `j` equal to `p[j]` and time `t`.
struct Point<'a> {
    x: &'a [f64],
    xdot: &'a [f64],
    xddot: &'a [f64],
    p: &'a [f64],
    t: f64,
}

fn eval_at(arena: &Arena, e: Id, pt: &Point<'_>) -> f64 {
    arena
        .eval(e, &|n: &Node| match n {
            Node::Var(i) => pt.x.get(*i as usize).copied(),
            Node::Param(j) => pt.p.get(*j as usize).copied(),
            Node::Time => Some(pt.t),
            Node::Der(inner) => match arena.node(*inner) {
                Node::Var(i) => pt.xdot.get(*i as usize).copied(),
                Node::Der(inner2) => match arena.node(*inner2) {
                    Node::Var(i) => pt.xddot.get(*i as usize).copied(),
                    _ => None,
                },
                _ => None,
            },
            Node::Const(_) => None,
            _ => None,
        })
        .expect("every leaf has a value")
}

fn eval_vars(arena: &Arena, e: Id, x: &[f64]) -> f64 {
    eval_at(
        arena,
        e,
        &Point {
            x,
            xdot: &[],
            xddot: &[],
            p: &[],
            t: 0.0,
        },
    )
}

/// Central difference of `f` at `x0`.
fn central(f: impl Fn(f64) -> f64, x0: f64) -> f64 {
    let h = FD_STEP * x0.abs().max(1.0);
    (f(x0 + h) - f(x0 - h)) / (2.0 * h)
}

fn close(got: f64, reference: f64) -> bool {
    got.is_finite() && (got - reference).abs() <= FD_TOL * got.abs().max(reference.abs()).max(1.0)
}

/// Builds `e` from variables `0..x.len()` and checks `diff(e, var k)` against a
/// central difference in `x[k]`, for every `k`.
fn check_gradient(x: &[f64], build: impl Fn(&mut Arena, &[Id]) -> Id) -> Result<(), TestCaseError> {
    let mut arena = Arena::new();
    let vars: Vec<Id> = (0..x.len() as u32).map(|i| arena.var(i)).collect();
    let e = build(&mut arena, &vars);
    for k in 0..x.len() {
        let d = arena.diff(e, vars[k]);
        let got = eval_vars(&arena, d, x);
        let reference = central(
            |xk| {
                let mut xs = x.to_vec();
                xs[k] = xk;
                eval_vars(&arena, e, &xs)
            },
            x[k],
        );
        prop_assert!(
            close(got, reference),
            "d/dx{k} at {x:?}: symbolic {got}, finite difference {reference}"
        );
    }
    Ok(())
}

fn f1(a: &mut Arena, f: Func1, x: Id) -> Id {
    a.f1(f, x)
}

/// A value with magnitude in `[lo, hi)`, of either sign.
fn away_from_zero(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo..hi, any::<bool>()).prop_map(|(m, neg)| if neg { -m } else { m })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 128,
        // a failure prints its minimal input; no regression file in the source tree
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn sum_rule(x in -5.0f64..5.0, y in -5.0f64..5.0, z in -5.0f64..5.0) {
        check_gradient(&[x, y, z], |a, v| {
            // 3x - 2y + z + 7, and a sum nested in a linear combination
            let s = a.linear_combination(7.0, &[(3.0, v[0]), (-2.0, v[1]), (1.0, v[2])]);
            let s2 = a.sub(v[1], v[2]);
            a.linear_combination(0.5, &[(2.0, s), (-4.0, s2)])
        })?;
    }

    #[test]
    fn product_rule(x in -3.0f64..3.0, y in -3.0f64..3.0, z in -3.0f64..3.0) {
        check_gradient(&[x, y, z], |a, v| {
            let xy = a.mul(v[0], v[1]);
            let s = a.add(v[2], v[0]);
            // x^2 y (z + x) z: a repeated factor exercises the exponent
            let xyz = a.product(&[xy, s, v[2], v[0]]);
            a.scale(-1.5, xyz)
        })?;
    }

    #[test]
    fn quotient_rule(x in -3.0f64..3.0, y in away_from_zero(0.5, 3.0), z in -3.0f64..3.0) {
        check_gradient(&[x, y, z], |a, v| {
            // (x + z) / (y * (1 + z^2))
            let num = a.add(v[0], v[2]);
            let z2 = a.powi(v[2], 2);
            let one_z2 = a.linear_combination(1.0, &[(1.0, z2)]);
            let den = a.mul(v[1], one_z2);
            a.div(num, den)
        })?;
    }

    #[test]
    fn integer_power_rule(
        x in away_from_zero(0.3, 2.5),
        y in -2.0f64..2.0,
        n in -4i32..=5,
    ) {
        check_gradient(&[x, y], |a, v| {
            // x^n + (x + 3)^n * y^2 and a product of powers x^n y^-? kept away from y=0
            let xn = a.powi(v[0], n);
            let s = a.linear_combination(3.0, &[(1.0, v[0])]);
            let sn = a.powi(s, n);
            let y2 = a.powi(v[1], 2);
            let t = a.mul(sn, y2);
            a.add(xn, t)
        })?;
        check_gradient(&[x, y], |a, v| {
            // x^n * (y + 4)^(-2) * x^2
            let s = a.linear_combination(4.0, &[(1.0, v[1])]);
            let xn = a.powi(v[0], n);
            let sm2 = a.powi(s, -2);
            let x2 = a.powi(v[0], 2);
            a.product(&[xn, sm2, x2])
        })?;
    }

    #[test]
    fn general_power_rule(x in 0.2f64..3.0, y in -2.0f64..2.0) {
        // both base and exponent variable
        check_gradient(&[x, y], |a, v| a.pow(v[0], v[1]))?;
        // non-integer constant exponent, constant base, and a composed exponent
        check_gradient(&[x, y], |a, v| {
            let c = a.constant(1.5);
            let p1 = a.pow(v[0], c);
            let two = a.constant(2.0);
            let p2 = a.pow(two, v[1]);
            let xy = a.mul(v[0], v[1]);
            let ey = a.f1(Func1::Sin, xy);
            let p3 = a.pow(v[0], ey);
            a.sum(&[p1, p2, p3])
        })?;
    }

    #[test]
    fn trigonometric_rules(x in -1.2f64..1.2, y in -3.0f64..3.0) {
        for f in [Func1::Sin, Func1::Cos, Func1::Tan] {
            // f(x), and f(x * y) so the chain rule runs through a product
            check_gradient(&[x], |a, v| f1(a, f, v[0]))?;
            check_gradient(&[x, y], |a, v| {
                let xy = a.mul(v[0], v[1]);
                let arg = a.scale(0.4, xy);
                f1(a, f, arg)
            })?;
        }
    }

    #[test]
    fn inverse_trigonometric_rules(x in -0.9f64..0.9, y in -3.0f64..3.0) {
        for f in [Func1::Asin, Func1::Acos, Func1::Atan] {
            check_gradient(&[x], |a, v| f1(a, f, v[0]))?;
            check_gradient(&[x, y], |a, v| {
                // f(x * cos(y)): the argument stays inside (-0.9, 0.9)
                let c = a.f1(Func1::Cos, v[1]);
                let arg = a.mul(v[0], c);
                f1(a, f, arg)
            })?;
        }
        // atan on its whole domain
        check_gradient(&[7.0 * x + y], |a, v| f1(a, Func1::Atan, v[0]))?;
    }

    #[test]
    fn hyperbolic_rules(x in -3.0f64..3.0, y in -1.0f64..1.0) {
        for f in [Func1::Sinh, Func1::Cosh, Func1::Tanh] {
            check_gradient(&[x], |a, v| f1(a, f, v[0]))?;
            check_gradient(&[x, y], |a, v| {
                let s = a.sub(v[0], v[1]);
                let arg = a.mul(s, v[1]);
                f1(a, f, arg)
            })?;
        }
    }

    #[test]
    fn exp_log_sqrt_rules(x in 0.1f64..5.0, y in -2.0f64..2.0) {
        check_gradient(&[x, y], |a, v| {
            let xy = a.mul(v[0], v[1]);
            f1(a, Func1::Exp, xy)
        })?;
        check_gradient(&[x], |a, v| f1(a, Func1::Log, v[0]))?;
        check_gradient(&[x, y], |a, v| {
            // log(x + y^2)
            let y2 = a.powi(v[1], 2);
            let s = a.add(v[0], y2);
            f1(a, Func1::Log, s)
        })?;
        check_gradient(&[x], |a, v| f1(a, Func1::Sqrt, v[0]))?;
        check_gradient(&[x, y], |a, v| {
            // sqrt(x + y^2 + 1)
            let y2 = a.powi(v[1], 2);
            let s = a.linear_combination(1.0, &[(1.0, v[0]), (1.0, y2)]);
            f1(a, Func1::Sqrt, s)
        })?;
    }

    #[test]
    fn abs_and_sign_rules(x in away_from_zero(0.05, 4.0), y in -2.0f64..2.0) {
        check_gradient(&[x], |a, v| f1(a, Func1::Abs, v[0]))?;
        check_gradient(&[x, y], |a, v| {
            // |x| * y + sign(x) * y^3: sign is locally constant away from 0
            let ab = f1(a, Func1::Abs, v[0]);
            let t1 = a.mul(ab, v[1]);
            let sg = f1(a, Func1::Sign, v[0]);
            let y3 = a.powi(v[1], 3);
            let t2 = a.mul(sg, y3);
            a.add(t1, t2)
        })?;
        // the derivative of sign itself is exactly zero away from 0
        let mut arena = Arena::new();
        let vx = arena.var(0);
        let s = arena.f1(Func1::Sign, vx);
        let d = arena.diff(s, vx);
        prop_assert_eq!(eval_vars(&arena, d, &[x]), 0.0);
    }

    #[test]
    fn atan2_rule_in_both_arguments(
        y in -3.0f64..3.0,
        x in -3.0f64..3.0,
    ) {
        // away from the origin and from the branch cut (x < 0, y = 0), for both the
        // plain and the composed arguments
        let smooth = |yy: f64, xx: f64| xx.hypot(yy) > 0.2 && !(xx < 0.0 && yy.abs() < 0.05);
        prop_assume!(smooth(y, x) && smooth(2.0 * y + x, x - 0.5 * y));
        check_gradient(&[y, x], |a, v| a.f2(Func2::Atan2, v[0], v[1]))?;
        check_gradient(&[y, x], |a, v| {
            // atan2(2y + x, x - 0.5 y) through linear arguments
            let num = a.linear_combination(0.0, &[(2.0, v[0]), (1.0, v[1])]);
            let den = a.linear_combination(0.0, &[(1.0, v[1]), (-0.5, v[0])]);
            a.f2(Func2::Atan2, num, den)
        })?;
    }

    #[test]
    fn min_max_rules_away_from_ties(x in -3.0f64..3.0, y in -3.0f64..3.0) {
        prop_assume!((x * x - y).abs() > 1e-3);
        for f in [Func2::Min, Func2::Max] {
            check_gradient(&[x, y], |a, v| {
                // min/max(x^2, y): both branches have nonzero, different gradients
                let x2 = a.powi(v[0], 2);
                a.f2(f, x2, v[1])
            })?;
        }
    }

    #[test]
    fn if_then_else_rule_away_from_the_switch(x in -3.0f64..3.0, y in -3.0f64..3.0) {
        prop_assume!((x - y).abs() > 1e-3);
        check_gradient(&[x, y], |a, v| {
            // if x < y then x*y^2 else sin(x) - y
            let c = a.cmp(Cmp::Lt, v[0], v[1]);
            let y2 = a.powi(v[1], 2);
            let then = a.mul(v[0], y2);
            let s = a.f1(Func1::Sin, v[0]);
            let other = a.sub(s, v[1]);
            a.ite(c, then, other)
        })?;
    }

    #[test]
    fn compositions(x in 0.3f64..2.0, y in 0.5f64..2.0, z in -1.0f64..1.0) {
        check_gradient(&[x, y], |a, v| {
            // sin(x*y) + exp(x)/y
            let xy = a.mul(v[0], v[1]);
            let s = a.f1(Func1::Sin, xy);
            let ex = a.f1(Func1::Exp, v[0]);
            let q = a.div(ex, v[1]);
            a.add(s, q)
        })?;
        check_gradient(&[x, y, z], |a, v| {
            // sqrt(x^2 + y^2) * atan(z / y) - log(x + y)^3 * cosh(z) + x^y / (1 + z^2)
            let x2 = a.powi(v[0], 2);
            let y2 = a.powi(v[1], 2);
            let r2 = a.add(x2, y2);
            let r = a.f1(Func1::Sqrt, r2);
            let zy = a.div(v[2], v[1]);
            let at = a.f1(Func1::Atan, zy);
            let t1 = a.mul(r, at);
            let s = a.add(v[0], v[1]);
            let l = a.f1(Func1::Log, s);
            let l3 = a.powi(l, 3);
            let ch = a.f1(Func1::Cosh, v[2]);
            let t2 = a.mul(l3, ch);
            let p = a.pow(v[0], v[1]);
            let z2 = a.powi(v[2], 2);
            let den = a.linear_combination(1.0, &[(1.0, z2)]);
            let t3 = a.div(p, den);
            a.linear_combination(0.0, &[(1.0, t1), (-1.0, t2), (1.0, t3)])
        })?;
    }

    #[test]
    fn partial_derivatives_with_respect_to_parameters_and_time(
        x in -2.0f64..2.0,
        p in 0.5f64..2.0,
        t in 0.0f64..3.0,
    ) {
        let mut arena = Arena::new();
        let vx = arena.var(0);
        let vp = arena.param(0);
        let vt = arena.time();
        // p * sin(x * t) + exp(-p * t)
        let xt = arena.mul(vx, vt);
        let s = arena.f1(Func1::Sin, xt);
        let t1 = arena.mul(vp, s);
        let pt = arena.product(&[vp, vt]);
        let npt = arena.neg(pt);
        let t2 = arena.f1(Func1::Exp, npt);
        let e = arena.add(t1, t2);
        let value = |arena: &Arena, id: Id, x: f64, p: f64, t: f64| {
            eval_at(arena, id, &Point { x: &[x], xdot: &[], xddot: &[], p: &[p], t })
        };
        let dp = arena.diff(e, vp);
        let got = value(&arena, dp, x, p, t);
        let reference = central(|pp| value(&arena, e, x, pp, t), p);
        prop_assert!(close(got, reference), "d/dp: {got} vs {reference}");
        let dt = arena.diff(e, vt);
        let got = value(&arena, dt, x, p, t);
        let reference = central(|tt| value(&arena, e, x, p, tt), t);
        prop_assert!(close(got, reference), "d/dt: {got} vs {reference}");
    }

    #[test]
    fn time_derivative_is_the_chain_rule(
        x in 0.3f64..2.0,
        y in 0.3f64..2.0,
        xdot in -3.0f64..3.0,
        ydot in -3.0f64..3.0,
        t in 0.0f64..2.0,
    ) {
        let mut arena = Arena::new();
        let (vx, vy) = (arena.var(0), arena.var(1));
        let vt = arena.time();
        let vp = arena.param(0);
        let p = 1.7;
        // Three expressions of x, y, time and a parameter (constant in time).
        let xy = arena.mul(vx, vy);
        let s = arena.f1(Func1::Sin, xy);
        let ex = arena.f1(Func1::Exp, vx);
        let q = arena.div(ex, vy);
        let e1 = arena.add(s, q);
        let pw = arena.pow(vx, vy);
        let tt = arena.mul(vt, vy);
        let c = arena.f1(Func1::Cos, tt);
        let pc = arena.product(&[vp, c]);
        let e2 = arena.add(pw, pc);
        let at = arena.f2(Func2::Atan2, vy, vx);
        let l = arena.f1(Func1::Log, xy);
        let e3 = arena.mul(at, l);
        for e in [e1, e2, e3] {
            let d = arena.time_derivative(e);
            let got = eval_at(
                &arena,
                d,
                &Point { x: &[x, y], xdot: &[xdot, ydot], xddot: &[], p: &[p], t },
            );
            // sum over the variables of (d e / d x_k) * xdot_k, plus d e / d t, with the
            // partials by central differences
            let at_point = |xs: [f64; 2], tt: f64| {
                eval_at(&arena, e, &Point { x: &xs, xdot: &[], xddot: &[], p: &[p], t: tt })
            };
            let de_dx = central(|v| at_point([v, y], t), x);
            let de_dy = central(|v| at_point([x, v], t), y);
            let de_dt = central(|v| at_point([x, y], v), t);
            let reference = de_dx * xdot + de_dy * ydot + de_dt;
            prop_assert!(
                close(got, reference),
                "d/dt {e:?}: symbolic {got}, chain rule {reference}"
            );
        }
    }

    #[test]
    fn time_derivative_of_derivative_terms(
        x in 0.3f64..2.0,
        y in -2.0f64..2.0,
        xdot in -3.0f64..3.0,
        ydot in -3.0f64..3.0,
        yddot in -3.0f64..3.0,
    ) {
        // e = x * der(y)^2 + sin(y): d/dt = der(x) der(y)^2 + 2 x der(y) der(der(y))
        // + cos(y) der(y); der(y) is a leaf of its own, with the rate der(der(y)).
        let mut arena = Arena::new();
        let (vx, vy) = (arena.var(0), arena.var(1));
        let dy = arena.der(vy);
        let dy2 = arena.powi(dy, 2);
        let t1 = arena.mul(vx, dy2);
        let s = arena.f1(Func1::Sin, vy);
        let e = arena.add(t1, s);
        let d = arena.time_derivative(e);
        let got = eval_at(
            &arena,
            d,
            &Point { x: &[x, y], xdot: &[xdot, ydot], xddot: &[0.0, yddot], p: &[], t: 0.0 },
        );
        let at_point = |x: f64, y: f64, ydot: f64| {
            eval_at(&arena, e, &Point { x: &[x, y], xdot: &[0.0, ydot], xddot: &[], p: &[], t: 0.0 })
        };
        let reference = central(|v| at_point(v, y, ydot), x) * xdot
            + central(|v| at_point(x, v, ydot), y) * ydot
            + central(|v| at_point(x, y, v), ydot) * yddot;
        prop_assert!(close(got, reference), "symbolic {got}, chain rule {reference}");
    }
}

/// Along a known trajectory `x(t) = 1.5 + sin(t)`, `y(t) = exp(-t/2)`, the time
/// derivative of `e(x, y, t)` evaluated with the exact rates equals the finite
/// difference of `e(x(t), y(t), t)` in `t`.
#[test]
fn time_derivative_along_a_trajectory() {
    let mut arena = Arena::new();
    let (vx, vy) = (arena.var(0), arena.var(1));
    let vt = arena.time();
    let xy = arena.mul(vx, vy);
    let s = arena.f1(Func1::Sin, xy);
    let ty = arena.mul(vt, vy);
    let th = arena.f1(Func1::Tanh, ty);
    let pw = arena.pow(vx, th);
    let m = arena.f2(Func2::Max, vx, vy);
    let e = arena.sum(&[s, pw, m]);
    let d = arena.time_derivative(e);
    let traj = |t: f64| {
        (
            [1.5 + t.sin(), (-t / 2.0).exp()],
            [t.cos(), -0.5 * (-t / 2.0).exp()],
        )
    };
    for k in 0..40 {
        let t = 0.1 + 0.15 * k as f64;
        let (xs, xd) = traj(t);
        let got = eval_at(
            &arena,
            d,
            &Point {
                x: &xs,
                xdot: &xd,
                xddot: &[],
                p: &[],
                t,
            },
        );
        let reference = central(
            |tt| {
                let (xs, _) = traj(tt);
                eval_at(
                    &arena,
                    e,
                    &Point {
                        x: &xs,
                        xdot: &[],
                        xddot: &[],
                        p: &[],
                        t: tt,
                    },
                )
            },
            t,
        );
        assert!(
            close(got, reference),
            "t = {t}: symbolic {got}, finite difference {reference}"
        );
    }
}
