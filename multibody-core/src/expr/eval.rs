//! Direct numeric evaluation (for folding and checks; compiled tapes do the fast work).

use crate::hash::HashMap;

use super::{Arena, Id, Node};

impl Arena {
    /// Evaluates `e`; `leaf` gives each leaf's value or `None` when it is unknown, which
    /// makes the whole result `None`.
    pub fn eval(&self, e: Id, leaf: &dyn Fn(&Node) -> Option<f64>) -> Option<f64> {
        let mut memo = HashMap::default();
        self.eval_rec(e, leaf, &mut memo)
    }

    fn eval_rec(
        &self,
        e: Id,
        leaf: &dyn Fn(&Node) -> Option<f64>,
        memo: &mut HashMap<Id, f64>,
    ) -> Option<f64> {
        if let Some(&v) = memo.get(&e) {
            return Some(v);
        }
        let v = match self.node(e) {
            Node::Const(b) => f64::from_bits(*b),
            n @ (Node::Var(_) | Node::Param(_) | Node::Time | Node::Der(_)) => leaf(n)?,
            Node::Sum(ts, c) => {
                let mut s = f64::from_bits(*c);
                for &(k, t) in self.terms(*ts).iter() {
                    s += f64::from_bits(k) * self.eval_rec(t, leaf, memo)?;
                }
                s
            }
            Node::Prod(fs) => {
                let mut p = 1.0;
                for &(b, n) in self.factors(*fs).iter() {
                    p *= self.eval_rec(b, leaf, memo)?.powi(n);
                }
                p
            }
            Node::Pow(a, b) => self
                .eval_rec(*a, leaf, memo)?
                .powf(self.eval_rec(*b, leaf, memo)?),
            Node::F1(f, a) => f.apply(self.eval_rec(*a, leaf, memo)?),
            Node::F2(f, a, b) => f.apply(
                self.eval_rec(*a, leaf, memo)?,
                self.eval_rec(*b, leaf, memo)?,
            ),
            Node::Cmp(op, a, b) => op.apply(
                self.eval_rec(*a, leaf, memo)?,
                self.eval_rec(*b, leaf, memo)?,
            ),
            Node::If(c, a, b) => {
                if self.eval_rec(*c, leaf, memo)? != 0.0 {
                    self.eval_rec(*a, leaf, memo)?
                } else {
                    self.eval_rec(*b, leaf, memo)?
                }
            }
        };
        memo.insert(e, v);
        Some(v)
    }
}
