//! Benchmark: the seed's spatial four-bar closed by a cut joint and by a
//! `UniversalSpherical` assembly, compiled and solved over 0..1.4399 s (rtol 1e-6,
//! atol 1e-8, output every 1 ms as in a plotting run), each repeated and the median
//! taken. The seed saw the assembly about 4x faster in Julia.
//!
//! `cargo run --release --example bench_fourbar` prints one JSON object per line with
//! `model`, `flatten_s`, `simplify_s`, `codegen_s`, `compile_s`, `init_s`, `solve_s`,
//! `steps`, `unknowns`; then a line with `solve_ratio` (cut joint / assembly) and
//! `compile_ratio`.

#[path = "fourbar_analytic.rs"]
#[allow(dead_code)]
mod fourbar_analytic;
#[path = "fourbar_cutjoint.rs"]
#[allow(dead_code)]
mod fourbar_cutjoint;

use std::time::Instant;

use multibody::prelude::*;

const T_END: f64 = 1.4399;
const REPEAT: usize = 7;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Compiles and solves `build()` `REPEAT` times; prints its JSON line and returns the
/// median compile and solve times.
fn run(name: &str, build: fn() -> System) -> Result<(f64, f64), multibody::Error> {
    let (mut flatten, mut simplify, mut codegen, mut init, mut solve) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut steps = 0;
    let mut unknowns = 0;
    for _ in 0..REPEAT {
        let model = build();
        let ssys = structural_simplify(&model)?;
        let times = ssys.statistics().times;
        flatten.push(times.flatten_s);
        simplify.push(times.simplify_s);
        codegen.push(times.codegen_s);
        unknowns = ssys.unknowns().len();
        let t0 = Instant::now();
        let problem = DaeProblem::new(&ssys, &[], (0.0, T_END))?;
        init.push(t0.elapsed().as_secs_f64());
        let options = SolverOptions::default().with_output_interval(0.0, T_END, 0.001);
        let t1 = Instant::now();
        let sol = problem.solve(&options)?;
        solve.push(t1.elapsed().as_secs_f64());
        steps = sol.statistics().steps;
    }
    let (f, s, c) = (median(flatten), median(simplify), median(codegen));
    let (i, v) = (median(init), median(solve));
    println!(
        "{{\"model\": \"{name}\", \"flatten_s\": {f:.6}, \"simplify_s\": {s:.6}, \"codegen_s\": {c:.6}, \"compile_s\": {:.6}, \"init_s\": {i:.6}, \"solve_s\": {v:.6}, \"steps\": {steps}, \"unknowns\": {unknowns}}}",
        f + s + c
    );
    Ok((f + s + c, v))
}

fn main() -> Result<(), multibody::Error> {
    let (cut_compile, cut_solve) = run("fourbar_cutjoint", || {
        fourbar_cutjoint::fourbar_cutjoint().into()
    })?;
    let (us_compile, us_solve) = run("fourbar_analytic", || {
        fourbar_analytic::fourbar_analytic().into()
    })?;
    println!(
        "{{\"solve_ratio\": {:.3}, \"compile_ratio\": {:.3}}}",
        cut_solve / us_solve,
        cut_compile / us_compile
    );
    Ok(())
}
