//! MSL's `Examples.Elementary.Pendulum`: a body swinging on a revolute joint with a
//! rotational damper between the joint's support and axis.
//!
//! `cargo run --release --example pendulum` writes `pendulum.png` and `pendulum.gif`.

use multibody::joints::Revolute;
use multibody::parts::Body;
use multibody::prelude::*;
use multibody::rotational::Damper;
use multibody::world::World;

system! {
    /// The model (MSL defaults: n = z, d = 0.1, m = 1, r_CM = {0.5, 0, 0}).
    pub fn pendulum() -> Pendulum {
        name: "pendulum";
        world = World::default();
        rev = Revolute { n: [0.0, 0.0, 1.0], axisflange: true };
        damper = Damper { d: 0.1 };
        body = Body { m: 1.0, r_CM: [0.5, 0.0, 0.0] };
        connect(world.frame_b, rev.frame_a);
        connect(rev.frame_b, body.frame_a);
        connect(damper.flange_b, rev.axis);
        connect(rev.support, damper.flange_a);
    }
}

fn main() -> Result<(), multibody::Error> {
    let model = pendulum();
    let ssys = structural_simplify(&model)?;
    println!("{}", ssys.statistics());
    println!("unknowns: {:?}", ssys.unknowns());
    let sol = DaeProblem::builder(&ssys, (0.0, 5.0))
        .value(model.rev.phi, 0.0)
        .value(model.rev.w, 0.0)
        .build()?
        .solve(&SolverOptions::default())?;
    println!("rev.phi(5) = {}", sol.final_value(model.rev.phi)?);
    Figure::new()
        .title("MSL Examples.Elementary.Pendulum")
        .panel(&sol, &[model.rev.phi])
        .panel(&sol, &[model.rev.w])
        .save("pendulum.png")?;
    println!("wrote pendulum.png");
    let options = RenderOptions {
        camera: [0.8, 0.3, 1.8],
        look_at: [0.0, -0.25, 0.0],
        times: Some((0..=100).map(|k| 0.05 * k as f64).collect()),
        ..RenderOptions::default()
    };
    render(&model, &sol, "pendulum.gif", &options)?;
    println!("wrote pendulum.gif");
    Ok(())
}
