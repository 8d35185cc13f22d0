//! Solving an equation for one of its leaves when it is linear in it.

use crate::hash::HashMap;

use super::{Arena, Id};

/// The solution of `e = 0` for a leaf `x`, when `e = a*x + b` with `a`, `b` free of `x`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LinearSolve {
    /// `x = -b / a`.
    pub solution: Id,
    /// `a`: where it may vanish, the solution is not safe to use.
    pub coefficient: Id,
}

impl Arena {
    /// Solves `e = 0` for the leaf `x` when `e` is linear in `x` with a coefficient that is
    /// not identically zero. Returns `None` when `x` does not occur or occurs nonlinearly.
    pub fn solve_linear(&mut self, e: Id, x: Id) -> Option<LinearSolve> {
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

    /// Whether `e` is linear (affine) in the leaf `x`: `x` may occur, but its coefficient
    /// is free of `x`.
    pub fn is_linear_in(&mut self, e: Id, x: Id) -> bool {
        let a = self.diff(e, x);
        !self.contains(a, x)
    }
}
