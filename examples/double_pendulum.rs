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
    let m = double_pendulum();
    let ssys = structural_simplify(&m)?;
    println!("{}", ssys.statistics());
    let (r1, r2) = (m.revolute1, m.revolute2);
    let sol = DaeProblem::builder(&ssys, (0.0, 3.0))
        .values(&[(r1.phi, 0.0), (r1.w, 0.0), (r2.phi, 0.0), (r2.w, 0.0)])
        .build()?
        .solve(&SolverOptions::default())?;
    Figure::new()
        .title("MSL Examples.Elementary.DoublePendulum")
        .panel(&sol, &[r1.phi, r2.phi])
        .panel(&sol, &[r1.w, r2.w])
        .save("double_pendulum.png")?;
    println!("wrote double_pendulum.png");
    let options = RenderOptions {
        camera: [1.2, 0.3, 3.0],
        look_at: [0.0, -0.4, 0.0],
        times: Some((0..=150).map(|k| 0.02 * k as f64).collect()),
        ..RenderOptions::default()
    };
    render(&m, &sol, "double_pendulum.gif", &options)?;
    println!("wrote double_pendulum.gif");
    Ok(())
}
