//! Benchmark: a chain of N inertias joined by spring-dampers, compiled and solved to
//! t = 10, against a hand-written residual and analytic Jacobian of the same chain
//! integrated by the same IDA, linear solver and tolerances in this process (both store
//! the trajectory at every step).
//!
//! `cargo run --release --example bench_rotational_chain [N ...]` prints one JSON object
//! per line: `n`, `flatten_s`, `simplify_s`, `codegen_s`, `init_s`, `solve_s`,
//! `compile_s` (flatten through codegen), `steps`, `baseline_solve_s`, `baseline_steps`
//! and `solve_ratio` (ours / baseline). Solves, ours and the baseline's alternating, are
//! the fastest of 2. A last line gives the growth of each phase between the two largest
//! sizes next to that of `N log N` (`n_log_n`).
//!
//! Compile phases and initialization are measured the way a program meets them: each
//! measurement is the first compilation of the model in a fresh process (this program
//! runs itself with `--compile-once N`; the child compiles a chain of 10 first, so code
//! and lazily built tables are warm, then builds the chain of N and compiles and
//! initializes it once). The fastest of 8 rounds counts, each round running every size
//! in turn. Every size then starts from the same allocator state: in one process, glibc
//! would keep the memory a chain of 1000 freed for the next round but return that of
//! 10 000 elements (hundreds of MB) to the kernel, so only the larger size would pay for
//! fresh pages again in every round. `BENCH_IN_PROCESS=1` compiles every round in this
//! process instead, for comparison; `BENCH_WARM=k` has each child compile its model k
//! times with glibc told to keep freed memory (the fastest counting), so that every
//! size runs from memory it has already faulted in.
//!
//! On Linux each row also gives the minor page faults per element of compiling
//! (`compile_faults_per_n`) and of initializing (`init_faults_per_n`) in the last
//! round: memory the allocator got fresh from the kernel, which on a virtual machine
//! costs about 1.5 us per page (see docs/benchmarks.md).

use std::time::Instant;

use multibody::LinearSolver;
use multibody::PhaseTimes;
use multibody::prelude::*;
use multibody::rotational::{Fixed, Inertia, SpringDamper};
use multibody_core::solve::ida::{
    self, DaeFunctions, EvalError, IdaMatrix, IdaSettings, OutputMode,
};

/// Rounds of compilation (and initialization) of every size; the fastest counts.
const COMPILE_ROUNDS: usize = 8;
/// Solves of each size, ours and the baseline's alternating; the fastest counts.
const SOLVE_REPS: usize = 2;

const J: f64 = 1.0;
const C: f64 = 1e3;
const D: f64 = 1.0;
const T_END: f64 = 10.0;
const RTOL: f64 = 1e-6;
const ATOL: f64 = 1e-8;

/// Minor page faults of this process so far (`None` where `/proc/self/stat` is
/// missing).
fn minor_faults() -> Option<u64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name (which may contain spaces): state is the first,
    // minflt the eighth.
    let rest = stat.get(stat.rfind(')')? + 2..)?;
    rest.split_whitespace().nth(7)?.parse().ok()
}

/// fixed - sd1 - inertia1 - sd2 - inertia2 - ... - inertiaN; the last inertia starts
/// displaced by 1 rad, the others at rest in place.
pub fn chain(n: usize) -> System {
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
        let phi_start = if k == n { 1.0 } else { 0.0 };
        let inertia = m.add_typed(
            &format!("inertia{k}"),
            &Inertia {
                J,
                phi_start,
                ..Default::default()
            },
        );
        m.connect_handles(&prev, &sd.flange_a);
        m.connect_handles(&sd.flange_b, &inertia.flange_a);
        prev = inertia.flange_b;
    }
    m
}

