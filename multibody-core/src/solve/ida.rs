//! Integration of implicit DAEs `F(t, y, y') = 0` with SUNDIALS IDA.
//!
//! This module is the single place where the project talks to SUNDIALS
//! through FFI. [`integrate`] creates a SUNDIALS context, the IDA memory,
//! vectors, the iteration matrix and a linear solver, runs the integration and
//! frees everything again (also on every error path) through an RAII guard.
//!
//! Model code implements [`DaeFunctions`]; failures inside model callbacks are
//! reported as [`EvalError`] and never unwind into C (panics are caught and
//! turned into unrecoverable callback failures). SUNDIALS' own printing to
//! stderr/stdout is switched off; its messages are forwarded to the `log`
//! crate and included in [`IdaError`].

use std::ffi::{c_int, c_long, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::ptr;

use sundials_sys as sys;

pub use crate::codegen::EvalError;

use super::linsol;
use super::sundials::{
    Callback, EvalLog, Objects, not_finite, origin_name, scatter_dense, vec_mut, vec_ref,
    write_csc_pattern,
};

/// The DAE F(t, y, y') = 0 with its Jacobian J = dF/dy + cj dF/dy'.
pub trait DaeFunctions {
    /// Number of unknowns (and equations).
    fn len(&self) -> usize;
    /// Returns `true` if the system has no unknowns.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Evaluates the residual `out = F(t, y, y')`.
    fn residual(&mut self, t: f64, y: &[f64], yp: &[f64], out: &mut [f64])
    -> Result<(), EvalError>;
    /// CSC sparsity pattern of J: (col_ptr of len `jacobian_dimension() + 1`, row_idx sorted within each column). None = no analytic Jacobian (only allowed with IdaMatrix::DenseDifferenceQuotient).
    fn jacobian_pattern(&self) -> Option<(Vec<usize>, Vec<usize>)>;
    /// Size of the matrix described by [`jacobian_pattern`](Self::jacobian_pattern):
    /// `len()` (the default) for J itself, more for an *extended* Jacobian (J bordered by
    /// intermediate quantities whose elimination gives J, see
    /// [`ExtendedJacobian`](crate::codegen::ExtendedJacobian)). An extended Jacobian is
    /// solved by the sparse LU only, with right-hand sides padded by zeros; only the first
    /// `len()` entries of its solution are used.
    fn jacobian_dimension(&self) -> usize {
        self.len()
    }
    /// Values of J in the CSC order of the pattern.
    fn jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        yp: &[f64],
        cj: f64,
        values: &mut [f64],
    ) -> Result<(), EvalError>;
    /// Number of crossing functions: where one passes through zero, the integration
    /// stops (an event; see [`Integrated::roots`]). None by default.
    fn n_roots(&self) -> usize {
        0
    }
    /// Evaluates the crossing functions `out = g(t, y, y')` (`n_roots()` of them).
    fn roots(&mut self, t: f64, y: &[f64], yp: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        let _ = (t, y, yp, out);
        Ok(())
    }
    /// Whether the crossing functions read `y'` (`true` by default). Where they do
    /// not, an ODE integrator passes them any finite `y'` instead of computing it.
    fn roots_read_derivatives(&self) -> bool {
        true
    }
}

/// How IDA's iteration matrix is stored, filled and factorized: what a
/// [`LinearSolver`](super::LinearSolver) choice resolves to for one problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IdaMatrix {
    /// SUNDIALS dense matrix filled from the analytic Jacobian
    Dense,
    /// SUNDIALS dense with IDA's difference-quotient Jacobian (no jacobian() calls)
    DenseDifferenceQuotient,
    /// SUNSparseMatrix (CSC) + the sparse LU of this crate (COLAMD order from faer, pivots replayed while the pattern is unchanged and they stay large)
    SparseLu,
}

/// Settings of an IDA integration.
#[derive(Clone, Debug)]
pub struct IdaSettings {
    /// Relative tolerance.
    pub rtol: f64,
    /// Scalar absolute tolerance (used when `atol_vector` is `None`).
    pub atol: f64,
    /// Per-component absolute tolerances (length n).
    pub atol_vector: Option<Vec<f64>>,
    /// Maximum step size (IDASetMaxStep).
    pub max_step: Option<f64>,
    /// Initial step size (IDASetInitStep).
    pub initial_step: Option<f64>,
    /// Maximum number of internal steps per output interval (IDASetMaxNumSteps).
    pub max_steps: usize,
    /// 1.0 differential, 0.0 algebraic (IDASetId); empty means all differential.
    pub id: Vec<f64>,
    /// Exclude algebraic components from the local error test (IDASetSuppressAlg);
    /// only applied when `id` is given.
    pub suppress_alg: bool,
    /// Linear solver for the Newton iteration.
    pub matrix: IdaMatrix,
    /// run IDACalcIC(IDA_YA_YDP_INIT) before integrating
    pub calc_ic: bool,
}

impl Default for IdaSettings {
    fn default() -> Self {
        Self {
            rtol: 1e-6,
            atol: 1e-8,
            atol_vector: None,
            max_step: None,
            initial_step: None,
            max_steps: 100_000,
            id: Vec::new(),
            suppress_alg: true,
            matrix: IdaMatrix::SparseLu,
            calc_ic: false,
        }
    }
}

/// Which times are reported to the output callback.
#[derive(Clone, Debug, PartialEq)]
pub enum OutputMode {
    /// These times (sorted, > t0), interpolated within the internal steps that pass them
    Times(Vec<f64>),
    /// Every internal step (the last one ends exactly at `t_end`)
    EveryStep {
        /// Final time; the last reported time equals it exactly.
        t_end: f64,
    },
}

/// Integrator statistics at the end of an integration (of IDA, and of CVODE and ARKODE
/// with the same meanings: see [`ode`](super::ode)).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct IdaStats {
    /// Internal steps taken (for ARKODE's methods including the partial steps from a
    /// step's start that locate crossings and reach output times).
    pub steps: u64,
    /// Residual evaluations, including those for difference-quotient Jacobians (for
    /// CVODE and ARKODE: right-hand side evaluations, each one evaluation of the
    /// residual; one more per reported point, for its derivatives, and those of
    /// `Method::Auto`'s stiffness checks are not counted).
    pub residual_evals: u64,
    /// Jacobian evaluations (analytic or difference quotient).
    pub jacobian_evals: u64,
    /// Local error test failures.
    pub error_test_failures: u64,
    /// Nonlinear (Newton) iterations.
    pub nonlinear_iterations: u64,
    /// Nonlinear solver convergence failures.
    pub nonlinear_convergence_failures: u64,
    /// Linear solver setups (Jacobian evaluation + factorization).
    pub linear_setups: u64,
}

impl IdaStats {
    /// Adds the counts of `other` (another integration of the same run).
    pub fn add(&mut self, other: &IdaStats) {
        self.steps += other.steps;
        self.residual_evals += other.residual_evals;
        self.jacobian_evals += other.jacobian_evals;
        self.error_test_failures += other.error_test_failures;
        self.nonlinear_iterations += other.nonlinear_iterations;
        self.nonlinear_convergence_failures += other.nonlinear_convergence_failures;
        self.linear_setups += other.linear_setups;
    }
}

/// Up to this many unknowns the automatic choice of linear solver takes a dense LU
/// (IDA, and CVODE's and ARKODE's implicit methods), above it the sparse LU.
pub(crate) const DENSE_UP_TO: usize = 24;

/// Failure of an integration (IDA, CVODE or ARKODE; the flag names which).
#[derive(Debug, Clone, thiserror::Error)]
#[error("the integrator failed at t = {t}: {flag} ({message})")]
pub struct IdaError {
    /// Last time reached by the integrator (t0 for setup errors).
    pub t: f64,
    /// Name of the SUNDIALS return flag (e.g. `IDA_CONV_FAIL`, `CV_TOO_MUCH_WORK`,
    /// `ARK_ERR_FAILURE`), or `INVALID_INPUT`
    /// / `SETUP_FAILED` for errors detected before integrating.
    pub flag: String,
    /// Explanation in words.
    pub message: String,
}

