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

/// The integration method of a solve. The methods other than [`Ida`](Self::Ida) and
/// [`Auto`](Self::Auto) need a model in ODE form: every unknown a state, every
/// derivative computed from the states (the mass matrix the identity, every algebraic
/// block solved inside, as for open chains and trees of bodies, and for loops whose
/// constraints the compiler solves); a model with algebraic unknowns is refused with an
/// error that names them. They do not use [`SolverOptions::linear_solver`]: the implicit
/// ones take a dense LU up to 24 states and the sparse LU above.
///
/// Values between steps: ARKODE interpolates within a step by a Hermite polynomial of
/// degree 5 at most, much less accurate than the long steps of the high-order explicit
/// methods (an oscillator by Verner 8(7) at rtol 1e-9: 1e-12 at the steps, 2.8e-6
/// between them). So the explicit methods of order above 5 (Verner 6(5) to 9(8))
/// reach each requested output time ([`SolverOptions::output_times`]) by integrating
/// from the start of its step (a second integrator, one partial step per output time,
/// the steps themselves unchanged; 3e-12 there), and every ARKODE method locates a
/// crossing (state event) on the solution integrated from the start of its step
/// (regula falsi, each trial a partial step) and restarts from the state integrated
/// to it (`x'' = -x`, rtol 1e-9, three crossings of its acceleration: within 2e-11 in
/// time and 1e-10 in the final state, where the interpolant put them up to 7e-7 off).
/// Dormand-Prince 5(4) and Kvaerno 5(4) interpolate their output times (2e-10 and
/// 5e-10 there). [`Solution::at`](super::Solution::at) interpolates between the
/// solution's points by cubic Hermite polynomials: with few, long steps, bound the
/// step with [`SolverOptions::max_step`] or ask for output times where values between
/// steps matter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Method {
    /// For a model in ODE form, [`Verner8`](Self::Verner8), switching to
    /// [`CvodeBdf`](Self::CvodeBdf) for the rest of the solve where the step size is
    /// held by the method's stability rather than its accuracy (the model is stiff
    /// there; checked every 25 steps from the Jacobian's largest eigenvalue, found by
    /// power iteration, times the step size); [`Ida`](Self::Ida) for a model with
    /// algebraic unknowns. Not the default: with a few times fewer steps, the points
    /// of a solution lie further apart, and values between them by
    /// [`Solution::at`](super::Solution::at) are interpolated less accurately (see
    /// above).
    Auto,
    /// The default: SUNDIALS IDA on the DAE `F(t, u, u') = 0`, variable-order BDF
    /// (orders 1 to 5); any model (DASSL in Dymola, `IDA()` in Sundials.jl).
    #[default]
    Ida,
    /// SUNDIALS CVODE, variable-order BDF (orders 1 to 5) with Newton iterations on the
    /// compiled Jacobian: stiff models (`CVODE_BDF()` in Sundials.jl, like `FBDF`).
    CvodeBdf,
    /// SUNDIALS CVODE, variable-order Adams-Moulton (orders 1 to 12) with fixed-point
    /// iterations: smooth non-stiff models at tight tolerances (`CVODE_Adams()`).
    CvodeAdams,
    /// ARKODE's explicit Dormand-Prince 5(4), `ARKODE_DORMAND_PRINCE_7_4_5` (`DP5`,
    /// Dymola's `Dopri45`, MATLAB's `ode45`).
    DormandPrince5,
    /// ARKODE's explicit Verner 6(5), `ARKODE_VERNER_9_5_6` (`Vern6`).
    Verner6,
    /// ARKODE's explicit Verner 7(6), `ARKODE_VERNER_10_6_7` (`Vern7`).
    Verner7,
    /// ARKODE's explicit Verner 8(7), `ARKODE_VERNER_13_7_8` (`Vern8`; the order of
    /// `DOP853`).
    Verner8,
    /// ARKODE's explicit Verner 9(8), `ARKODE_VERNER_16_8_9` (`Vern9`).
    Verner9,
    /// ARKODE's diagonally implicit Kvaerno 5(4), `ARKODE_KVAERNO_7_4_5` (`Kvaerno5`),
    /// L-stable, with Newton iterations on the compiled Jacobian: stiff models.
    Kvaerno5,
}

impl Method {
    /// The ODE method this is (`None` for IDA and the automatic choice).
    pub(crate) fn ode(self) -> Option<super::ode::OdeMethod> {
        use super::ode::OdeMethod as O;
        Some(match self {
            Method::Auto | Method::Ida => return None,
            Method::CvodeBdf => O::CvodeBdf,
            Method::CvodeAdams => O::CvodeAdams,
            Method::DormandPrince5 => O::Explicit("ARKODE_DORMAND_PRINCE_7_4_5"),
            Method::Verner6 => O::Explicit("ARKODE_VERNER_9_5_6"),
            Method::Verner7 => O::Explicit("ARKODE_VERNER_10_6_7"),
            Method::Verner8 => O::Explicit("ARKODE_VERNER_13_7_8"),
            Method::Verner9 => O::Explicit("ARKODE_VERNER_16_8_9"),
            Method::Kvaerno5 => O::Implicit("ARKODE_KVAERNO_7_4_5"),
        })
    }
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
    /// The integration method (default [`Method::Ida`]).
    pub method: Method,
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
            method: Method::Ida,
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
