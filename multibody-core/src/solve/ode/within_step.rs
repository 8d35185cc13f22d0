//! Values within an accepted step of ARKODE's methods, reached by integrating from the
//! step's start instead of from ARKODE's interpolant.
//!
//! ARKODE interpolates between the ends of a step by a Hermite polynomial of degree 5
//! at most. With the long steps of high-order methods that is far less accurate than
//! the step: Verner 8(7) at rtol 1e-9 gave an oscillator's output times 2.8e-6 off
//! (its steps 1e-12), and Verner 9(8) put crossings 7e-7 off. Here a time within the
//! step is reached by an integration from the step's start with the stop time set to
//! it (its first step the whole interval, shorter than the accepted step and so within
//! the tolerance), so the value carries the method's error:
//!
//! - [`locate_crossing`] finds the earliest sign change of any crossing function on the
//!   integrated solution by the Illinois variant of regula falsi (as SUNDIALS' own root
//!   finding does on the interpolant; `earliest_crossing.rs`), bracketed by the step's
//!   start and end, until the bracket is as narrow as SUNDIALS' root tolerance
//!   (`100 u (|t| + |h|)`). It returns
//!   the bracket's right end, where the functions that crossed have their new sign, with
//!   the state integrated to it (the integration restarts from there) and which
//!   functions crossed, in which direction. It runs on the integrator itself: the
//!   segment ends at the crossing.
//! - [`integrate_to`] on a second integrator of the same method ([`open_probe`],
//!   sharing the callback data) gives output times within a step of the methods whose
//!   order exceeds the interpolant's, leaving the integration itself undisturbed: one
//!   partial step per output time.

use std::cell::Cell;
use std::ffi::{c_int, c_void};

use sundials_sys as sys;

use super::super::ida::{IdaError, IdaSettings};
use super::super::sundials::{vec_mut, vec_ref};
use super::earliest_crossing;
use super::{
    ARK_ONE_STEP, ARK_TSTOP_RETURN, ARKodeEvolve, ARKodeReset, ARKodeRootInit, ARKodeSStolerances,
    ARKodeSVtolerances, ARKodeSetInitStep, ARKodeSetMaxNumSteps, ARKodeSetMinStep,
    ARKodeSetStopTime, ARKodeSetUserData, ERKStepCreate, ERKStepSetTableName, Guard, rhs_cb,
};

unsafe extern "C" {
    fn ARKodeGetCurrentTime(mem: *mut c_void, tcur: *mut f64) -> c_int;
}

/// The order of an ARKODE explicit table from its name (`ARKODE_VERNER_13_7_8`: 8, the
/// last number, as every ARKODE table is named).
fn table_order(table: &str) -> Option<u32> {
    table.rsplit('_').next()?.parse().ok()
}

/// Whether output times within a step of the explicit `table` are integrated to rather
/// than interpolated: for orders above 5 (ERKStep's interpolant has degree 5 at most,
/// and order - 1 for lower orders; measured in `options.rs`'s `Method` docs, Dormand-
/// Prince 5(4)'s interpolated outputs are about as accurate as its steps, Verner 7(6)
/// to 9(8)'s far less). A table whose order cannot be read counts as high.
pub(super) fn integrates_outputs(table: &str) -> bool {
    table_order(table).is_none_or(|q| q > 5)
}

