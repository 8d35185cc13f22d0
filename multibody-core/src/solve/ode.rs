//! Integration of explicit ODEs `u' = f(t, u)` with SUNDIALS CVODE (BDF and Adams) and
//! ARKODE (explicit and diagonally implicit Runge-Kutta methods).
//!
//! [`integrate_monitored`] has the contract of IDA's
//! [`ida::integrate_monitored`](super::ida::integrate_monitored): outputs at given times
//! or at every step, a step monitor that may stop the integration, crossing functions
//! that stop it at an event, statistics, and errors that say what failed. Every SUNDIALS
//! object is owned by a guard that frees it on every return path; model callbacks never
//! unwind into C.
//!
//! A compiled system whose residual is `u' - g(t, u)` (every unknown a state, every
//! derivative computed from the states) is such an ODE: [`ExplicitDae`] gives its
//! `f = g` and `df/du` from the residual and the DAE Jacobian at `u' = 0`, `cj = 0`.

use std::ffi::{CString, c_char, c_int, c_long, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::ptr;

use sundials_sys as sys;

use super::ida::{
    DaeFunctions, EvalError, IdaError, IdaSettings, IdaStats, Integrated, OutputMode, invalid,
    validate,
};
use super::linsol;
use super::sundials::{
    Callback, EvalLog, Objects, not_finite, origin_name, scatter_dense, vec_mut, vec_ref,
    write_csc_pattern,
};

mod earliest_crossing;
mod within_step;

/// An ODE `u' = f(t, u)` with, optionally, its Jacobian `df/du` and crossing functions.
pub trait OdeFunctions {
    /// Number of states.
    fn len(&self) -> usize;
    /// Returns `true` if the system has no states.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Evaluates `ydot = f(t, y)`.
    fn rhs(&mut self, t: f64, y: &[f64], ydot: &mut [f64]) -> Result<(), EvalError>;
    /// CSC pattern of `df/du` (col_ptr of length `len() + 1`, rows sorted within each
    /// column); `None` (the default) when there is none: the implicit methods then use
    /// SUNDIALS' dense difference quotients.
    fn jacobian_pattern(&self) -> Option<(Vec<usize>, Vec<usize>)> {
        None
    }
    /// Values of `df/du` in the CSC order of the pattern.
    fn jacobian(&mut self, t: f64, y: &[f64], values: &mut [f64]) -> Result<(), EvalError> {
        let _ = (t, y, values);
        Err(EvalError {
            message: "no Jacobian".into(),
            recoverable: false,
        })
    }
    /// Number of crossing functions (none by default).
    fn n_roots(&self) -> usize {
        0
    }
    /// Evaluates the crossing functions `out = g(t, y, ydot)` with `ydot = f(t, y)`.
    fn roots(&mut self, t: f64, y: &[f64], ydot: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        let _ = (t, y, ydot, out);
        Ok(())
    }
    /// Whether the crossing functions read `ydot` (`true` by default). Where they do
    /// not, the integrator passes the last `ydot` it computed (finite, maybe of another
    /// point) instead of evaluating `f` for them.
    fn roots_read_derivatives(&self) -> bool {
        true
    }
}

/// A DAE whose residual is `F = u' - g(t, u)` seen as the ODE `u' = g(t, u)`:
/// `g = -F(t, u, 0)` and `dg/du = -(dF/du)` (the DAE Jacobian at `cj = 0`). Only
/// valid for such residuals (see `CompiledDae::is_explicit_ode`).
pub struct ExplicitDae<'f> {
    f: &'f mut dyn DaeFunctions,
    zeros: Vec<f64>,
}

impl<'f> ExplicitDae<'f> {
    /// The ODE of `f` (whose Jacobian must not be extended).
    pub fn new(f: &'f mut dyn DaeFunctions) -> Self {
        let n = f.len();
        ExplicitDae {
            f,
            zeros: vec![0.0; n],
        }
    }
}

impl OdeFunctions for ExplicitDae<'_> {
    fn len(&self) -> usize {
        self.f.len()
    }
    fn rhs(&mut self, t: f64, y: &[f64], ydot: &mut [f64]) -> Result<(), EvalError> {
        self.f.residual(t, y, &self.zeros, ydot)?;
        ydot.iter_mut().for_each(|v| *v = -*v);
        Ok(())
    }
    fn jacobian_pattern(&self) -> Option<(Vec<usize>, Vec<usize>)> {
        if self.f.jacobian_dimension() != self.f.len() {
            return None;
        }
        self.f.jacobian_pattern()
    }
    fn jacobian(&mut self, t: f64, y: &[f64], values: &mut [f64]) -> Result<(), EvalError> {
        self.f.jacobian(t, y, &self.zeros, 0.0, values)?;
        values.iter_mut().for_each(|v| *v = -*v);
        Ok(())
    }
    fn n_roots(&self) -> usize {
        self.f.n_roots()
    }
    fn roots(&mut self, t: f64, y: &[f64], ydot: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        self.f.roots(t, y, ydot, out)
    }
    fn roots_read_derivatives(&self) -> bool {
        self.f.roots_read_derivatives()
    }
}

/// The integration method of an [`integrate_monitored`] call.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OdeMethod {
    /// CVODE's variable-order BDF (orders 1 to 5) with Newton iterations.
    CvodeBdf,
    /// CVODE's variable-order Adams-Moulton (orders 1 to 12) with fixed-point
    /// iterations.
    CvodeAdams,
    /// ARKODE's ERKStep with the explicit Butcher table of this name (for example
    /// `ARKODE_VERNER_13_7_8`).
    Explicit(&'static str),
    /// ARKODE's ARKStep with the diagonally implicit Butcher table of this name (for
    /// example `ARKODE_KVAERNO_7_4_5`), with Newton iterations.
    Implicit(&'static str),
    /// Verner 8(7) (`ARKODE_VERNER_13_7_8`), switching to [`CvodeBdf`](Self::CvodeBdf)
    /// for the rest of the integration where the model turns out stiff: every
    /// [`STIFFNESS_CHECK_STEPS`] steps the largest eigenvalue of `df/du` is estimated
    /// by power iteration (difference quotients of `f`); where the step size times it
    /// exceeds [`STIFF_STEP_RATIO`] at two checks in a row, the step is held by the
    /// method's stability (its stability region reaches 5.9 along the negative real
    /// axis), not by its accuracy. Also where the right-hand side fails recoverably (a
    /// value out of its domain in a trial stage): the explicit stepper cannot retry
    /// with a shorter step, BDF can. A solve keeps the decision for its later segments
    /// (after events) too.
    Auto,
}

/// Steps between two stiffness checks of [`OdeMethod::Auto`].
pub const STIFFNESS_CHECK_STEPS: usize = 25;
/// Step size times the spectral radius of `df/du` above which [`OdeMethod::Auto`]
/// counts a step as limited by stability.
pub const STIFF_STEP_RATIO: f64 = 3.5;
/// The explicit method of [`OdeMethod::Auto`].
const AUTO_NONSTIFF: OdeMethod = OdeMethod::Explicit("ARKODE_VERNER_13_7_8");

impl OdeMethod {
    fn implicit(self) -> bool {
        matches!(self, OdeMethod::CvodeBdf | OdeMethod::Implicit(_))
    }
    fn cvode(self) -> bool {
        matches!(self, OdeMethod::CvodeBdf | OdeMethod::CvodeAdams)
    }
    /// What an integration starts with.
    fn first(self) -> OdeMethod {
        if self == OdeMethod::Auto {
            AUTO_NONSTIFF
        } else {
            self
        }
    }
    /// The prefix of the return flags' names.
    fn flag_prefix(self) -> &'static str {
        if self.cvode() { "CV" } else { "ARK" }
    }
}

