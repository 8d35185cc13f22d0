//! Benchmark (`cargo bench --bench residual_eval`): one evaluation of the compiled
//! residual of a rotational chain (N inertias joined by spring-dampers) against a
//! hand-written residual of the same chain, both timed in this process on the same
//! inputs. Prints one JSON object per N with the times per evaluation and their ratio
//! (`ratio` = compiled / hand-written; about 1 means the tape costs what plain Rust
//! does).

use std::hint::black_box;
use std::time::Instant;

use multibody::prelude::*;
use multibody::rotational::{Fixed, Inertia, SpringDamper};

const C: f64 = 1e3;
const D: f64 = 1.0;
const J: f64 = 1.0;

fn chain(n: usize) -> System {
    let mut m = System::new(format!("chain{n}"));
    let fixed = m.add_typed("fixed", &Fixed::default());
    let mut prev = fixed.flange;
    for k in 1..=n {
        let sd = m.add_typed(
            &format!("sd{k}"),
            &SpringDamper {
                c: C,
                d: D,
                ..Default::default()
            },
        );
        let inertia = m.add_typed(
            &format!("inertia{k}"),
            &Inertia {
                J,
                ..Default::default()
            },
        );
        m.connect_handles(&prev, &sd.flange_a);
        m.connect_handles(&sd.flange_b, &inertia.flange_a);
        prev = inertia.flange_b;
    }
    m
}

/// `0 = phi' - w`, `0 = J w' - (tau_{k+1} - tau_k)`, `tau_k = c (phi_k - phi_{k-1}) +
/// d (w_k - w_{k-1})`, written out by hand.
fn hand_written(n: usize, y: &[f64], yp: &[f64], out: &mut [f64]) {
    let tau = |k: usize| -> f64 {
        if k == n + 1 {
            return 0.0;
        }
        let (phi, w) = (y[k - 1], y[n + k - 1]);
        let (phi0, w0) = if k == 1 {
            (0.0, 0.0)
        } else {
            (y[k - 2], y[n + k - 2])
        };
        C * (phi - phi0) + D * (w - w0)
    };
    for k in 1..=n {
        out[k - 1] = yp[k - 1] - y[n + k - 1];
        out[n + k - 1] = J * yp[n + k - 1] - (tau(k + 1) - tau(k));
    }
}

/// Seconds per call of `f`, the fastest of 5 batches.
fn time_per_call(reps: usize, mut f: impl FnMut()) -> f64 {
    (0..5)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..reps {
                f();
            }
            t.elapsed().as_secs_f64() / reps as f64
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() -> Result<(), multibody::Error> {
    for n in [10usize, 100, 1000] {
        let ssys = structural_simplify(&chain(n))?;
        let tape = &ssys.compiled().residual;
        let mut ws = tape.workspace();
        let inputs: Vec<f64> = (0..tape.n_inputs())
            .map(|i| 0.1 + 1e-3 * i as f64)
            .collect();
        let mut out = vec![0.0; tape.n_outputs()];
        let reps = 2_000_000 / n;
        let compiled = time_per_call(reps, || {
            tape.eval(black_box(&inputs), &mut ws, &mut out)
                .expect("residual");
            black_box(&out);
        });
        let y: Vec<f64> = (0..2 * n).map(|i| 0.1 + 1e-3 * i as f64).collect();
        let yp = y.clone();
        let mut hand_out = vec![0.0; 2 * n];
        let hand = time_per_call(reps, || {
            hand_written(n, black_box(&y), black_box(&yp), &mut hand_out);
            black_box(&hand_out);
        });
        println!(
            "{{\"n\": {n}, \"compiled_s\": {compiled:.3e}, \"hand_written_s\": {hand:.3e}, \"ratio\": {:.2}}}",
            compiled / hand
        );
    }
    Ok(())
}
