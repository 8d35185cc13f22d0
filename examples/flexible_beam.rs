//! A flexible beam (FlexibleBodies' beam, seed `001`): the seed's I-profile steel beam,
//! 1.58 m long, as a cantilever. Prints the seed's "classic pitfall" (the static
//! shortening under an axial thrust with 1, 5, 10 and 15 lengthening modes against the
//! equivalent spring), the first bending eigenfrequencies against the closed form, and
//! the tip deflection under a transverse load against `P L^3 / (3 E I)`; then swings
//! the beam as a pendulum with a mass at its end and writes `flexible_beam.png` (the
//! end's deflection).

use multibody::blocks::{Constant3, Sine};
use multibody::forces::WorldForce;
use multibody::joints::Revolute;
use multibody::parts::{Body, FlexibleBeam, clamped_free_root, section_properties};
use multibody::prelude::*;
use multibody::rotational::Position;
use multibody::world::World;
use multibody::{Pole, SteadyStateOptions, linearize, steady_state};

/// The beam clamped to the world at its `frame_a` (no gravity), loaded at its end by
/// `force` (resolved in the world).
pub fn cantilever(beam: FlexibleBeam, force: [f64; 3]) -> System {
    system! {
        name: "cantilever";
        world = World { g: 0.0, ..Default::default() };
        beam = beam;
        load = WorldForce::default();
        value = Constant3 { k: force };
        connect(world.frame_b, beam.frame_a);
        connect(beam.frame_b, load.frame_b);
        connect(value.y, load.force);
    }
    .into()
}

/// The end's displacement `beam.u_b` of `model` (a [`cantilever`] of a critically
/// damped beam) after `t_end`, settled under its load.
pub fn settled_end(model: &System, t_end: f64) -> Result<[f64; 3], multibody::Error> {
    let ssys = structural_simplify(model)?;
    let sol = DaeProblem::new(&ssys, &[], (0.0, t_end))?.solve(&SolverOptions {
        rtol: 1e-9,
        atol: 1e-14,
        ..SolverOptions::default()
    })?;
    let u = |i: usize| sol.final_value(format!("beam.u_b[{i}]").as_str());
    Ok([u(1)?, u(2)?, u(3)?])
}

/// The poles of `model` linearized at its start.
pub fn poles(model: &System) -> Result<Vec<Pole>, multibody::Error> {
    let ssys = structural_simplify(model)?;
    let point = DaeProblem::new(&ssys, &[], (0.0, 1.0))?.operating_point();
    Ok(linearize(&ssys, &point, &[], &[])?.poles())
}

/// The natural frequencies of `model` linearized at its start \[rad/s\], ascending,
/// without the zero ones and each once.
pub fn natural_frequencies(model: &System) -> Result<Vec<f64>, multibody::Error> {
    let mut w: Vec<f64> = poles(model)?
        .iter()
        .map(|p| p.frequency)
        .filter(|w| *w > 1e-6)
        .collect();
    w.sort_by(f64::total_cmp);
    w.dedup_by(|a, b| (*a - *b).abs() < 1e-9 * b.abs());
    Ok(w)
}

/// The bending eigenfrequencies of the cantilever `beam` (no load) \[rad/s\], ascending.
pub fn frequencies(beam: FlexibleBeam) -> Result<Vec<f64>, multibody::Error> {
    natural_frequencies(&cantilever(beam, [0.0; 3]))
}

/// The seed's beam (bending in the xy plane only) with a 0.5 kg mass at its end, on a
/// motor that swings it about z through `phi = pi/4 (1 - cos(pi t))` (a quarter turn
/// and back every 2 s), without gravity.
pub fn swung_arm() -> System {
    let quarter = std::f64::consts::FRAC_PI_4;
    system! {
        name: "flexible_arm";
        world = World { g: 0.0, ..Default::default() };
        hinge = Revolute { axisflange: true, ..Default::default() };
        motor = Position { exact: true, ..Default::default() };
        angle = Sine { amplitude: -quarter, f: 0.5, phase: 0.5 * std::f64::consts::PI, offset: quarter };
        beam = FlexibleBeam { n_bending_xz: 0, ..FlexibleBeam::default() };
        mass = Body { m: 0.5, I_11: 0.0, I_22: 0.0, I_33: 0.0 };
        connect(world.frame_b, hinge.frame_a);
        connect(angle.y, motor.phi_ref);
        connect(motor.flange, hinge.axis);
        connect(hinge.frame_b, beam.frame_a);
        connect(beam.frame_b, mass.frame_a);
    }
    .into()
}