pub(super) fn invalid(t: f64, message: impl Into<String>) -> IdaError {
    IdaError {
        t,
        flag: "INVALID_INPUT".into(),
        message: message.into(),
    }
}

/// State shared with the C callbacks through IDA's user-data pointer.
struct CallbackData<'a> {
    f: &'a mut dyn DaeFunctions,
    n: usize,
    solver: IdaMatrix,
    /// Validated pattern (usize, for scattering into the dense matrix).
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Same pattern as SUNDIALS indices (written into the sparse matrix).
    col_ptr_i: Vec<sys::sunindextype>,
    row_idx_i: Vec<sys::sunindextype>,
    /// Jacobian values buffer for the dense path.
    values: Vec<f64>,
    /// Last failure reported by a model callback.
    log: EvalLog,
}

/// Owns the IDA memory and the callback data of one integration and frees them in
/// Drop, before the SUNDIALS objects they use.
struct Guard<'a> {
    mem: *mut c_void,
    data: *mut CallbackData<'a>,
    o: Objects,
}

impl Drop for Guard<'_> {
    fn drop(&mut self) {
        // SAFETY: both pointers are null or owned by this guard (IDACreate,
        // Box::into_raw); `o` is dropped after this, its context last.
        unsafe {
            if !self.mem.is_null() {
                sys::IDAFree(&mut self.mem);
            }
            if !self.data.is_null() {
                drop(Box::from_raw(self.data));
            }
        }
    }
}

impl Guard<'_> {
    fn take_eval_error(&mut self) -> Option<(f64, Callback, EvalError)> {
        // SAFETY: as above; callbacks only run inside SUNDIALS calls.
        unsafe { self.data.as_mut().and_then(|d| d.log.last.take()) }
    }

    /// Builds an [`IdaError`] for a failed SUNDIALS call.
    fn error(&mut self, t: f64, flag: c_int, context: &str, settings: &IdaSettings) -> IdaError {
        let eval = self.take_eval_error();
        let sundials = self.o.take_message();
        let mut message = describe_flag(flag, eval.as_ref(), settings);
        if !context.is_empty() {
            message = format!("{context}: {message}");
        }
        let eval_used = matches!(
            flag,
            sys::IDA_RES_FAIL
                | sys::IDA_REP_RES_ERR
                | sys::IDA_FIRST_RES_FAIL
                | sys::IDA_NO_RECOVERY
        ) || (matches!(flag, sys::IDA_LSETUP_FAIL)
            && matches!(eval, Some((_, Callback::Jacobian, _))));
        if let (false, Some((te, origin, e))) = (eval_used, &eval) {
            message.push_str(&format!(
                "; last model evaluation error ({}) at t = {te}: {}",
                origin_name(*origin),
                e.message
            ));
        }
        if let Some(s) = sundials {
            message.push_str(&format!(" [SUNDIALS: {}]", s.trim()));
        }
        IdaError {
            t,
            flag: flag_name(flag),
            message,
        }
    }

    fn check(
        &mut self,
        flag: c_int,
        t: f64,
        what: &str,
        settings: &IdaSettings,
    ) -> Result<(), IdaError> {
        if flag < 0 {
            let mut e = self.error(t, flag, what, settings);
            if e.flag.starts_with("IDA_UNKNOWN") {
                e.flag = "SETUP_FAILED".into();
            }
            Err(e)
        } else {
            Ok(())
        }
    }

    fn setup_failed(&mut self, t: f64, message: String) -> IdaError {
        self.o.setup_failed(t, message)
    }
}

/// Name of an IDA return flag.
fn flag_name(flag: c_int) -> String {
    let s = match flag {
        sys::IDA_SUCCESS => "IDA_SUCCESS",
        sys::IDA_TSTOP_RETURN => "IDA_TSTOP_RETURN",
        sys::IDA_ROOT_RETURN => "IDA_ROOT_RETURN",
        sys::IDA_WARNING => "IDA_WARNING",
        sys::IDA_TOO_MUCH_WORK => "IDA_TOO_MUCH_WORK",
        sys::IDA_TOO_MUCH_ACC => "IDA_TOO_MUCH_ACC",
        sys::IDA_ERR_FAIL => "IDA_ERR_FAIL",
        sys::IDA_CONV_FAIL => "IDA_CONV_FAIL",
        sys::IDA_LINIT_FAIL => "IDA_LINIT_FAIL",
        sys::IDA_LSETUP_FAIL => "IDA_LSETUP_FAIL",
        sys::IDA_LSOLVE_FAIL => "IDA_LSOLVE_FAIL",
        sys::IDA_RES_FAIL => "IDA_RES_FAIL",
        sys::IDA_REP_RES_ERR => "IDA_REP_RES_ERR",
        sys::IDA_RTFUNC_FAIL => "IDA_RTFUNC_FAIL",
        sys::IDA_CONSTR_FAIL => "IDA_CONSTR_FAIL",
        sys::IDA_FIRST_RES_FAIL => "IDA_FIRST_RES_FAIL",
        sys::IDA_LINESEARCH_FAIL => "IDA_LINESEARCH_FAIL",
        sys::IDA_NO_RECOVERY => "IDA_NO_RECOVERY",
        sys::IDA_NLS_INIT_FAIL => "IDA_NLS_INIT_FAIL",
        sys::IDA_NLS_SETUP_FAIL => "IDA_NLS_SETUP_FAIL",
        sys::IDA_NLS_FAIL => "IDA_NLS_FAIL",
        sys::IDA_MEM_NULL => "IDA_MEM_NULL",
        sys::IDA_MEM_FAIL => "IDA_MEM_FAIL",
        sys::IDA_ILL_INPUT => "IDA_ILL_INPUT",
        sys::IDA_NO_MALLOC => "IDA_NO_MALLOC",
        sys::IDA_BAD_EWT => "IDA_BAD_EWT",
        sys::IDA_BAD_K => "IDA_BAD_K",
        sys::IDA_BAD_T => "IDA_BAD_T",
        sys::IDA_BAD_DKY => "IDA_BAD_DKY",
        sys::IDA_VECTOROP_ERR => "IDA_VECTOROP_ERR",
        sys::IDA_CONTEXT_ERR => "IDA_CONTEXT_ERR",
        other => return format!("IDA_UNKNOWN({other})"),
    };
    s.to_string()
}

