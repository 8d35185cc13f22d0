//! What the SUNDIALS integrators ([`ida`](super::ida), [`ode`](super::ode)) share: a
//! context whose objects (vectors, matrix, linear and nonlinear solver) are freed in
//! order, SUNDIALS' messages caught instead of printed, the model's evaluation errors
//! recorded for the messages, slices over vectors, dense Jacobians scattered.

use std::ffi::{CStr, c_char, c_int, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::ptr;

use sundials_sys as sys;

use super::ida::{EvalError, IdaError};

/// Which callback produced an [`EvalError`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Callback {
    /// The residual (IDA) or the right-hand side (CVODE, ARKODE).
    Residual,
    Jacobian,
    /// The crossing functions.
    Roots,
}

/// The name of a callback in messages.
pub(super) fn origin_name(o: Callback) -> &'static str {
    match o {
        Callback::Residual => "residual",
        Callback::Jacobian => "Jacobian",
        Callback::Roots => "crossing functions",
    }
}

/// The last failure of a model callback, kept for the error message.
#[derive(Default)]
pub(super) struct EvalLog {
    pub(super) last: Option<(f64, Callback, EvalError)>,
}

impl EvalLog {
    /// Records `e` from `origin` at `t`; the callback's return code (1 recoverable, -1
    /// not).
    pub(super) fn record(&mut self, t: f64, origin: Callback, e: EvalError) -> c_int {
        let code = if e.recoverable { 1 } else { -1 };
        log::debug!(
            "{origin:?} evaluation failed at t = {t} (recoverable: {}): {}",
            e.recoverable,
            e.message
        );
        self.last = Some((t, origin, e));
        code
    }

    /// The return code of a crossing-function callback with `result` and values `out`:
    /// 0, or the failure recorded as unrecoverable (no integrator recovers from one).
    pub(super) fn record_roots(
        &mut self,
        t: f64,
        result: Result<(), EvalError>,
        out: &[f64],
    ) -> c_int {
        match result {
            Ok(()) if out.iter().all(|v| v.is_finite()) => 0,
            Ok(()) => self.record(
                t,
                Callback::Roots,
                EvalError {
                    message: "a crossing function is not finite".into(),
                    recoverable: false,
                },
            ),
            Err(e) => self.record(
                t,
                Callback::Roots,
                EvalError {
                    recoverable: false,
                    ..e
                },
            ),
        }
    }

    /// Records a caught panic as an unrecoverable evaluation error.
    pub(super) fn record_panic(
        &mut self,
        t: f64,
        origin: Callback,
        p: &(dyn std::any::Any + Send),
    ) -> c_int {
        let message = if let Some(s) = p.downcast_ref::<&str>() {
            (*s).to_string()
        } else if let Some(s) = p.downcast_ref::<String>() {
            s.clone()
        } else {
            "unknown panic payload".into()
        };
        let e = EvalError {
            message: format!("panic in model function: {message}"),
            recoverable: false,
        };
        self.record(t, origin, e)
    }
}

/// Receives SUNDIALS error messages instead of printing them.
#[derive(Default)]
pub(super) struct ErrSink {
    last: Option<String>,
}

unsafe extern "C" fn error_handler_cb(
    _line: c_int,
    func: *const c_char,
    _file: *const c_char,
    msg: *const c_char,
    err_code: sys::SUNErrCode,
    err_user_data: *mut c_void,
    _ctx: sys::SUNContext,
) {
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: SUNDIALS passes NUL-terminated strings (or null) and the ErrSink
        // pointer registered with the handler.
        unsafe {
            let text = |p: *const c_char| {
                if p.is_null() {
                    String::new()
                } else {
                    CStr::from_ptr(p).to_string_lossy().into_owned()
                }
            };
            let (func, msg) = (text(func), text(msg));
            log::debug!("SUNDIALS error {err_code} in {func}: {msg}");
            if let Some(sink) = err_user_data.cast::<ErrSink>().as_mut() {
                sink.last = Some(if func.is_empty() {
                    msg
                } else {
                    format!("{func}: {msg}")
                });
            }
        }
    }));
}

