//! The spatial four-bar of the seed tutorial closed analytically: the cut-joint
//! version's revolute joints j3, j4, j5 and rev, rev1 replaced by one
//! `UniversalSpherical` rod, whose length constraint is the only loop equation (iterated
//! on the prismatic coordinate `j2.s`).
//!
//! `cargo run --release --example fourbar_analytic` writes `fourbar_analytic.png`
//! (`j2.s`) and `fourbar_analytic.gif` (its animation).

use multibody::joints::{Prismatic, Revolute, UniversalSpherical};
use multibody::parts::{BodyShape, FixedTranslation};
use multibody::prelude::*;
use multibody::world::World;

system! {
    /// The model of the seed tutorial (`fourbar_analytic` there).
    pub fn fourbar_analytic() -> FourbarAnalytic {
        name: "fourbar_analytic";
        world = World::default();
        j1 = Revolute { n: [1.0, 0.0, 0.0], w_start: 5.235987755983, state_priority: 12.0, radius: 0.1 };
        j2 = Prismatic { n: [1.0, 0.0, 0.0], s_start: -0.2 };
        b1 = BodyShape { r: [0.0, 0.5, 0.1], radius: 0.03 };
        b2 = BodyShape { r: [0.0, 0.2, 0.0], radius: 0.03 };
        b3 = FixedTranslation { r: [1.2, 0.0, 0.0], radius: 0.0 };
        joint_us = UniversalSpherical { n1_a: [0.0, 1.0, 0.0], rRod_ia: [-1.0, 0.3, 0.1] };
        connect(j2.frame_b, b2.frame_a);
        connect(j1.frame_b, b1.frame_a);
        connect(j1.frame_a, world.frame_b);
        connect(b1.frame_b, joint_us.frame_b);
        connect(joint_us.frame_a, b2.frame_b);
        connect(b3.frame_a, world.frame_b);
        connect(b3.frame_b, j2.frame_a);
    }
}

fn main() -> Result<(), multibody::Error> {
    let model = fourbar_analytic();
    let ssys = structural_simplify(&model)?;
    println!("{}", ssys.statistics());
    println!("unknowns: {:?}", ssys.unknowns());
    println!("mass matrix diagonal: {:?}", ssys.mass_matrix_diagonal());
    let sol = DaeProblem::new(&ssys, &[], (0.0, 1.4399))?
        .solve(&SolverOptions::default().with_output_interval(0.0, 1.4399, 0.0025))?;
    println!("{:?}", sol.statistics());
    plot(&sol, &[model.j2.s], "fourbar_analytic.png")?;
    println!("wrote fourbar_analytic.png");
    let options = RenderOptions {
        camera: [2.2, 1.2, 2.2],
        look_at: [0.6, 0.2, 0.0],
        times: Some((0..=143).map(|k| 0.01 * k as f64).collect()),
        ..RenderOptions::default()
    };
    render(&model, &sol, "fourbar_analytic.gif", &options)?;
    println!("wrote fourbar_analytic.gif");
    Ok(())
}
