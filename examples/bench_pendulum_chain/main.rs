//! Benchmark: an N-link 3-D pendulum (revolute joints about z, each link a BodyShape
//! `r = {0.5, 0, 0}` with its 1 kg mass at the tip and inertia diag(0.001); gravity
//! 9.81 along -y; at rest, all angles 0), solved for 10 s at rtol 1e-6, atol 1e-8,
//! against a hand-written residual in minimal coordinates (`0 = [q' - v; tau(q, v, v')]`
//! with the 3-D recursive Newton-Euler equations of [`rne`], what a competent engineer
//! writes in C) integrated by the same IDA with its dense difference-quotient Jacobian,
//! in this process.
//!
//! `cargo run --release --example bench_pendulum_chain [N ...]` prints one JSON object
//! per line with the keys of the rotational chain benchmark for the model with tunable
//! parameters (the default), and `evaluated_compile_s`, `evaluated_solve_s`,
//! `evaluated_steps` and `evaluated_solve_ratio` for the same model compiled with
//! every parameter folded in as a constant (`SimplifyOptions::evaluate_parameters`),
//! as the hand-written residual has them (compile phases and initialization the
//! fastest of 5 rounds, each compiling every size and both variants in turn, so that a
//! slow spell of the machine hits every size alike; solves, ours and the baseline's,
//! the fastest of 3 interleaved repetitions up to N = 100, `BENCH_REPS=k` to change
//! that), then the growth of the compile time between the two largest sizes next to
//! that of `N log N`.
//!
//! Environment variables: `BENCH_STATS` prints the translation statistics and tape
//! diagnostics (operation counts, timed residual evaluations, extended-Jacobian
//! variants), `BENCH_EVAL_ONLY` (with `BENCH_STATS`) only times residual evaluations,
//! `BENCH_LINEAR_SOLVER=dense|sparse|plain|dq` forces IDA's linear solver,
//! `BENCH_SKIP_METHODS` skips the rows per method (below), `BENCH_ONLY_OURS` skips the
//! baseline, `BENCH_PRE_FILL=k` sets
//! `LinearBlockLimits::pre_elimination_fill` (`none` disables it), `BENCH_DAE_FORM`
//! leaves the acceleration block to IDA as algebraic unknowns, `BENCH_MAX_TEARING=k` sets
//! `LinearBlockLimits::max_inline_tearing` (at N = 20 the 231-equation acceleration
//! block torn to 38 variables and solved dense takes 0.41 s against 0.25 s by the
//! sparse LU).
//!
//! After each size's row, a row per integration method (`n`, `method`, `steps`,
//! `rhs_evals`, `solve_s`; for the explicit methods `baseline_solve_s`,
//! `baseline_steps` and `solve_ratio` against the articulated-body algorithm of
//! [`aba`] integrated by the same ARKODE method), and at the end the rows of a stiff
//! chain of 20 spring-damper-coupled masses.

mod aba;
mod methods;
mod rne;
mod stiff_chain;

use std::time::Instant;

use rne::{Link, Rne};

use multibody::joints::Revolute;
use multibody::parts::BodyShape;
use multibody::prelude::*;
use multibody::world::World;
use multibody::{LinearSolver, SimplifyOptions, structural_simplify_with};
use multibody_core::solve::ida::{self, IdaMatrix, IdaSettings, OutputMode};

const T_END: f64 = 10.0;
const RTOL: f64 = 1e-6;
const ATOL: f64 = 1e-8;
const G: f64 = 9.81;
const L: f64 = 0.5;
const M: f64 = 1.0;
const I_ZZ: f64 = 0.001;
/// The chain is chaotic for N > 2, so the two solutions are compared early, at 1 s.
const T_CHECK: f64 = 1.0;

fn chain(n: usize) -> System {
    let mut m = System::new(format!("pendulum_chain{n}"));
    let world = m.add_typed(
        "world",
        &World {
            g: G,
            ..Default::default()
        },
    );
    let mut prev = world.frame_b;
    for k in 1..=n {
        let joint = m.add_typed(&format!("rev{k}"), &Revolute::default());
        let link = m.add_typed(
            &format!("link{k}"),
            &BodyShape {
                r: [L, 0.0, 0.0],
                r_CM: Some([L, 0.0, 0.0]),
                m: M,
                I_diag: [0.001, 0.001, I_ZZ],
                ..Default::default()
            },
        );
        m.connect_handles(&prev, &joint.frame_a);
        m.connect_handles(&joint.frame_b, &link.frame_a);
        prev = link.frame_b;
    }
    m
}

