//! A free body tumbling in the world without gravity, once with Cardan angles and once
//! with a quaternion (the default) as orientation states: the same motion, the
//! quaternion version without the gimbal lock of the angles. The start angular velocity
//! is given as in MSL, by `w_0_start` (resolved in the world).
//!
//! `cargo run --release --example free_body` writes `free_body.png`.

use multibody::parts::{Body, OrientationStates};
use multibody::prelude::*;
use multibody::world::World;

system! {
    /// A body spinning about its intermediate principal axis (the unstable one).
    pub fn free_body(states: OrientationStates) -> FreeBody {
        name: "free_body";
        world = World { g: 0.0 };
        body = Body { m: 1.0, I_11: 0.1, I_22: 0.2, I_33: 0.3, orientation_states: states,
                      w_0_start: [0.05, 2.0, 0.0] };
    }
}

fn main() -> Result<(), multibody::Error> {
    let mut series = Vec::new();
    for states in [OrientationStates::Cardan, OrientationStates::Quaternion] {
        let ssys = structural_simplify(&free_body(states))?;
        println!(
            "{states:?}: {} unknowns {:?}",
            ssys.unknowns().len(),
            ssys.unknowns()
        );
        let sol = DaeProblem::new(&ssys, &[], (0.0, 10.0))?.solve(&SolverOptions {
            rtol: 1e-8,
            atol: 1e-10,
            ..SolverOptions::default()
        })?;
        println!(
            "  w_a(10) = {:?}",
            [
                sol.final_value("body.w_a[1]")?,
                sol.final_value("body.w_a[2]")?,
                sol.final_value("body.w_a[3]")?,
            ]
        );
        series.push(sol);
    }
    plot_figure(
        &series[1],
        &[
            &["body.w_a[1]", "body.w_a[2]", "body.w_a[3]"],
            &["body.q_v[1]", "body.q_v[2]", "body.q_v[3]", "body.q_4"],
        ],
        "free_body.png",
        &PlotOptions::default(),
    )?;
    println!("wrote free_body.png");
    Ok(())
}