type RhsFn = Option<unsafe extern "C" fn(f64, sys::N_Vector, sys::N_Vector, *mut c_void) -> c_int>;
type RootFn = Option<unsafe extern "C" fn(f64, sys::N_Vector, *mut f64, *mut c_void) -> c_int>;
type JacFn = Option<
    unsafe extern "C" fn(
        f64,
        sys::N_Vector,
        sys::N_Vector,
        sys::SUNMatrix,
        *mut c_void,
        sys::N_Vector,
        sys::N_Vector,
        sys::N_Vector,
    ) -> c_int,
>;

// ARKODE is built and linked by sundials-sys (feature `arkode`), whose bindings leave
// out its headers: the functions used here, declared from SUNDIALS 7.1's `arkode.h`,
// `arkode_ls.h`, `arkode_erkstep.h` and `arkode_arkstep.h`.
unsafe extern "C" {
    fn ERKStepCreate(f: RhsFn, t0: f64, y0: sys::N_Vector, ctx: sys::SUNContext) -> *mut c_void;
    fn ERKStepSetTableName(mem: *mut c_void, etable: *const c_char) -> c_int;
    fn ERKStepGetNumRhsEvals(mem: *mut c_void, nfe: *mut c_long) -> c_int;
    fn ARKStepCreate(
        fe: RhsFn,
        fi: RhsFn,
        t0: f64,
        y0: sys::N_Vector,
        ctx: sys::SUNContext,
    ) -> *mut c_void;
    fn ARKStepSetTableName(mem: *mut c_void, itable: *const c_char, etable: *const c_char)
    -> c_int;
    fn ARKStepGetNumRhsEvals(mem: *mut c_void, nfe: *mut c_long, nfi: *mut c_long) -> c_int;
    fn ARKodeSStolerances(mem: *mut c_void, rtol: f64, atol: f64) -> c_int;
    fn ARKodeSVtolerances(mem: *mut c_void, rtol: f64, atol: sys::N_Vector) -> c_int;
    fn ARKodeSetUserData(mem: *mut c_void, data: *mut c_void) -> c_int;
    fn ARKodeSetMaxNumSteps(mem: *mut c_void, mxsteps: c_long) -> c_int;
    fn ARKodeSetMaxStep(mem: *mut c_void, h: f64) -> c_int;
    fn ARKodeSetMinStep(mem: *mut c_void, h: f64) -> c_int;
    fn ARKodeSetInitStep(mem: *mut c_void, h: f64) -> c_int;
    fn ARKodeSetStopTime(mem: *mut c_void, t: f64) -> c_int;
    fn ARKodeReset(mem: *mut c_void, t: f64, y: sys::N_Vector) -> c_int;
    fn ARKodeRootInit(mem: *mut c_void, nrtfn: c_int, g: RootFn) -> c_int;
    fn ARKodeSetNoInactiveRootWarn(mem: *mut c_void) -> c_int;
    fn ARKodeGetRootInfo(mem: *mut c_void, rootsfound: *mut c_int) -> c_int;
    fn ARKodeEvolve(
        mem: *mut c_void,
        tout: f64,
        yout: sys::N_Vector,
        tret: *mut f64,
        itask: c_int,
    ) -> c_int;
    fn ARKodeGetDky(mem: *mut c_void, t: f64, k: c_int, dky: sys::N_Vector) -> c_int;
    fn ARKodeSetLinearSolver(
        mem: *mut c_void,
        ls: sys::SUNLinearSolver,
        a: sys::SUNMatrix,
    ) -> c_int;
    fn ARKodeSetJacFn(mem: *mut c_void, jac: JacFn) -> c_int;
    fn ARKodeSetNonlinCRDown(mem: *mut c_void, crdown: f64) -> c_int;
    fn ARKodeGetNumSteps(mem: *mut c_void, v: *mut c_long) -> c_int;
    fn ARKodeGetNumErrTestFails(mem: *mut c_void, v: *mut c_long) -> c_int;
    fn ARKodeGetNumJacEvals(mem: *mut c_void, v: *mut c_long) -> c_int;
    fn ARKodeGetNumNonlinSolvIters(mem: *mut c_void, v: *mut c_long) -> c_int;
    fn ARKodeGetNumNonlinSolvConvFails(mem: *mut c_void, v: *mut c_long) -> c_int;
    fn ARKodeGetNumLinSolvSetups(mem: *mut c_void, v: *mut c_long) -> c_int;
    fn ARKodeGetReturnFlagName(flag: c_long) -> *mut c_char;
    fn ARKodeFree(mem: *mut *mut c_void);
}

const ARK_ONE_STEP: c_int = 2;
const ARK_TSTOP_RETURN: c_int = 1;
const ARK_ROOT_RETURN: c_int = 2;
const ARK_TOO_MUCH_WORK: c_int = -1;

/// State shared with the C callbacks through the user-data pointer.
struct OdeData<'a> {
    f: &'a mut dyn OdeFunctions,
    n: usize,
    dense: bool,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    col_ptr_i: Vec<sys::sunindextype>,
    row_idx_i: Vec<sys::sunindextype>,
    values: Vec<f64>,
    /// Number of crossing functions (as told to SUNDIALS).
    n_roots: usize,
    /// `f(t, y)` for the crossing functions.
    ydot: Vec<f64>,
    log: EvalLog,
}