/// The links of [`chain`], for the hand-written baselines.
fn links(n: usize) -> Vec<Link> {
    let link = Link {
        axis: [0.0, 0.0, 1.0],
        r: [L, 0.0, 0.0],
        r_cm: [L, 0.0, 0.0],
        m: M,
        inertia: [[I_ZZ, 0.0, 0.0], [0.0, I_ZZ, 0.0], [0.0, 0.0, I_ZZ]],
    };
    vec![link; n]
}

/// The chain of [`chain`] for the baseline.
fn baseline_chain(n: usize) -> Rne {
    Rne::new(links(n), [0.0, -G, 0.0])
}

/// Solves the baseline; returns its solve time, its steps and `q1` at `T_CHECK`.
fn baseline(n: usize) -> (f64, u64, f64) {
    let mut f = baseline_chain(n);
    let y0 = vec![0.0; 2 * n];
    // Consistent accelerations: solve M(q) a = -h(q, v) by Newton on tau(a) = 0 (linear).
    let mut yp0 = vec![0.0; 2 * n];
    let mut tau0 = vec![0.0; n];
    let zero = vec![0.0; n];
    f.torques(&zero, &zero, &zero, &mut tau0);
    let mut mass = vec![vec![0.0; n]; n];
    for j in 0..n {
        let mut e = vec![0.0; n];
        e[j] = 1.0;
        let mut t = vec![0.0; n];
        f.torques(&zero, &zero, &e, &mut t);
        for i in 0..n {
            mass[i][j] = t[i] - tau0[i];
        }
    }
    let a = solve_dense(mass, tau0.iter().map(|x| -x).collect());
    yp0[n..].copy_from_slice(&a);
    let settings = IdaSettings {
        rtol: RTOL,
        atol: ATOL,
        matrix: IdaMatrix::DenseDifferenceQuotient,
        id: vec![1.0; 2 * n],
        ..IdaSettings::default()
    };
    let (mut ts, mut ys) = (Vec::new(), Vec::new());
    let t0 = Instant::now();
    let stats = ida::integrate(
        &mut f,
        0.0,
        &y0,
        &yp0,
        &settings,
        &OutputMode::EveryStep { t_end: T_END },
        &mut |t, y, _| {
            ts.push(t);
            ys.extend_from_slice(y);
            true
        },
    )
    .expect("baseline solve");
    let elapsed = t0.elapsed().as_secs_f64();
    log_stats(&stats);
    let k = ts.partition_point(|&t| t < T_CHECK).max(1);
    let (ta, tb) = (ts[k - 1], ts[k]);
    let (qa, qb) = (ys[(k - 1) * 2 * n], ys[k * 2 * n]);
    let q1 = qa + (qb - qa) * (T_CHECK - ta) / (tb - ta);
    (elapsed, stats.steps, q1)
}

