//! The planar four-bar linkage of the seed tutorial: four bars of length 1.5 m joined by
//! five revolute joints (two at the world, so the linkage can also turn about it), one
//! of them a `RevolutePlanarLoopConstraint` that closes the planar loop, and dampers on
//! the first two joints. Two degrees of freedom, lightly damped; the rhombus folds flat
//! on the way.
//!
//! `cargo run --release --example fourbar` writes `fourbar.png` (angles and angular
//! velocities of j1..j3) and `fourbar.gif` (its animation).

use multibody::joints::{Revolute, RevolutePlanarLoopConstraint};
use multibody::parts::BodyShape;
use multibody::prelude::*;
use multibody::rotational::Damper;
use multibody::world::World;

/// Length of each bar \[m\].
const L: f64 = 1.5;

system! {
    /// The model of the seed tutorial (`j4` closes the loop).
    pub fn fourbar() -> Fourbar {
        name: "fourbar";
        world = World::default();
        j1 = Revolute { axisflange: true };
        j2 = Revolute { axisflange: true };
        j3 = Revolute::default();
        j4 = RevolutePlanarLoopConstraint::default();
        j5 = Revolute::default();
        b1 = BodyShape { m: 1.0, r: [L, 0.0, 0.0], radius: 0.03 };
        b2 = BodyShape { m: 1.0, r: [0.0, L, 0.0], radius: 0.03 };
        b3 = BodyShape { m: 1.0, r: [-L, 0.0, 0.0], radius: 0.03 };
        b4 = BodyShape { m: 1.0, r: [0.0, -L, 0.0], radius: 0.03 };
        damper1 = Damper { d: 0.1 };
        damper2 = Damper { d: 0.1 };
        connect(world.frame_b, j1.frame_a);
        connect(j1.frame_b, b1.frame_a);
        connect(b1.frame_b, j2.frame_a);
        connect(j2.frame_b, b2.frame_a);
        connect(b2.frame_b, j3.frame_a);
        connect(j3.frame_b, b3.frame_a);
        connect(b3.frame_b, j4.frame_a);
        connect(j4.frame_b, b4.frame_a);
        connect(b4.frame_b, j5.frame_a);
        connect(j5.frame_b, world.frame_b);
        connect(j1.axis, damper1.flange_a);
        connect(j1.support, damper1.flange_b);
        connect(j2.axis, damper2.flange_a);
        connect(j2.support, damper2.flange_b);
    }
}

fn main() -> Result<(), multibody::Error> {
    let model = fourbar();
    let ssys = structural_simplify(&model)?;
    println!("{}", ssys.statistics());
    println!("unknowns: {:?}", ssys.unknowns());
    let sol = DaeProblem::builder(&ssys, (0.0, 10.0))
        .value(model.j1.phi, 0.1)
        .build()?
        .solve(&SolverOptions::default().with_output_interval(0.0, 10.0, 0.01))?;
    println!("{:?}", sol.statistics());
    Figure::new()
        .title("Planar four-bar of the tutorial")
        .panel(&sol, &[model.j1.phi, model.j2.phi, model.j3.phi])
        .panel(&sol, &[model.j1.w, model.j2.w, model.j3.w])
        .save("fourbar.png")?;
    println!("wrote fourbar.png");
    let options = RenderOptions {
        camera: [4.0, -1.0, 4.0],
        look_at: [0.0, -1.0, 0.0],
        fov: 60.0,
        times: Some((0..=200).map(|k| 0.05 * k as f64).collect()),
        ..RenderOptions::default()
    };
    render(&model, &sol, "fourbar.gif", &options)?;
    println!("wrote fourbar.gif");
    Ok(())
}
