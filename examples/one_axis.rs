//! MSL's one-axis robot test (`Systems.RobotR3.OneAxis`): a motor with its analog
//! current controller drives a 19.5 kg.m2 load through an elastic gearbox with bearing
//! friction, under a cascaded position and speed controller, along a planned 120 degree
//! move; the friction sticks and slips as the load settles. The run terminates half a
//! second after the move, at 1.4981317 s.
//!
//! `cargo run --release --example one_axis` writes `one_axis.png`.

use multibody::prelude::*;
use multibody::robot_r3::OneAxis;

fn main() -> Result<(), multibody::Error> {
    let mut model = System::new("OneAxis");
    model.add("", &OneAxis::default());
    let ssys = structural_simplify(&model)?;
    println!("{}", ssys.statistics());
    println!("states: {:?}", ssys.states());
    let sol = DaeProblem::new(&ssys, &[], (0.0, 1.6))?.solve(&SolverOptions {
        rtol: 1e-8,
        atol: 1e-10,
        ..SolverOptions::default()
    })?;
    let end = sol.terminated().map_or(1.6, |e| e.t);
    if let Some(e) = sol.terminated() {
        println!("terminated at t = {:.7} s: {}", e.t, e.message);
    }
    let friction = "axis.gear.bearingFriction";
    println!(
        "{} events, {} steps; the friction's mode switches at:",
        sol.events().len(),
        sol.statistics().steps
    );
    let mode = format!("{friction}.mode");
    let mut last = f64::NAN;
    for e in sol.events() {
        let m = sol.at(mode.as_str(), (e.t + 1e-9).min(end))?;
        if m != last {
            println!("  t = {:.7} s: mode {m}", e.t);
            last = m;
        }
    }
    Figure::new()
        .title("MSL RobotR3 OneAxis")
        .panel(&sol, &["axis.initializeFlange.phi_flange"])
        .panel(&sol, &["axis.initializeFlange.w_flange"])
        .panel(&sol, &["axis.motor.La.i"])
        .panel(&sol, &["axis.gear.spring.phi_rel"])
        .panel(&sol, &["axis.controller.PI.x"])
        .panel(&sol, &[mode.as_str()])
        .options(PlotOptions {
            columns: 3,
            ..PlotOptions::default()
        })
        .save("one_axis.png")?;
    println!("wrote one_axis.png");
    Ok(())
}
