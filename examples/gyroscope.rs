//! The seed's gyroscope accuracy experiment: a heavy symmetric top (a spinning rotor on
//! a ball joint under gravity) simulated with three choices of orientation states:
//! Cardan angles of a good sequence (x, z, y: the two tilts first, the spin about the
//! symmetry axis last, so the middle angle stays small), a quaternion, and Cardan angles
//! of a bad sequence (z, y, x: the spin is the middle angle, which passes +-90 degrees,
//! near gimbal lock, twice per revolution). For each, at tolerances 1e-4 to 1e-10: the
//! error of the symmetry axis against a 1e-12 solution, the drift of the three
//! invariants of the top (energy, angular momentum about the vertical and about the
//! symmetry axis), and the number of steps.
//!
//! `cargo run --release --example gyroscope` prints the table (Markdown), writes
//! `gyroscope.png` (the symmetry axis' tip) and `gyroscope.gif`.

use multibody::joints::Spherical;
use multibody::parts::{Body, OrientationStates};
use multibody::prelude::*;
use multibody::world::World;

/// Mass of the top \[kg\].
pub const MASS: f64 = 1.0;
/// Distance of the centre of mass from the support, along the symmetry axis \[m\].
pub const LENGTH: f64 = 0.1;
/// Moment of inertia about a transverse axis through the support \[kg m2\].
pub const I_TRANSVERSE: f64 = 0.02;
/// Moment of inertia about the symmetry axis \[kg m2\].
pub const I_AXIAL: f64 = 0.015;
/// Spin about the symmetry axis at the start \[rad/s\].
pub const SPIN: f64 = 50.0;
/// Tilt of the symmetry axis from the vertical at the start, about x \[rad\].
pub const TILT: f64 = 0.3;
/// Gravity of the world \[m/s2\].
pub const G: f64 = 9.80665;
/// Simulated time \[s\].
pub const T_END: f64 = 10.0;

/// The three choices of orientation states compared.
pub const CHOICES: [(&str, OrientationStates, [usize; 3]); 3] = [
    ("good Cardan sequence", OrientationStates::Cardan, [1, 3, 2]),
    ("quaternion", OrientationStates::Quaternion, [1, 2, 3]),
    ("bad Cardan sequence", OrientationStates::Cardan, [3, 2, 1]),
];

/// The top: the rotor is the root body (its orientation states as chosen), held at the
/// world's origin by a ball joint; its symmetry axis is its y axis, gravity along -y.
/// Started tilted by `TILT` about x, spinning at `SPIN` about its axis.
pub fn top(states: OrientationStates, sequence: [usize; 3]) -> System {
    let axis = [0.0, TILT.cos(), TILT.sin()];
    let mut m = System::new("gyroscope");
    let world = m.add_typed("world", &World::default());
    let ball = m.add_typed("ball", &Spherical::default());
    let rotor = m.add_typed(
        "rotor",
        &Body {
            m: MASS,
            r_CM: [0.0, LENGTH, 0.0],
            // About the centre of mass: the transverse moment less m l^2.
            I_11: I_TRANSVERSE - MASS * LENGTH * LENGTH,
            I_22: I_AXIAL,
            I_33: I_TRANSVERSE - MASS * LENGTH * LENGTH,
            orientation_states: states,
            sequence_angle_states: sequence,
            angles_start: [TILT, 0.0, 0.0],
            sequence_start: [1, 2, 3],
            angles_fixed: true,
            w_0_start: axis.map(|a| SPIN * a),
            w_0_fixed: true,
            ..Default::default()
        },
    );
    m.connect_handles(&world.frame_b, &ball.frame_a);
    m.connect_handles(&ball.frame_b, &rotor.frame_a);
    m
}

/// The symmetry axis (the rotor's y axis) resolved in the world at every point of `sol`.
pub fn axis(sol: &Solution) -> Vec<[f64; 3]> {
    let row: Vec<Vec<f64>> = (1..=3)
        .map(|j| {
            sol.get(format!("rotor.frame_a.R.T[2,{j}]").as_str())
                .unwrap()
        })
        .collect();
    (0..sol.t().len())
        .map(|k| [row[0][k], row[1][k], row[2][k]])
        .collect()
}

