//! A spherical pendulum: a body on a ball joint whose relative rotation (Cardan angles)
//! is the state, started off the vertical plane so it swings in 3-D.
//!
//! `cargo run --release --example spherical_pendulum` writes `spherical_pendulum.png`.

use multibody::joints::Spherical;
use multibody::parts::BodyShape;
use multibody::prelude::*;
use multibody::world::World;

system! {
    /// The model: a 1 m, 1 kg link on a ball joint with angle states.
    pub fn spherical_pendulum() -> SphericalPendulum {
        name: "spherical_pendulum";
        world = World::default();
        joint = Spherical { state: true };
        link = BodyShape { r: [1.0, 0.0, 0.0], m: 1.0 };
        connect(world.frame_b, joint.frame_a);
        connect(joint.frame_b, link.frame_a);
    }
}

fn main() -> Result<(), multibody::Error> {
    let model = spherical_pendulum();
    let ssys = structural_simplify(&model)?;
    println!("{}", ssys.statistics());
    println!("states: {:?}", ssys.states());
    // Handles of vectors index from 0: `joint.phi[0]` is the variable `joint.phi[1]`.
    let (phi, phi_d) = (model.joint.phi, model.joint.phi_d);
    let sol = DaeProblem::builder(&ssys, (0.0, 5.0))
        .values(&[
            (phi[0], 0.5),
            (phi[1], 0.0),
            (phi[2], -0.3),
            (phi_d[0], 1.0),
        ])
        .build()?
        .solve(&SolverOptions::default())?;
    Figure::new()
        .title("Spherical pendulum")
        .panel(&sol, &model.link.frame_b.r_0.to_array())
        .panel(&sol, &phi.to_array())
        .save("spherical_pendulum.png")?;
    println!("wrote spherical_pendulum.png");
    Ok(())
}
