//! The crane crab of the seed's efficiency table: a trolley that runs freely on a rail,
//! with a load hanging from it on a rigid rope (a pendulum). Started with the load
//! swung out, trolley and load swing against each other about their common centre of
//! mass, at w^2 = g (M + m) / (M l) for small angles (point load, massless rope).
//!
//! `cargo run --release --example crane_crab` writes `crane_crab.png` and
//! `crane_crab.gif`.

use multibody::joints::{Prismatic, Revolute};
use multibody::parts::{Body, FixedTranslation};
use multibody::prelude::*;
use multibody::world::World;

/// Mass of the trolley \[kg\].
pub const M_TROLLEY: f64 = 10.0;
/// Mass of the load \[kg\].
pub const M_LOAD: f64 = 5.0;
/// Length of the rope \[m\].
pub const ROPE: f64 = 1.2;

/// The crane crab: trolley on a prismatic joint along x, the load on a revolute about z.
pub fn crane_crab() -> System {
    system! {
        name: "crane_crab";
        world = World::default();
        rail = Prismatic { n: [1.0, 0.0, 0.0] };
        trolley = Body { m: M_TROLLEY, I_11: 0.0, I_22: 0.0, I_33: 0.0, radius: 0.1 };
        hook = Revolute { n: [0.0, 0.0, 1.0], phi_start: 0.3 };
        rope = FixedTranslation { r: [0.0, -ROPE, 0.0] };
        load = Body { m: M_LOAD, I_11: 0.0, I_22: 0.0, I_33: 0.0, radius: 0.08 };
        connect(world.frame_b, rail.frame_a);
        connect(rail.frame_b, trolley.frame_a);
        connect(rail.frame_b, hook.frame_a);
        connect(hook.frame_b, rope.frame_a);
        connect(rope.frame_b, load.frame_a);
    }
    .into()
}

fn main() -> Result<(), multibody::Error> {
    let model = crane_crab();
    let ssys = structural_simplify(&model)?;
    println!("{}", ssys.statistics());
    let sol = DaeProblem::builder(&ssys, (0.0, 6.0))
        .value("rail.s", 0.0)
        .value("rail.v", 0.0)
        .value("hook.phi", 0.3)
        .value("hook.w", 0.0)
        .build()?
        .solve(&SolverOptions::default())?;
    Figure::new()
        .title("Crane crab")
        .panel(&sol, &["rail.s"])
        .panel(&sol, &["hook.phi"])
        .save("crane_crab.png")?;
    println!("wrote crane_crab.png");
    let options = RenderOptions {
        camera: [0.0, -0.5, 3.5],
        look_at: [0.0, -0.6, 0.0],
        times: Some((0..=60).map(|k| 0.1 * f64::from(k)).collect()),
        ..RenderOptions::default()
    };
    render(&model, &sol, "crane_crab.gif", &options)?;
    println!("wrote crane_crab.gif");
    Ok(())
}