/// The same chain by hand in absolute coordinates: u = [phi_1..phi_N, w_1..w_N],
/// `0 = phi' - w`, `0 = J w' - (tau_{k+1} - tau_k)` with
/// `tau_k = c (phi_k - phi_{k-1}) + d (w_k - w_{k-1})` (phi_0 = w_0 = 0, tau_{N+1} = 0).
pub struct Baseline {
    /// Number of inertias.
    pub n: usize,
}

impl Baseline {
    fn tau(&self, y: &[f64], k: usize) -> f64 {
        // k in 1..=n+1
        let n = self.n;
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
    }
}

impl DaeFunctions for Baseline {
    fn len(&self) -> usize {
        2 * self.n
    }
    fn residual(
        &mut self,
        _t: f64,
        y: &[f64],
        yp: &[f64],
        out: &mut [f64],
    ) -> Result<(), EvalError> {
        let n = self.n;
        for k in 1..=n {
            out[k - 1] = yp[k - 1] - y[n + k - 1];
            out[n + k - 1] = J * yp[n + k - 1] - (self.tau(y, k + 1) - self.tau(y, k));
        }
        Ok(())
    }
    fn jacobian_pattern(&self) -> Option<(Vec<usize>, Vec<usize>)> {
        let n = self.n;
        let mut col_ptr = vec![0];
        let mut rows = Vec::new();
        // Column j = phi_j: rows n+j-1 -1.., torque rows j-1, j, j+1 (0-based n + ...).
        for j in 0..n {
            let mut r = vec![j];
            for k in j.saturating_sub(1)..=(j + 1).min(n - 1) {
                r.push(n + k);
            }
            r.sort_unstable();
            r.dedup();
            rows.extend(&r);
            col_ptr.push(rows.len());
        }
        for j in 0..n {
            let mut r = vec![j];
            for k in j.saturating_sub(1)..=(j + 1).min(n - 1) {
                r.push(n + k);
            }
            r.sort_unstable();
            r.dedup();
            rows.extend(&r);
            col_ptr.push(rows.len());
        }
        Some((col_ptr, rows))
    }
    fn jacobian(
        &mut self,
        _t: f64,
        _y: &[f64],
        _yp: &[f64],
        cj: f64,
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        let n = self.n;
        let (col_ptr, rows) = self.jacobian_pattern().expect("pattern");
        for j in 0..2 * n {
            let is_w = j >= n;
            let k = if is_w { j - n } else { j };
            let g = if is_w { D } else { C };
            for p in col_ptr[j]..col_ptr[j + 1] {
                let r = rows[p];
                values[p] = if r < n {
                    // Kinematic row r: phi_r' - w_r.
                    match (is_w, r == k) {
                        (false, true) => cj,
                        (true, true) => -1.0,
                        _ => 0.0,
                    }
                } else {
                    // Dynamic row i: J w_i' - tau_{i+1} + tau_i with
                    // tau_i = g (x_i - x_{i-1}) and tau_{i+1} = g (x_{i+1} - x_i).
                    let i = r - n;
                    let mut v = if is_w && i == k { J * cj } else { 0.0 };
                    if i == k {
                        v += g;
                        if i + 1 < n {
                            v += g;
                        }
                    } else if k + 1 == i || i + 1 == k {
                        v -= g;
                    }
                    v
                };
            }
        }
        Ok(())
    }
}

fn baseline(n: usize, matrix: IdaMatrix) -> (f64, u64, f64) {
    let (t, stats, last) = baseline_stats(n, matrix);
    if std::env::var("BENCH_STATS").is_ok() {
        eprintln!("baseline {stats:?}");
    }
    (t, stats.steps, last)
}

