//! The benchmark bicycle of Meijaard, Papadopoulos, Ruina and Schwab (2007), built from
//! the library's bodies, joints and rolling contacts with the paper's Table 1
//! parameters: the rear frame with its rider, carried from the ground by joints (the
//! rear hub's x, y and height, then yaw, lean and pitch); the rear wheel on it; the front
//! frame on the steer axis (tilted back by 18 degrees, trail 0.08 m) and the front
//! wheel; both wheels roll without slip (`RollingContact`), the front one closing the
//! loop through the ground. Lean and steer torques are the model's inputs. (The wheels'
//! discs are shapes for the animation, of negligible density: the wheels' masses are
//! the bodies'.)
//!
//! `cargo run --release --example bicycle` linearizes the bicycle at upright, straight
//! running for speeds from 0 to 10 m/s and writes `bicycle_eigenvalues.png` (the paper's
//! figure: weave from 0.68 m/s, self-stable between 4.29 and 6.02 m/s), then rides it at
//! 4.6 m/s from a lean-rate kick and writes `bicycle.png` and `bicycle.gif` (its first
//! 2.5 s).

use multibody::joints::{Prismatic, Revolute, RollingContact};
use multibody::parts::{Body, BodyCylinder, FixedTranslation};
use multibody::plot::{Panel, Series, plot_panels};
use multibody::prelude::*;
use multibody::rotational::Torque;
use multibody::world::World;
use multibody::{
    DaeProblem, PlotOptions, SimplifyOptions, linearize_in, nalgebra, structural_simplify_with,
};

/// The steer axis's tilt from the vertical, pi / 10 \[rad\].
pub const LAMBDA: f64 = std::f64::consts::PI / 10.0;
/// Radius of the rear wheel \[m\].
pub const R_REAR: f64 = 0.3;
/// Radius of the front wheel \[m\].
pub const R_FRONT: f64 = 0.35;

/// The benchmark bicycle (x forward, y left, z up; gravity 9.81 along -z): the rear
/// frame with its rider is carried by joints from the ground (the rear hub's x, y and
/// height, then yaw, lean and pitch), the wheels turn on revolute joints and roll
/// without slip through `RollingContact`s. Its inputs are the lean torque
/// `lean_torque.tau` (about the heading's x axis, between the ground and the rear
/// frame, as the paper's) and the steer torque `steer_torque.tau` (between the frames,
/// about the steer axis pointing down); simplify it with
/// `SimplifyOptions::open_inputs`.
pub fn bicycle() -> System {
    let (s, c) = (LAMBDA.sin(), LAMBDA.cos());
    system! {
        name: "bicycle";
        world = World { n: [0.0, 0.0, -1.0], g: 9.81 };
        lean = Revolute { n: [1.0, 0.0, 0.0], axisflange: true, state_priority: 50.0, radius: 0.0 };
        rear_spin = Revolute { n: [0.0, 1.0, 0.0], state_priority: 50.0 };
        steer = Revolute { n: [s, 0.0, -c], axisflange: true, state_priority: 60.0 };
        px = Prismatic { n: [1.0, 0.0, 0.0], state_priority: 1.0, width: 0.0 };
        py = Prismatic { n: [0.0, 1.0, 0.0], state_priority: 1.0, width: 0.0 };
        pz = Prismatic { n: [0.0, 0.0, 1.0], state_priority: -100.0, width: 0.0 };
        yaw = Revolute { n: [0.0, 0.0, 1.0], state_priority: 2.0, radius: 0.0 };
        pitch = Revolute { n: [0.0, 1.0, 0.0], state_priority: -100.0, radius: 0.0 };
        front_spin = Revolute { n: [0.0, 1.0, 0.0], state_priority: 10.0 };
        rear_wheel = Body { m: 2.0, I_11: 0.0603, I_22: 0.12, I_33: 0.0603 };
        rear = RollingContact { radius: R_REAR };
        frame = Body {
            m: 85.0, r_CM: [0.3, 0.0, 0.6], I_11: 9.2, I_22: 11.0, I_33: 2.8, I_31: -2.4,
        };
        to_steer = FixedTranslation { r: [1.1, 0.0, -R_REAR] };
        fork = Body {
            m: 4.0, r_CM: [-0.2, 0.0, 0.7], I_11: 0.05892, I_22: 0.06, I_33: 0.00708,
            I_31: 0.00756,
        };
        to_front = FixedTranslation { r: [-0.08, 0.0, R_FRONT] };
        front_wheel = Body { m: 3.0, I_11: 0.1405, I_22: 0.28, I_33: 0.1405 };
        front = RollingContact { radius: R_FRONT };
        rear_disc = BodyCylinder {
            r: [0.0, 0.02, 0.0], r_shape: [0.0, -0.01, 0.0], diameter: Some(2.0 * R_REAR),
            density: 1e-9, color: [0.2, 0.2, 0.2],
        };
        front_disc = BodyCylinder {
            r: [0.0, 0.02, 0.0], r_shape: [0.0, -0.01, 0.0], diameter: Some(2.0 * R_FRONT),
            density: 1e-9, color: [0.2, 0.2, 0.2],
        };
        lean_torque = Torque::default();
        steer_torque = Torque::default();
        connect(world.frame_b, px.frame_a);
        connect(px.frame_b, py.frame_a);
        connect(py.frame_b, pz.frame_a);
        connect(pz.frame_b, yaw.frame_a);
        connect(yaw.frame_b, lean.frame_a);
        connect(lean.frame_b, pitch.frame_a);
        connect(pitch.frame_b, frame.frame_a);
        connect(pitch.frame_b, rear_spin.frame_a);
        connect(rear_spin.frame_b, rear_wheel.frame_a);
        connect(rear_spin.frame_b, rear.frame_a);
        connect(rear_spin.frame_b, rear_disc.frame_a);
        connect(pitch.frame_b, to_steer.frame_a);
        connect(to_steer.frame_b, steer.frame_a);
        connect(steer.frame_b, fork.frame_a);
        connect(steer.frame_b, to_front.frame_a);
        connect(to_front.frame_b, front_spin.frame_a);
        connect(front_spin.frame_b, front_wheel.frame_a);
        connect(front_spin.frame_b, front.frame_a);
        connect(front_spin.frame_b, front_disc.frame_a);
        connect(lean_torque.flange, lean.axis);
        connect(steer_torque.flange, steer.axis);
    }
    .into()
}

