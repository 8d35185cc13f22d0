//! Symbolic differentiation: with respect to a leaf, and with respect to time.

use crate::hash::HashMap;

use super::{Arena, Cmp, Func1, Func2, Id, Node};

/// How leaves differentiate.
#[derive(Clone, Copy)]
enum LeafRule {
    /// d/d(leaf): 1 for that leaf, 0 for every other.
    Wrt(Id),
    /// d/dt: `der(x)` for variables and derivatives, 1 for time, 0 for parameters.
    Time,
}

impl Arena {
    /// Partial derivative of `e` with respect to the leaf `wrt` (a variable, parameter,
    /// time or `der(x)` node; `der(x)` counts as independent of `x`).
    pub fn diff(&mut self, e: Id, wrt: Id) -> Id {
        let mut memo = HashMap::default();
        self.diff_rec(e, LeafRule::Wrt(wrt), &mut memo)
    }

    /// Partial derivatives of `e` with respect to several leaves, sharing no work across
    /// them but one call per leaf.
    pub fn gradient(&mut self, e: Id, wrt: &[Id]) -> Vec<Id> {
        wrt.iter().map(|&w| self.diff(e, w)).collect()
    }

    /// Total time derivative of `e`: variables `x` become `der(x)`.
    pub fn time_derivative(&mut self, e: Id) -> Id {
        let mut memo = HashMap::default();
        self.diff_rec(e, LeafRule::Time, &mut memo)
    }

    fn diff_rec(&mut self, e: Id, rule: LeafRule, memo: &mut HashMap<Id, Id>) -> Id {
        if let Some(&d) = memo.get(&e) {
            return d;
        }
        let node = *self.node(e);
        let d = match node {
            Node::Const(_) => self.zero(),
            Node::Var(_) | Node::Der(_) | Node::Param(_) | Node::Time => match rule {
                LeafRule::Wrt(w) => {
                    if w == e {
                        self.one()
                    } else {
                        self.zero()
                    }
                }
                LeafRule::Time => match node {
                    Node::Var(_) | Node::Der(_) => self.der(e),
                    Node::Time => self.one(),
                    _ => self.zero(),
                },
            },
            Node::Sum(ts, _) => {
                // Copied: differentiating grows the pools.
                let ts = self.terms(ts).to_vec();
                let mut terms = Vec::with_capacity(ts.len());
                for &(k, t) in &ts {
                    let dt = self.diff_rec(t, rule, memo);
                    terms.push((f64::from_bits(k), dt));
                }
                self.linear_combination(0.0, &terms)
            }
            Node::Prod(fs) => {
                let fs = self.factors(fs).to_vec();
                let mut terms = Vec::new();
                for i in 0..fs.len() {
                    let (b, n) = fs[i];
                    let db = self.diff_rec(b, rule, memo);
                    if self.as_const(db) == Some(0.0) {
                        continue;
                    }
                    let mut factors = Vec::with_capacity(fs.len() + 1);
                    for (j, &(bj, nj)) in fs.iter().enumerate() {
                        let f = if j == i {
                            self.powi(bj, nj - 1)
                        } else {
                            self.powi(bj, nj)
                        };
                        factors.push(f);
                    }
                    factors.push(db);
                    let p = self.product(&factors);
                    terms.push((n as f64, p));
                }
                self.linear_combination(0.0, &terms)
            }
            Node::Pow(a, b) => {
                let da = self.diff_rec(a, rule, memo);
                let db = self.diff_rec(b, rule, memo);
                // d(a^b) = a^b * (db * ln a + b * da / a)
                let ln_a = self.f1(Func1::Log, a);
                let t1 = self.product(&[db, ln_a]);
                let t2 = {
                    let q = self.div(da, a);
                    self.mul(b, q)
                };
                let s = self.add(t1, t2);
                self.mul(e, s)
            }
            Node::F1(Func1::NoEvent, a) => {
                // The derivative's relations are those of `a`: no events either.
                let da = self.diff_rec(a, rule, memo);
                self.f1(Func1::NoEvent, da)
            }
            Node::F1(f, a) => {
                let da = self.diff_rec(a, rule, memo);
                if self.as_const(da) == Some(0.0) {
                    self.zero()
                } else {
                    let outer = self.f1_derivative(f, a, e);
                    self.mul(outer, da)
                }
            }
            Node::F2(f, a, b) => {
                let da = self.diff_rec(a, rule, memo);
                let db = self.diff_rec(b, rule, memo);
                match f {
                    Func2::Atan2 => {
                        // atan2(y, x): (x dy - y dx) / (x^2 + y^2)
                        let xdy = self.mul(b, da);
                        let ydx = self.mul(a, db);
                        let num = self.sub(xdy, ydx);
                        let x2 = self.powi(b, 2);
                        let y2 = self.powi(a, 2);
                        let den = self.add(x2, y2);
                        self.div(num, den)
                    }
                    Func2::Min => {
                        let c = self.cmp(Cmp::Lt, a, b);
                        self.ite(c, da, db)
                    }
                    Func2::Max => {
                        let c = self.cmp(Cmp::Gt, a, b);
                        self.ite(c, da, db)
                    }
                }
            }
            Node::Cmp(..) => self.zero(),
            Node::If(c, a, b) => {
                let da = self.diff_rec(a, rule, memo);
                let db = self.diff_rec(b, rule, memo);
                self.ite(c, da, db)
            }
        };
        memo.insert(e, d);
        d
    }

    /// f'(a) for a unary function; `fa` is the node `f(a)` itself.
    fn f1_derivative(&mut self, f: Func1, a: Id, fa: Id) -> Id {
        match f {
            Func1::Sin => self.f1(Func1::Cos, a),
            Func1::Cos => {
                let s = self.f1(Func1::Sin, a);
                self.neg(s)
            }
            Func1::Tan => {
                let t2 = self.powi(fa, 2);
                self.linear_combination(1.0, &[(1.0, t2)])
            }
            Func1::Asin | Func1::Acos => {
                let a2 = self.powi(a, 2);
                let one_minus = self.linear_combination(1.0, &[(-1.0, a2)]);
                let r = self.f1(Func1::Sqrt, one_minus);
                let inv = self.powi(r, -1);
                if f == Func1::Asin { inv } else { self.neg(inv) }
            }
            Func1::Atan => {
                let a2 = self.powi(a, 2);
                let den = self.linear_combination(1.0, &[(1.0, a2)]);
                self.powi(den, -1)
            }
            Func1::Exp => fa,
            Func1::Log => self.powi(a, -1),
            Func1::Sqrt => {
                let inv = self.powi(fa, -1);
                self.scale(0.5, inv)
            }
            Func1::Abs => self.f1(Func1::Sign, a),
            Func1::Sign => self.zero(),
            Func1::Sinh => self.f1(Func1::Cosh, a),
            Func1::Cosh => self.f1(Func1::Sinh, a),
            Func1::Tanh => {
                let t2 = self.powi(fa, 2);
                self.linear_combination(1.0, &[(-1.0, t2)])
            }
            Func1::NoEvent => self.one(),
            // Constant between events.
            Func1::Pre => self.zero(),
        }
    }
}
