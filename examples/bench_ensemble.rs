//! Benchmark: an ensemble of 1 000 solves of a 5-link pendulum chain with random link
//! lengths (one compiled model, the lengths its parameters), on 1 thread and on 2.
//!
//! `cargo run --release --example bench_ensemble` prints one JSON object: the times of
//! both runs (medians of 3) and the speed-up; the two give the same solutions.

use std::time::Instant;

use multibody::joints::Revolute;
use multibody::parts::{Body, FixedTranslation};
use multibody::prelude::*;
use multibody::world::World;
use multibody::{EnsembleOptions, solve_ensemble};

const LINKS: usize = 5;
const SOLVES: usize = 1000;
const T_END: f64 = 2.0;

/// A chain of `LINKS` links: a revolute joint about z, a massless link of tunable length
/// `link{k}.r[1]` and a point mass of 1 kg at its end.
fn chain() -> System {
    let mut m = System::new("chain");
    let world = m.add_typed("world", &World::default());
    let mut prev = world.frame_b;
    for k in 1..=LINKS {
        let joint = m.add_typed(&format!("joint{k}"), &Revolute::default());
        let link = m.add_typed(
            &format!("link{k}"),
            &FixedTranslation {
                r: [0.5, 0.0, 0.0],
                ..Default::default()
            },
        );
        let mass = m.add_typed(
            &format!("mass{k}"),
            &Body {
                m: 1.0,
                I_11: 0.001,
                I_22: 0.001,
                I_33: 0.001,
                ..Default::default()
            },
        );
        m.connect_handles(&prev, &joint.frame_a);
        m.connect_handles(&joint.frame_b, &link.frame_a);
        m.connect_handles(&link.frame_b, &mass.frame_a);
        prev = link.frame_b;
    }
    m
}

/// Random lengths in [0.3, 0.7) m (xorshift, fixed seed), one set per solve.
fn lengths() -> Vec<Vec<(String, f64)>> {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..SOLVES)
        .map(|_| {
            (1..=LINKS)
                .map(|k| (format!("link{k}.r[1]"), 0.3 + 0.4 * next()))
                .collect()
        })
        .collect()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Result<(), multibody::Error> {
    let ssys = structural_simplify(&chain())?;
    let values = lengths();
    let options = SolverOptions {
        rtol: 1e-6,
        atol: 1e-8,
        output_times: Some(vec![T_END]),
        ..SolverOptions::default()
    };
    let run = |threads: usize| -> Result<(f64, Vec<f64>), multibody::Error> {
        let mut times = Vec::new();
        let mut finals = Vec::new();
        for _ in 0..3 {
            let t0 = Instant::now();
            let solutions = solve_ensemble(
                &ssys,
                (0.0, T_END),
                &values,
                &options,
                &EnsembleOptions { threads },
            )?;
            times.push(t0.elapsed().as_secs_f64());
            finals = solutions
                .into_iter()
                .map(|s| s.and_then(|s| Ok(s.final_value("joint1.phi")?)))
                .collect::<Result<_, _>>()?;
        }
        Ok((median(times), finals))
    };
    let (one, finals_one) = run(1)?;
    let (two, finals_two) = run(2)?;
    assert_eq!(
        finals_one, finals_two,
        "the same solutions on 1 and 2 threads"
    );
    println!(
        "{{\"bench\": \"ensemble\", \"solves\": {SOLVES}, \"links\": {LINKS}, \"t_end\": {T_END}, \
         \"threads_1_s\": {one:.4}, \"threads_2_s\": {two:.4}, \"speedup\": {:.3}}}",
        one / two
    );
    Ok(())
}
