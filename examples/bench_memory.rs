//! Benchmark: memory and threads.
//!
//! 1. **Memory is returned.** Builds, compiles and solves (1 s) 1 000 structurally
//!    different 3-D pendulum chains of 5 to 7 links with random lengths, masses and joint
//!    axes, one after the other in this process, dropping each; prints the resident
//!    memory after 50 and after 1 000 models and their ratio (`rss_ratio`, target: at
//!    most 1.5).
//! 2. **Compiles run in parallel.** Builds and compiles two different large models (a
//!    rotational chain of 4 000 inertias and a 3-D pendulum chain of 150 links) once on
//!    one thread, one after the other, and once on two threads at the same time;
//!    prints both wall times and `parallel_speedup` = one thread / two threads (target:
//!    at least 1.5 on 2 cores). The fastest of 5 rounds counts.
//!
//! `cargo run --release --example bench_memory` prints one JSON object per line.
//! `BENCH_MODELS=k` changes the number of models of part 1.

use std::time::Instant;

use multibody::joints::Revolute;
use multibody::parts::BodyShape;
use multibody::prelude::*;
use multibody::rotational::{Fixed, Inertia, SpringDamper};
use multibody::world::World;

/// A small random number generator (xorshift), so that runs are repeatable.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// A pendulum chain of `n` links with random lengths, masses and axes.
fn random_chain(n: usize, rng: &mut Rng) -> System {
    let mut m = System::new(format!("random_chain{n}"));
    let world = m.add_typed("world", &World::default());
    let mut prev = world.frame_b;
    for k in 1..=n {
        // A random axis: its components enter the joint's rotation as constants, so
        // every model has expressions of its own.
        let axis = [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), 1.0];
        let joint = m.add_typed(
            &format!("rev{k}"),
            &Revolute {
                n: axis,
                ..Default::default()
            },
        );
        let l = rng.range(0.2, 0.8);
        let link = m.add_typed(
            &format!("link{k}"),
            &BodyShape {
                r: [l, rng.range(-0.1, 0.1), rng.range(-0.1, 0.1)],
                r_CM: Some([l / 2.0, rng.range(-0.05, 0.05), 0.0]),
                m: rng.range(0.5, 2.0),
                ..Default::default()
            },
        );
        m.connect_handles(&prev, &joint.frame_a);
        m.connect_handles(&joint.frame_b, &link.frame_a);
        prev = link.frame_b;
    }
    m
}

/// A rotational chain of `n` spring-dampers and inertias.
fn rotational_chain(n: usize) -> System {
    let mut m = System::new(format!("chain{n}"));
    let fixed = m.add_typed("fixed", &Fixed::default());
    let mut prev = fixed.flange;
    for k in 1..=n {
        let sd = m.add_typed(
            &format!("sd{k}"),
            &SpringDamper {
                c: 1e4,
                d: 10.0,
                ..Default::default()
            },
        );
        let inertia = m.add_typed(
            &format!("inertia{k}"),
            &Inertia {
                J: 0.1,
                phi_start: if k == n { 1.0 } else { 0.0 },
                ..Default::default()
            },
        );
        m.connect_handles(&prev, &sd.flange_a);
        m.connect_handles(&sd.flange_b, &inertia.flange_a);
        prev = inertia.flange_b;
    }
    m
}

/// Resident memory of this process in bytes (Linux; `None` elsewhere).
fn resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

fn mb(b: Option<u64>) -> String {
    b.map_or("null".into(), |b| format!("{:.1}", b as f64 / 1e6))
}

/// Builds, compiles and solves one random model for 1 s.
fn one_model(rng: &mut Rng) -> Result<(), multibody::Error> {
    let n = 5 + (rng.next() * 3.0) as usize;
    let model = random_chain(n, rng);
    let ssys = structural_simplify(&model)?;
    let sol = DaeProblem::new(&ssys, &[], (0.0, 1.0))?.solve(&SolverOptions::default())?;
    assert!(sol.t().len() > 1);
    Ok(())
}

fn memory(models: usize) -> Result<(), multibody::Error> {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let before = resident_bytes();
    let mut after_50 = None;
    let t0 = Instant::now();
    for k in 1..=models {
        one_model(&mut rng)?;
        if k == 50 {
            after_50 = resident_bytes();
        }
    }
    let elapsed = t0.elapsed().as_secs_f64();
    let after_all = resident_bytes();
    let ratio = match (after_50, after_all) {
        (Some(a), Some(b)) => format!("{:.3}", b as f64 / a as f64),
        _ => "null".into(),
    };
    println!(
        "{{\"part\":\"memory\",\"models\":{models},\"rss_start_mb\":{},\"rss_after_50_mb\":{},\
         \"rss_after_all_mb\":{},\"rss_ratio\":{ratio},\"seconds_per_model\":{:.5}}}",
        mb(before),
        mb(after_50),
        mb(after_all),
        elapsed / models as f64
    );
    Ok(())
}

/// Builds and compiles model `which` (0: the rotational chain, 1: the pendulum chain).
fn compile(which: usize) -> Result<usize, multibody::Error> {
    let model = if which == 0 {
        rotational_chain(4000)
    } else {
        random_chain(150, &mut Rng(7))
    };
    Ok(structural_simplify(&model)?.unknowns().len())
}

fn threads() -> Result<(), Box<dyn std::error::Error>> {
    // Warm the code and the allocator.
    compile(0)?;
    compile(1)?;
    let (mut one, mut two) = (f64::INFINITY, f64::INFINITY);
    let mut each = [f64::INFINITY; 2];
    for _ in 0..5 {
        let t0 = Instant::now();
        compile(0)?;
        let t1 = Instant::now();
        compile(1)?;
        let t2 = Instant::now();
        each[0] = each[0].min((t1 - t0).as_secs_f64());
        each[1] = each[1].min((t2 - t1).as_secs_f64());
        one = one.min((t2 - t0).as_secs_f64());
        let t0 = Instant::now();
        std::thread::scope(|s| -> Result<(), String> {
            let a = s.spawn(|| compile(0).map_err(|e| e.to_string()));
            let b = s.spawn(|| compile(1).map_err(|e| e.to_string()));
            a.join().map_err(|_| "thread panicked")??;
            b.join().map_err(|_| "thread panicked")??;
            Ok(())
        })?;
        two = two.min(t0.elapsed().as_secs_f64());
    }
    println!(
        "{{\"part\":\"threads\",\"rotational_s\":{:.4},\"pendulum_s\":{:.4},\
         \"one_thread_s\":{one:.4},\"two_threads_s\":{two:.4},\"parallel_speedup\":{:.3}}}",
        each[0],
        each[1],
        one / two
    );
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // `--compile k`: compile model k three times (for comparing with two processes).
    let args: Vec<String> = std::env::args().collect();
    if args.get(1).map(String::as_str) == Some("--compile") {
        let which: usize = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(0);
        for _ in 0..3 {
            compile(which)?;
        }
        return Ok(());
    }
    let models = std::env::var("BENCH_MODELS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1000);
    memory(models)?;
    threads()?;
    Ok(())
}