impl OdeData<'_> {
    /// The crossing functions at `(t, y)` into `out`, with `f(t, y)` computed into
    /// `ydot` first where they read it.
    fn roots(&mut self, t: f64, y: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        let OdeData { f, ydot, .. } = self;
        if f.roots_read_derivatives() {
            f.rhs(t, y, ydot)?;
        }
        f.roots(t, y, ydot, out)
    }
}

/// Owns the integrator's memory and the callback data of one integration and frees
/// them in Drop, before the SUNDIALS objects they use.
struct Guard<'a> {
    method: OdeMethod,
    mem: *mut c_void,
    /// A second ERKStep integrator of the same method and callback data, for output
    /// times within a step (`within_step.rs`); null when there is none.
    probe: *mut c_void,
    data: *mut OdeData<'a>,
    o: Objects,
}

impl Drop for Guard<'_> {
    fn drop(&mut self) {
        // SAFETY: the pointers are null or owned by this guard; `o` is dropped after
        // this, its context last.
        unsafe {
            if !self.probe.is_null() {
                ARKodeFree(&mut self.probe);
            }
            if !self.mem.is_null() {
                if self.method.cvode() {
                    sys::CVodeFree(&mut self.mem);
                } else {
                    ARKodeFree(&mut self.mem);
                }
            }
            if !self.data.is_null() {
                drop(Box::from_raw(self.data));
            }
        }
    }
}

impl Guard<'_> {
    fn setup_failed(&mut self, t: f64, message: String) -> IdaError {
        self.o.setup_failed(t, message)
    }

    /// The error of a failed SUNDIALS call.
    fn error(&mut self, t: f64, flag: c_int, context: &str, settings: &IdaSettings) -> IdaError {
        // SAFETY: as in setup_failed; callbacks only run inside SUNDIALS calls.
        let eval = unsafe { self.data.as_mut().and_then(|d| d.log.last.take()) };
        let sundials = self.o.take_message();
        let name = flag_name(self.method, flag);
        let mut message = describe(&name, eval.as_ref(), settings);
        if !context.is_empty() {
            message = format!("{context}: {message}");
        }
        if !name.contains("RHSFUNC")
            && !name.contains("LSETUP")
            && let Some((te, origin, e)) = &eval
        {
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
            flag: name,
            message,
        }
    }

    fn check(&mut self, flag: c_int, t: f64, what: &str, s: &IdaSettings) -> Result<(), IdaError> {
        if flag < 0 {
            let mut e = self.error(t, flag, what, s);
            e.flag = "SETUP_FAILED".into();
            Err(e)
        } else {
            Ok(())
        }
    }
}

/// The name of a CVODE or ARKODE return flag (`CV_CONV_FAILURE`, `ARK_ERR_FAILURE`).
fn flag_name(method: OdeMethod, flag: c_int) -> String {
    // SAFETY: both functions return a malloc'd, NUL-terminated string (freed here).
    unsafe {
        let p = if method.cvode() {
            sys::CVodeGetReturnFlagName(c_long::from(flag))
        } else {
            ARKodeGetReturnFlagName(c_long::from(flag))
        };
        if p.is_null() {
            return format!("{}_UNKNOWN({flag})", method.flag_prefix());
        }
        let s = std::ffi::CStr::from_ptr(p).to_string_lossy().into_owned();
        libc_free(p.cast());
        s
    }
}

unsafe extern "C" {
    #[link_name = "free"]
    fn libc_free(p: *mut c_void);
}

/// Explains a return flag in words.
fn describe(
    name: &str,
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
    let kind = name.split_once('_').map_or(name, |(_, k)| k);
    match kind {
        "TOO_MUCH_WORK" => format!(
            "more than SolverOptions::max_steps = {} steps before the next reported point",
            settings.max_steps
        ),
        "TOO_MUCH_ACC" => {
            "the requested accuracy could not be reached (rtol/atol too small)".into()
        }
        "ERR_FAILURE" => {
            "error test failed repeatedly (step size became too small; stiff or discontinuous?)"
                .into()
        }
        "CONV_FAILURE" => {
            "nonlinear solver failed to converge repeatedly (singular Jacobian?)".into()
        }
        "LSETUP_FAIL" => match eval {
            Some((_, Callback::Jacobian, _)) => eval_msg("the Jacobian function failed"),
            _ => "linear solver failed (singular iteration matrix)".into(),
        },
        "LSOLVE_FAIL" => "linear solver failed (singular iteration matrix)".into(),
        "RHSFUNC_FAIL" | "UNREC_RHSFUNC_ERR" => eval_msg("the right-hand side failed"),
        "REPTD_RHSFUNC_ERR" => eval_msg("the right-hand side failed recoverably and repeatedly"),
        "FIRST_RHSFUNC_ERR" => eval_msg("the right-hand side failed at the first call"),
        "RTFUNC_FAIL" => eval_msg("the crossing functions failed"),
        "ILL_INPUT" => "invalid input".into(),
        "MEM_FAIL" => "memory allocation failed".into(),
        _ => format!("SUNDIALS returned {name}"),
    }
}

/// Records a caught panic as an unrecoverable evaluation error.
///
/// # Safety
/// `ud` is the callback data pointer (or null) and not otherwise borrowed.
unsafe fn record_panic(
    ud: *mut c_void,
    t: f64,
    o: Callback,
    p: &(dyn std::any::Any + Send),
) -> c_int {
    // SAFETY: guaranteed by the caller.
    match unsafe { ud.cast::<OdeData<'_>>().as_mut() } {
        Some(d) => d.log.record_panic(t, o, p),
        None => -1,
    }
}

unsafe extern "C" fn rhs_cb(
    t: f64,
    y: sys::N_Vector,
    ydot: sys::N_Vector,
    ud: *mut c_void,
) -> c_int {
    let r = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: ud is the OdeData owned by the guard; two serial vectors of length n.
        unsafe {
            let Some(d) = ud.cast::<OdeData<'_>>().as_mut() else {
                return -1;
            };
            let n = d.n;
            let (y, out) = (vec_ref(y, n), vec_mut(ydot, n));
            match d.f.rhs(t, y, out).map(|()| not_finite(out, "derivative")) {
                Ok(None) => 0,
                Ok(Some(e)) | Err(e) => d.log.record(t, Callback::Residual, e),
            }
        }
    }));
    // SAFETY: the borrow inside the closure has ended.
    r.unwrap_or_else(|p| unsafe { record_panic(ud, t, Callback::Residual, p.as_ref()) })
}

