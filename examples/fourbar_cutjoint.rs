//! The spatial four-bar of the seed tutorial with a cut joint: six revolute joints, one
//! prismatic joint and four bodies; `j5` (`iscut`) closes the loop with the three
//! orientation residues instead of propagating an orientation. `j1` carries the higher
//! state priority: its angle alone determines the configuration everywhere.
//!
//! `cargo run --release --example fourbar_cutjoint` writes `fourbar_cutjoint.png`
//! (`j2.s`, the prismatic coordinate) and `fourbar_cutjoint.gif` (its animation).

use multibody::joints::{Prismatic, Revolute};
use multibody::parts::{BodyShape, FixedTranslation};
use multibody::prelude::*;
use multibody::world::World;

/// The model of the seed tutorial (`fourbar2` there).
pub fn fourbar_cutjoint() -> Model<Fourbar2> {
    fourbar_with_cut(Some("j5"))
}

system! {
    /// The same mechanism with the joint named `cut` (`j2`, `j3`, `j4`, `j5`, `rev`,
    /// `rev1`) as its cut joint, or with none (the loop is then broken at a connection).
    pub fn fourbar_with_cut(cut: Option<&str>) -> Fourbar2 {
        name: "fourbar2";
        world = World::default();
        j1 = Revolute { n: [1.0, 0.0, 0.0], w_start: 5.235987755982989, state_priority: 10.0, radius: 0.1 };
        j2 = Prismatic { n: [1.0, 0.0, 0.0], s_start: -0.2, iscut: cut == Some("j2") };
        b1 = BodyShape { r: [0.0, 0.5, 0.1], radius: 0.03 };
        b2 = BodyShape { r: [0.0, 0.2, 0.0], radius: 0.03 };
        b3 = BodyShape { r: [-1.0, 0.3, 0.1], radius: 0.03 };
        rev = Revolute { n: [0.0, 1.0, 0.0], iscut: cut == Some("rev") };
        rev1 = Revolute { iscut: cut == Some("rev1") };
        j3 = Revolute { n: [1.0, 0.0, 0.0], iscut: cut == Some("j3") };
        j4 = Revolute { n: [0.0, 1.0, 0.0], iscut: cut == Some("j4") };
        j5 = Revolute { n: [0.0, 0.0, 1.0], iscut: cut == Some("j5") };
        b0 = FixedTranslation { r: [1.2, 0.0, 0.0], radius: 0.0 };
        connect(j2.frame_b, b2.frame_a);
        connect(j1.frame_b, b1.frame_a);
        connect(rev.frame_a, b2.frame_b);
        connect(rev.frame_b, rev1.frame_a);
        connect(rev1.frame_b, b3.frame_a);
        connect(world.frame_b, j1.frame_a);
        connect(b1.frame_b, j3.frame_a);
        connect(j3.frame_b, j4.frame_a);
        connect(j4.frame_b, j5.frame_a);
        connect(j5.frame_b, b3.frame_b);
        connect(b0.frame_a, world.frame_b);
        connect(b0.frame_b, j2.frame_a);
    }
}

fn main() -> Result<(), multibody::Error> {
    let model = fourbar_cutjoint();
    let ssys = structural_simplify(&model)?;
    println!("{}", ssys.statistics());
    println!("unknowns: {:?}", ssys.unknowns());
    let sol = DaeProblem::new(&ssys, &[], (0.0, 1.4399))?
        .solve(&SolverOptions::default().with_output_interval(0.0, 1.4399, 0.0025))?;
    println!("{:?}", sol.statistics());
    plot(&sol, &[model.j2.s], "fourbar_cutjoint.png")?;
    println!("wrote fourbar_cutjoint.png");
    let options = RenderOptions {
        camera: [2.2, 1.2, 2.2],
        look_at: [0.6, 0.2, 0.0],
        times: Some((0..=143).map(|k| 0.01 * k as f64).collect()),
        ..RenderOptions::default()
    };
    render(&model, &sol, "fourbar_cutjoint.gif", &options)?;
    println!("wrote fourbar_cutjoint.gif");
    Ok(())
}