/// Explains an IDA return flag in words.
fn describe_flag(
    flag: c_int,
    eval: Option<&(f64, Callback, EvalError)>,
    settings: &IdaSettings,
) -> String {
    let eval_msg = |what: &str| match eval {
        Some((t, o, e)) => format!(
            "{what}: {} (in the {} function at t = {t})",
            e.message,
            origin_name(*o)
        ),
        None => format!("{what}: no message"),
    };
    match flag {
        sys::IDA_TOO_MUCH_WORK => format!(
            "more than SolverOptions::max_steps = {} steps before the next reported point",
            settings.max_steps
        ),
        sys::IDA_TOO_MUCH_ACC => "the requested accuracy could not be reached (rtol/atol too small)".into(),
        sys::IDA_ERR_FAIL => {
            "error test failed repeatedly (step size became too small; stiff or discontinuous?)".into()
        }
        sys::IDA_CONV_FAIL => {
            "nonlinear solver failed to converge repeatedly (singular Jacobian or inconsistent model?)".into()
        }
        sys::IDA_LINIT_FAIL => "the linear solver could not be initialized".into(),
        sys::IDA_LSETUP_FAIL => match eval {
            Some((_, Callback::Jacobian, _)) => eval_msg("the Jacobian function failed"),
            _ => "linear solver failed (singular iteration matrix)".into(),
        },
        sys::IDA_LSOLVE_FAIL => "linear solver failed (singular iteration matrix)".into(),
        sys::IDA_RES_FAIL => eval_msg("the residual function failed"),
        sys::IDA_REP_RES_ERR => eval_msg("the residual function failed recoverably and repeatedly"),
        sys::IDA_FIRST_RES_FAIL => eval_msg("the residual function failed at the first call of the initial condition calculation"),
        sys::IDA_NO_RECOVERY => eval_msg("the initial condition calculation could not recover from a failed evaluation"),
        sys::IDA_LINESEARCH_FAIL => {
            "the initial condition calculation failed in its line search (no consistent initial values found; bad id or initial guess?)".into()
        }
        sys::IDA_CONSTR_FAIL => "the initial condition calculation could not satisfy the constraints".into(),
        sys::IDA_NLS_INIT_FAIL | sys::IDA_NLS_SETUP_FAIL | sys::IDA_NLS_FAIL => {
            "the nonlinear solver failed unrecoverably".into()
        }
        sys::IDA_MEM_FAIL => "memory allocation failed".into(),
        sys::IDA_ILL_INPUT => "invalid input to IDA".into(),
        sys::IDA_BAD_EWT => {
            "an error weight became non-positive (a component with zero absolute tolerance reached zero?)".into()
        }
        sys::IDA_BAD_T => "requested time outside the interval covered by the last step".into(),
        sys::IDA_VECTOROP_ERR => "a vector operation failed".into(),
        other => format!("IDA returned flag {other}"),
    }
}

/// Records a caught panic as an unrecoverable evaluation error.
///
/// # Safety
/// `ud` is the callback data pointer (or null) and not otherwise borrowed.
unsafe fn record_panic(
    ud: *mut c_void,
    t: f64,
    origin: Callback,
    p: &(dyn std::any::Any + Send),
) -> c_int {
    // SAFETY: guaranteed by the caller.
    match unsafe { ud.cast::<CallbackData<'_>>().as_mut() } {
        Some(d) => d.log.record_panic(t, origin, p),
        None => -1,
    }
}

unsafe extern "C" fn residual_cb(
    t: sys::sunrealtype,
    yy: sys::N_Vector,
    yp: sys::N_Vector,
    rr: sys::N_Vector,
    ud: *mut c_void,
) -> c_int {
    let r = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: ud points to the CallbackData owned by the guard; IDA passes
        // three distinct serial vectors of length n.
        unsafe {
            let Some(d) = ud.cast::<CallbackData<'_>>().as_mut() else {
                return -1;
            };
            let n = d.n;
            let (y, ypv, out) = (vec_ref(yy, n), vec_ref(yp, n), vec_mut(rr, n));
            match d
                .f
                .residual(t, y, ypv, out)
                .map(|()| not_finite(out, "residual component"))
            {
                Ok(None) => 0,
                Ok(Some(e)) | Err(e) => d.log.record(t, Callback::Residual, e),
            }
        }
    }));
    // SAFETY: the borrow inside the closure has ended.
    r.unwrap_or_else(|p| unsafe { record_panic(ud, t, Callback::Residual, p.as_ref()) })
}

unsafe extern "C" fn root_cb(
    t: sys::sunrealtype,
    yy: sys::N_Vector,
    yp: sys::N_Vector,
    gout: *mut sys::sunrealtype,
    ud: *mut c_void,
) -> c_int {
    let r = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: ud points to the CallbackData owned by the guard; IDA passes two
        // serial vectors of length n and an array of n_roots values.
        unsafe {
            let Some(d) = ud.cast::<CallbackData<'_>>().as_mut() else {
                return -1;
            };
            let n = d.n;
            let nr = d.f.n_roots();
            let (y, ypv) = (vec_ref(yy, n), vec_ref(yp, n));
            let out = std::slice::from_raw_parts_mut(gout, nr);
            let result = d.f.roots(t, y, ypv, out);
            d.log.record_roots(t, result, out)
        }
    }));
    // SAFETY: the borrow inside the closure has ended.
    r.unwrap_or_else(|p| unsafe { record_panic(ud, t, Callback::Roots, p.as_ref()) })
}

#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn jacobian_cb(
    t: sys::sunrealtype,
    cj: sys::sunrealtype,
    yy: sys::N_Vector,
    yp: sys::N_Vector,
    _rr: sys::N_Vector,
    jac: sys::SUNMatrix,
    ud: *mut c_void,
    _tmp1: sys::N_Vector,
    _tmp2: sys::N_Vector,
    _tmp3: sys::N_Vector,
) -> c_int {
    let r = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: ud points to the CallbackData owned by the guard; `jac` is
        // the matrix created for the selected solver (dense n x n or CSC
        // sparse with capacity >= nnz).
        unsafe {
            let Some(d) = ud.cast::<CallbackData<'_>>().as_mut() else {
                return -1;
            };
            let n = d.n;
            let (y, ypv) = (vec_ref(yy, n), vec_ref(yp, n));
            match d.solver {
                IdaMatrix::SparseLu => {
                    // IDA zeroes the matrix, including its pattern, before every call.
                    let Some(values) = write_csc_pattern(jac, &d.col_ptr_i, &d.row_idx_i) else {
                        return -1;
                    };
                    match d.f.jacobian(t, y, ypv, cj, values) {
                        Ok(()) => 0,
                        Err(e) => d.log.record(t, Callback::Jacobian, e),
                    }
                }
                IdaMatrix::Dense | IdaMatrix::DenseDifferenceQuotient => {
                    let CallbackData { f, values, .. } = &mut *d;
                    if let Err(e) = f.jacobian(t, y, ypv, cj, values) {
                        return d.log.record(t, Callback::Jacobian, e);
                    }
                    if let Some(e) = not_finite(&d.values, "Jacobian entry") {
                        return d.log.record(t, Callback::Jacobian, e);
                    }
                    let data = sys::SUNDenseMatrix_Data(jac);
                    if data.is_null() {
                        return -1;
                    }
                    let dense = std::slice::from_raw_parts_mut(data, n * n);
                    scatter_dense(n, &d.col_ptr, &d.row_idx, &d.values, dense);
                    0
                }
            }
        }
    }));
    // SAFETY: the borrow inside the closure has ended.
    r.unwrap_or_else(|p| unsafe { record_panic(ud, t, Callback::Jacobian, p.as_ref()) })
}

pub(super) fn validate(
    n: usize,
    t0: f64,
    y0: &[f64],
    yp0: &[f64],
    settings: &IdaSettings,
    output: &OutputMode,
) -> Result<(), IdaError> {
    if y0.len() != n || yp0.len() != n {
        return Err(invalid(
            t0,
            format!(
                "y0 has length {} and yp0 length {}, but the system has {n} unknowns",
                y0.len(),
                yp0.len()
            ),
        ));
    }
    if !t0.is_finite() {
        return Err(invalid(t0, "t0 is not finite"));
    }
    if let Some(i) = y0.iter().chain(yp0).position(|v| !v.is_finite()) {
        return Err(invalid(
            t0,
            format!("initial value {i} (y0 then yp0) is not finite"),
        ));
    }
    if !settings.id.is_empty() && settings.id.len() != n {
        return Err(invalid(
            t0,
            format!("id has length {}, expected {n}", settings.id.len()),
        ));
    }
    if !(settings.rtol >= 0.0 && settings.rtol.is_finite()) {
        return Err(invalid(t0, "rtol must be finite and >= 0"));
    }
    match &settings.atol_vector {
        Some(a) if a.len() != n => {
            return Err(invalid(
                t0,
                format!("atol_vector has length {}, expected {n}", a.len()),
            ));
        }
        Some(a) if a.iter().any(|v| !(*v >= 0.0 && v.is_finite())) => {
            return Err(invalid(t0, "atol_vector entries must be finite and >= 0"));
        }
        None if !(settings.atol >= 0.0 && settings.atol.is_finite()) => {
            return Err(invalid(t0, "atol must be finite and >= 0"));
        }
        _ => {}
    }
    match output {
        OutputMode::Times(times) => {
            let mut prev = t0;
            for &t in times {
                if !(t > prev && t.is_finite()) {
                    return Err(invalid(
                        t0,
                        format!(
                            "output times must be finite, strictly increasing and > t0 = {t0} (got {t} after {prev})"
                        ),
                    ));
                }
                prev = t;
            }
        }
        OutputMode::EveryStep { t_end } => {
            if !(*t_end > t0 && t_end.is_finite()) {
                return Err(invalid(
                    t0,
                    format!("t_end = {t_end} must be finite and > t0 = {t0}"),
                ));
            }
        }
    }
    Ok(())
}

