//! Solving: consistent initialization, integration with SUNDIALS, and solutions.
//!
//! [`DaeProblem::new`] evaluates parameters and start values and runs the
//! initialization (its own problem at t0, solved by damped Newton); [`DaeProblem::solve`]
//! integrates with IDA, or for a model in ODE form with CVODE or ARKODE
//! ([`SolverOptions::method`]), and returns a [`Solution`]. The only FFI of the project
//! lives in [`ida`], [`ode`] and the linear solver glue.

mod builder;
mod dynamic;
mod ensemble;
mod error;
mod events;
pub mod ida;
mod init;
mod inputs;
mod linearize;
mod linsol;
mod newton;
pub mod ode;
mod options;
mod problem;
mod project;
mod solution;
mod steady;
mod sundials;

pub use builder::ProblemBuilder;
pub use ensemble::{EnsembleOptions, solve_ensemble};
pub use error::{InitError, SolutionError, SolveError};
pub use ida::IdaStats;
pub use inputs::InputSignal;
pub use linearize::{LinearModel, OperatingPoint, Pole, linearize, linearize_in};
pub use options::{LinearSolver, Method, SolverOptions};
pub use problem::{DaeProblem, InitReport};
pub use solution::{Event, Segment, Solution, Termination};
pub use steady::{SteadyStateOptions, steady_state};
