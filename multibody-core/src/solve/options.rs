//! Options of the integrator.

use crate::names::number;

/// Which linear solver IDA's Newton iteration uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum LinearSolver {
    /// Dense for up to 24 unknowns, [`Sparse`](Self::Sparse) above (the default).
    #[default]
    Auto,
    /// SUNDIALS' dense LU with the compiled Jacobian.
    Dense,
    /// Sparse LU (COLAMD order, pivots replayed) with the compiled sparse Jacobian, extended by intermediates
    /// where that keeps it much sparser (multibody chains; see
    /// [`ExtendedJacobian`](crate::codegen::ExtendedJacobian)).
    Sparse,
    /// Sparse LU with the plain compiled Jacobian, never extended (for the benchmarks'
    /// comparisons).
    #[doc(hidden)]
    SparsePlain,
    /// SUNDIALS' dense LU with IDA's difference-quotient Jacobian (for the benchmarks'
    /// comparisons).
    #[doc(hidden)]
    DenseDifferenceQuotient,
}

/// Options of [`DaeProblem::solve`](super::DaeProblem::solve).
#[derive(Clone, Debug, PartialEq)]
pub struct SolverOptions {
    /// Relative tolerance (default 1e-6).
    pub rtol: f64,
    /// Absolute tolerance (default 1e-8).
    pub atol: f64,
    /// Largest step size (default: none).
    pub max_step: Option<f64>,
    /// First step size (default: IDA's estimate).
    pub initial_step: Option<f64>,
    /// Times at which to report the solution (default: none, every internal step is
    /// reported; the final time is always reported).
    pub output_times: Option<Vec<f64>>,
    /// Largest number of internal steps between two reported points (default
    /// 500 000).
    pub max_steps: usize,
    /// Largest number of reported points (default 500 000).
    pub max_points: usize,
    /// Leave algebraic unknowns out of the local error test, as `IDASetSuppressAlg`
    /// (default true).
    pub suppress_alg: bool,
    /// The linear solver (default [`LinearSolver::Auto`]).
    pub linear_solver: LinearSolver,
    /// Solve the algebraic unknowns of every reported point again from the purely
    /// algebraic equations (loop closures, rod lengths) by Newton, with the states as
    /// reported, so constraints hold to round-off at the outputs rather than to the
    /// integrator's tolerance; the integration is not affected (default true; skipped
    /// for more than 64 algebraic unknowns).
    pub project_outputs: bool,
    /// Before integrating, specialize the residual and its Jacobian to this problem's
    /// parameter values (`CompiledDae::specialize`): terms that vanish for these values
    /// (a zero offset, a unit factor) are dropped, so tunable parameters cost about
    /// what folded ones do. Takes a few milliseconds per 10 000 instructions; results
    /// agree with the unspecialized functions up to rounding and the folding rules of
    /// `Tape::specialize` (default true).
    pub specialize_parameters: bool,
}

impl Default for SolverOptions {
    fn default() -> Self {
        SolverOptions {
            rtol: 1e-6,
            atol: 1e-8,
            max_step: None,
            initial_step: None,
            output_times: None,
            max_steps: 500_000,
            max_points: 500_000,
            suppress_alg: true,
            linear_solver: LinearSolver::Auto,
            project_outputs: true,
            specialize_parameters: true,
        }
    }
}

impl SolverOptions {
    /// Checks the options for a problem over `tspan`: the message of the first one that
    /// cannot be used.
    pub(crate) fn check(&self, tspan: (f64, f64)) -> Result<(), String> {
        let positive = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(format!(
                    "SolverOptions::{name} = {} must be a positive, finite number",
                    number(v)
                ))
            }
        };
        for (name, v) in [("rtol", self.rtol), ("atol", self.atol)] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(format!(
                    "SolverOptions::{name} = {} must be a finite number, zero or positive",
                    number(v)
                ));
            }
        }
        if self.rtol == 0.0 && self.atol == 0.0 {
            return Err(
                "SolverOptions::rtol and atol are both zero: at least one must be \
                        positive"
                    .into(),
            );
        }
        if self.rtol > 0.0 && self.rtol < 1e-15 {
            return Err(format!(
                "SolverOptions::rtol = {} is below the precision of floating-point numbers \
                 (at least 1e-15)",
                number(self.rtol)
            ));
        }
        if let Some(h) = self.max_step {
            positive("max_step", h)?;
        }
        if let Some(h) = self.initial_step {
            positive("initial_step", h)?;
        }
        if self.max_steps == 0 {
            return Err("SolverOptions::max_steps must be at least 1".into());
        }
        if self.max_points < 2 {
            return Err(
                "SolverOptions::max_points must be at least 2 (the initial and the \
                        final time)"
                    .into(),
            );
        }
        if let Some(times) = &self.output_times
            && let Some(&t) = times
                .iter()
                .find(|&&t| !(t.is_finite() && t >= tspan.0 && t <= tspan.1))
        {
            return Err(format!(
                "the output time {} in SolverOptions::output_times is not in the time span \
                 [{}, {}]",
                number(t),
                number(tspan.0),
                number(tspan.1)
            ));
        }
        Ok(())
    }

    /// Output times `t0, t0 + dt, ...` up to `t1` (inclusive within rounding).
    pub fn with_output_interval(mut self, t0: f64, t1: f64, dt: f64) -> Self {
        let n = ((t1 - t0) / dt + 1e-9).floor() as usize;
        self.output_times = Some((1..=n).map(|k| t0 + k as f64 * dt).collect());
        self
    }
}