fn stats(mem: *mut c_void) -> IdaStats {
    let get = |f: unsafe extern "C" fn(*mut c_void, *mut c_long) -> c_int| -> u64 {
        let mut v: c_long = 0;
        // SAFETY: mem is a valid IDA memory block; f writes one long.
        let flag = unsafe { f(mem, &mut v) };
        if flag == 0 {
            u64::try_from(v).unwrap_or(0)
        } else {
            0
        }
    };
    IdaStats {
        steps: get(sys::IDAGetNumSteps),
        residual_evals: get(sys::IDAGetNumResEvals) + get(sys::IDAGetNumLinResEvals),
        jacobian_evals: get(sys::IDAGetNumJacEvals),
        error_test_failures: get(sys::IDAGetNumErrTestFails),
        nonlinear_iterations: get(sys::IDAGetNumNonlinSolvIters),
        nonlinear_convergence_failures: get(sys::IDAGetNumNonlinSolvConvFails),
        linear_setups: get(sys::IDAGetNumLinSolvSetups),
    }
}

/// IDA created for `f` from `(t0, y0, yp0)` with `settings` (and the crossing
/// functions of `f`, if any), stopping at `t_stop`: the guard that owns it, and the
/// vectors of the unknowns and their derivatives.
#[allow(clippy::type_complexity)]
fn open<'a>(
    f: &'a mut dyn DaeFunctions,
    t0: f64,
    y0: &[f64],
    yp0: &[f64],
    settings: &IdaSettings,
    t_stop: Option<f64>,
    t_scale: f64,
) -> Result<(Guard<'a>, sys::N_Vector, sys::N_Vector), IdaError> {
    let n = f.len();
    let n_roots = f.n_roots();
    // Jacobian pattern.
    let pattern = f.jacobian_pattern();
    let dim = f.jacobian_dimension();
    if dim < n || (dim > n && settings.matrix != IdaMatrix::SparseLu) {
        return Err(invalid(
            t0,
            format!(
                "jacobian_dimension() is {dim} for {n} unknowns; an extended Jacobian needs IdaMatrix::SparseLu"
            ),
        ));
    }
    let (col_ptr, row_idx) = match (pattern, settings.matrix) {
        (Some((c, r)), _) => {
            if !linsol::valid_csc(dim, &c, &r) {
                return Err(invalid(
                    t0,
                    "jacobian_pattern is not a valid CSC pattern (col_ptr of length jacobian_dimension() + 1 from 0 to nnz, rows < jacobian_dimension() strictly increasing per column)",
                ));
            }
            (c, r)
        }
        (None, IdaMatrix::DenseDifferenceQuotient) => (Vec::new(), Vec::new()),
        (None, s) => {
            return Err(invalid(
                t0,
                format!(
                    "linear solver {s:?} needs an analytic Jacobian, but jacobian_pattern() returned None"
                ),
            ));
        }
    };
    let nnz = row_idx.len();
    let n_i = sys::sunindextype::try_from(n).map_err(|_| invalid(t0, "system too large"))?;
    let dim_i = sys::sunindextype::try_from(dim).map_err(|_| invalid(t0, "system too large"))?;
    let nnz_i =
        sys::sunindextype::try_from(nnz.max(1)).map_err(|_| invalid(t0, "Jacobian too large"))?;
    let max_steps = c_long::try_from(settings.max_steps).unwrap_or(c_long::MAX);

    let data = CallbackData {
        f,
        n,
        solver: settings.matrix,
        col_ptr_i: col_ptr.iter().map(|&v| v as sys::sunindextype).collect(),
        row_idx_i: row_idx.iter().map(|&v| v as sys::sunindextype).collect(),
        values: if settings.matrix == IdaMatrix::Dense {
            vec![0.0; nnz]
        } else {
            Vec::new()
        },
        col_ptr,
        row_idx,
        log: EvalLog::default(),
    };
    let o = Objects::new().map_err(|m| IdaError {
        t: t0,
        flag: "SETUP_FAILED".into(),
        message: m,
    })?;
    let mut g = Guard {
        mem: ptr::null_mut(),
        data: Box::into_raw(Box::new(data)),
        o,
    };

    // SAFETY: all SUNDIALS objects are created here and owned by `g`, which
    // frees them on every return path. The callback data passed to SUNDIALS stays
    // valid until after the IDA memory is freed. Slices over the vectors are only
    // created between SUNDIALS calls.
    unsafe {
        let yy = g.o.vector(y0).map_err(|m| g.setup_failed(t0, m))?;
        let yp = g.o.vector(yp0).map_err(|m| g.setup_failed(t0, m))?;

        g.mem = sys::IDACreate(g.o.ctx);
        if g.mem.is_null() {
            return Err(g.setup_failed(t0, "IDACreate failed".into()));
        }
        let mem = g.mem;
        let flag = sys::IDAInit(mem, Some(residual_cb), t0, yy, yp);
        g.check(flag, t0, "IDAInit", settings)?;
        let flag = sys::IDASetUserData(mem, g.data.cast::<c_void>());
        g.check(flag, t0, "IDASetUserData", settings)?;
        let flag = match &settings.atol_vector {
            Some(a) => {
                let av = g.o.vector(a).map_err(|m| g.setup_failed(t0, m))?;
                sys::IDASVtolerances(mem, settings.rtol, av)
            }
            None => sys::IDASStolerances(mem, settings.rtol, settings.atol),
        };
        g.check(flag, t0, "setting tolerances", settings)?;
        if let Some(h) = settings.max_step {
            let flag = sys::IDASetMaxStep(mem, h);
            g.check(flag, t0, "IDASetMaxStep", settings)?;
        }
        if let Some(h) = settings.initial_step {
            let flag = sys::IDASetInitStep(mem, h);
            g.check(flag, t0, "IDASetInitStep", settings)?;
        }
        let flag = sys::IDASetMaxNumSteps(mem, max_steps);
        g.check(flag, t0, "IDASetMaxNumSteps", settings)?;
        // A step below the resolution of time cannot advance it: stop instead of
        // shrinking forever (a solution that blows up, or a singular model).
        let t_scale = t_scale.abs().max(t0.abs()).max(1e-300);
        let flag = sys::IDASetMinStep(mem, 4.0 * f64::EPSILON * t_scale);
        g.check(flag, t0, "IDASetMinStep", settings)?;
        if !settings.id.is_empty() || settings.calc_ic {
            let id = if settings.id.is_empty() {
                vec![1.0; n]
            } else {
                settings.id.clone()
            };
            let idv = g.o.vector(&id).map_err(|m| g.setup_failed(t0, m))?;
            let flag = sys::IDASetId(mem, idv);
            g.check(flag, t0, "IDASetId", settings)?;
        }
        if !settings.id.is_empty() {
            let flag = sys::IDASetSuppressAlg(mem, c_int::from(settings.suppress_alg));
            g.check(flag, t0, "IDASetSuppressAlg", settings)?;
        }

        // Linear solver.
        match settings.matrix {
            IdaMatrix::Dense | IdaMatrix::DenseDifferenceQuotient => {
                g.o.mat = sys::SUNDenseMatrix(n_i, n_i, g.o.ctx);
                if g.o.mat.is_null() {
                    return Err(g.setup_failed(t0, "SUNDenseMatrix failed".into()));
                }
                g.o.ls = sys::SUNLinSol_Dense(yy, g.o.mat, g.o.ctx);
                if g.o.ls.is_null() {
                    return Err(g.setup_failed(t0, "SUNLinSol_Dense failed".into()));
                }
            }
            IdaMatrix::SparseLu => {
                g.o.mat = sys::SUNSparseMatrix(dim_i, dim_i, nnz_i, sys::CSC_MAT as c_int, g.o.ctx);
                if g.o.mat.is_null() {
                    return Err(g.setup_failed(t0, "SUNSparseMatrix failed".into()));
                }
                g.o.ls = linsol::new_sparse_lu_solver(g.o.ctx);
                if g.o.ls.is_null() {
                    return Err(g.setup_failed(t0, "creating the faer linear solver failed".into()));
                }
            }
        }
        let flag = sys::IDASetLinearSolver(mem, g.o.ls, g.o.mat);
        g.check(flag, t0, "IDASetLinearSolver", settings)?;
        if settings.matrix != IdaMatrix::DenseDifferenceQuotient {
            let flag = sys::IDASetJacFn(mem, Some(jacobian_cb));
            g.check(flag, t0, "IDASetJacFn", settings)?;
        }

        if let Some(te) = t_stop {
            let flag = sys::IDASetStopTime(mem, te);
            g.check(flag, t0, "IDASetStopTime", settings)?;
        }
        if n_roots > 0 {
            let nr =
                c_int::try_from(n_roots).map_err(|_| invalid(t0, "too many crossing functions"))?;
            let flag = sys::IDARootInit(mem, nr, Some(root_cb));
            g.check(flag, t0, "IDARootInit", settings)?;
            // A crossing function that is zero at the start (a step at t0) is no event.
            let flag = sys::IDASetNoInactiveRootWarn(mem);
            g.check(flag, t0, "IDASetNoInactiveRootWarn", settings)?;
        }
        Ok((g, yy, yp))
    }
}

