//! MSL's `Examples.Elementary.DoublePendulum`: two boxes on revolute joints, the first
//! joint damped.
//!
//! `cargo run --release --example double_pendulum` writes `double_pendulum.png` and
//! `double_pendulum.gif`.

use multibody::joints::Revolute;
use multibody::parts::BodyBox;
use multibody::prelude::*;
use multibody::rotational::Damper;
use multibody::world::World;

system! {
    /// The model (MSL: boxes of 0.5 m x 0.06 m, damper d = 0.1 on the first joint).
    pub fn double_pendulum() -> DoublePendulum {
        name: "double_pendulum";
        world = World::default();
        revolute1 = Revolute { n: [0.0, 0.0, 1.0], axisflange: true };
        damper = Damper { d: 0.1 };
        box_body1 = BodyBox { r: [0.5, 0.0, 0.0], width: Some(0.06) };
        revolute2 = Revolute { n: [0.0, 0.0, 1.0] };
        box_body2 = BodyBox { r: [0.5, 0.0, 0.0], width: Some(0.06) };
        connect(damper.flange_b, revolute1.axis);
        connect(revolute1.support, damper.flange_a);
        connect(world.frame_b, revolute1.frame_a);
        connect(revolute1.frame_b, box_body1.frame_a);
        connect(box_body1.frame_b, revolute2.frame_a);
        connect(revolute2.frame_b, box_body2.frame_a);
    }
}

fn main() -> Result<(), multibody::Error> {
    let ssys = structural_simplify(&double_pendulum())?;
    println!("{}", ssys.statistics());
    let start = [
        ("revolute1.phi", 0.0),
        ("revolute1.w", 0.0),
        ("revolute2.phi", 0.0),
        ("revolute2.w", 0.0),
    ];
    let sol = DaeProblem::new(&ssys, &start, (0.0, 3.0))?.solve(&SolverOptions::default())?;
    plot_figure(
        &sol,
        &[
            &["revolute1.phi", "revolute2.phi"],
            &["revolute1.w", "revolute2.w"],
        ],
        "double_pendulum.png",
        &PlotOptions::default(),
    )?;
    println!("wrote double_pendulum.png");
    let options = RenderOptions {
        camera: [1.2, 0.3, 3.0],
        look_at: [0.0, -0.4, 0.0],
        times: Some((0..=150).map(|k| 0.02 * k as f64).collect()),
        ..RenderOptions::default()
    };
    render(&double_pendulum(), &sol, "double_pendulum.gif", &options)?;
    println!("wrote double_pendulum.gif");
    Ok(())
}