/// A SUNDIALS context and the objects made in it, freed in Drop (the objects first, the
/// context, then the message sink it reports to). An integrator's memory must be freed
/// before these.
pub(super) struct Objects {
    pub(super) ctx: sys::SUNContext,
    pub(super) ls: sys::SUNLinearSolver,
    pub(super) nls: sys::SUNNonlinearSolver,
    pub(super) mat: sys::SUNMatrix,
    vectors: Vec<sys::N_Vector>,
    sink: *mut ErrSink,
}

impl Objects {
    /// A new context that reports its errors to a sink (and the `log` crate) instead
    /// of printing them.
    pub(super) fn new() -> Result<Objects, String> {
        let mut o = Objects {
            ctx: ptr::null_mut(),
            ls: ptr::null_mut(),
            nls: ptr::null_mut(),
            mat: ptr::null_mut(),
            vectors: Vec::new(),
            sink: Box::into_raw(Box::<ErrSink>::default()),
        };
        // SAFETY: the context is created here and owned by `o`; the sink outlives it.
        unsafe {
            if sys::SUNContext_Create(sys::comm_no_mpi(), &mut o.ctx) != 0 || o.ctx.is_null() {
                o.ctx = ptr::null_mut();
                return Err("SUNContext_Create failed".into());
            }
            sys::SUNContext_SetLogger(o.ctx, ptr::null_mut());
            sys::SUNContext_ClearErrHandlers(o.ctx);
            sys::SUNContext_PushErrHandler(o.ctx, Some(error_handler_cb), o.sink.cast::<c_void>());
        }
        Ok(o)
    }

    /// A serial vector owned by these objects, filled with `values`.
    pub(super) fn vector(&mut self, values: &[f64]) -> Result<sys::N_Vector, String> {
        let len =
            sys::sunindextype::try_from(values.len()).map_err(|_| "vector too long".to_string())?;
        // SAFETY: ctx is valid; the new vector has `values.len()` entries.
        unsafe {
            let v = sys::N_VNew_Serial(len, self.ctx);
            if v.is_null() {
                return Err("N_VNew_Serial failed".into());
            }
            self.vectors.push(v);
            if !values.is_empty() {
                let p = sys::N_VGetArrayPointer(v);
                if p.is_null() {
                    return Err("N_VGetArrayPointer returned null".into());
                }
                ptr::copy_nonoverlapping(values.as_ptr(), p, values.len());
            }
            Ok(v)
        }
    }

    /// Takes the last SUNDIALS error message, if any (between SUNDIALS calls only).
    pub(super) fn take_message(&mut self) -> Option<String> {
        // SAFETY: the sink is owned here and SUNDIALS writes it only during its calls.
        unsafe { self.sink.as_mut().and_then(|s| s.last.take()) }
    }

    /// A `SETUP_FAILED` error at `t` with `message` and SUNDIALS' last message.
    pub(super) fn setup_failed(&mut self, t: f64, mut message: String) -> IdaError {
        if let Some(s) = self.take_message() {
            message.push_str(&format!(" [SUNDIALS: {}]", s.trim()));
        }
        IdaError {
            t,
            flag: "SETUP_FAILED".into(),
            message,
        }
    }
}

impl Drop for Objects {
    fn drop(&mut self) {
        // SAFETY: every pointer is null or owned here and made by the matching
        // constructor; the context is freed after the objects made in it, the sink it
        // references after the context.
        unsafe {
            if !self.nls.is_null() {
                sys::SUNNonlinSolFree(self.nls);
            }
            if !self.ls.is_null() {
                sys::SUNLinSolFree(self.ls);
            }
            if !self.mat.is_null() {
                sys::SUNMatDestroy(self.mat);
            }
            for v in self.vectors.drain(..) {
                if !v.is_null() {
                    sys::N_VDestroy(v);
                }
            }
            if !self.ctx.is_null() {
                sys::SUNContext_Free(&mut self.ctx);
            }
            if !self.sink.is_null() {
                drop(Box::from_raw(self.sink));
            }
        }
    }
}

