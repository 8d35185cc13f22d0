//! The centrifugal governor of the seed's efficiency table: two flyballs on arms hinged
//! at the top of a vertical shaft that turns at a constant speed; the arms swing out
//! until the balls' weight and their centripetal force balance, at cos(theta) =
//! g / (w^2 L) for point masses on massless arms. Dampers on the hinges let them settle.
//!
//! `cargo run --release --example governor` writes `governor.png` (the arms' angles) and
//! `governor.gif`.

use multibody::blocks::Constant;
use multibody::joints::Revolute;
use multibody::parts::{Body, FixedTranslation};
use multibody::prelude::*;
use multibody::rotational::{Damper, Speed};
use multibody::world::World;

/// Length of the arms \[m\].
pub const L: f64 = 0.3;
/// Speed of the shaft \[rad/s\].
pub const W: f64 = 8.0;

/// The governor: shaft (a revolute joint about the vertical y, driven at `W`), two arms of
/// length `L` hinged at its top about the shaft's z axis (one each way), balls of 1 kg.
pub fn governor() -> System {
    system! {
        name: "governor";
        world = World::default();
        shaft = Revolute { n: [0.0, 1.0, 0.0], axisflange: true };
        drive = Speed { exact: true };
        speed = Constant { k: W };
        top = FixedTranslation { r: [0.0, 0.5, 0.0] };
        hinge1 = Revolute { n: [0.0, 0.0, 1.0], axisflange: true, phi_start: 0.2 };
        hinge2 = Revolute { n: [0.0, 0.0, -1.0], axisflange: true, phi_start: 0.2 };
        arm1 = FixedTranslation { r: [0.0, -L, 0.0] };
        arm2 = FixedTranslation { r: [0.0, -L, 0.0] };
        ball1 = Body { m: 1.0, I_11: 0.0, I_22: 0.0, I_33: 0.0, radius: 0.04 };
        ball2 = Body { m: 1.0, I_11: 0.0, I_22: 0.0, I_33: 0.0, radius: 0.04 };
        damper1 = Damper { d: 0.2 };
        damper2 = Damper { d: 0.2 };
        connect(world.frame_b, shaft.frame_a);
        connect(speed.y, drive.w_ref);
        connect(drive.flange, shaft.axis);
        connect(shaft.frame_b, top.frame_a);
        connect(top.frame_b, hinge1.frame_a);
        connect(top.frame_b, hinge2.frame_a);
        connect(hinge1.frame_b, arm1.frame_a);
        connect(hinge2.frame_b, arm2.frame_a);
        connect(arm1.frame_b, ball1.frame_a);
        connect(arm2.frame_b, ball2.frame_a);
        connect(hinge1.axis, damper1.flange_b);
        connect(hinge1.support, damper1.flange_a);
        connect(hinge2.axis, damper2.flange_b);
        connect(hinge2.support, damper2.flange_a);
    }
    .into()
}

fn main() -> Result<(), multibody::Error> {
    let model = governor();
    let ssys = structural_simplify(&model)?;
    println!("{}", ssys.statistics());
    let sol = DaeProblem::builder(&ssys, (0.0, 20.0))
        .value("shaft.phi", 0.0)
        .value("hinge1.w", 0.0)
        .value("hinge2.w", 0.0)
        .build()?
        .solve(&SolverOptions {
            rtol: 1e-8,
            atol: 1e-10,
            ..SolverOptions::default()
        })?;
    let theta = (9.80665 / (W * W * L)).acos();
    println!(
        "arms at {:.6} and {:.6} rad; cos(theta) = g / (w^2 L) gives {theta:.6}",
        sol.final_value("hinge1.phi")?,
        sol.final_value("hinge2.phi")?
    );
    Figure::new()
        .title("Centrifugal governor")
        .panel(&sol, &["hinge1.phi", "hinge2.phi"])
        .save("governor.png")?;
    println!("wrote governor.png");
    let options = RenderOptions {
        camera: [0.0, 0.6, 2.0],
        look_at: [0.0, 0.3, 0.0],
        times: Some((0..=80).map(|k| 0.05 * f64::from(k)).collect()),
        ..RenderOptions::default()
    };
    render(&model, &sol, "governor.gif", &options)?;
    println!("wrote governor.gif");
    Ok(())
}