fn baseline_stats(n: usize, matrix: IdaMatrix) -> (f64, ida::IdaStats, f64) {
    let mut f = Baseline { n };
    let mut y0 = vec![0.0; 2 * n];
    y0[n - 1] = 1.0;
    let mut yp0 = vec![0.0; 2 * n];
    // Consistent derivatives: w' = (tau_{k+1} - tau_k) / J.
    for k in 1..=n {
        yp0[n + k - 1] = (f.tau(&y0, k + 1) - f.tau(&y0, k)) / J;
    }
    let settings = IdaSettings {
        rtol: RTOL,
        atol: ATOL,
        matrix,
        id: vec![1.0; 2 * n],
        ..IdaSettings::default()
    };
    // Stores the trajectory at every step, as a solution object does.
    let (mut ts, mut ys, mut yps) = (Vec::new(), Vec::new(), Vec::new());
    let t0 = Instant::now();
    let stats = ida::integrate(
        &mut f,
        0.0,
        &y0,
        &yp0,
        &settings,
        &OutputMode::EveryStep { t_end: T_END },
        &mut |t, y, yp| {
            ts.push(t);
            ys.extend_from_slice(y);
            yps.extend_from_slice(yp);
            true
        },
    )
    .expect("baseline solve");
    let elapsed = t0.elapsed().as_secs_f64();
    let last = ys[ys.len() - 2 * n + n - 1];
    (elapsed, stats, last)
}

/// Argument that makes this program a compile-once child (see the module doc).
const CHILD_FLAG: &str = "--compile-once";

/// One measurement of compiling and initializing a model: seconds of each compile
/// phase, seconds of initialization, and minor page faults of compiling and of
/// initializing.
#[derive(Clone, Copy)]
struct Measured {
    times: PhaseTimes,
    init_s: f64,
    compile_faults: Option<u64>,
    init_faults: Option<u64>,
}

impl Measured {
    /// The fastest of `self` and `later` phase by phase, with the faults of `later`.
    fn fastest(self, later: Measured) -> Measured {
        Measured {
            times: PhaseTimes {
                flatten_s: self.times.flatten_s.min(later.times.flatten_s),
                simplify_s: self.times.simplify_s.min(later.times.simplify_s),
                codegen_s: self.times.codegen_s.min(later.times.codegen_s),
            },
            init_s: self.init_s.min(later.init_s),
            ..later
        }
    }
}

/// Compiles and initializes `model` once, timing each phase and counting page faults.
fn measure(model: &System) -> Result<Measured, multibody::Error> {
    let f0 = minor_faults();
    let ssys = structural_simplify(model)?;
    let times = ssys.statistics().times;
    let f1 = minor_faults();
    let t0 = Instant::now();
    drop(DaeProblem::new(&ssys, &[], (0.0, T_END))?);
    let init_s = t0.elapsed().as_secs_f64();
    let f2 = minor_faults();
    let diff = |a: Option<u64>, b: Option<u64>| Some(b?.saturating_sub(a?));
    Ok(Measured {
        times,
        init_s,
        compile_faults: diff(f0, f1),
        init_faults: diff(f1, f2),
    })
}

/// The child's side: compile a tiny chain first (so code, lazily initialized tables and
/// the symbol table's first block are warm), then build the chain of `n` and compile and
/// initialize it once (`BENCH_WARM=k`: k times, the fastest counting), printing
/// `flatten simplify codegen init compile_faults init_faults` (faults of the last time,
/// `-` where unknown).
fn compile_once(n: usize) -> Result<(), multibody::Error> {
    measure(&chain(10))?;
    let model = chain(n);
    let mut c = measure(&model)?;
    for _ in 1..warm_repetitions().unwrap_or(1) {
        c = c.fastest(measure(&model)?);
    }
    let faults = |f: Option<u64>| f.map_or("-".to_string(), |f| f.to_string());
    println!(
        "{:e} {:e} {:e} {:e} {} {}",
        c.times.flatten_s,
        c.times.simplify_s,
        c.times.codegen_s,
        c.init_s,
        faults(c.compile_faults),
        faults(c.init_faults)
    );
    Ok(())
}

/// `BENCH_WARM=k`: each child compiles its model k times, with glibc told to keep
/// freed memory, and the fastest counts (every size then runs from memory it already
/// faulted in).
fn warm_repetitions() -> Option<usize> {
    std::env::var("BENCH_WARM").ok()?.parse().ok()
}