/// Creates `g.probe`: an ERKStep integrator of `table` with `g`'s callback data,
/// tolerances (`atol` a vector or `settings.atol`) and maximum number of steps, for
/// [`integrate_to`] (no smallest step: an output time may lie closer to a step's start
/// than the integration's smallest step).
///
/// # Safety
/// `g` holds its callback data and SUNDIALS context; `y` is a serial vector of its
/// length (copied).
pub(super) unsafe fn open_probe(
    g: &mut Guard<'_>,
    table: &std::ffi::CStr,
    (t0, y): (f64, sys::N_Vector),
    atol: Option<sys::N_Vector>,
    max_steps: std::ffi::c_long,
    settings: &IdaSettings,
) -> Result<(), IdaError> {
    // SAFETY: guaranteed by the caller; the probe is owned by `g`, freed in its Drop.
    unsafe {
        g.probe = ERKStepCreate(Some(rhs_cb), t0, y, g.o.ctx);
        if g.probe.is_null() {
            return Err(g.setup_failed(t0, "creating the output integrator failed".into()));
        }
        let mem = g.probe;
        let flag = ERKStepSetTableName(mem, table.as_ptr());
        g.check(flag, t0, "setting the output integrator's table", settings)?;
        let flag = ARKodeSetUserData(mem, g.data.cast::<c_void>());
        g.check(flag, t0, "ARKodeSetUserData", settings)?;
        let flag = match atol {
            Some(a) => ARKodeSVtolerances(mem, settings.rtol, a),
            None => ARKodeSStolerances(mem, settings.rtol, settings.atol),
        };
        g.check(flag, t0, "setting tolerances", settings)?;
        let flag = ARKodeSetMaxNumSteps(mem, max_steps);
        g.check(flag, t0, "ARKodeSetMaxNumSteps", settings)?;
        Ok(())
    }
}

/// At most this many trial times per crossing (the bracket reaches its tolerance in
/// about five).
const MAX_TRIALS: usize = 40;

/// Integrates `mem` (the integrator of `g` or its probe) from `(t_prev, y_prev)` (the
/// start of a step) to `t` with the stop time at `t`, into `y`, its first step the
/// whole interval. The crossing functions are switched off (the segment ends at a
/// crossing; the probe has none); the counters keep counting.
///
/// # Safety
/// `g` is an ARKODE method's guard between SUNDIALS calls and `mem` its integrator or
/// probe; `y_prev` and `y` are serial vectors of its length.
pub(super) unsafe fn integrate_to(
    g: &mut Guard<'_>,
    mem: *mut c_void,
    (t_prev, y_prev): (f64, sys::N_Vector),
    t: f64,
    y: sys::N_Vector,
    settings: &IdaSettings,
) -> Result<(), IdaError> {
    // SAFETY: guaranteed by the caller.
    unsafe {
        let n = (*g.data).n;
        if t == t_prev {
            vec_mut(y, n).copy_from_slice(vec_ref(y_prev, n));
            return Ok(());
        }
        if mem == g.mem {
            let flag = ARKodeRootInit(mem, 0, None);
            g.check(flag, t, "ARKodeRootInit", settings)?;
            // A crossing may lie closer to the step's start than the smallest step
            // allowed in the integration (which ends here).
            let flag = ARKodeSetMinStep(mem, 0.0);
            g.check(flag, t, "ARKodeSetMinStep", settings)?;
        }
        // Before the reset, which takes it as the first step (no step estimation).
        let flag = ARKodeSetInitStep(mem, t - t_prev);
        g.check(flag, t_prev, "ARKodeSetInitStep", settings)?;
        let flag = ARKodeReset(mem, t_prev, y_prev);
        g.check(flag, t_prev, "ARKodeReset", settings)?;
        let flag = ARKodeSetStopTime(mem, t);
        g.check(flag, t_prev, "ARKodeSetStopTime", settings)?;
        let mut reached = t_prev;
        loop {
            let flag = ARKodeEvolve(mem, t, y, &mut reached, ARK_ONE_STEP);
            if flag < 0 {
                return Err(g.error(reached, flag, "integrating within a step", settings));
            }
            if flag == ARK_TSTOP_RETURN || reached >= t {
                return Ok(());
            }
        }
    }
}

