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
    let ssys = structural_simplify(&spherical_pendulum())?;
    println!("{}", ssys.statistics());
    println!("states: {:?}", ssys.states());
    let start = [
        ("joint.phi[1]", 0.5),
        ("joint.phi[2]", 0.0),
        ("joint.phi[3]", -0.3),
        ("joint.phi_d[1]", 1.0),
    ];
    let sol = DaeProblem::new(&ssys, &start, (0.0, 5.0))?.solve(&SolverOptions::default())?;
    plot_figure(
        &sol,
        &[
            &[
                "link.frame_b.r_0[1]",
                "link.frame_b.r_0[2]",
                "link.frame_b.r_0[3]",
            ],
            &["joint.phi[1]", "joint.phi[2]", "joint.phi[3]"],
        ],
        "spherical_pendulum.png",
        &PlotOptions::default(),
    )?;
    println!("wrote spherical_pendulum.png");
    Ok(())
}
