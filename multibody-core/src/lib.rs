//! The modeling compiler and solver behind `multibody`: symbolic expressions, models,
//! structural analysis, code generation, SUNDIALS IDA and plots. Domain-agnostic.
//!
//! The pipeline: a [`model::System`] tree is flattened ([`model::flatten`]), simplified
//! ([`simplify::structural_simplify`]: alias elimination, index reduction, state
//! selection, sorting, tearing, code generation), initialized and integrated
//! ([`solve::DaeProblem`]), and read back by name ([`solve::Solution`]).

pub mod codegen;
pub mod control;
mod error;
pub mod expr;
pub mod hash;
pub mod model;
pub mod names;
pub mod plot;
pub mod simplify;
pub mod solve;
pub(crate) mod sparse_lu;
pub mod structure;

pub use error::Error;
pub use expr::Expr;
pub use model::System;
/// The linear algebra crate of [`solve::LinearModel`].
pub use nalgebra;
pub use simplify::{SimplifiedSystem, structural_simplify};
pub use solve::{DaeProblem, Solution, SolverOptions};