/// Creates a slice over a serial vector.
///
/// # Safety
/// `v` must be a valid serial N_Vector of length `n` that is not mutated while the
/// slice lives.
pub(super) unsafe fn vec_ref<'a>(v: sys::N_Vector, n: usize) -> &'a [f64] {
    if n == 0 {
        return &[];
    }
    // SAFETY: guaranteed by the caller.
    unsafe { std::slice::from_raw_parts(sys::N_VGetArrayPointer(v), n) }
}

/// Mutable variant of [`vec_ref`].
///
/// # Safety
/// As [`vec_ref`], and no other reference to the data may be live.
pub(super) unsafe fn vec_mut<'a>(v: sys::N_Vector, n: usize) -> &'a mut [f64] {
    if n == 0 {
        return &mut [];
    }
    // SAFETY: guaranteed by the caller.
    unsafe { std::slice::from_raw_parts_mut(sys::N_VGetArrayPointer(v), n) }
}

/// Writes the CSC `values` of the pattern (`col_ptr`, `row_idx`) into the column-major
/// dense `n x n` matrix `dense` (zero elsewhere).
pub(super) fn scatter_dense(
    n: usize,
    col_ptr: &[usize],
    row_idx: &[usize],
    values: &[f64],
    dense: &mut [f64],
) {
    dense.fill(0.0);
    for j in 0..n {
        for k in col_ptr[j]..col_ptr[j + 1] {
            dense[j * n + row_idx[k]] = values[k];
        }
    }
}

/// The position of the first value that is not finite, as an evaluation error of
/// `what` (`"residual component"`) that the integrator may recover from.
pub(super) fn not_finite(values: &[f64], what: &str) -> Option<EvalError> {
    values
        .iter()
        .position(|v| !v.is_finite())
        .map(|i| EvalError {
            message: format!("{what} {i} is not finite"),
            recoverable: true,
        })
}

/// Writes the CSC pattern (`col_ptr`, `row_idx`) into the SUNDIALS sparse matrix `jac`
/// (growing its storage if needed) and returns its value array (`row_idx.len()`
/// entries, in the pattern's order), or `None` where SUNDIALS fails.
///
/// # Safety
/// `jac` is a valid CSC `SUNSparseMatrix` with `col_ptr.len() - 1` columns, not
/// otherwise borrowed while the slice lives.
pub(super) unsafe fn write_csc_pattern<'a>(
    jac: sys::SUNMatrix,
    col_ptr: &[sys::sunindextype],
    row_idx: &[sys::sunindextype],
) -> Option<&'a mut [f64]> {
    let nnz = row_idx.len();
    // SAFETY: guaranteed by the caller; the copies fit the storage checked here.
    unsafe {
        if (sys::SUNSparseMatrix_NNZ(jac) as usize) < nnz
            && sys::SUNSparseMatrix_Reallocate(jac, nnz as sys::sunindextype) != 0
        {
            return None;
        }
        let ptrs = sys::SUNSparseMatrix_IndexPointers(jac);
        let rows = sys::SUNSparseMatrix_IndexValues(jac);
        let data = sys::SUNSparseMatrix_Data(jac);
        if ptrs.is_null() || rows.is_null() || data.is_null() {
            return None;
        }
        ptr::copy_nonoverlapping(col_ptr.as_ptr(), ptrs, col_ptr.len());
        ptr::copy_nonoverlapping(row_idx.as_ptr(), rows, nnz);
        Some(std::slice::from_raw_parts_mut(data, nnz))
    }
}
