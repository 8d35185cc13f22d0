//! Closed-form references and the tight solver options the 1-D tests compare against
//! them (each test file includes this module and uses what it needs).

#![allow(dead_code)]

use multibody::prelude::*;

/// Tolerances far below the tests' comparison thresholds: rtol 1e-10, atol 1e-12.
pub fn tight() -> SolverOptions {
    SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        ..SolverOptions::default()
    }
}

/// x(t) of `m x'' + d x' + c x = 0` from x0, v0 (underdamped, or undamped for d = 0).
pub fn damped(m: f64, d: f64, c: f64, x0: f64, v0: f64, t: f64) -> f64 {
    let w0 = (c / m).sqrt();
    let zeta = d / (2.0 * (c * m).sqrt());
    let wd = w0 * (1.0 - zeta * zeta).sqrt();
    let a = zeta * w0;
    (-a * t).exp() * (x0 * (wd * t).cos() + (v0 + a * x0) / wd * (wd * t).sin())
}

/// The complete elliptic integral of the first kind K(k), by the arithmetic-geometric
/// mean.
pub fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - k * k).sqrt());
    // Quadratic convergence: a fixed number of rounds (a tolerance on a - b may never
    // be met by rounding).
    for _ in 0..40 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}
