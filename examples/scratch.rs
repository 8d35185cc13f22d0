#[path = "../tests/support/mechanics.rs"]
mod mechanics;
use mechanics::*;
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
    println!("unknowns {:?}", ssys.unknowns());
    let opts = SolverOptions { rtol: 1e-9, atol: 1e-11, output_times: Some((0..=109).map(|k| k as f64 * 0.01).collect()), ..Default::default() };
    let sol = DaeProblem::new(&ssys, &[("j1.phi", 0.1)], (0.0, 1.09)).unwrap().solve(&opts);
    let sol = match sol { Ok(s) => s, Err(e) => { println!("ERR {e}"); return; } };
    let r = [[L,0.,0.],[0.,L,0.],[-L,0.,0.],[0.,-L,0.]];
    let mut total = vec![0.0; sol.t().len()];
    for (k, rr) in r.iter().enumerate() {
        let p = MassProps { m: 1.0, r_cm: [rr[0]/2.0, rr[1]/2.0, rr[2]/2.0], inertia: [[0.001,0.,0.],[0.,0.001,0.],[0.,0.,0.001]] };
        let e = body_energy(&sol, &format!("b{}.body", k+1), p, 9.80665, [0.0,-1.0,0.0]);
        for (t, e) in total.iter_mut().zip(e) { *t += e; }
    }
    let js: Vec<Vec<f64>> = ["j1.phi","j2.phi","j3.phi","j5.phi"].iter().map(|n| sol.get(n).unwrap()).collect();
    for k in (0..sol.t().len()).step_by(10).chain(100..sol.t().len()) { println!("t {:.3} E {:.8} j {:.4} {:.4} {:.4} {:.4}", sol.t()[k], total[k], js[0][k], js[1][k], js[2][k], js[3][k]); }
    println!("{:?}", sol.statistics());
}