/// The states the lean-steer motion is linearized in: lean, steer and their rates first.
pub const STATES: [&str; 10] = [
    "lean.phi",
    "steer.phi",
    "lean.w",
    "steer.w",
    "rear_spin.phi",
    "rear_spin.w",
    "px.s",
    "py.s",
    "yaw.phi",
    "front_spin.phi",
];

/// The start of a straight run at `speed` \[m/s\], upright, with the lean rate
/// `lean_rate` \[rad/s\].
pub fn straight_run(speed: f64, lean_rate: f64) -> Vec<(&'static str, f64)> {
    vec![
        ("px.s", 0.0),
        ("py.s", 0.0),
        ("yaw.phi", 0.0),
        ("lean.phi", 0.0),
        ("rear_spin.phi", 0.0),
        ("steer.phi", 0.0),
        ("front_spin.phi", 0.0),
        ("lean.w", lean_rate),
        ("rear_spin.w", speed / R_REAR),
        ("steer.w", 0.0),
    ]
}

fn main() -> Result<(), multibody::Error> {
    let model = bicycle();
    let options = SimplifyOptions {
        open_inputs: true,
        ..SimplifyOptions::default()
    };
    let ssys = structural_simplify_with(&model, &options)?;
    println!("{}", ssys.statistics());
    println!("states: {:?}", ssys.states());
    println!("inputs: {:?}", ssys.inputs());

    // The eigenvalues of the lean and steer motion against the speed (the paper's
    // figure 3): linearized in upright, straight running, in lean, steer and their rates.
    let speeds: Vec<f64> = (0..=200).map(|k| 0.05 * f64::from(k)).collect();
    let mut re = vec![Vec::new(); 4];
    let mut im = vec![Vec::new(); 4];
    for &v in &speeds {
        let point = DaeProblem::new(&ssys, &straight_run(v, 0.0), (0.0, 1.0))?.operating_point();
        let lin = linearize_in(&ssys, &point, &[], &[], &STATES)?;
        let a = nalgebra::DMatrix::from_fn(4, 4, |i, j| lin.a[(i, j)]);
        let mut e: Vec<_> = a.complex_eigenvalues().iter().copied().collect();
        e.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
        for (k, e) in e.iter().enumerate() {
            re[k].push(e.re);
            im[k].push(e.im.abs());
        }
    }
    let series = |values: &[Vec<f64>], name: &str| -> Vec<Series> {
        values
            .iter()
            .enumerate()
            .map(|(k, y)| Series {
                label: format!("{name} {}", k + 1),
                t: speeds.clone(),
                y: y.clone(),
            })
            .collect()
    };
    let panel = |title: &str, series: Vec<Series>| Panel {
        title: Some(title.into()),
        x_label: "v [m/s]".into(),
        y_label: "[1/s]".into(),
        series,
    };
    plot_panels(
        &[
            panel("real parts of the eigenvalues", series(&re, "Re")),
            panel("imaginary parts", series(&im, "|Im|")),
        ],
        std::path::Path::new("bicycle_eigenvalues.png"),
        &PlotOptions::default(),
    )?;
    println!("wrote bicycle_eigenvalues.png");

    // A ride at 4.6 m/s, inside the self-stable range, from a lean-rate kick.
    let sol =
        DaeProblem::new(&ssys, &straight_run(4.6, 0.5), (0.0, 5.0))?.solve(&SolverOptions {
            rtol: 1e-8,
            atol: 1e-10,
            ..SolverOptions::default()
        })?;
    Figure::new()
        .title("Benchmark bicycle at 4.6 m/s")
        .panel(&sol, &["lean.phi", "steer.phi"])
        .panel(&sol, &["lean.w", "steer.w"])
        .panel(&sol, &["rear_spin.w"])
        .panel(&sol, &["px.s", "py.s"])
        .save("bicycle.png")?;
    println!("wrote bicycle.png");
    let options = RenderOptions {
        camera: [5.5, 10.0, 3.0],
        look_at: [5.5, 0.0, 0.5],
        up: [0.0, 0.0, 1.0],
        grid_level: Some(0.0),
        times: Some((0..=50).map(|k| 0.05 * f64::from(k)).collect()),
        ..RenderOptions::default()
    };
    render(&model, &sol, "bicycle.gif", &options)?;
    println!("wrote bicycle.gif");
    Ok(())
}
