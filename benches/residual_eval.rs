//! Benchmark (`cargo bench --bench residual_eval`): one evaluation of the compiled
//! residual of a rotational chain (N inertias joined by spring-dampers) against the
//! hand-written residual of the same chain (model and residual from
//! `examples/bench_rotational_chain.rs`), both timed in this process on the same inputs. Prints one JSON object per N with the times per evaluation and their ratio
//! (`ratio` = compiled / hand-written; about 1 means the tape costs what plain Rust
//! does).

#[path = "../examples/bench_rotational_chain.rs"]
#[allow(dead_code)]
mod rotational_chain;

use std::hint::black_box;
use std::time::Instant;

use multibody::prelude::*;
use multibody_core::solve::ida::DaeFunctions;

use rotational_chain::{Baseline, chain};

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
    for n in [10usize, 100, 1000, 10000] {
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
        let mut hand_written = Baseline { n };
        let hand = time_per_call(reps, || {
            hand_written
                .residual(0.0, black_box(&y), black_box(&yp), &mut hand_out)
                .expect("residual");
            black_box(&hand_out);
        });
        println!(
            "{{\"n\": {n}, \"compiled_s\": {compiled:.3e}, \"hand_written_s\": {hand:.3e}, \"ratio\": {:.2}}}",
            compiled / hand
        );
    }
    Ok(())
}