#[allow(dead_code)]
fn main() -> Result<(), multibody::Error> {
    let beam = FlexibleBeam::default();
    let (a, _i_y, i_z) = section_properties(beam.cross_section);
    let (e, l) = (beam.E, beam.l);
    println!(
        "axial thrust of 1 kN: the end's shortening against the equivalent spring F l / (E A)"
    );
    let thrust = -1000.0;
    let spring = thrust * l / (e * a);
    for n in [1, 5, 10, 15] {
        let model = cantilever(
            FlexibleBeam {
                n_lengthening: n,
                n_bending_xy: 0,
                n_bending_xz: 0,
                ..FlexibleBeam::default()
            },
            [thrust, 0.0, 0.0],
        );
        let ssys = structural_simplify(&model)?;
        let point = steady_state(&ssys, &[], &[], &[], &SteadyStateOptions::default())?;
        let names = ssys.unknowns();
        let tip: f64 = (0..n)
            .map(|i| {
                let k = names
                    .iter()
                    .position(|s| s == &format!("beam.q.x[{}]", i + 1))
                    .expect("a modal coordinate");
                // sin((2i - 1) pi / 2) at the end.
                point.u[k] * if i % 2 == 0 { 1.0 } else { -1.0 }
            })
            .sum();
        println!(
            "  {n:2} modes: spring {:.4e} m, beam {:.4e} m, error {:.1} %",
            spring,
            tip,
            100.0 * (1.0 - tip / spring)
        );
    }
    let w = frequencies(FlexibleBeam {
        n_bending_xz: 0,
        damping: 0.0,
        ..FlexibleBeam::default()
    })?;
    let rho_a = beam.rho * a;
    for (n, w) in w.iter().take(3).enumerate() {
        let bl = clamped_free_root(n + 1);
        println!(
            "bending mode {}: {w:.4} rad/s, closed form {:.4}",
            n + 1,
            bl * bl * (e * i_z / (rho_a * l.powi(4))).sqrt()
        );
    }
    // A pendulum: the beam on a revolute joint about z, a 1 kg mass at its end, released
    // horizontal.
    let model: System = system! {
        name: "flexible_pendulum";
        world = World::default();
        hinge = Revolute::default();
        beam = FlexibleBeam { n_bending_xz: 0, ..FlexibleBeam::default() };
        mass = Body { m: 1.0, I_11: 0.0, I_22: 0.0, I_33: 0.0 };
        connect(world.frame_b, hinge.frame_a);
        connect(hinge.frame_b, beam.frame_a);
        connect(beam.frame_b, mass.frame_a);
    }
    .into();
    let ssys = structural_simplify(&model)?;
    let sol = DaeProblem::new(&ssys, &[("hinge.phi", 0.0), ("hinge.w", 0.0)], (0.0, 3.0))?
        .solve(&SolverOptions::default())?;
    Figure::new()
        .title("Flexible pendulum")
        .panel(&sol, &["hinge.phi"])
        .panel(&sol, &["beam.u_b[2]"])
        .save("flexible_beam.png")?;
    println!("wrote flexible_beam.png");
    // An arm: the beam with a 0.5 kg mass at its end, swung by a motor through a
    // quarter turn and back (without gravity), bends visibly (the end lags by up to 5 %
    // of the length).
    let model = swung_arm();
    let ssys = structural_simplify(&model)?;
    let sol = DaeProblem::new(&ssys, &[], (0.0, 4.0))?.solve(&SolverOptions::default())?;
    let options = RenderOptions {
        camera: [0.6, 0.6, 3.5],
        look_at: [0.6, 0.6, 0.0],
        times: Some((0..=80).map(|k| 0.05 * f64::from(k)).collect()),
        ..RenderOptions::default()
    };
    render(&model, &sol, "flexible_beam.gif", &options)?;
    println!("wrote flexible_beam.gif");
    Ok(())
}
