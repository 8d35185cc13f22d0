//! The earliest sign change among crossing functions within a bracket, by regula falsi
//! with Illinois weights (the method of SUNDIALS' `arkRootfind`) and a bisection where
//! two trials did not halve the bracket (flat crossings, where the secant alone creeps),
//! on values a caller computes: [`narrow`] asks for the functions at trial times
//! through a closure.
//!
//! What holds: at the bracket's left end no function has changed sign since the start
//! of the step (functions zero there take no part), at its right end at least one has
//! (or reached zero). Each trial keeps that, so the right end returned is a time where
//! the functions that crossed have their new sign, no later than the bracket's
//! tolerance after the earliest crossing.

use std::ffi::c_int;

/// Whether function `i` has changed sign since the start (where its value was
/// `start[i]`), or reached zero; a function zero at the start never has.
pub(super) fn changed(start: &[f64], i: usize, v: f64) -> bool {
    start[i] != 0.0 && (v == 0.0 || (v > 0.0) != (start[i] > 0.0))
}

/// Whether any function of `values` has changed sign since `start`.
pub(super) fn any_changed(start: &[f64], values: &[f64]) -> bool {
    (0..values.len()).any(|i| changed(start, i, values[i]))
}

/// Narrows the bracket `(a, ga)`, `(b, gb)` (the functions' values at both ends, none
/// changed since `start` at `a`, some at `b`) to width `tol` or less, or to a right end
/// where the changed functions are exactly zero and none changed strictly within, in
/// at most `max_trials` calls of `trial(t)` (the functions at `t`). `h` is the step's
/// length: a secant that lands within `tol / 2` of the left end is moved inward by
/// `min(1/2, (b - a) / h)` of the bracket (as SUNDIALS does), so that flat crossings
/// still narrow it; one within `tol / 2` of the right end is moved to `b - tol / 2`
/// (a crossing there, the common case at ARKODE's own crossing time, then ends the
/// search). Returns the right end and the functions there.
///
/// # Errors
/// The first error of `trial`.
pub(super) fn narrow<E>(
    start: &[f64],
    (mut a, mut ga): (f64, Vec<f64>),
    (mut b, mut gb): (f64, Vec<f64>),
    (tol, h): (f64, f64),
    max_trials: usize,
    mut trial: impl FnMut(f64) -> Result<Vec<f64>, E>,
) -> Result<(f64, Vec<f64>), E> {
    // The weight of the left end's values in the secant: halved when the left end was
    // kept twice in a row, doubled when the right end was, else 1 (Illinois).
    let mut weight = 1.0;
    let mut kept_a_before = None;
    // The bracket's width one and two trials ago: where two trials did not halve it
    // (the secant creeping up on a flat crossing), the next trial bisects.
    let mut widths = [f64::INFINITY; 2];
    for _ in 0..max_trials {
        // Functions that changed strictly (not to an exact zero): where none has, the
        // right end is an exact crossing.
        let strict: Vec<usize> = (0..gb.len())
            .filter(|&i| changed(start, i, gb[i]) && gb[i] != 0.0)
            .collect();
        if b - a <= tol || strict.is_empty() {
            return Ok((b, gb));
        }
        // The secant of each function that changed crosses at `b - fraction (b - a)`,
        // fraction in (0, 1) (opposite signs at the two ends); the earliest counts.
        let fraction = strict
            .iter()
            .map(|&i| gb[i] / (gb[i] - weight * ga[i]))
            .filter(|f| f.is_finite())
            .fold(0.0f64, f64::max);
        let (half, width) = (0.5 * tol, b - a);
        let mut t = b - fraction * width;
        if width > 0.5 * widths[0] {
            t = a + 0.5 * width;
        }
        widths = [widths[1], width];
        if t - a < half {
            // Creeping up on a flat crossing from the left: a bisection-like step.
            t = a + (width / h).min(0.5) * width;
        }
        // A crossing within `tol / 2` of `b` ends the search with the next trial.
        t = t.min(b - half);
        let gt = trial(t)?;
        let kept_a = any_changed(start, &gt);
        if kept_a {
            (b, gb) = (t, gt);
        } else {
            (a, ga) = (t, gt);
        }
        weight = match (kept_a_before, kept_a) {
            (Some(true), true) => weight * 0.5,
            (Some(false), false) => weight * 2.0,
            _ => 1.0,
        };
        kept_a_before = Some(kept_a);
    }
    log::debug!("crossing bracket [{a}, {b}] still wider than {tol} after {max_trials} trials");
    Ok((b, gb))
}

