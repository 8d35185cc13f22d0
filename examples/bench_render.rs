//! Times the rendering of the planar four-bar: 200 frames at 600x600 to a GIF (the
//! simulation is not timed).
//!
//! `cargo run --release --example bench_render` prints one JSON line and writes
//! `bench_render.gif`.

#[path = "fourbar.rs"]
#[allow(dead_code)]
mod fourbar_example;

use std::time::Instant;

use multibody::prelude::*;

fn main() -> Result<(), multibody::Error> {
    let model = fourbar_example::fourbar();
    let ssys = structural_simplify(&model)?;
    let sol = DaeProblem::new(&ssys, &[("j1.phi", 0.1)], (0.0, 10.0))?
        .solve(&SolverOptions::default().with_output_interval(0.0, 10.0, 0.01))?;
    let frames = 200;
    let options = RenderOptions {
        width: 600,
        height: 600,
        camera: [4.0, -1.0, 4.0],
        look_at: [0.0, -1.0, 0.0],
        times: Some((0..frames).map(|k| 0.05 * k as f64).collect()),
        ..RenderOptions::default()
    };
    let start = Instant::now();
    render(&model, &sol, "bench_render.gif", &options)?;
    let seconds = start.elapsed().as_secs_f64();
    let bytes = std::fs::metadata("bench_render.gif").map_or(0, |m| m.len());
    println!(
        "{{\"bench\":\"render_fourbar\",\"frames\":{frames},\"width\":{},\"height\":{},\"seconds\":{seconds:.3},\"ms_per_frame\":{:.2},\"gif_bytes\":{bytes}}}",
        options.width,
        options.height,
        1e3 * seconds / frames as f64
    );
    Ok(())
}
