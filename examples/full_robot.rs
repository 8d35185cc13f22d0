//! MSL's six-axis robot (`Systems.RobotR3.FullRobot`): six motors with their current
//! controllers, gearboxes with bearing friction that sticks and slips (elastic on the
//! first three axes), cascaded position and speed controllers, and the arm with a 15 kg
//! load, along a synchronized point-to-point move of all six joints. The run terminates
//! half a second after the move, at 1.8560450 s.
//!
//! `cargo run --release --example full_robot` prints the compile phases and the solve
//! time, and writes `full_robot.png` (joint angles, motor currents, friction modes) and
//! `full_robot.gif` (the arm moving).

use std::time::Instant;

use multibody::prelude::*;
use multibody::robot_r3::FullRobot;

/// The names as `&str`s.
fn as_str(names: &[String]) -> Vec<&str> {
    names.iter().map(String::as_str).collect()
}

fn main() -> Result<(), multibody::Error> {
    let mut model = System::new("FullRobot");
    model.add("", &FullRobot::default());
    let t0 = Instant::now();
    let ssys = structural_simplify(&model)?;
    let compile = t0.elapsed().as_secs_f64();
    println!("{}", ssys.statistics());
    let t0 = Instant::now();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 2.0))?.solve(&SolverOptions {
        rtol: 1e-8,
        atol: 1e-10,
        ..SolverOptions::default()
    })?;
    let solve = t0.elapsed().as_secs_f64();
    let times = ssys.statistics().times;
    println!(
        "{{\"model\": \"FullRobot\", \"states\": {}, \"flatten_s\": {:.6}, \"simplify_s\": {:.6}, \
         \"codegen_s\": {:.6}, \"compile_s\": {compile:.6}, \"solve_s\": {solve:.6}, \
         \"steps\": {}, \"events\": {}}}",
        ssys.states().len(),
        times.flatten_s,
        times.simplify_s,
        times.codegen_s,
        sol.statistics().steps,
        sol.events().len()
    );
    if let Some(e) = sol.terminated() {
        println!("terminated at t = {:.7} s: {}", e.t, e.message);
    }
    let joints: Vec<String> = (1..=6).map(|k| format!("mechanics.r{k}.phi")).collect();
    let currents: Vec<String> = (1..=6).map(|k| format!("axis{k}.motor.La.i")).collect();
    let modes: Vec<String> = (1..=6)
        .map(|k| format!("axis{k}.gear.bearingFriction.mode"))
        .collect();
    Figure::new()
        .title("MSL RobotR3 FullRobot")
        .panel(&sol, &as_str(&joints))
        .panel(&sol, &as_str(&currents))
        .panel(&sol, &as_str(&modes))
        .save("full_robot.png")?;
    println!("wrote full_robot.png");
    let end = sol.terminated().map_or(2.0, |e| e.t);
    let options = RenderOptions {
        camera: [2.2, 1.6, 2.6],
        look_at: [0.0, 0.9, 0.0],
        times: Some((0..=90).map(|k| end * f64::from(k) / 90.0).collect()),
        ..RenderOptions::default()
    };
    render(&model, &sol, "full_robot.gif", &options)?;
    println!("wrote full_robot.gif");
    Ok(())
}