/// Root information of `values` against `start`: per function +1 where it rose through
/// zero, -1 where it fell, 0 where it has not changed sign (as ARKODE reports it).
pub(super) fn directions(start: &[f64], values: &[f64]) -> Vec<c_int> {
    (0..values.len())
        .map(|i| match (changed(start, i, values[i]), start[i] < 0.0) {
            (false, _) => 0,
            (true, true) => 1,
            (true, false) => -1,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `narrow` on `f` over [0, 1] (step length 1, tolerance 1e-13, 40 trials at most);
    /// the right end, the directions there and the trials.
    fn run(f: impl Fn(f64) -> Vec<f64>) -> (f64, Vec<c_int>, usize) {
        let start = f(0.0);
        let mut trials = 0;
        let (b, gb) = narrow::<()>(
            &start,
            (0.0, f(0.0)),
            (1.0, f(1.0)),
            (1e-13, 1.0),
            40,
            |t| {
                trials += 1;
                Ok(f(t))
            },
        )
        .unwrap();
        (b, directions(&start, &gb), trials)
    }

    #[test]
    fn the_earliest_of_two_crossings_is_found_with_its_direction() {
        // t - 0.5 rises at 0.5; 0.3 - t falls at 0.3, first.
        let (b, dirs, trials) = run(|t| vec![t - 0.5, 0.3 - t]);
        assert!(b >= 0.3 && b - 0.3 <= 1e-13, "{b}");
        assert_eq!(dirs, vec![0, -1]);
        assert!(trials <= 5, "{trials} trials");
    }

    #[test]
    fn a_flat_crossing_converges_from_the_right() {
        // (t - 0.3)^3 (a triple root): the right end has the new sign.
        // The secant alone crept up on it from the left and never moved the right end
        // (still 1 after 40 trials); with a bisection where two trials do not halve the
        // bracket it narrows, linearly (2.4e-6 after 40).
        let (b, dirs, _) = run(|t| vec![(t - 0.3f64).powi(3)]);
        assert!(b >= 0.3 && b - 0.3 < 1e-5, "{b}");
        assert_eq!(dirs, vec![1]);
    }

    #[test]
    fn an_exact_zero_at_the_right_end_does_not_hide_an_earlier_crossing() {
        // t - 1 is exactly zero at the bracket's right end; 0.4 - t falls earlier.
        let (b, dirs, _) = run(|t| vec![t - 1.0, 0.4 - t]);
        assert!(b >= 0.4 && b - 0.4 <= 1e-13, "{b}");
        assert_eq!(dirs, vec![0, -1]);
    }

    #[test]
    fn a_function_zero_at_the_start_takes_no_part() {
        // t is zero at the start (and never changes sign after); t - 0.6 rises at 0.6.
        let (b, dirs, _) = run(|t| vec![t, t - 0.6]);
        assert!(b >= 0.6 && b - 0.6 <= 1e-13, "{b}");
        assert_eq!(dirs, vec![0, 1]);
    }

    #[test]
    fn an_exact_crossing_at_a_trial_ends_the_search_there() {
        // 0.5 - t: the first secant lands on 0.5 exactly.
        let (b, dirs, trials) = run(|t| vec![0.5 - t]);
        assert_eq!(b, 0.5);
        assert_eq!(dirs, vec![-1]);
        assert_eq!(trials, 1);
    }
}
