//! Shared helpers of the integration tests: the Modelica Association's reference
//! trajectories and their tube comparison.

#![allow(dead_code)]

use std::path::PathBuf;

use multibody::{Solution, SolverOptions};

/// The directory of the MSL reference trajectories kept in this repository
/// (`tests/data/msl`, with their provenance and licence in its README).
pub fn reference_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/msl")
}

/// A reference file: time and named signals.
pub struct Reference {
    /// Column names (without `time`).
    pub names: Vec<String>,
    /// Time column.
    pub t: Vec<f64>,
    /// One column per signal.
    pub y: Vec<Vec<f64>>,
}

/// Reads `<model>.csv` of the reference directory.
pub fn read_reference(model: &str) -> Reference {
    let path = reference_dir().join(format!("{model}.csv"));
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .expect("header")
        .split(',')
        .map(|s| s.trim_matches('"').to_string())
        .collect();
    let names = header[1..].to_vec();
    let mut t = Vec::new();
    let mut y = vec![Vec::new(); names.len()];
    for line in lines {
        if line.trim().is_empty() {
            continue;
        }
        let v: Vec<f64> = line
            .split(',')
            .map(|x| x.parse().unwrap_or(f64::NAN))
            .collect();
        t.push(v[0]);
        for (k, col) in y.iter_mut().enumerate() {
            col.push(v[k + 1]);
        }
    }
    Reference { names, t, y }
}

/// The result of comparing one signal.
#[derive(Debug)]
pub struct TubeResult {
    /// Signal name.
    pub signal: String,
    /// Points outside the tube.
    pub failures: usize,
    /// Largest distance outside the tube, relative to its half-height.
    pub worst: f64,
    /// Where the worst point is.
    pub worst_t: f64,
}

/// Compares the signals of `sol` with the reference in the Modelica Association's
/// tube (csv-compare): around each reference point a rectangle of half-width
/// `tol * t_end` in time and half-height `tol * max(y_max - y_min, |y_min|, 1e-3)` in
/// value; our value at each reference time must lie in the union of the rectangles.
pub fn tube_compare(
    sol: &Solution,
    reference: &Reference,
    signals: &[&str],
    tol: f64,
) -> Vec<TubeResult> {
    let t_end = *reference.t.last().expect("non-empty");
    let dt = tol * t_end;
    let mut results = Vec::new();
    for &name in signals {
        let k = reference
            .names
            .iter()
            .position(|n| n == name)
            .unwrap_or_else(|| panic!("the reference has no signal {name}"));
        let yr = &reference.y[k];
        let (ymin, ymax) = yr
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        let dy = tol * (ymax - ymin).max(ymin.abs()).max(1e-3);
        let ours = sol
            .sample(&[name], &reference.t)
            .expect("signal in solution")
            .remove(0);
        let mut failures = 0;
        let mut worst = 0.0f64;
        let mut worst_t = 0.0;
        let mut lo = 0;
        for (i, &t) in reference.t.iter().enumerate() {
            while reference.t[lo] < t - dt {
                lo += 1;
            }
            let mut j = lo;
            let (mut wmin, mut wmax) = (f64::INFINITY, f64::NEG_INFINITY);
            while j < reference.t.len() && reference.t[j] <= t + dt {
                wmin = wmin.min(yr[j]);
                wmax = wmax.max(yr[j]);
                j += 1;
            }
            let v = ours[i];
            let out = if v < wmin - dy {
                (wmin - dy - v) / dy
            } else if v > wmax + dy {
                (v - wmax - dy) / dy
            } else if v.is_nan() {
                f64::INFINITY
            } else {
                0.0
            };
            if out > 0.0 {
                failures += 1;
                if out > worst {
                    worst = out;
                    worst_t = t;
                }
            }
        }
        results.push(TubeResult {
            signal: name.to_string(),
            failures,
            worst,
            worst_t,
        });
    }
    results
}

/// Asserts that every signal lies in the tube.
pub fn assert_in_tube(model: &str, sol: &Solution, signals: &[&str]) {
    let reference = read_reference(model);
    let results = tube_compare(sol, &reference, signals, 2e-3);
    let bad: Vec<&TubeResult> = results.iter().filter(|r| r.failures > 0).collect();
    assert!(
        bad.is_empty(),
        "{model}: signals outside the 2e-3 tube: {bad:#?}"
    );
}

/// Tight tolerances (rtol 1e-10, atol 1e-12) with `n + 1` output times over `(0, t_end)`.
pub fn tight_options(t_end: f64, n: usize) -> SolverOptions {
    SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        output_times: Some((0..=n).map(|k| k as f64 * t_end / n as f64).collect()),
        ..SolverOptions::default()
    }
}