/// The crossing ARKODE found at `t_root` in the step from `(t_prev, y_prev)`, located
/// on the integrated solution (see the module documentation); `roots` is ARKODE's root
/// information of that step. Returns the crossing's time, with `y` the state integrated
/// to it, and the root information there (per function, +1 where it rose through zero
/// between the step's start and that time, -1 where it fell, else 0). Where no function
/// changes sign on the integrated solution within the step (ARKODE's interpolant did,
/// the solution not, to roundoff) it keeps `t_root` and `roots`, with `y` integrated to
/// `t_root`.
///
/// # Safety
/// As [`integrate_to`] on `g`'s integrator, right after ARKODE returned the crossing
/// (before any other SUNDIALS call on it).
pub(super) unsafe fn locate_crossing(
    g: &mut Guard<'_>,
    (t_prev, y_prev): (f64, sys::N_Vector),
    t_root: f64,
    y: sys::N_Vector,
    roots: &[c_int],
    settings: &IdaSettings,
) -> Result<(f64, Vec<c_int>), IdaError> {
    // SAFETY: guaranteed by the caller; the data is owned by the guard and no SUNDIALS
    // call runs while it is borrowed here.
    unsafe {
        let mut t_hi = t_root;
        let flag = ARKodeGetCurrentTime(g.mem, &mut t_hi);
        g.check(flag, t_root, "ARKodeGetCurrentTime", settings)?;
        let n = (*g.data).n;
        let mem = g.mem;
        // The functions at the step's start; those zero there take no part (ARKODE
        // re-reads them within its first step; where it flagged one, its crossing stays
        // ARKODE's).
        let start = crossings(g, t_prev, vec_ref(y_prev, n))?;
        if (0..start.len()).any(|i| start[i] == 0.0 && roots[i] != 0) {
            integrate_to(g, mem, (t_prev, y_prev), t_root, y, settings)?;
            return Ok((t_root, roots.to_vec()));
        }
        // The time `y` holds.
        let at = Cell::new(t_root);
        // The functions at `t` of the solution integrated to it (left in `y`).
        let trial = |g: &mut Guard<'_>, t: f64| -> Result<Vec<f64>, IdaError> {
            integrate_to(g, mem, (t_prev, y_prev), t, y, settings)?;
            at.set(t);
            crossings(g, t, vec_ref(y, n))
        };
        let at_root = trial(g, t_root)?;
        let (left, right) = if earliest_crossing::any_changed(&start, &at_root) {
            ((t_prev, start.clone()), (t_root, at_root))
        } else if t_hi > t_root {
            let at_hi = trial(g, t_hi)?;
            ((t_root, at_root), (t_hi, at_hi))
        } else {
            ((t_root, at_root.clone()), (t_root, at_root))
        };
        if !earliest_crossing::any_changed(&start, &right.1) {
            if at.get() != t_root {
                trial(g, t_root)?;
            }
            log::debug!("crossing at t = {t_root} on the interpolant, none on the solution");
            return Ok((t_root, roots.to_vec()));
        }
        let tol = 100.0 * f64::EPSILON * (t_hi.abs() + (t_hi - t_prev).abs());
        let (b, gb) = earliest_crossing::narrow(
            &start,
            left,
            right,
            (tol, t_hi - t_prev),
            MAX_TRIALS,
            |t| trial(g, t),
        )?;
        if at.get() != b {
            trial(g, b)?;
        }
        log::trace!("crossing at t = {t_root} on the interpolant, {b} integrated");
        Ok((b, earliest_crossing::directions(&start, &gb)))
    }
}

/// The crossing functions at `(t, y)` (with `f(t, y)` where they read it).
///
/// # Safety
/// No SUNDIALS call is running on `g`.
unsafe fn crossings(g: &mut Guard<'_>, t: f64, y: &[f64]) -> Result<Vec<f64>, IdaError> {
    // SAFETY: guaranteed by the caller; the data is owned by the guard.
    let d = unsafe { &mut *g.data };
    let mut out = vec![0.0; d.n_roots];
    let r = d.roots(t, y, &mut out);
    let failed = |message: String| IdaError {
        t,
        flag: format!("{}_RTFUNC_FAIL", g.method.flag_prefix()),
        message,
    };
    match r {
        Err(e) => Err(failed(format!(
            "the crossing functions failed while locating a crossing: {}",
            e.message
        ))),
        Ok(()) => match out.iter().position(|v| !v.is_finite()) {
            Some(i) => Err(failed(format!(
                "crossing function {i} is not finite ({}) while locating a crossing",
                out[i]
            ))),
            None => Ok(out),
        },
    }
}
