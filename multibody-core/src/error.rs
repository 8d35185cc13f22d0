//! The top-level error: one variant per phase, each with its own error type (boxed, so
//! that `Result<_, Error>` stays small).

use crate::codegen::CodegenError;
use crate::model::ModelError;
use crate::plot::PlotError;
use crate::simplify::SimplifyError;
use crate::solve::{InitError, SolutionError, SolveError};

/// Anything that can go wrong from declaring a model to plotting its solution.
///
/// Its `Debug` form is the message itself, so that `fn main() -> Result<(), Error>`
/// and `unwrap()` print what went wrong as a user reads it; match on the variants (or
/// the stage errors they hold) to tell failures apart.
#[derive(thiserror::Error)]
pub enum Error {
    /// The model's declarations or connections are wrong, or it is unbalanced.
    #[error(transparent)]
    Model(Box<ModelError>),
    /// Structural simplification failed (structural singularity, state selection).
    #[error(transparent)]
    Simplify(Box<SimplifyError>),
    /// Compiling expressions failed.
    #[error(transparent)]
    Codegen(Box<CodegenError>),
    /// Consistent initial values could not be found.
    #[error(transparent)]
    Init(Box<InitError>),
    /// The integrator failed.
    #[error(transparent)]
    Solve(Box<SolveError>),
    /// A solution was asked for something it does not have.
    #[error(transparent)]
    Solution(Box<SolutionError>),
    /// Plotting failed.
    #[error(transparent)]
    Plot(Box<PlotError>),
}

impl std::fmt::Debug for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        std::fmt::Display::fmt(self, f)
    }
}

macro_rules! boxed_from {
    ($($t:ty => $v:ident),*) => {$(
        impl From<$t> for Error {
            fn from(e: $t) -> Error {
                Error::$v(Box::new(e))
            }
        }
    )*};
}

boxed_from!(
    ModelError => Model,
    SimplifyError => Simplify,
    CodegenError => Codegen,
    InitError => Init,
    SolveError => Solve,
    SolutionError => Solution,
    PlotError => Plot
);
