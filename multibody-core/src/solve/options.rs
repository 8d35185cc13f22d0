//! Options of the integrator.

/// Which linear solver IDA's Newton iteration uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum LinearSolverChoice {
    /// Dense for up to 24 unknowns, [`Sparse`](Self::Sparse) above (the default).
    #[default]
    Auto,
    /// SUNDIALS' dense LU with the compiled Jacobian.
    Dense,
    /// Sparse LU (COLAMD order, pivots replayed) with the compiled sparse Jacobian, extended by intermediates
    /// where that keeps it much sparser (multibody chains; see
    /// [`ExtendedJacobian`](crate::codegen::ExtendedJacobian)).
    Sparse,
    /// Sparse LU with the plain compiled Jacobian, never extended (for
    /// comparisons).
    SparsePlain,
    /// SUNDIALS' dense LU with IDA's difference-quotient Jacobian (for comparisons).
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
    /// Largest number of reported points, and of internal steps between two output
    /// times (default 500 000).
    pub max_steps: usize,
    /// Leave algebraic unknowns out of the local error test, as `IDASetSuppressAlg`
    /// (default true).
    pub suppress_alg: bool,
    /// The linear solver (default [`LinearSolverChoice::Auto`]).
    pub linear_solver: LinearSolverChoice,
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
            suppress_alg: true,
            linear_solver: LinearSolverChoice::Auto,
            project_outputs: true,
            specialize_parameters: true,
        }
    }
}

impl SolverOptions {
    /// Output times `t0, t0 + dt, ...` up to `t1` (inclusive within rounding).
    pub fn with_output_interval(mut self, t0: f64, t1: f64, dt: f64) -> Self {
        let n = ((t1 - t0) / dt + 1e-9).floor() as usize;
        self.output_times = Some((1..=n).map(|k| t0 + k as f64 * dt).collect());
        self
    }
}