fn solve_dense(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for k in 0..n {
        let p = (k..n)
            .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
            .unwrap();
        a.swap(k, p);
        b.swap(k, p);
        for i in k + 1..n {
            let l = a[i][k] / a[k][k];
            for j in k..n {
                a[i][j] -= l * a[k][j];
            }
            b[i] -= l * b[k];
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        x[k] = (b[k] - (k + 1..n).map(|j| a[k][j] * x[j]).sum::<f64>()) / a[k][k];
    }
    x
}

/// Debug messages of the library on stderr (with `BENCH_STATS=1`).
struct StderrLog;

impl log::Log for StderrLog {
    fn enabled(&self, m: &log::Metadata<'_>) -> bool {
        m.level() <= log::Level::Debug
    }
    fn log(&self, r: &log::Record<'_>) {
        eprintln!("  [{}] {}", r.level(), r.args());
    }
    fn flush(&self) {}
}

static LOGGER: StderrLog = StderrLog;

fn main() -> Result<(), multibody::Error> {
    if std::env::var("BENCH_STATS").is_ok() {
        let _ = log::set_logger(&LOGGER).map(|()| log::set_max_level(log::LevelFilter::Debug));
    }
    let sizes: Vec<usize> = {
        let args: Vec<usize> = std::env::args()
            .skip(1)
            .filter_map(|a| a.parse().ok())
            .collect();
        if args.is_empty() {
            vec![1, 5, 20, 100, 500]
        } else {
            args
        }
    };
    let mut linear_blocks = multibody_core::simplify::LinearBlockLimits::default();
    if let Some(k) = std::env::var("BENCH_MAX_TEARING")
        .ok()
        .and_then(|v| v.parse().ok())
    {
        linear_blocks.max_inline_tearing = k;
    }
    if let Ok(v) = std::env::var("BENCH_PRE_FILL") {
        linear_blocks.pre_elimination_fill = v.parse().ok();
    }
    if std::env::var("BENCH_DAE_FORM").is_ok() {
        linear_blocks.sparse_inline = false;
    }
    let options = SimplifyOptions {
        linear_blocks,
        ..SimplifyOptions::default()
    };
    // Parameters tunable (the default), then every parameter folded in as a constant,
    // as the hand-written residual has them.
    let variants = [
        options.clone(),
        SimplifyOptions {
            evaluate_parameters: true,
            ..options
        },
    ];
    let opts = SolverOptions {
        rtol: RTOL,
        atol: ATOL,
        linear_solver: match std::env::var("BENCH_LINEAR_SOLVER").as_deref() {
            Ok("dense") => LinearSolver::Dense,
            Ok("sparse") => LinearSolver::Sparse,
            Ok("plain") => LinearSolver::SparsePlain,
            Ok("dq") => LinearSolver::DenseDifferenceQuotient,
            _ => LinearSolver::Auto,
        },
        ..SolverOptions::default()
    };
    // Compile phases and initialization: the fastest of several rounds, the sizes and
    // both variants interleaved within each round so that a slow spell of this noisy
    // machine hits every size alike (and the first round's page faults count for none).
    let models: Vec<System> = sizes.iter().map(|&n| chain(n)).collect();
    let mut compiled: Vec<[Option<Compiled>; 2]> = sizes.iter().map(|_| [None, None]).collect();
    for _round in 0..COMPILE_ROUNDS {
        for (model, best) in models.iter().zip(&mut compiled) {
            for (variant, best) in variants.iter().zip(best.iter_mut()) {
                let c = compile(model, variant)?;
                *best = Some(match best.take() {
                    None => c,
                    Some(b) => b.fastest_with(c),
                });
            }
        }
    }
    drop(models);
    let mut compile_rows: Vec<(usize, f64)> = Vec::new();
    for (&n, [tunable, evaluated]) in sizes.iter().zip(compiled) {
        let (Some(tunable), Some(evaluated)) = (tunable, evaluated) else {
            unreachable!("every round compiles every size and variant");
        };
        let Some(mut tunable) = run(tunable, &opts)? else {
            continue;
        };
        let mut evaluated = run(evaluated, &opts)?.expect("not only evaluating");
        compile_rows.push((n, tunable.compile_s));
        let with_baseline = n <= 100 && std::env::var("BENCH_ONLY_OURS").is_err();
        let mut base: Option<(f64, u64, f64)> = None;
        // This machine is noisy: each solve is repeated, interleaved, and the fastest
        // repetition counts.
        let reps = std::env::var("BENCH_REPS")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(if n <= 100 { 3 } else { 1 });
        for rep in 0..reps {
            if rep > 0 {
                tunable.solve_s = tunable.solve_s.min(solve(&tunable.ssys, &opts)?.0);
                evaluated.solve_s = evaluated.solve_s.min(solve(&evaluated.ssys, &opts)?.0);
            }
            if with_baseline {
                let b = baseline(n);
                base = Some(match base {
                    Some(prev) if prev.0 <= b.0 => prev,
                    _ => b,
                });
            }
        }
        let baseline_part = if let Some((b, steps, q1)) = base {
            for ours in [tunable.q1, evaluated.q1] {
                assert!(
                    (q1 - ours).abs() < 1e-3 * (1.0 + q1.abs()),
                    "the two solutions disagree: {ours} vs {q1}"
                );
            }
            format!(
                ", \"baseline_solve_s\": {b:.6}, \"baseline_steps\": {steps}, \"solve_ratio\": {:.3}, \"evaluated_solve_ratio\": {:.3}, \"baseline_q1_at_1s\": {q1:.6}",
                tunable.solve_s / b,
                evaluated.solve_s / b
            )
        } else {
            String::new()
        };
        let t = tunable.times;
        println!(
            "{{\"n\": {n}, \"flatten_s\": {:.6}, \"simplify_s\": {:.6}, \"codegen_s\": {:.6}, \"init_s\": {:.6}, \"solve_s\": {:.6}, \"compile_s\": {:.6}, \"steps\": {}, \"unknowns\": {}, \"states\": {}, \"q1_at_1s\": {:.6}, \"evaluated_compile_s\": {:.6}, \"evaluated_solve_s\": {:.6}, \"evaluated_steps\": {}{baseline_part}}}",
            t.flatten_s,
            t.simplify_s,
            t.codegen_s,
            tunable.init_s,
            tunable.solve_s,
            tunable.compile_s,
            tunable.steps,
            tunable.unknowns,
            tunable.states,
            tunable.q1,
            evaluated.compile_s,
            evaluated.solve_s,
            evaluated.steps,
        );
        if std::env::var("BENCH_SKIP_METHODS").is_err() {
            methods::rows(n, &tunable.ssys, reps)?;
        }
    }
    if std::env::var("BENCH_SKIP_METHODS").is_err() {
        methods::stiff_rows(20)?;
    }
    if let [.., (n0, c0), (n1, c1)] = compile_rows.as_slice() {
        let nlogn = |n: usize| n as f64 * (n as f64).ln();
        println!(
            "{{\"growth_from\": {n0}, \"growth_to\": {n1}, \"n_log_n\": {:.2}, \"compile\": {:.2}}}",
            nlogn(*n1) / nlogn(*n0),
            c1 / c0
        );
    }
    Ok(())
}

/// One compiled and solved variant of the chain.
struct Run {
    ssys: SimplifiedSystem,
    times: multibody::PhaseTimes,
    compile_s: f64,
    init_s: f64,
    solve_s: f64,
    steps: u64,
    unknowns: usize,
    states: usize,
    /// `rev1.phi` at `T_CHECK`.
    q1: f64,
}

/// Rounds of compilation (and initialization) of every size; the fastest counts.
const COMPILE_ROUNDS: usize = 5;

/// One compilation of a variant: the compiled model and the times of its phases and of
/// its initialization (the fastest over rounds once merged).
struct Compiled {
    ssys: SimplifiedSystem,
    times: multibody::PhaseTimes,
    init_s: f64,
}

impl Compiled {
    /// This compilation with each time the smaller of its own and `other`'s.
    fn fastest_with(self, other: Compiled) -> Compiled {
        let (b, t) = (self.times, other.times);
        Compiled {
            ssys: self.ssys,
            times: multibody::PhaseTimes {
                flatten_s: b.flatten_s.min(t.flatten_s),
                simplify_s: b.simplify_s.min(t.simplify_s),
                codegen_s: b.codegen_s.min(t.codegen_s),
            },
            init_s: self.init_s.min(other.init_s),
        }
    }
}

/// Compiles `model` once and times its initialization.
fn compile(model: &System, options: &SimplifyOptions) -> Result<Compiled, multibody::Error> {
    let ssys = structural_simplify_with(model, options)?;
    let times = ssys.statistics().times;
    let t0 = Instant::now();
    drop(DaeProblem::new(&ssys, &[], (0.0, T_END))?);
    let init_s = t0.elapsed().as_secs_f64();
    Ok(Compiled {
        ssys,
        times,
        init_s,
    })
}

/// Solves a compiled variant; `None` when `BENCH_EVAL_ONLY` stops after the
/// diagnostics.
fn run(compiled: Compiled, opts: &SolverOptions) -> Result<Option<Run>, multibody::Error> {
    let Compiled {
        ssys,
        times,
        init_s,
    } = compiled;
    if std::env::var("BENCH_STATS").is_ok() {
        diagnostics(&ssys);
        if std::env::var("BENCH_EVAL_ONLY").is_ok() {
            return Ok(None);
        }
    }
    let (solve_s, sol) = solve(&ssys, opts)?;
    Ok(Some(Run {
        times,
        compile_s: times.flatten_s + times.simplify_s + times.codegen_s,
        init_s,
        solve_s,
        steps: sol.statistics().steps,
        unknowns: ssys.unknowns().len(),
        states: ssys.states().len(),
        q1: sol.at("rev1.phi", T_CHECK)?,
        ssys,
    }))
}

/// Solves `ssys` from its start values to `T_END`: the time taken and the solution.
fn solve(
    ssys: &SimplifiedSystem,
    opts: &SolverOptions,
) -> Result<(f64, multibody::Solution), multibody::Error> {
    let prob = DaeProblem::new(ssys, &[], (0.0, T_END))?;
    let t1 = Instant::now();
    let sol = prob.solve(opts)?;
    let solve_s = t1.elapsed().as_secs_f64();
    log_stats(sol.statistics());
    Ok((solve_s, sol))
}

/// Integrator counters on stderr (set `BENCH_STATS=1`).
fn log_stats(stats: &ida::IdaStats) {
    if std::env::var("BENCH_STATS").is_ok() {
        eprintln!("{stats:?}");
    }
}

/// Compilation report, tape profile, a timed residual loop and extended-Jacobian
/// variants on stderr (set `BENCH_STATS=1`; `BENCH_EVAL_ONLY=1` skips the solves).
fn diagnostics(ssys: &multibody::SimplifiedSystem) {
    let c = ssys.compiled();
    eprintln!(
        "{}\n  residual tape {} ops, Jacobian {} non-zeros in {} colours",
        ssys.statistics(),
        c.residual.len(),
        c.jacobian().nnz(),
        c.jacobian().n_colors()
    );
    eprintln!(
        "  residual ops ({} runs, {} in the parameter prelude): {:?}",
        c.residual.runs(),
        c.residual.prelude_len(),
        c.residual.op_counts()
    );
    // The problem's parameter values, every unknown and derivative 0.1.
    let params = DaeProblem::new(ssys, &[], (0.0, T_END))
        .map(|p| p.parameter_values().to_vec())
        .unwrap_or_default();
    let mut inputs = vec![0.1; c.residual.n_inputs()];
    for (j, &p) in params.iter().enumerate() {
        inputs[c.layout.param(j)] = p;
    }
    let reps = if std::env::var("BENCH_EVAL_ONLY").is_ok() {
        20000
    } else {
        2000
    };
    let specialized = c.specialize(&params);
    for (what, tape) in [
        ("residual", &c.residual),
        ("specialized residual", &specialized.residual),
    ] {
        let mut ws = tape.workspace();
        let mut out = vec![0.0; tape.n_outputs()];
        let t = Instant::now();
        for _ in 0..reps {
            tape.eval(&inputs, &mut ws, &mut out).expect("residual");
        }
        let per = t.elapsed().as_secs_f64() / reps as f64;
        eprintln!(
            "  {what}: {} ops; sparse solves (size, matrix entries, LU entries, refactor multiply-adds): {:?}",
            tape.len(),
            ws.sparse_factor_sizes()
        );
        eprintln!(
            "  {what} eval {:.2} us ({:.2} ns per instruction)",
            per * 1e6,
            per * 1e9 / tape.len() as f64
        );
    }
    for k in [0, 2, 8] {
        let e = multibody_core::codegen::ExtendedJacobian::new(
            &c.residual,
            c.layout.n,
            c.layout.u(0),
            c.layout.up(0),
            k,
        );
        eprintln!(
            "  extended Jacobian (max fill {k}): {} cuts, {} non-zeros in {} colours",
            e.n_cuts(),
            e.nnz(),
            e.n_colors()
        );
    }
    if let Some(e) = specialized.extended() {
        eprintln!(
            "  extended Jacobian of the specialized residual: {} cuts, {} non-zeros in {} colours",
            e.n_cuts(),
            e.nnz(),
            e.n_colors()
        );
    }
    if let Some(e) = c.extended() {
        eprintln!(
            "  extended Jacobian used: {} cuts, {} non-zeros in {} colours",
            e.n_cuts(),
            e.nnz(),
            e.n_colors()
        );
    }
}