unsafe extern "C" fn root_cb(t: f64, y: sys::N_Vector, gout: *mut f64, ud: *mut c_void) -> c_int {
    let r = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: ud is the OdeData owned by the guard; y has n entries, gout n_roots.
        unsafe {
            let Some(d) = ud.cast::<OdeData<'_>>().as_mut() else {
                return -1;
            };
            let n = d.n;
            let y = vec_ref(y, n);
            let out = std::slice::from_raw_parts_mut(gout, d.n_roots);
            let result = d.roots(t, y, out);
            d.log.record_roots(t, result, out)
        }
    }));
    // SAFETY: the borrow inside the closure has ended.
    r.unwrap_or_else(|p| unsafe { record_panic(ud, t, Callback::Roots, p.as_ref()) })
}

#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn jacobian_cb(
    t: f64,
    y: sys::N_Vector,
    _fy: sys::N_Vector,
    jac: sys::SUNMatrix,
    ud: *mut c_void,
    _tmp1: sys::N_Vector,
    _tmp2: sys::N_Vector,
    _tmp3: sys::N_Vector,
) -> c_int {
    let r = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: ud is the OdeData owned by the guard; `jac` is the dense n x n or the
        // CSC matrix of capacity >= nnz made for it.
        unsafe {
            let Some(d) = ud.cast::<OdeData<'_>>().as_mut() else {
                return -1;
            };
            let n = d.n;
            let y = vec_ref(y, n);
            let OdeData { f, values, .. } = &mut *d;
            if let Err(e) = f.jacobian(t, y, values) {
                return d.log.record(t, Callback::Jacobian, e);
            }
            if let Some(e) = not_finite(&d.values, "Jacobian entry") {
                return d.log.record(t, Callback::Jacobian, e);
            }
            if d.dense {
                let data = sys::SUNDenseMatrix_Data(jac);
                if data.is_null() {
                    return -1;
                }
                let dense = std::slice::from_raw_parts_mut(data, n * n);
                scatter_dense(n, &d.col_ptr, &d.row_idx, &d.values, dense);
            } else {
                let Some(data) = write_csc_pattern(jac, &d.col_ptr_i, &d.row_idx_i) else {
                    return -1;
                };
                data.copy_from_slice(&d.values);
            }
            0
        }
    }));
    // SAFETY: the borrow inside the closure has ended.
    r.unwrap_or_else(|p| unsafe { record_panic(ud, t, Callback::Jacobian, p.as_ref()) })
}

/// Statistics of the integrator in `mem`.
fn stats(method: OdeMethod, mem: *mut c_void) -> IdaStats {
    let get = |f: unsafe extern "C" fn(*mut c_void, *mut c_long) -> c_int| -> u64 {
        let mut v: c_long = 0;
        // SAFETY: mem is a valid integrator memory; f writes one long.
        let flag = unsafe { f(mem, &mut v) };
        if flag == 0 {
            u64::try_from(v).unwrap_or(0)
        } else {
            0
        }
    };
    if method.cvode() {
        return IdaStats {
            steps: get(sys::CVodeGetNumSteps),
            residual_evals: get(sys::CVodeGetNumRhsEvals) + get(sys::CVodeGetNumLinRhsEvals),
            jacobian_evals: get(sys::CVodeGetNumJacEvals),
            error_test_failures: get(sys::CVodeGetNumErrTestFails),
            nonlinear_iterations: get(sys::CVodeGetNumNonlinSolvIters),
            nonlinear_convergence_failures: get(sys::CVodeGetNumNonlinSolvConvFails),
            linear_setups: get(sys::CVodeGetNumLinSolvSetups),
        };
    }
    let rhs = {
        let (mut fe, mut fi): (c_long, c_long) = (0, 0);
        // SAFETY: mem is an ERKStep or ARKStep memory as the method says.
        let flag = unsafe {
            match method {
                OdeMethod::Explicit(_) => ERKStepGetNumRhsEvals(mem, &mut fe),
                _ => ARKStepGetNumRhsEvals(mem, &mut fe, &mut fi),
            }
        };
        if flag == 0 {
            (fe + fi).max(0) as u64
        } else {
            0
        }
    };
    let implicit = method.implicit();
    IdaStats {
        steps: get(ARKodeGetNumSteps),
        residual_evals: rhs,
        jacobian_evals: if implicit {
            get(ARKodeGetNumJacEvals)
        } else {
            0
        },
        error_test_failures: get(ARKodeGetNumErrTestFails),
        nonlinear_iterations: if implicit {
            get(ARKodeGetNumNonlinSolvIters)
        } else {
            0
        },
        nonlinear_convergence_failures: if implicit {
            get(ARKodeGetNumNonlinSolvConvFails)
        } else {
            0
        },
        linear_setups: if implicit {
            get(ARKodeGetNumLinSolvSetups)
        } else {
            0
        },
    }
}

