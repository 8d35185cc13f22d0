//! Compiled model functions: the residual F(t, u, u') of a DAE, its sparse Jacobian
//! J = dF/du + cj dF/du', observed variables and small algebraic blocks.
//!
//! Expressions of an [`Arena`](crate::expr::Arena) are compiled by a [`TapeBuilder`] into
//! a flat [`Tape`]: a vector of small instructions in static single assignment form (one
//! register per instruction), with common subexpressions shared (each arena node is
//! compiled once, and identical instructions are numbered once) and dead code removed.
//! A tape evaluates values ([`Tape::eval`]) and forward-mode tangents in several
//! directions at once ([`Tape::forward`]). [`DaeJacobian`] turns the structural
//! dependencies of a residual tape into a CSC pattern, colours its columns and evaluates
//! the Jacobian by compressed forward mode.
//!
//! Statements ([`Stmt`]) executed before the outputs assign leaves (explicitly solved
//! variables) or solve small dense linear systems (torn linear blocks); forward mode
//! differentiates through those solves exactly.

mod compile;
pub mod dae;
mod elimination_queue;
mod extended;
mod forward;
mod schedule;
mod sparsity;
mod specialize;
mod specialize_solve;
mod tape;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_extended;
#[cfg(test)]
mod tests_specialize;

pub use compile::TapeBuilder;
pub use extended::{DEFAULT_MAX_FILL, ExtendedJacobian, ExtendedWorkspace};
pub use sparsity::{DaeJacobian, JacobianWorkspace};
pub use tape::{Tape, Workspace};

use crate::expr::Id;

/// A statement executed in order before outputs are read: the sorted, solved equations
/// that [`structural_simplify`](crate::simplify::structural_simplify) hands to the
/// compiler, on plain expression ids.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Stmt {
    /// `target := expr`: `target` is a leaf node (a `Var` or `Der` node) of the arena;
    /// after this statement, expressions compiled later read the value of `expr` for it.
    Assign {
        /// The leaf that receives the value.
        target: Id,
        /// The expression computing it.
        expr: Id,
        /// The equation this solves, an index into the caller's equations, for
        /// messages (`usize::MAX` for a temporary).
        equation: usize,
    },
    /// Solves the dense linear system `A x + c = 0` for the leaves `targets` (k of
    /// them). Closed form when k == 1 (`x = -c / a`), LU with partial pivoting
    /// otherwise. A zero or tiny pivot, or a non-finite solution, is a recoverable
    /// [`EvalError`] at evaluation time.
    LinearSolve {
        /// The k leaves solved for, in the order of the columns of `A`.
        targets: Vec<Id>,
        /// Row-major k*k expressions of the matrix `A`.
        a: Vec<Id>,
        /// The k expressions of the constant vector `c`.
        c: Vec<Id>,
    },
    /// Solves the sparse linear system `A x + c = 0` for the leaves `targets` with the
    /// refactorizing sparse LU (pivots replayed between calls while they stay large). A
    /// singular matrix or a non-finite solution is a recoverable [`EvalError`].
    SparseLinearSolve {
        /// The k leaves solved for, in the order of the columns of `A`.
        targets: Vec<Id>,
        /// The structurally non-zero entries of `A`: `(row, column, expression)`, each
        /// position at most once.
        entries: Vec<(usize, usize, Id)>,
        /// The k expressions of the constant vector `c`.
        c: Vec<Id>,
    },
}

/// An error evaluating a compiled function (a singular linear block, a value outside a
/// function's domain, a non-finite result).
#[derive(Debug, Clone)]
pub struct EvalError {
    /// Human-readable description of what went wrong.
    pub message: String,
    /// `true` if the integrator may retry with a smaller step (e.g. a value outside the
    /// domain of a function), `false` to stop the integration.
    pub recoverable: bool,
}

/// Errors found while compiling expressions into a tape.
#[derive(Debug, thiserror::Error)]
pub enum CodegenError {
    /// An expression uses a leaf that is neither an input nor assigned by an earlier
    /// statement; the string is the leaf's id and node in debug form.
    #[error("undefined leaf {0}: it is neither an input nor assigned by an earlier statement")]
    UndefinedLeaf(String),
    /// The target of a statement is not a leaf node (`Var`, `Param`, `Time` or `Der`).
    #[error("statement target {0} is not a leaf")]
    NotALeaf(String),
    /// A linear-solve statement whose dimensions do not agree.
    #[error("malformed linear solve: {0}")]
    BadLinearSolve(String),
    /// An input slot outside `0..n_inputs`.
    #[error("input slot {slot} out of range (the tape has {n_inputs} inputs)")]
    SlotOutOfRange {
        /// The slot requested.
        slot: usize,
        /// The number of input slots of the tape.
        n_inputs: usize,
    },
}
