//! The top-level error: one variant per phase, each with its own error type.

use crate::codegen::CodegenError;
use crate::model::ModelError;
use crate::plot::PlotError;
use crate::simplify::SimplifyError;
use crate::solve::{InitError, SolutionError, SolveError};

/// Anything that can go wrong from declaring a model to plotting its solution.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The model's declarations or connections are wrong, or it is unbalanced.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// Structural simplification failed (structural singularity, state selection).
    #[error(transparent)]
    Simplify(#[from] SimplifyError),
    /// Compiling expressions failed.
    #[error(transparent)]
    Codegen(#[from] CodegenError),
    /// Consistent initial values could not be found.
    #[error(transparent)]
    Init(#[from] InitError),
    /// The integrator failed.
    #[error(transparent)]
    Solve(#[from] SolveError),
    /// A solution was asked for something it does not have.
    #[error(transparent)]
    Solution(#[from] SolutionError),
    /// Plotting failed.
    #[error(transparent)]
    Plot(#[from] PlotError),
}