/// The integrator for `f` from `(t0, y0)` by `method`, stopping at `t_stop`: the guard
/// that owns it and the vector of the states.
fn open<'a>(
    f: &'a mut dyn OdeFunctions,
    method: OdeMethod,
    t0: f64,
    y0: &[f64],
    settings: &IdaSettings,
    t_stop: f64,
    with_probe: bool,
) -> Result<(Guard<'a>, sys::N_Vector), IdaError> {
    let n = f.len();
    let n_roots = f.n_roots();
    let pattern = if method.implicit() {
        f.jacobian_pattern()
    } else {
        None
    };
    if let Some((c, r)) = &pattern
        && !linsol::valid_csc(n, c, r)
    {
        return Err(invalid(t0, "jacobian_pattern is not a valid CSC pattern"));
    }
    let sparse = pattern.is_some() && n > super::ida::DENSE_UP_TO;
    let (col_ptr, row_idx) = pattern.clone().unwrap_or_default();
    let nnz = row_idx.len();
    let n_i = sys::sunindextype::try_from(n).map_err(|_| invalid(t0, "system too large"))?;
    let data = OdeData {
        f,
        n,
        dense: !sparse,
        col_ptr_i: col_ptr.iter().map(|&v| v as sys::sunindextype).collect(),
        row_idx_i: row_idx.iter().map(|&v| v as sys::sunindextype).collect(),
        values: vec![0.0; nnz],
        col_ptr,
        row_idx,
        n_roots,
        ydot: vec![0.0; n],
        log: EvalLog::default(),
    };
    let o = Objects::new().map_err(|m| IdaError {
        t: t0,
        flag: "SETUP_FAILED".into(),
        message: m,
    })?;
    let mut g = Guard {
        method,
        mem: ptr::null_mut(),
        probe: ptr::null_mut(),
        data: Box::into_raw(Box::new(data)),
        o,
    };
    let max_steps = c_long::try_from(settings.max_steps).unwrap_or(c_long::MAX);
    let t_scale = t_stop.abs().max(t0.abs()).max(1e-300);
    let min_step = 4.0 * f64::EPSILON * t_scale;
    let name = |table: &str| CString::new(table).map_err(|_| invalid(t0, "bad table name"));

    // SAFETY: every SUNDIALS object is created here and owned by `g`, which frees them
    // on every return path; the callback data outlives the integrator's memory.
    unsafe {
        let y = g.o.vector(y0).map_err(|m| g.setup_failed(t0, m))?;
        let atol = match &settings.atol_vector {
            Some(a) => Some(g.o.vector(a).map_err(|m| g.setup_failed(t0, m))?),
            None => None,
        };
        if method.implicit() {
            if sparse {
                let nnz_i = sys::sunindextype::try_from(nnz.max(1))
                    .map_err(|_| invalid(t0, "Jacobian too large"))?;
                g.o.mat = sys::SUNSparseMatrix(n_i, n_i, nnz_i, sys::CSC_MAT as c_int, g.o.ctx);
                g.o.ls = linsol::new_sparse_lu_solver(g.o.ctx);
            } else {
                g.o.mat = sys::SUNDenseMatrix(n_i, n_i, g.o.ctx);
                if !g.o.mat.is_null() {
                    g.o.ls = sys::SUNLinSol_Dense(y, g.o.mat, g.o.ctx);
                }
            }
            if g.o.mat.is_null() || g.o.ls.is_null() {
                return Err(g.setup_failed(t0, "creating the linear solver failed".into()));
            }
        }
        let has_jac = pattern.is_some();
        let ud = g.data.cast::<c_void>();
        if method.cvode() {
            let lmm = if method == OdeMethod::CvodeBdf {
                sys::CV_BDF
            } else {
                sys::CV_ADAMS
            };
            g.mem = sys::CVodeCreate(lmm, g.o.ctx);
            if g.mem.is_null() {
                return Err(g.setup_failed(t0, "CVodeCreate failed".into()));
            }
            let mem = g.mem;
            let flag = sys::CVodeInit(mem, Some(rhs_cb), t0, y);
            g.check(flag, t0, "CVodeInit", settings)?;
            let flag = sys::CVodeSetUserData(mem, ud);
            g.check(flag, t0, "CVodeSetUserData", settings)?;
            let flag = match atol {
                Some(a) => sys::CVodeSVtolerances(mem, settings.rtol, a),
                None => sys::CVodeSStolerances(mem, settings.rtol, settings.atol),
            };
            g.check(flag, t0, "setting tolerances", settings)?;
            if method.implicit() {
                let flag = sys::CVodeSetLinearSolver(mem, g.o.ls, g.o.mat);
                g.check(flag, t0, "CVodeSetLinearSolver", settings)?;
                if has_jac {
                    let flag = sys::CVodeSetJacFn(mem, Some(jacobian_cb));
                    g.check(flag, t0, "CVodeSetJacFn", settings)?;
                }
            } else {
                g.o.nls = sys::SUNNonlinSol_FixedPoint(y, 0, g.o.ctx);
                if g.o.nls.is_null() {
                    return Err(g.setup_failed(t0, "SUNNonlinSol_FixedPoint failed".into()));
                }
                let flag = sys::CVodeSetNonlinearSolver(mem, g.o.nls);
                g.check(flag, t0, "CVodeSetNonlinearSolver", settings)?;
            }
            let flag = sys::CVodeSetMaxNumSteps(mem, max_steps);
            g.check(flag, t0, "CVodeSetMaxNumSteps", settings)?;
            if let Some(h) = settings.max_step {
                let flag = sys::CVodeSetMaxStep(mem, h);
                g.check(flag, t0, "CVodeSetMaxStep", settings)?;
            }
            if let Some(h) = settings.initial_step {
                let flag = sys::CVodeSetInitStep(mem, h);
                g.check(flag, t0, "CVodeSetInitStep", settings)?;
            }
            let flag = sys::CVodeSetMinStep(mem, min_step);
            g.check(flag, t0, "CVodeSetMinStep", settings)?;
            let flag = sys::CVodeSetStopTime(mem, t_stop);
            g.check(flag, t0, "CVodeSetStopTime", settings)?;
            if n_roots > 0 {
                let nr = c_int::try_from(n_roots).map_err(|_| invalid(t0, "too many roots"))?;
                let flag = sys::CVodeRootInit(mem, nr, Some(root_cb));
                g.check(flag, t0, "CVodeRootInit", settings)?;
                let flag = sys::CVodeSetNoInactiveRootWarn(mem);
                g.check(flag, t0, "CVodeSetNoInactiveRootWarn", settings)?;
            }
        } else {
            g.mem = match method {
                OdeMethod::Explicit(_) => ERKStepCreate(Some(rhs_cb), t0, y, g.o.ctx),
                _ => ARKStepCreate(None, Some(rhs_cb), t0, y, g.o.ctx),
            };
            if g.mem.is_null() {
                return Err(g.setup_failed(t0, "creating the ARKODE stepper failed".into()));
            }
            let mem = g.mem;
            let flag = match method {
                OdeMethod::Explicit(table) => ERKStepSetTableName(mem, name(table)?.as_ptr()),
                OdeMethod::Implicit(table) => ARKStepSetTableName(
                    mem,
                    name(table)?.as_ptr(),
                    name("ARKODE_ERK_NONE")?.as_ptr(),
                ),
                _ => unreachable!("CVODE methods and Auto are handled elsewhere"),
            };
            g.check(flag, t0, "setting the Butcher table", settings)?;
            let flag = ARKodeSetUserData(mem, ud);
            g.check(flag, t0, "ARKodeSetUserData", settings)?;
            let flag = match atol {
                Some(a) => ARKodeSVtolerances(mem, settings.rtol, a),
                None => ARKodeSStolerances(mem, settings.rtol, settings.atol),
            };
            g.check(flag, t0, "setting tolerances", settings)?;
            if method.implicit() {
                let flag = ARKodeSetLinearSolver(mem, g.o.ls, g.o.mat);
                g.check(flag, t0, "ARKodeSetLinearSolver", settings)?;
                // ARKODE tests a stage's first Newton correction against the
                // convergence rate estimated in the previous stage (SUNDIALS 7.1,
                // `arkStep_NlsConvTest`, although its comment says the rate starts at
                // 1): after a fast stage, a first correction far above the tolerance
                // passed, with the trivial predictor's large first corrections.
                // Unconverged stages fooled the error test (x'' = -x at rtol 1e-6: 7e-2
                // off). With the rate's decay factor at 1 the estimate never drops
                // below the 1 each linear setup starts it at, so every correction is
                // tested as it is (5.4e-7 off; about 45 % more Newton iterations).
                let flag = ARKodeSetNonlinCRDown(mem, 1.0);
                g.check(flag, t0, "ARKodeSetNonlinCRDown", settings)?;
                if has_jac {
                    let flag = ARKodeSetJacFn(mem, Some(jacobian_cb));
                    g.check(flag, t0, "ARKodeSetJacFn", settings)?;
                }
            }
            let flag = ARKodeSetMaxNumSteps(mem, max_steps);
            g.check(flag, t0, "ARKodeSetMaxNumSteps", settings)?;
            if let Some(h) = settings.max_step {
                let flag = ARKodeSetMaxStep(mem, h);
                g.check(flag, t0, "ARKodeSetMaxStep", settings)?;
            }
            if let Some(h) = settings.initial_step {
                let flag = ARKodeSetInitStep(mem, h);
                g.check(flag, t0, "ARKodeSetInitStep", settings)?;
            }
            let flag = ARKodeSetMinStep(mem, min_step);
            g.check(flag, t0, "ARKodeSetMinStep", settings)?;
            let flag = ARKodeSetStopTime(mem, t_stop);
            g.check(flag, t0, "ARKodeSetStopTime", settings)?;
            if let (true, OdeMethod::Explicit(table)) = (with_probe, method) {
                within_step::open_probe(&mut g, &name(table)?, (t0, y), atol, max_steps, settings)?;
            }
            if n_roots > 0 {
                let nr = c_int::try_from(n_roots).map_err(|_| invalid(t0, "too many roots"))?;
                let flag = ARKodeRootInit(mem, nr, Some(root_cb));
                g.check(flag, t0, "ARKodeRootInit", settings)?;
                let flag = ARKodeSetNoInactiveRootWarn(mem);
                g.check(flag, t0, "ARKodeSetNoInactiveRootWarn", settings)?;
            }
        }
        Ok((g, y))
    }
}