/// The parent's side: run a compile-once child for `n` and read what it printed.
fn run_child(n: usize) -> Result<Measured, String> {
    let exe = std::env::current_exe().map_err(|e| format!("cannot find this program: {e}"))?;
    let mut child = std::process::Command::new(&exe);
    child.arg(CHILD_FLAG).arg(n.to_string());
    if warm_repetitions().is_some() {
        // Past these thresholds glibc would return freed memory to the kernel.
        child.env(
            "GLIBC_TUNABLES",
            "glibc.malloc.trim_threshold=4294967296:glibc.malloc.mmap_threshold=4294967296",
        );
    }
    let out = child
        .output()
        .map_err(|e| format!("cannot run {}: {e}", exe.display()))?;
    let text = String::from_utf8_lossy(&out.stdout);
    let fields: Vec<&str> = text.split_whitespace().collect();
    let bad = || {
        format!(
            "the compile-once child for N = {n} failed ({}): {}{}",
            out.status,
            text.trim(),
            String::from_utf8_lossy(&out.stderr).trim()
        )
    };
    if !out.status.success() || fields.len() != 6 {
        return Err(bad());
    }
    let secs = |k: usize| fields[k].parse::<f64>().map_err(|_| bad());
    Ok(Measured {
        times: PhaseTimes {
            flatten_s: secs(0)?,
            simplify_s: secs(1)?,
            codegen_s: secs(2)?,
        },
        init_s: secs(3)?,
        compile_faults: fields[4].parse().ok(),
        init_faults: fields[5].parse().ok(),
    })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some(CHILD_FLAG) {
        let n = args
            .get(1)
            .and_then(|a| a.parse().ok())
            .ok_or("--compile-once needs the chain's size")?;
        return Ok(compile_once(n)?);
    }
    let sizes: Vec<usize> = {
        let given: Vec<usize> = args.iter().filter_map(|a| a.parse().ok()).collect();
        if given.is_empty() {
            vec![10, 100, 1000, 10000]
        } else {
            given
        }
    };
    // Per size: n, flatten, simplify, codegen, init and solve seconds (for the growth line).
    let mut rows: Vec<[f64; 6]> = Vec::new();
    // Compile phases and initialization: each measurement is the first compilation of
    // the model in a fresh process (see the module doc); the fastest of several rounds,
    // the sizes interleaved within each round so that a slow spell of this noisy machine
    // hits every size alike.
    // With BENCH_IN_PROCESS set, every round compiles in this process instead (the
    // protocol before, for comparison: the allocator then keeps what small models freed).
    let in_process = std::env::var("BENCH_IN_PROCESS").is_ok();
    let models: Vec<System> = if in_process {
        sizes.iter().map(|&n| chain(n)).collect()
    } else {
        Vec::new()
    };
    let mut best: Vec<Option<Measured>> = vec![None; sizes.len()];
    for _round in 0..COMPILE_ROUNDS {
        for (k, &n) in sizes.iter().enumerate() {
            let c = match models.get(k) {
                Some(model) => measure(model)?,
                None => run_child(n)?,
            };
            best[k] = Some(best[k].map_or(c, |b| b.fastest(c)));
        }
    }
    for (n, measured) in sizes.iter().copied().zip(best) {
        let Measured {
            times,
            init_s,
            compile_faults,
            init_faults,
        } = measured.expect("every round compiles every size");
        let ssys = structural_simplify(&chain(n))?;
        let prob = DaeProblem::new(&ssys, &[], (0.0, T_END))?;
        let choice = if ssys.unknowns().len() <= 24 {
            LinearSolver::Dense
        } else {
            LinearSolver::Sparse
        };
        let opts = SolverOptions {
            rtol: RTOL,
            atol: ATOL,
            linear_solver: choice,
            ..SolverOptions::default()
        };
        let linear = if choice == LinearSolver::Dense {
            IdaMatrix::Dense
        } else {
            IdaMatrix::SparseLu
        };
        let only_ours = std::env::var("BENCH_ONLY_OURS").is_ok();
        // Solves, ours and the baseline's, alternate; the fastest of each counts.
        let mut solve_s = f64::INFINITY;
        let mut sol = None;
        let mut base: Option<(f64, u64, f64)> = None;
        for _ in 0..if only_ours { 1 } else { SOLVE_REPS } {
            let t1 = Instant::now();
            let s = prob.solve(&opts)?;
            solve_s = solve_s.min(t1.elapsed().as_secs_f64());
            sol = Some(s);
            if !only_ours {
                let b = baseline(n, linear);
                base = Some(match base {
                    Some(prev) if prev.0 <= b.0 => prev,
                    _ => b,
                });
            }
        }
        let sol = sol.expect("at least one solve");
        let ours_last = sol.final_value(format!("inertia{n}.phi"))?;
        if std::env::var("BENCH_STATS").is_ok() {
            eprintln!("ours {:?}", sol.statistics());
        }
        let per_n = |f: Option<u64>| {
            f.map_or("null".to_string(), |f| {
                format!("{:.2}", f as f64 / n as f64)
            })
        };
        if only_ours {
            let per = |x: f64| x / n as f64 * 1e6;
            eprintln!(
                "n={n} per element (us): flatten {:.2} simplify {:.2} codegen {:.2} init {:.2} \
                 (page faults per element: compile {}, init {})",
                per(times.flatten_s),
                per(times.simplify_s),
                per(times.codegen_s),
                per(init_s),
                per_n(compile_faults),
                per_n(init_faults),
            );
            continue;
        }
        let (baseline_solve_s, baseline_steps, base_last) = base.expect("solved with the baseline");
        assert!(
            (ours_last - base_last).abs() < 1e-3,
            "the two solutions disagree: {ours_last} vs {base_last}"
        );
        let compile_s = times.flatten_s + times.simplify_s + times.codegen_s;
        rows.push([
            n as f64,
            times.flatten_s,
            times.simplify_s,
            times.codegen_s,
            init_s,
            solve_s,
        ]);
        println!(
            "{{\"n\": {n}, \"flatten_s\": {:.6}, \"simplify_s\": {:.6}, \"codegen_s\": {:.6}, \"init_s\": {init_s:.6}, \"solve_s\": {solve_s:.6}, \"compile_s\": {compile_s:.6}, \"steps\": {}, \"baseline_solve_s\": {baseline_solve_s:.6}, \"baseline_steps\": {baseline_steps}, \"solve_ratio\": {:.3}, \"states\": {}, \"compile_faults_per_n\": {}, \"init_faults_per_n\": {}}}",
            times.flatten_s,
            times.simplify_s,
            times.codegen_s,
            sol.statistics().steps,
            solve_s / baseline_solve_s,
            ssys.states().len(),
            per_n(compile_faults),
            per_n(init_faults),
        );
    }
    print_growth(&rows);
    Ok(())
}

/// One more JSON line: how each phase grew between the two largest sizes, next to the
/// growth of `N log N` over the same step (the target: no phase grows faster).
fn print_growth(rows: &[[f64; 6]]) {
    let mut sorted = rows.to_vec();
    sorted.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let [.., small, large] = sorted.as_slice() else {
        return;
    };
    let nlogn = |n: f64| n * n.ln();
    let ratio = |k: usize| large[k] / small[k];
    println!(
        "{{\"growth_from\": {}, \"growth_to\": {}, \"n_log_n\": {:.2}, \"flatten\": {:.2}, \"simplify\": {:.2}, \"codegen\": {:.2}, \"init\": {:.2}, \"solve\": {:.2}}}",
        small[0],
        large[0],
        nlogn(large[0]) / nlogn(small[0]),
        ratio(1),
        ratio(2),
        ratio(3),
        ratio(4),
        ratio(5),
    );
}
