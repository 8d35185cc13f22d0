use multibody::joints::{Revolute, RevolutePlanarLoopConstraint};
use multibody::parts::BodyShape;
use multibody::prelude::*;
use multibody::rotational::Damper;
use multibody::world::World;
const L: f64 = 1.5;
fn main() {
    let m = system! {
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
        damper1 = Damper { d: 0.0 };
        damper2 = Damper { d: 0.0 };
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
    };
    let ssys = structural_simplify(&m).unwrap();
    for w in ssys.warnings() { println!("W: {w}\n"); }
    println!("{}", ssys.statistics());
}