/// One step of the integrator towards `t_end`: the flag and the time reached.
///
/// # Safety
/// `g.mem` is a valid integrator memory for `g.method` and `y` its state vector.
unsafe fn step(g: &Guard<'_>, t_end: f64, y: sys::N_Vector, t: &mut f64) -> c_int {
    // SAFETY: guaranteed by the caller.
    unsafe {
        if g.method.cvode() {
            sys::CVode(g.mem, t_end, y, t, sys::CV_ONE_STEP)
        } else {
            ARKodeEvolve(g.mem, t_end, y, t, ARK_ONE_STEP)
        }
    }
}

/// The interpolated state at `t` within the last step, into `out`.
///
/// # Safety
/// As [`step`]; `out` is a serial vector of length n.
unsafe fn dky(g: &Guard<'_>, t: f64, out: sys::N_Vector) -> c_int {
    // SAFETY: guaranteed by the caller.
    unsafe {
        if g.method.cvode() {
            sys::CVodeGetDky(g.mem, t, 0, out)
        } else {
            ARKodeGetDky(g.mem, t, 0, out)
        }
    }
}

/// Integrates `f` from `(t0, y0)` by `method`, with the contract of IDA's
/// [`ida::integrate_monitored`](super::ida::integrate_monitored): `on_output(t, y,
/// ydot)` at t0 and every output (with `ydot = f(t, y)`), `on_step` after every step,
/// crossing functions that stop it. `settings` give the tolerances, step limits and
/// maximum number of steps (`id`, `suppress_alg`, `calc_ic` and `matrix` are not used:
/// the implicit methods take the dense LU up to 24 states and the sparse LU above, with
/// `f`'s Jacobian, or dense difference quotients without one).
#[allow(clippy::type_complexity, clippy::too_many_arguments)]
pub fn integrate_monitored(
    f: &mut dyn OdeFunctions,
    method: OdeMethod,
    t0: f64,
    y0: &[f64],
    settings: &IdaSettings,
    output: &OutputMode,
    on_output: &mut dyn FnMut(f64, &[f64], &[f64]) -> bool,
    mut on_step: Option<&mut dyn FnMut(f64, &[f64], &[f64]) -> bool>,
) -> Result<Integrated, IdaError> {
    let mut current = method.first();
    let detect = method == OdeMethod::Auto;
    let mut run = integrate_run(
        f,
        current,
        detect,
        true,
        (t0, y0),
        settings,
        output,
        on_output,
        on_step.as_deref_mut(),
    )?;
    let mut stats = run.integrated.stats;
    while let Some(t) = run.stiff_at {
        let (_, y, _) = run.integrated.stopped.take().expect("stopped where stiff");
        log::debug!("{current:?} is held by stability at t = {t}: switching to CVODE's BDF");
        current = OdeMethod::CvodeBdf;
        let rest = match output {
            OutputMode::Times(times) => {
                OutputMode::Times(times.iter().copied().filter(|&tout| tout > t).collect())
            }
            OutputMode::EveryStep { t_end } => OutputMode::EveryStep { t_end: *t_end },
        };
        run = integrate_run(
            f,
            current,
            false,
            false,
            (t, &y),
            settings,
            &rest,
            on_output,
            on_step.as_deref_mut(),
        )?;
        stats.add(&run.integrated.stats);
    }
    run.integrated.stats = stats;
    run.integrated.switched = current != method.first();
    Ok(run.integrated)
}

/// How one run of [`integrate_run`] ended.
struct Run {
    integrated: Integrated,
    /// Where the stiffness check stopped it (with the point in `integrated.stopped`).
    stiff_at: Option<f64>,
}