/// Integrate from t0; `on_output(t, y, yp)` is called for t0 (with the consistent values
/// after calc_ic if enabled) and every output, and returns `false` to stop (the
/// integration then fails with the flag `STOPPED`). Returns statistics.
#[allow(clippy::type_complexity)]
pub fn integrate(
    f: &mut dyn DaeFunctions,
    t0: f64,
    y0: &[f64],
    yp0: &[f64],
    settings: &IdaSettings,
    output: &OutputMode,
    on_output: &mut dyn FnMut(f64, &[f64], &[f64]) -> bool,
) -> Result<IdaStats, IdaError> {
    integrate_monitored(f, t0, y0, yp0, settings, output, on_output, None).map(|r| r.stats)
}

/// Consistent values at `t0` after the model's discrete values changed (an event):
/// IDA's `IDACalcIC` keeps the differential unknowns (those `settings.id` marks 1) and
/// computes the algebraic ones and every derivative. `tout1` is where the integration
/// heads next (it scales IDA's trial step).
pub fn consistent_values(
    f: &mut dyn DaeFunctions,
    t0: f64,
    y0: &[f64],
    yp0: &[f64],
    settings: &IdaSettings,
    tout1: f64,
) -> Result<(Vec<f64>, Vec<f64>), IdaError> {
    let n = f.len();
    if n == 0 {
        return Ok((Vec::new(), Vec::new()));
    }
    let settings = IdaSettings {
        calc_ic: true,
        ..settings.clone()
    };
    let (mut g, yy, yp) = open(f, t0, y0, yp0, &settings, None, tout1)?;
    // SAFETY: every SUNDIALS object is owned by `g`; the slices are read after the
    // last SUNDIALS call.
    unsafe {
        let flag = sys::IDACalcIC(g.mem, sys::IDA_YA_YDP_INIT, tout1);
        g.check(
            flag,
            t0,
            "consistent values after an event (IDACalcIC)",
            &settings,
        )?;
        let flag = sys::IDAGetConsistentIC(g.mem, yy, yp);
        g.check(flag, t0, "IDAGetConsistentIC", &settings)?;
        Ok((vec_ref(yy, n).to_vec(), vec_ref(yp, n).to_vec()))
    }
}

/// A system without unknowns as IDA sees it when it has crossing functions (of time
/// alone): one unknown `z` with `z' = 0`, so that they are watched all the same.
struct Placeholder<'a> {
    inner: &'a mut dyn DaeFunctions,
}

impl DaeFunctions for Placeholder<'_> {
    fn len(&self) -> usize {
        1
    }

    fn residual(
        &mut self,
        _: f64,
        _: &[f64],
        yp: &[f64],
        out: &mut [f64],
    ) -> Result<(), EvalError> {
        out[0] = yp[0];
        Ok(())
    }

    fn jacobian_pattern(&self) -> Option<(Vec<usize>, Vec<usize>)> {
        Some((vec![0, 1], vec![0]))
    }

    fn jacobian(
        &mut self,
        _: f64,
        _: &[f64],
        _: &[f64],
        cj: f64,
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        values[0] = cj;
        Ok(())
    }

    fn n_roots(&self) -> usize {
        self.inner.n_roots()
    }

    fn roots(&mut self, t: f64, _: &[f64], _: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        self.inner.roots(t, &[], &[], out)
    }
}

/// [`integrate_monitored`] of a system without unknowns but with crossing functions,
/// through a [`Placeholder`].
#[allow(clippy::type_complexity)]
fn integrate_placeholder(
    f: &mut dyn DaeFunctions,
    t0: f64,
    settings: &IdaSettings,
    output: &OutputMode,
    on_output: &mut dyn FnMut(f64, &[f64], &[f64]) -> bool,
    on_step: Option<&mut dyn FnMut(f64, &[f64], &[f64]) -> bool>,
) -> Result<Integrated, IdaError> {
    let settings = IdaSettings {
        id: vec![1.0],
        atol_vector: None,
        matrix: IdaMatrix::Dense,
        calc_ic: false,
        ..settings.clone()
    };
    let mut p = Placeholder { inner: f };
    let mut step = on_step;
    let mut on_step = step
        .as_mut()
        .map(|m| move |t: f64, _: &[f64], _: &[f64]| m(t, &[], &[]));
    let r = integrate_monitored(
        &mut p,
        t0,
        &[0.0],
        &[0.0],
        &settings,
        output,
        &mut |t, _, _| on_output(t, &[], &[]),
        on_step
            .as_mut()
            .map(|m| m as &mut dyn FnMut(f64, &[f64], &[f64]) -> bool),
    )?;
    Ok(Integrated {
        stopped: r.stopped.map(|(t, _, _)| (t, Vec::new(), Vec::new())),
        ..r
    })
}

/// How an integration with a step monitor ended.
#[derive(Clone, Debug)]
pub struct Integrated {
    /// Statistics.
    pub stats: IdaStats,
    /// Where the monitor or a crossing function stopped it, with the unknowns and
    /// derivatives there (`None` when it reached the final time).
    pub stopped: Option<(f64, Vec<f64>, Vec<f64>)>,
    /// Where a crossing function stopped it: per crossing function, +1 where it
    /// passed through zero rising, -1 falling, 0 where it did not (empty otherwise).
    /// The point of the crossing has been reported as an output.
    pub roots: Vec<i32>,
    /// Whether the integration went over to a method for stiff models on the way
    /// ([`OdeMethod::Auto`](super::ode::OdeMethod::Auto); always false for IDA).
    pub switched: bool,
}

