//! The modeling compiler and solver behind `multibody`: symbolic expressions, models,
//! structural analysis, code generation, SUNDIALS IDA and plots. Domain-agnostic.

pub mod codegen;
pub mod expr;
pub mod model;
pub mod names;
pub mod plot;
/// Integration of differential-algebraic equations with SUNDIALS IDA.
pub mod solve;
pub mod structure;