/// One integration by `method` (not `Auto`); with `detect`, stops where the model
/// turns out stiff (see [`OdeMethod::Auto`]); with `report_start`, reports t0.
#[allow(clippy::type_complexity, clippy::too_many_arguments)]
fn integrate_run(
    f: &mut dyn OdeFunctions,
    method: OdeMethod,
    detect: bool,
    report_start: bool,
    (t0, y0): (f64, &[f64]),
    settings: &IdaSettings,
    output: &OutputMode,
    on_output: &mut dyn FnMut(f64, &[f64], &[f64]) -> bool,
    mut on_step: Option<&mut (dyn FnMut(f64, &[f64], &[f64]) -> bool + '_)>,
) -> Result<Run, IdaError> {
    let n = f.len();
    let zeros = vec![0.0; n];
    let plain = IdaSettings {
        id: Vec::new(),
        ..settings.clone()
    };
    validate(n, t0, y0, &zeros, &plain, output)?;
    if n == 0 {
        return Err(invalid(
            t0,
            "an ODE method needs at least one state (use IDA for a system without states)",
        ));
    }
    let t_end = match output {
        OutputMode::Times(times) => times.last().copied().unwrap_or(t0),
        OutputMode::EveryStep { t_end } => *t_end,
    };
    let n_roots = f.n_roots();
    // Output times within a step of the high-order explicit methods are integrated to
    // (ARKODE's interpolant has degree 5 at most).
    let integrate_outputs = matches!(output, OutputMode::Times(_))
        && matches!(method, OdeMethod::Explicit(table) if within_step::integrates_outputs(table));
    let (mut g, y) = open(f, method, t0, y0, settings, t_end, integrate_outputs)?;
    let stopped_err = |t: f64| IdaError {
        t,
        flag: "STOPPED".into(),
        message: "the output callback stopped the integration".into(),
    };
    let mut ydot = vec![0.0; n];
    // `f(t, y)` for a reported point, through the callback data.
    let eval = |g: &mut Guard<'_>, t: f64, y: &[f64], ydot: &mut [f64]| -> Result<(), IdaError> {
        // SAFETY: no SUNDIALS call is running; the data is owned by the guard.
        let d = unsafe { &mut *g.data };
        d.f.rhs(t, y, ydot).map_err(|e| IdaError {
            t,
            flag: format!("{}_RHSFUNC_FAIL", method.flag_prefix()),
            message: format!(
                "the right-hand side failed at a reported point: {}",
                e.message
            ),
        })
    };
    // SAFETY: the vectors are owned by `g`; slices over them live between SUNDIALS calls.
    unsafe {
        eval(&mut g, t0, y0, &mut ydot)?;
        if report_start && !on_output(t0, y0, &ydot) {
            return Err(stopped_err(t0));
        }
        let far =
            |tout: f64| (tout - t0).abs() > 1e3 * f64::EPSILON * t0.abs().max(tout.abs()).max(1.0);
        if !far(t_end) {
            let times = match output {
                OutputMode::Times(times) => times.clone(),
                OutputMode::EveryStep { t_end } => vec![*t_end],
            };
            for tout in times {
                if !on_output(tout, y0, &ydot) {
                    return Err(stopped_err(t0));
                }
            }
            return Ok(Run {
                integrated: Integrated {
                    stats: stats(method, g.mem),
                    stopped: None,
                    roots: Vec::new(),
                    switched: false,
                },
                stiff_at: None,
            });
        }
        let ky = g.o.vector(&zeros).map_err(|m| g.setup_failed(t0, m))?;
        let mut next_output = 0;
        let mut t = t0;
        let mut stopped = None;
        let mut roots = Vec::new();
        let mut steps_since_output = 0usize;
        let mut stiffness = detect.then(|| Stiffness::new(n, t0));
        let mut stiff_at = None;
        let (tstop_flag, root_flag) = if method.cvode() {
            (sys::CV_TSTOP_RETURN, sys::CV_ROOT_RETURN)
        } else {
            (ARK_TSTOP_RETURN, ARK_ROOT_RETURN)
        };
        // The start of the step (the last accepted step's end): where `Auto` takes up a
        // failed explicit integration, and from where ARKODE's methods locate a crossing
        // on the integrated solution and integrate to output times (`within_step.rs`;
        // CVODE's interpolant has the method's order).
        let refine = n_roots > 0 && !method.cvode();
        let y_prev = if detect || refine || integrate_outputs {
            Some(g.o.vector(y0).map_err(|m| g.setup_failed(t0, m))?)
        } else {
            None
        };
        let mut t_prev = t0;
        loop {
            if let Some(yp) = y_prev {
                t_prev = t;
                vec_mut(yp, n).copy_from_slice(vec_ref(y, n));
            }
            let flag = step(&g, t_end, y, &mut t);
            if flag < 0 {
                // The explicit stepper gives up on a right-hand side that failed
                // recoverably; `Auto` goes on with BDF from the last step.
                let recoverable = (*g.data)
                    .log
                    .last
                    .as_ref()
                    .is_some_and(|(_, _, e)| e.recoverable);
                if let (true, Some(yp)) = (detect && recoverable, y_prev)
                    && flag_name(method, flag) == "ARK_UNREC_RHSFUNC_ERR"
                {
                    log::debug!(
                        "{method:?} failed at t = {t} on a recoverable model error: switching to BDF at t = {t_prev}"
                    );
                    let (tl, yl) = (t_prev, vec_ref(yp, n).to_vec());
                    eval(&mut g, tl, &yl, &mut ydot)?;
                    stopped = Some((tl, yl, ydot.clone()));
                    stiff_at = Some(tl);
                    break;
                }
                return Err(g.error(t, flag, "", settings));
            }
            let done = flag == tstop_flag || t >= t_end;
            let root = flag == root_flag && !done;
            let reported_before = next_output;
            let mut at_t = false;
            steps_since_output += 1;
            let mut info: Vec<c_int> = Vec::new();
            if root {
                info.resize(n_roots, 0);
                let flag = if method.cvode() {
                    sys::CVodeGetRootInfo(g.mem, info.as_mut_ptr())
                } else {
                    ARKodeGetRootInfo(g.mem, info.as_mut_ptr())
                };
                if flag < 0 {
                    return Err(g.error(t, flag, "reading the crossings", settings));
                }
            }
            // ARKODE's methods locate a crossing on the integrated solution, not on the
            // interpolant, and restart from the state integrated to it; outputs within
            // the step are integrated to as well (the interpolant is gone).
            let to_crossing = y_prev.filter(|_| root && refine);
            if let Some(yp) = to_crossing {
                (t, info) =
                    within_step::locate_crossing(&mut g, (t_prev, yp), t, y, &info, settings)?;
            }
            // What reaches the output times within this step: the integrator itself after
            // a crossing (the segment ends there), the probe for the high-order methods,
            // or (`None`) the interpolant.
            let integrator_to_outputs = if to_crossing.is_some() {
                Some(g.mem)
            } else {
                integrate_outputs.then_some(g.probe)
            };
            match output {
                OutputMode::Times(times) => {
                    while let Some(&tout) = times.get(next_output) {
                        if tout > t && !done {
                            break;
                        }
                        next_output += 1;
                        if tout >= t {
                            eval(&mut g, t, vec_ref(y, n), &mut ydot)?;
                            at_t = true;
                            if !on_output(tout, vec_ref(y, n), &ydot) {
                                return Err(stopped_err(t));
                            }
                            continue;
                        }
                        if let (Some(mem), Some(yp)) = (integrator_to_outputs, y_prev) {
                            within_step::integrate_to(
                                &mut g,
                                mem,
                                (t_prev, yp),
                                tout,
                                ky,
                                settings,
                            )?;
                        } else {
                            let flag = dky(&g, tout, ky);
                            if flag < 0 {
                                return Err(g.error(
                                    tout,
                                    flag,
                                    "interpolating an output",
                                    settings,
                                ));
                            }
                        }
                        eval(&mut g, tout, vec_ref(ky, n), &mut ydot)?;
                        if !on_output(tout, vec_ref(ky, n), &ydot) {
                            return Err(stopped_err(t));
                        }
                    }
                }
                OutputMode::EveryStep { t_end } => {
                    let reported = if done { *t_end } else { t };
                    eval(&mut g, t, vec_ref(y, n), &mut ydot)?;
                    at_t = true;
                    if !on_output(reported, vec_ref(y, n), &ydot) {
                        return Err(stopped_err(t));
                    }
                }
            }
            if done {
                break;
            }
            if !at_t && (root || on_step.is_some()) {
                eval(&mut g, t, vec_ref(y, n), &mut ydot)?;
            }
            if root {
                if matches!(output, OutputMode::Times(_))
                    && !at_t
                    && !on_output(t, vec_ref(y, n), &ydot)
                {
                    return Err(stopped_err(t));
                }
                roots = info;
                stopped = Some((t, vec_ref(y, n).to_vec(), ydot.clone()));
                break;
            }
            if matches!(output, OutputMode::EveryStep { .. }) || next_output > reported_before {
                steps_since_output = 0;
            } else if steps_since_output >= settings.max_steps {
                let flag = if method.cvode() {
                    sys::CV_TOO_MUCH_WORK
                } else {
                    ARK_TOO_MUCH_WORK
                };
                return Err(g.error(t, flag, "", settings));
            }
            if let Some(m) = on_step.as_mut()
                && !m(t, vec_ref(y, n), &ydot)
            {
                stopped = Some((t, vec_ref(y, n).to_vec(), ydot.clone()));
                break;
            }
            if let Some(check) = stiffness.as_mut()
                && check.after_step(&mut *(*g.data).f, t, vec_ref(y, n))
            {
                if !at_t {
                    eval(&mut g, t, vec_ref(y, n), &mut ydot)?;
                }
                stiff_at = Some(t);
                stopped = Some((t, vec_ref(y, n).to_vec(), ydot.clone()));
                break;
            }
        }
        let mut st = stats(method, g.mem);
        if !g.probe.is_null() {
            // The output times' integrations are steps and evaluations too.
            let probe = stats(method, g.probe);
            st.steps += probe.steps;
            st.residual_evals += probe.residual_evals;
            st.error_test_failures += probe.error_test_failures;
        }
        log::debug!("{method:?} finished at t = {t}: {st:?}");
        Ok(Run {
            integrated: Integrated {
                stats: st,
                stopped,
                roots,
                switched: false,
            },
            stiff_at,
        })
    }
}