/// The top's invariants at every point of `sol`: energy \[J\], angular momentum about
/// the vertical and about the symmetry axis \[kg m2/s\].
pub fn invariants(sol: &Solution) -> Vec<[f64; 3]> {
    let w: Vec<Vec<f64>> = (1..=3)
        .map(|i| sol.get(format!("rotor.w_a[{i}]").as_str()).unwrap())
        .collect();
    let axes = axis(sol);
    // The vertical (world y) resolved in the rotor: the second column of its T.
    let up: Vec<Vec<f64>> = (1..=3)
        .map(|i| {
            sol.get(format!("rotor.frame_a.R.T[{i},2]").as_str())
                .unwrap()
        })
        .collect();
    (0..sol.t().len())
        .map(|k| {
            let (wx, wy, wz) = (w[0][k], w[1][k], w[2][k]);
            // Inertia about the support in the rotor's axes: diag(A, C, A).
            let l = [I_TRANSVERSE * wx, I_AXIAL * wy, I_TRANSVERSE * wz];
            let energy = 0.5 * (l[0] * wx + l[1] * wy + l[2] * wz) + MASS * G * LENGTH * axes[k][1];
            let vertical = l[0] * up[0][k] + l[1] * up[1][k] + l[2] * up[2][k];
            [energy, vertical, l[1]]
        })
        .collect()
}

/// One row of the table: the largest distance of the axis from the reference's at the
/// output times, the largest drift of each invariant, and the steps.
pub struct Row {
    /// Largest distance of the symmetry axis (a unit vector) from the reference's.
    pub error: f64,
    /// Largest change of energy, angular momentum about the vertical and about the
    /// symmetry axis from their start values.
    pub drift: [f64; 3],
    /// Integration steps.
    pub steps: u64,
}

/// Output times of the comparison: every 10 ms.
pub fn output_times() -> Vec<f64> {
    (1..=(T_END * 100.0) as usize)
        .map(|k| k as f64 * 0.01)
        .collect()
}

/// Solves the top of `ssys` at tolerance `rtol` (atol `rtol / 100`) with outputs every
/// 10 ms.
pub fn solve(ssys: &SimplifiedSystem, rtol: f64) -> Result<Solution, multibody::Error> {
    DaeProblem::new(ssys, &[], (0.0, T_END))?.solve(&SolverOptions {
        rtol,
        atol: rtol * 1e-2,
        output_times: Some(output_times()),
        max_steps: 5_000_000,
        ..SolverOptions::default()
    })
}

/// The row of `sol` against the reference axis `reference`.
pub fn row(sol: &Solution, reference: &[[f64; 3]]) -> Row {
    let axes = axis(sol);
    let error = axes
        .iter()
        .zip(reference)
        .map(|(a, b)| {
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
        })
        .fold(0.0, f64::max);
    let inv = invariants(sol);
    let mut drift = [0.0f64; 3];
    for v in &inv {
        for i in 0..3 {
            drift[i] = drift[i].max((v[i] - inv[0][i]).abs());
        }
    }
    Row {
        error,
        drift,
        steps: sol.statistics().steps,
    }
}

#[allow(dead_code)]
fn main() -> Result<(), multibody::Error> {
    let tolerances = [1e-4, 1e-6, 1e-8, 1e-10];
    let compiled: Vec<SimplifiedSystem> = CHOICES
        .iter()
        .map(|(_, states, sequence)| structural_simplify(&top(*states, *sequence)))
        .collect::<Result<_, _>>()?;
    // The reference: the quaternion at 1e-12.
    let reference = solve(&compiled[1], 1e-12)?;
    let reference_axis = axis(&reference);
    println!(
        "| rtol | {} | {} | {} |",
        CHOICES[0].0, CHOICES[1].0, CHOICES[2].0
    );
    println!("|---|---|---|---|");
    for rtol in tolerances {
        let cells: Vec<String> = compiled
            .iter()
            .map(|ssys| match solve(ssys, rtol) {
                Ok(sol) => {
                    let r = row(&sol, &reference_axis);
                    format!(
                        "error {:.1e}, drift E {:.1e} / L_v {:.1e} / L_s {:.1e}, {} steps",
                        r.error, r.drift[0], r.drift[1], r.drift[2], r.steps
                    )
                }
                Err(e) => format!("failed: {e}"),
            })
            .collect();
        println!(
            "| {rtol:.0e} | {} | {} | {} |",
            cells[0], cells[1], cells[2]
        );
    }
    Figure::new()
        .title("Gyroscope: the symmetry axis (quaternion, rtol 1e-12)")
        .panel(
            &reference,
            &["rotor.frame_a.R.T[2,1]", "rotor.frame_a.R.T[2,3]"],
        )
        .save("gyroscope.png")?;
    println!("wrote gyroscope.png");
    let options = RenderOptions {
        camera: [0.4, 0.3, 0.6],
        look_at: [0.0, 0.05, 0.0],
        times: Some((0..=100).map(|k| 0.02 * f64::from(k)).collect()),
        ..RenderOptions::default()
    };
    render(
        &top(CHOICES[1].1, CHOICES[1].2),
        &reference,
        "gyroscope.gif",
        &options,
    )?;
    println!("wrote gyroscope.gif");
    Ok(())
}
