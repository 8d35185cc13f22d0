//! Damped Newton's method on a compiled residual with its exact sparse Jacobian.

use crate::codegen::{DaeJacobian, Tape};

use super::linsol::IterationLu;

/// Options of [`newton`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct NewtonOptions {
    /// Converged when every residual is at most this (absolute).
    pub ftol: f64,
    /// Or when the step is at most this relative to the iterate.
    pub xtol: f64,
    /// Iteration limit.
    pub max_iterations: usize,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        NewtonOptions {
            ftol: 1e-10,
            xtol: 1e-13,
            max_iterations: 60,
        }
    }
}

/// The outcome of [`newton`].
#[derive(Clone, Debug)]
pub(crate) struct NewtonOutcome {
    /// Whether it converged.
    pub converged: bool,
    /// Iterations made.
    pub iterations: usize,
    /// The final residuals.
    pub residuals: Vec<f64>,
    /// Why it stopped, when it did not converge.
    pub reason: String,
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| {
        if x.is_nan() {
            f64::INFINITY
        } else {
            m.max(x.abs())
        }
    })
}

fn norm2(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>()
}

/// Solves `tape(inputs) = 0` for the `n` inputs from `z_offset` (the first `n` outputs
/// are the residuals), starting from the values in `inputs`, with a backtracking line
/// search on the squared residual norm. `inputs` holds the last iterate on return.
pub(crate) fn newton(
    tape: &Tape,
    jacobian: &DaeJacobian,
    inputs: &mut [f64],
    z_offset: usize,
    options: NewtonOptions,
) -> NewtonOutcome {
    let n = jacobian.n;
    let mut ws = tape.workspace();
    let mut jws = jacobian.workspace(tape);
    let mut f = vec![0.0; tape.n_outputs()];
    let mut f_trial = vec![0.0; tape.n_outputs()];
    let mut values = vec![0.0; jacobian.nnz()];
    let col_ptr: Vec<i64> = jacobian.col_ptr.iter().map(|&c| c as i64).collect();
    let row_idx: Vec<i64> = jacobian.row_idx.iter().map(|&r| r as i64).collect();
    let mut lu = IterationLu::default();
    let mut delta = vec![0.0; n];
    let mut z_old = vec![0.0; n];
    let fail = |it: usize, f: &[f64], reason: String| NewtonOutcome {
        converged: false,
        iterations: it,
        residuals: f[..n].to_vec(),
        reason,
    };
    if let Err(e) = tape.eval(inputs, &mut ws, &mut f) {
        return fail(0, &vec![f64::NAN; n], e.message);
    }
    for it in 0..=options.max_iterations {
        let fnorm = max_abs(&f[..n]);
        if fnorm <= options.ftol {
            return NewtonOutcome {
                converged: true,
                iterations: it,
                residuals: f[..n].to_vec(),
                reason: String::new(),
            };
        }
        if it == options.max_iterations {
            return fail(it, &f, "iteration limit reached".into());
        }
        if let Err(e) = jacobian.eval(tape, inputs, 0.0, &mut jws, &mut values) {
            return fail(it, &f, e.message);
        }
        if let Err(e) = lu.factorize(n, &col_ptr, &row_idx, &values) {
            log::debug!("Newton: factorization failed: {e:?}");
            return fail(it, &f, "the Jacobian is singular".into());
        }
        for i in 0..n {
            delta[i] = -f[i];
        }
        if let Err(e) = lu.solve_in_place(&mut delta) {
            return fail(it, &f, format!("the Newton step failed ({e:?})"));
        }
        z_old.copy_from_slice(&inputs[z_offset..z_offset + n]);
        let f0 = norm2(&f[..n]);
        let mut lambda = 1.0;
        let mut accepted = false;
        while lambda >= 1e-6 {
            for i in 0..n {
                inputs[z_offset + i] = z_old[i] + lambda * delta[i];
            }
            if tape.eval(inputs, &mut ws, &mut f_trial).is_ok() {
                let f1 = norm2(&f_trial[..n]);
                if f1.is_finite() && f1 <= (1.0 - 1e-4 * lambda) * f0 {
                    accepted = true;
                    break;
                }
            }
            lambda *= 0.5;
        }
        if !accepted {
            // Take the full step anyway once: Newton may need to cross a hump.
            for i in 0..n {
                inputs[z_offset + i] = z_old[i] + delta[i];
            }
            if tape.eval(inputs, &mut ws, &mut f_trial).is_err()
                || !norm2(&f_trial[..n]).is_finite()
            {
                inputs[z_offset..z_offset + n].copy_from_slice(&z_old);
                return fail(it + 1, &f, "no step reduces the residuals".into());
            }
        }
        std::mem::swap(&mut f, &mut f_trial);
        let step = (0..n)
            .map(|i| (inputs[z_offset + i] - z_old[i]).abs() / (1.0 + z_old[i].abs()))
            .fold(0.0, f64::max);
        if step <= options.xtol && max_abs(&f[..n]) <= options.ftol.sqrt() {
            return NewtonOutcome {
                converged: true,
                iterations: it + 1,
                residuals: f[..n].to_vec(),
                reason: String::new(),
            };
        }
    }
    fail(options.max_iterations, &f, "iteration limit reached".into())
}