/// [`integrate`], with `on_step(t, y, yp)` called after every internal step (after the
/// outputs up to `t` are reported): `false` ends the integration there, successfully,
/// with the point where it stopped.
#[allow(clippy::type_complexity, clippy::too_many_arguments)]
pub fn integrate_monitored(
    f: &mut dyn DaeFunctions,
    t0: f64,
    y0: &[f64],
    yp0: &[f64],
    settings: &IdaSettings,
    output: &OutputMode,
    on_output: &mut dyn FnMut(f64, &[f64], &[f64]) -> bool,
    mut on_step: Option<&mut dyn FnMut(f64, &[f64], &[f64]) -> bool>,
) -> Result<Integrated, IdaError> {
    let n = f.len();
    validate(n, t0, y0, yp0, settings, output)?;

    if n == 0 && f.n_roots() > 0 {
        return integrate_placeholder(f, t0, settings, output, on_output, on_step);
    }
    if n == 0 {
        // Nothing to integrate: report the requested times.
        on_output(t0, &[], &[]);
        match output {
            OutputMode::Times(times) => times.iter().for_each(|&t| {
                on_output(t, &[], &[]);
            }),
            OutputMode::EveryStep { t_end } => {
                on_output(*t_end, &[], &[]);
            }
        }
        return Ok(Integrated {
            stats: IdaStats::default(),
            stopped: None,
            roots: Vec::new(),
            switched: false,
        });
    }
    let t_last = match output {
        OutputMode::Times(times) => times.last().copied(),
        OutputMode::EveryStep { t_end } => Some(*t_end),
    };
    let n_roots = f.n_roots();
    let (mut g, yy, yp) = open(f, t0, y0, yp0, settings, t_last, t_last.unwrap_or(t0))?;
    let mem = g.mem;

    // SAFETY: every SUNDIALS object is owned by `g`, which frees them on every return
    // path; slices over the vectors are only created between SUNDIALS calls.
    unsafe {
        if settings.calc_ic {
            let tout1 = match output {
                OutputMode::Times(times) => times.first().copied(),
                OutputMode::EveryStep { t_end } => Some(*t_end),
            }
            .unwrap_or(t0 + 1e-3 * t0.abs().max(1.0));
            let flag = sys::IDACalcIC(mem, sys::IDA_YA_YDP_INIT, tout1);
            g.check(flag, t0, "consistent initial values (IDACalcIC)", settings)?;
            let flag = sys::IDAGetConsistentIC(mem, yy, yp);
            g.check(flag, t0, "IDAGetConsistentIC", settings)?;
        }
        let stopped_err = |t: f64| IdaError {
            t,
            flag: "STOPPED".into(),
            message: "the output callback stopped the integration".into(),
        };
        if !on_output(t0, vec_ref(yy, n), vec_ref(yp, n)) {
            return Err(stopped_err(t0));
        }

        // One internal step at a time up to the stop time; requested output times are
        // interpolated within the step that passed them (IDA's own dense output).
        let t_end = t_last.unwrap_or(t0);
        let (ky, kyp) = (
            g.o.vector(&vec![0.0; n])
                .map_err(|m| g.setup_failed(t0, m))?,
            g.o.vector(&vec![0.0; n])
                .map_err(|m| g.setup_failed(t0, m))?,
        );
        let mut next_output = 0;
        let mut t = t0;
        let mut stopped = None;
        let mut roots = Vec::new();
        // Times IDA cannot step to from t0 (a restart just before an output time or the
        // end): they take the values at t0.
        let far =
            |tout: f64| (tout - t0).abs() > 1e3 * f64::EPSILON * t0.abs().max(tout.abs()).max(1.0);
        if !far(t_end) {
            let times = match output {
                OutputMode::Times(times) => times.clone(),
                OutputMode::EveryStep { t_end } => vec![*t_end],
            };
            for tout in times {
                if !on_output(tout, vec_ref(yy, n), vec_ref(yp, n)) {
                    return Err(stopped_err(t0));
                }
            }
            return Ok(Integrated {
                stats: stats(mem),
                stopped: None,
                roots: Vec::new(),
                switched: false,
            });
        }
        // The first call's target sets IDA's estimate of the first step: the first
        // output time, as when integrating to each output in turn.
        let mut target = match output {
            OutputMode::Times(times) => times.iter().copied().find(|&t| far(t)).unwrap_or(t_end),
            OutputMode::EveryStep { t_end } => *t_end,
        };
        // Steps since the last reported point (IDA counts per call, and every call here
        // is one step).
        let mut steps_since_output = 0usize;
        loop {
            let flag = sys::IDASolve(mem, target, &mut t, yy, yp, sys::IDA_ONE_STEP);
            target = t_end;
            if flag < 0 {
                return Err(g.error(t, flag, "", settings));
            }
            let done = flag == sys::IDA_TSTOP_RETURN || t >= t_end;
            let root = flag == sys::IDA_ROOT_RETURN && !done;
            let reported_before = next_output;
            let mut reported_at_t = false;
            steps_since_output += 1;
            match output {
                OutputMode::Times(times) => {
                    while let Some(&tout) = times.get(next_output) {
                        if tout > t && !done {
                            break;
                        }
                        next_output += 1;
                        if tout >= t {
                            // The step ends on the output time (or the stop time).
                            if !on_output(tout, vec_ref(yy, n), vec_ref(yp, n)) {
                                return Err(stopped_err(t));
                            }
                            reported_at_t = true;
                            continue;
                        }
                        let flag = sys::IDAGetDky(mem, tout, 0, ky);
                        g.check(flag, tout, "IDAGetDky", settings)?;
                        let flag = sys::IDAGetDky(mem, tout, 1, kyp);
                        g.check(flag, tout, "IDAGetDky", settings)?;
                        if !on_output(tout, vec_ref(ky, n), vec_ref(kyp, n)) {
                            return Err(stopped_err(t));
                        }
                    }
                }
                OutputMode::EveryStep { t_end } => {
                    let reported = if done { *t_end } else { t };
                    if !on_output(reported, vec_ref(yy, n), vec_ref(yp, n)) {
                        return Err(stopped_err(t));
                    }
                }
            }
            if done {
                break;
            }
            if root {
                // The left limit at the event is a point of the solution.
                if matches!(output, OutputMode::Times(_))
                    && !reported_at_t
                    && !on_output(t, vec_ref(yy, n), vec_ref(yp, n))
                {
                    return Err(stopped_err(t));
                }
                let mut info: Vec<i32> = vec![0; n_roots];
                let flag = sys::IDAGetRootInfo(mem, info.as_mut_ptr());
                g.check(flag, t, "IDAGetRootInfo", settings)?;
                roots = info;
                stopped = Some((t, vec_ref(yy, n).to_vec(), vec_ref(yp, n).to_vec()));
                break;
            }
            if matches!(output, OutputMode::EveryStep { .. }) || next_output > reported_before {
                steps_since_output = 0;
            } else if steps_since_output >= settings.max_steps {
                return Err(g.error(t, sys::IDA_TOO_MUCH_WORK, "", settings));
            }
            if let Some(m) = on_step.as_mut()
                && !m(t, vec_ref(yy, n), vec_ref(yp, n))
            {
                stopped = Some((t, vec_ref(yy, n).to_vec(), vec_ref(yp, n).to_vec()));
                break;
            }
        }
        let st = stats(mem);
        log::debug!("IDA finished at t = {t}: {st:?}");
        Ok(Integrated {
            stats: st,
            stopped,
            roots,
            switched: false,
        })
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;

    /// Robertson's chemical kinetics as a DAE.
    struct Robertson {
        analytic: bool,
    }

    impl DaeFunctions for Robertson {
        fn len(&self) -> usize {
            3
        }
        fn residual(
            &mut self,
            _t: f64,
            y: &[f64],
            yp: &[f64],
            r: &mut [f64],
        ) -> Result<(), EvalError> {
            r[0] = -0.04 * y[0] + 1e4 * y[1] * y[2] - yp[0];
            r[1] = 0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1] - yp[1];
            r[2] = y[0] + y[1] + y[2] - 1.0;
            Ok(())
        }
        fn jacobian_pattern(&self) -> Option<(Vec<usize>, Vec<usize>)> {
            self.analytic
                .then(|| (vec![0, 3, 6, 9], vec![0, 1, 2, 0, 1, 2, 0, 1, 2]))
        }
        fn jacobian(
            &mut self,
            _t: f64,
            y: &[f64],
            _yp: &[f64],
            cj: f64,
            v: &mut [f64],
        ) -> Result<(), EvalError> {
            // column y1
            v[0] = -0.04 - cj;
            v[1] = 0.04;
            v[2] = 1.0;
            // column y2
            v[3] = 1e4 * y[2];
            v[4] = -1e4 * y[2] - 6e7 * y[1] - cj;
            v[5] = 1.0;
            // column y3
            v[6] = 1e4 * y[1];
            v[7] = -1e4 * y[1];
            v[8] = 1.0;
            Ok(())
        }
    }

    fn robertson(solver: IdaMatrix) -> (Vec<(f64, Vec<f64>)>, IdaStats) {
        let mut f = Robertson {
            analytic: solver != IdaMatrix::DenseDifferenceQuotient,
        };
        let settings = IdaSettings {
            rtol: 1e-8,
            atol_vector: Some(vec![1e-12, 1e-16, 1e-12]),
            id: vec![1.0, 1.0, 0.0],
            matrix: solver,
            ..IdaSettings::default()
        };
        let times: Vec<f64> = (0..7).map(|k| 0.4 * 10f64.powi(k)).collect();
        let mut out = Vec::new();
        let stats = integrate(
            &mut f,
            0.0,
            &[1.0, 0.0, 0.0],
            &[-0.04, 0.04, 0.0],
            &settings,
            &OutputMode::Times(times),
            &mut |t, y, _| {
                out.push((t, y.to_vec()));
                true
            },
        )
        .unwrap();
        (out, stats)
    }

    #[test]
    fn robertson_all_solvers() {
        let reference = [9.8517e-01, 3.3864e-05, 1.4794e-02];
        let results: Vec<_> = [
            IdaMatrix::Dense,
            IdaMatrix::DenseDifferenceQuotient,
            IdaMatrix::SparseLu,
        ]
        .into_iter()
        .map(robertson)
        .collect();
        for (out, stats) in &results {
            assert_eq!(out.len(), 8);
            assert_eq!(out[0].0, 0.0);
            assert_eq!(out[1].0, 0.4);
            assert_eq!(out[7].0, 4e5);
            for i in 0..3 {
                let rel = (out[1].1[i] - reference[i]).abs() / reference[i];
                assert!(
                    rel < 1e-4,
                    "component {i}: {} vs {}",
                    out[1].1[i],
                    reference[i]
                );
            }
            let y = &out[7].1;
            assert!((y[0] + y[1] + y[2] - 1.0).abs() < 1e-10);
            assert!(stats.steps > 0 && stats.residual_evals > 0 && stats.jacobian_evals > 0);
            assert!(stats.linear_setups > 0 && stats.nonlinear_iterations > 0);
        }
        let (base, _) = &results[0];
        for (other, _) in &results[1..] {
            for (a, b) in base.iter().zip(other) {
                for i in [0, 2] {
                    assert!(
                        (a.1[i] - b.1[i]).abs() < 1e-6,
                        "t = {}: {:?} vs {:?}",
                        a.0,
                        a.1,
                        b.1
                    );
                }
                assert!(
                    (a.1[1] - b.1[1]).abs() < 1e-6 * a.1[1].abs().max(1e-4),
                    "t = {}: {:?} vs {:?}",
                    a.0,
                    a.1,
                    b.1
                );
            }
        }
    }

    /// x' = v, v' = -x, 0 = z - x; optionally failing for t > fail_after.
    struct Oscillator {
        fail_after: Option<f64>,
        panic_after: Option<f64>,
    }

    impl DaeFunctions for Oscillator {
        fn len(&self) -> usize {
            3
        }
        fn residual(
            &mut self,
            t: f64,
            y: &[f64],
            yp: &[f64],
            r: &mut [f64],
        ) -> Result<(), EvalError> {
            if self.fail_after.is_some_and(|tf| t > tf) {
                return Err(EvalError {
                    message: "sqrt of negative argument in spring".into(),
                    recoverable: false,
                });
            }
            if self.panic_after.is_some_and(|tf| t > tf) {
                panic!("model bug");
            }
            r[0] = yp[0] - y[1];
            r[1] = yp[1] + y[0];
            r[2] = y[2] - y[0];
            Ok(())
        }
        fn jacobian_pattern(&self) -> Option<(Vec<usize>, Vec<usize>)> {
            Some((vec![0, 3, 5, 6], vec![0, 1, 2, 0, 1, 2]))
        }
        fn jacobian(
            &mut self,
            _t: f64,
            _y: &[f64],
            _yp: &[f64],
            cj: f64,
            v: &mut [f64],
        ) -> Result<(), EvalError> {
            v.copy_from_slice(&[cj, 1.0, -1.0, -1.0, cj, 1.0]);
            Ok(())
        }
    }

    fn osc_settings(solver: IdaMatrix) -> IdaSettings {
        IdaSettings {
            rtol: 1e-10,
            atol: 1e-12,
            id: vec![1.0, 1.0, 0.0],
            matrix: solver,
            ..IdaSettings::default()
        }
    }

    #[test]
    fn oscillator_times_and_every_step() {
        for solver in [
            IdaMatrix::Dense,
            IdaMatrix::DenseDifferenceQuotient,
            IdaMatrix::SparseLu,
        ] {
            let mut f = Oscillator {
                fail_after: None,
                panic_after: None,
            };
            let times: Vec<f64> = (1..=20).map(|k| 0.5 * k as f64).collect();
            let mut out = Vec::new();
            integrate(
                &mut f,
                0.0,
                &[1.0, 0.0, 1.0],
                &[0.0, -1.0, 0.0],
                &osc_settings(solver),
                &OutputMode::Times(times.clone()),
                &mut |t, y, _| {
                    out.push((t, y.to_vec()));
                    true
                },
            )
            .unwrap();
            assert_eq!(out.len(), times.len() + 1);
            for (k, (t, y)) in out.iter().enumerate() {
                if k > 0 {
                    assert_eq!(*t, times[k - 1]);
                }
                assert!((y[0] - t.cos()).abs() < 1e-6, "{solver:?} t = {t}: {y:?}");
                assert!((y[1] + t.sin()).abs() < 1e-6, "{solver:?} t = {t}: {y:?}");
                assert!((y[2] - t.cos()).abs() < 1e-6, "{solver:?} t = {t}: {y:?}");
            }

            let mut ts = Vec::new();
            let stats = integrate(
                &mut f,
                0.0,
                &[1.0, 0.0, 1.0],
                &[0.0, -1.0, 0.0],
                &osc_settings(solver),
                &OutputMode::EveryStep { t_end: 3.0 },
                &mut |t, y, _| {
                    assert!((y[0] - t.cos()).abs() < 1e-6);
                    ts.push(t);
                    true
                },
            )
            .unwrap();
            assert!(ts.len() > 10);
            assert_eq!(ts[0], 0.0);
            assert_eq!(*ts.last().unwrap(), 3.0);
            assert!(ts.windows(2).all(|w| w[1] > w[0]), "{ts:?}");
            let len = ts.len() as u64;
            assert!(
                len <= stats.steps + 1 && len >= stats.steps,
                "{len} outputs, {} steps",
                stats.steps
            );
        }
    }

    #[test]
    fn fatal_eval_error_is_reported() {
        for solver in [IdaMatrix::Dense, IdaMatrix::SparseLu] {
            let mut f = Oscillator {
                fail_after: Some(1.0),
                panic_after: None,
            };
            let settings = IdaSettings {
                max_step: Some(0.01),
                ..osc_settings(solver)
            };
            let mut last_t = 0.0;
            let err = integrate(
                &mut f,
                0.0,
                &[1.0, 0.0, 1.0],
                &[0.0, -1.0, 0.0],
                &settings,
                &OutputMode::Times(vec![0.5, 2.0]),
                &mut |t, _, _| {
                    last_t = t;
                    true
                },
            )
            .unwrap_err();
            assert_eq!(last_t, 0.5);
            assert_eq!(err.flag, "IDA_RES_FAIL");
            assert!(err.t <= 1.0 && err.t > 0.98, "{err}");
            assert!(
                err.message.contains("sqrt of negative argument in spring"),
                "{err}"
            );
            assert!(err.message.contains("residual function failed"), "{err}");
        }
    }

    #[test]
    fn panic_in_callback_is_caught() {
        let mut f = Oscillator {
            fail_after: None,
            panic_after: Some(0.5),
        };
        let err = integrate(
            &mut f,
            0.0,
            &[1.0, 0.0, 1.0],
            &[0.0, -1.0, 0.0],
            &osc_settings(IdaMatrix::SparseLu),
            &OutputMode::Times(vec![1.0]),
            &mut |_, _, _| true,
        )
        .unwrap_err();
        assert_eq!(err.flag, "IDA_RES_FAIL");
        assert!(err.message.contains("model bug"), "{err}");
    }

    #[test]
    fn too_much_work_and_invalid_input() {
        let mut f = Oscillator {
            fail_after: None,
            panic_after: None,
        };
        let settings = IdaSettings {
            max_steps: 5,
            ..osc_settings(IdaMatrix::SparseLu)
        };
        let err = integrate(
            &mut f,
            0.0,
            &[1.0, 0.0, 1.0],
            &[0.0, -1.0, 0.0],
            &settings,
            &OutputMode::Times(vec![100.0]),
            &mut |_, _, _| true,
        )
        .unwrap_err();
        assert_eq!(err.flag, "IDA_TOO_MUCH_WORK");
        assert!(
            err.message
                .contains("more than SolverOptions::max_steps = 5 steps"),
            "{err}"
        );
        assert!(err.t > 0.0 && err.t < 100.0);

        let err = integrate(
            &mut f,
            0.0,
            &[1.0, 0.0, 1.0],
            &[0.0, -1.0, 0.0],
            &settings,
            &OutputMode::Times(vec![2.0, 1.0]),
            &mut |_, _, _| true,
        )
        .unwrap_err();
        assert_eq!(err.flag, "INVALID_INPUT");

        let mut r = Robertson { analytic: false };
        let err = integrate(
            &mut r,
            0.0,
            &[1.0, 0.0, 0.0],
            &[-0.04, 0.04, 0.0],
            &IdaSettings::default(),
            &OutputMode::Times(vec![1.0]),
            &mut |_, _, _| true,
        )
        .unwrap_err();
        assert_eq!(err.flag, "INVALID_INPUT");
        assert!(err.message.contains("jacobian_pattern"));
    }

    #[test]
    fn calc_ic_fixes_inconsistent_algebraic_value() {
        for solver in [IdaMatrix::Dense, IdaMatrix::SparseLu] {
            let mut f = Oscillator {
                fail_after: None,
                panic_after: None,
            };
            let settings = IdaSettings {
                calc_ic: true,
                ..osc_settings(solver)
            };
            let mut out = Vec::new();
            integrate(
                &mut f,
                0.0,
                &[1.0, 0.0, 5.0],
                &[0.0, 0.0, 0.0],
                &settings,
                &OutputMode::Times(vec![1.0, 2.0]),
                &mut |t, y, yp| {
                    out.push((t, y.to_vec(), yp.to_vec()));
                    true
                },
            )
            .unwrap();
            let (t, y, yp) = &out[0];
            assert_eq!(*t, 0.0);
            assert!((y[2] - 1.0).abs() < 1e-8, "{y:?}");
            assert_eq!(y[0], 1.0);
            assert!((yp[1] + 1.0).abs() < 1e-8, "{yp:?}");
            let (t, y, _) = &out[2];
            assert!((y[0] - t.cos()).abs() < 1e-6 && (y[2] - t.cos()).abs() < 1e-6);
        }
    }

    /// Chain of `m` unit masses with unit springs and fixed ends,
    /// y = [x0, v0, x1, v1, ...]: x_i' = v_i, v_i' = x_{i-1} - 2 x_i + x_{i+1}.
    struct Chain {
        m: usize,
    }

    impl DaeFunctions for Chain {
        fn len(&self) -> usize {
            2 * self.m
        }
        fn residual(
            &mut self,
            _t: f64,
            y: &[f64],
            yp: &[f64],
            r: &mut [f64],
        ) -> Result<(), EvalError> {
            let m = self.m;
            for i in 0..m {
                let left = if i > 0 { y[2 * (i - 1)] } else { 0.0 };
                let right = if i + 1 < m { y[2 * (i + 1)] } else { 0.0 };
                r[2 * i] = yp[2 * i] - y[2 * i + 1];
                r[2 * i + 1] = yp[2 * i + 1] - (left - 2.0 * y[2 * i] + right);
            }
            Ok(())
        }
        fn jacobian_pattern(&self) -> Option<(Vec<usize>, Vec<usize>)> {
            let m = self.m;
            let mut cp = vec![0];
            let mut ri = Vec::new();
            for i in 0..m {
                // column x_i: rows v_{i-1} eq, x_i eq, v_i eq, v_{i+1} eq
                if i > 0 {
                    ri.push(2 * i - 1);
                }
                ri.push(2 * i);
                ri.push(2 * i + 1);
                if i + 1 < m {
                    ri.push(2 * i + 3);
                }
                cp.push(ri.len());
                // column v_i: rows x_i eq, v_i eq
                ri.push(2 * i);
                ri.push(2 * i + 1);
                cp.push(ri.len());
            }
            Some((cp, ri))
        }
        fn jacobian(
            &mut self,
            _t: f64,
            _y: &[f64],
            _yp: &[f64],
            cj: f64,
            v: &mut [f64],
        ) -> Result<(), EvalError> {
            let m = self.m;
            let mut k = 0;
            for i in 0..m {
                let mut push = |x: f64| {
                    v[k] = x;
                    k += 1;
                };
                if i > 0 {
                    push(-1.0);
                }
                push(cj);
                push(2.0);
                if i + 1 < m {
                    push(-1.0);
                }
                push(-1.0);
                push(cj);
            }
            Ok(())
        }
    }

    #[test]
    fn sparse_chain_of_2000_unknowns() {
        let m = 1000;
        let mode = 500.0;
        let omega = 2.0 * (mode * std::f64::consts::PI / (2.0 * (m as f64 + 1.0))).sin();
        let shape: Vec<f64> = (0..m)
            .map(|i| (mode * std::f64::consts::PI * (i as f64 + 1.0) / (m as f64 + 1.0)).sin())
            .collect();
        let mut y0 = vec![0.0; 2 * m];
        let mut yp0 = vec![0.0; 2 * m];
        for i in 0..m {
            y0[2 * i] = shape[i];
            yp0[2 * i + 1] = -omega * omega * shape[i];
        }
        let mut f = Chain { m };
        let settings = IdaSettings {
            rtol: 1e-8,
            atol: 1e-10,
            ..IdaSettings::default()
        };
        let mut max_err: f64 = 0.0;
        let stats = integrate(
            &mut f,
            0.0,
            &y0,
            &yp0,
            &settings,
            &OutputMode::Times(vec![2.0, 5.0]),
            &mut |t, y, _| {
                for i in 0..m {
                    max_err = max_err.max((y[2 * i] - shape[i] * (omega * t).cos()).abs());
                }
                true
            },
        )
        .unwrap();
        assert!(max_err < 1e-4, "max error {max_err}");
        assert!(stats.steps > 0);
    }
}
