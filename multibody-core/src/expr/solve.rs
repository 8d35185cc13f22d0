//! Solving an equation for one of its leaves when it is linear in it.

use std::cell::Cell;

use crate::hash::HashMap;

use super::{Arena, Id, Node};

/// The solution of `e = 0` for a leaf `x`, when `e = a*x + b` with `a`, `b` free of `x`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LinearSolve {
    /// `x = -b / a`.
    pub solution: Id,
    /// `a`: where it may vanish, the solution is not safe to use.
    pub coefficient: Id,
}

thread_local! {
    /// The other terms of a direct solve, kept per thread (most equations of a large
    /// model are solved this way: one allocation each otherwise).
    static OTHER_TERMS: Cell<Vec<(f64, Id)>> = const { Cell::new(Vec::new()) };
}

impl Arena {
    /// Solves `e = 0` for the leaf `x` when `e` is linear in `x` with a coefficient that is
    /// not identically zero. Returns `None` when `x` does not occur or occurs nonlinearly.
    pub fn solve_linear(&mut self, e: Id, x: Id) -> Option<LinearSolve> {
        if let Some(direct) = self.solve_direct_term(e, x) {
            return direct;
        }
        self.solve_linear_general(e, x)
    }

    /// [`solve_linear`](Self::solve_linear) by differentiation and substitution, for any
    /// form of `e`.
    pub(crate) fn solve_linear_general(&mut self, e: Id, x: Id) -> Option<LinearSolve> {
        let a = self.diff(e, x);
        if self.as_const(a) == Some(0.0) || self.contains(a, x) {
            return None;
        }
        let mut map = HashMap::default();
        map.insert(x, self.zero());
        let b = self.substitute_leaves(e, &map);
        let nb = self.neg(b);
        let solution = self.div(nb, a);
        Some(LinearSolve {
            solution,
            coefficient: a,
        })
    }

    /// [`solve_linear`](Self::solve_linear) without differentiating or substituting
    /// when `e` is a sum with `x` as one of its terms: `Some(result)` when no other term
    /// contains `x` (the coefficient is that term's constant, the solution the other
    /// terms, computed with the same operations, and so the same rounding, as the
    /// general path), `None` when the general path must decide.
    fn solve_direct_term(&mut self, e: Id, x: Id) -> Option<Option<LinearSolve>> {
        let Node::Sum(ts, c) = *self.node(e) else {
            return None;
        };
        let terms = self.terms(ts);
        let pos = terms.iter().position(|&(_, t)| t == x)?;
        let k = f64::from_bits(terms[pos].0);
        let inv = 1.0 / k;
        let mut others = OTHER_TERMS.take();
        others.clear();
        others.extend(
            terms
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != pos)
                .map(|(_, &(kk, t))| (inv * -f64::from_bits(kk), t)),
        );
        let nonlinear = others.iter().any(|&(_, t)| self.contains(t, x));
        let solution =
            (!nonlinear).then(|| self.linear_combination(inv * -f64::from_bits(c), &others));
        OTHER_TERMS.set(others);
        let solution = solution?;
        Some(Some(LinearSolve {
            solution,
            coefficient: self.constant(k),
        }))
    }

    /// Whether `e` is linear (affine) in the leaf `x`: `x` may occur, but its coefficient
    /// is free of `x`.
    pub fn is_linear_in(&mut self, e: Id, x: Id) -> bool {
        let a = self.diff(e, x);
        !self.contains(a, x)
    }
}