/// The stiffness check of [`OdeMethod::Auto`].
struct Stiffness {
    steps: usize,
    t_last: f64,
    /// Checks in a row that found the step held by stability.
    in_a_row: usize,
    fy: Vec<f64>,
    fw: Vec<f64>,
    w: Vec<f64>,
    yw: Vec<f64>,
}

impl Stiffness {
    fn new(n: usize, t0: f64) -> Self {
        Stiffness {
            steps: 0,
            t_last: t0,
            in_a_row: 0,
            fy: vec![0.0; n],
            fw: vec![0.0; n],
            w: vec![0.0; n],
            yw: vec![0.0; n],
        }
    }

    /// Called after each step (ending at `t` with `y`): whether the model is stiff
    /// here.
    fn after_step(&mut self, f: &mut dyn OdeFunctions, t: f64, y: &[f64]) -> bool {
        let h = t - self.t_last;
        self.t_last = t;
        self.steps += 1;
        if !self.steps.is_multiple_of(STIFFNESS_CHECK_STEPS) {
            return false;
        }
        let Some(rho) = self.spectral_radius(f, t, y) else {
            return false;
        };
        if h * rho > STIFF_STEP_RATIO {
            self.in_a_row += 1;
        } else {
            self.in_a_row = 0;
        }
        log::trace!("stiffness check at t = {t}: h = {h}, rho = {rho}");
        self.in_a_row >= 2
    }

    /// The largest modulus of the eigenvalues of `df/du` at `(t, y)`, by power
    /// iteration with difference quotients (the geometric mean of two successive
    /// growth factors, which also settles for a complex pair of a normal matrix).
    fn spectral_radius(&mut self, f: &mut dyn OdeFunctions, t: f64, y: &[f64]) -> Option<f64> {
        const ITERATIONS: usize = 8;
        let n = y.len();
        f.rhs(t, y, &mut self.fy).ok()?;
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let y_norm = norm(y);
        // A start with every component (no eigenvector is likely orthogonal to it).
        for (i, w) in self.w.iter_mut().enumerate() {
            *w = 1.0 + (i % 7) as f64 * 0.1 * if i % 2 == 0 { 1.0 } else { -1.0 };
        }
        let mut growth = Vec::with_capacity(ITERATIONS);
        for _ in 0..ITERATIONS {
            let wn = norm(&self.w);
            if !(wn > 0.0 && wn.is_finite()) {
                return None;
            }
            let eps = 1e-7 * (1.0 + y_norm) / wn;
            for i in 0..n {
                self.yw[i] = y[i] + eps * self.w[i];
            }
            f.rhs(t, &self.yw, &mut self.fw).ok()?;
            for i in 0..n {
                self.w[i] = (self.fw[i] - self.fy[i]) / (eps * wn);
            }
            growth.push(norm(&self.w));
        }
        let k = growth.len();
        let rho = (growth[k - 1] * growth[k - 2]).sqrt();
        rho.is_finite().then_some(rho)
    }
}
