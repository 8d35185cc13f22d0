//! MSL's `Examples.Loops.EngineV6`: a V6 engine of six cylinders, each a crank, a
//! connecting rod and a piston in a planar loop closed by `RevolutePlanarLoopConstraint`,
//! with MSL's rough gas force (`Examples.Loops.Utilities.GasForce2`), driving a
//! crankshaft with a load inertia of 1 kg m2 and a load torque quadratic in speed: one
//! degree of freedom. Started at 10 rad/s, it runs up.
//!
//! `cargo run --release --example engine_v6` prints the compile and solve times (JSON)
//! and the speed reached, writes `engine_v6.png` and `engine_v6.gif`.

use std::time::Instant;

use multibody::blocks::{CriticalDamping, Init};
use multibody::interfaces::Frame;
use multibody::joints::{Prismatic, Revolute, RevolutePlanarLoopConstraint};
use multibody::parts::{BodyBox, BodyCylinder, FixedRotation, FixedTranslation, RotationType};
use multibody::prelude::*;
use multibody::rotational::{Inertia, QuadraticSpeedDependentTorque, TorqueSensor};
use multibody::translational::PartialCompliant;
use multibody::world::World;

/// Length of the cylinder volume \[m\] (MSL `cylinderTopPosition - (pistonLength +
/// rodLength - crankPinOffset)`).
pub const CYLINDER_LENGTH: f64 = 0.22;
/// Crank radius \[m\] (MSL `crankPinOffset`).
pub const CRANK: f64 = 0.1;
/// Length of the connecting rod \[m\].
pub const ROD: f64 = 0.2;
/// Distance of the cylinder top from the crankshaft \[m\].
pub const TOP: f64 = 0.42;
/// Length of the piston \[m\].
pub const PISTON: f64 = 0.1;
/// Bore \[m\].
pub const BORE: f64 = 0.1;
/// Per cylinder: crank angle offset and inclination of the cylinder \[deg\] (MSL).
pub const CYLINDERS: [(f64, f64); 6] = [
    (-30.0, -30.0),
    (90.0, 30.0),
    (210.0, -30.0),
    (210.0, 30.0),
    (90.0, -30.0),
    (-30.0, 30.0),
];

component! {
    /// MSL `Examples.Loops.Utilities.GasForce2`: a rough approximation of the gas force
    /// in a cylinder of length `L` and bore `d`: the pressure [bar] as polynomials of
    /// the normalized position `x = 1 - s_rel / L`, one pair while compressing
    /// (`v_rel < 0`), another while expanding; the force pushes the flanges apart.
    pub struct GasForce2 {
        /// Length of the cylinder \[m\].
        parameter L: f64 = 0.22;
        /// Diameter of the cylinder \[m\].
        parameter d: f64 = 0.1;
        /// Dead volume \[m3\] (`V = k0 + k1 (1 - x)`).
        parameter k0: f64 = 0.01;
        /// Swept volume factor \[m3\].
        parameter k1: f64 = 1.0;
        /// Gas constant (`p V = k T`) \[J/K\].
        parameter k: f64 = 1.0;
        extends PartialCompliant { flange_a, flange_b, s_rel, f };
        /// Normalized position `1 - s_rel / L`.
        variable x: Real;
        /// Relative speed of the flanges (< 0 compressing) \[m/s\].
        variable v_rel: Real;
        /// Cylinder pressure \[Pa\].
        variable press: Real;
        /// Volume \[m3\].
        variable V: Real;
        /// Temperature \[K\].
        variable T: Real;
        equation {
            x = 1.0 - s_rel / L;
            v_rel = der(s_rel);
            let compressing = if_else(
                lt(x, 0.986061),
                177.4132 * x * x * x * x - 287.2189 * x * x * x + 151.8252 * x * x - 24.9973 * x + 2.4,
                2836360.0 * x * x * x * x - 10569296.0 * x * x * x + 14761814.0 * x * x - 9158505.0 * x + 2129670.0,
            );
            let expanding = if_else(
                gt(x, 0.933),
                -3929704.0 * x * x * x * x + 14748765.0 * x * x * x - 20747000.0 * x * x + 12964477.0 * x - 3036495.0,
                145.930 * x * x * x * x - 131.707 * x * x * x + 17.3438 * x * x + 17.9272 * x + 2.4,
            );
            press = 1e5 * if_else(lt(v_rel, 0.0), compressing, expanding);
            f = -press * PI * d * d / 4.0;
            V = k0 + k1 * (1.0 - x);
            press * V = k * T;
        }
    }
}

/// The piston (MSL `Cylinder.piston`): steel, 0.1 m long, of the bore's diameter.
pub fn piston() -> BodyCylinder {
    BodyCylinder {
        r: [0.0, PISTON, 0.0],
        diameter: Some(BORE),
        ..BodyCylinder::default()
    }
}

/// The connecting rod (MSL `Cylinder.connectingRod`).
pub fn connecting_rod() -> BodyBox {
    BodyBox {
        r: [0.0, ROD, 0.0],
        r_shape: [0.0, -0.02, 0.0],
        width_direction: [1.0, 0.0, 0.0],
        width: Some(0.02),
        height: Some(0.06),
        ..BodyBox::default()
    }
}

/// A journal or the pin of the crankshaft (MSL `crank1`, `crank3`): 0.12 m long, 0.1 m
/// between its frames, of `diameter`.
pub fn crank_cylinder(diameter: f64) -> BodyCylinder {
    BodyCylinder {
        r: [0.1, 0.0, 0.0],
        r_shape: [-0.01, 0.0, 0.0],
        length: Some(0.12),
        diameter: Some(diameter),
        ..BodyCylinder::default()
    }
}

/// A crank web (MSL `crank2`, `crank4`): from the journal to the pin (`y` = the crank
/// radius) or back (`-` it).
pub fn crank_web(y: f64) -> BodyBox {
    BodyBox {
        r: [0.0, y, 0.0],
        width_direction: [1.0, 0.0, 0.0],
        width: Some(0.02),
        height: Some(0.05),
        ..BodyBox::default()
    }
}

/// The bodies of a cylinder with their mass properties: (path of the body inside the
/// cylinder, properties).
pub fn cylinder_bodies() -> [(&'static str, multibody::parts::MassProperties); 6] {
    [
        ("piston.body", piston().mass_properties()),
        ("connecting_rod.body", connecting_rod().mass_properties()),
        ("crank1.body", crank_cylinder(0.05).mass_properties()),
        ("crank2.body", crank_web(CRANK).mass_properties()),
        ("crank3.body", crank_cylinder(0.03).mass_properties()),
        ("crank4.body", crank_web(-CRANK).mass_properties()),
    ]
}

component! {
    /// MSL `Examples.Loops.Utilities.Cylinder`: a piston in an inclined cylinder, its
    /// connecting rod and its part of the crankshaft (crank webs and pin), the loop
    /// closed at the crank pin by `RevolutePlanarLoopConstraint`, the gas force between
    /// the cylinder and the piston. `crank_b` is `crank_a` moved by 0.2 m along x,
    /// `cylinder_b` likewise `cylinder_a`: cylinders are chained.
    pub struct Cylinder {
        /// Inclination of the cylinder about x \[rad\].
        structural inclination: f64 = 0.0;
        /// Offset of the crank angle about x \[rad\].
        structural crank_offset: f64 = 0.0;
        /// The engine block, at this cylinder.
        connector cylinder_a: Frame;
        /// The engine block, at the next cylinder.
        connector cylinder_b: Frame;
        /// The crankshaft, at this cylinder.
        connector crank_a: Frame;
        /// The crankshaft, at the next cylinder.
        connector crank_b: Frame;
        /// The piston.
        component piston: BodyCylinder = piston();
        /// The connecting rod.
        component connecting_rod: BodyBox = connecting_rod();
        /// The wrist pin.
        component b2: Revolute = Revolute { n: [1.0, 0.0, 0.0], ..Revolute::default() };
        /// The crank pin, closing the loop.
        component b1: RevolutePlanarLoopConstraint = RevolutePlanarLoopConstraint { n: [1.0, 0.0, 0.0], ..RevolutePlanarLoopConstraint::default() };
        /// Crankshaft journal.
        component crank1: BodyCylinder = crank_cylinder(0.05);
        /// First crank web.
        component crank2: BodyBox = crank_web(CRANK);
        /// Crank pin.
        component crank3: BodyCylinder = crank_cylinder(0.03);
        /// Second crank web.
        component crank4: BodyBox = crank_web(-CRANK);
        /// To the middle of the crank pin.
        component mid: FixedTranslation = FixedTranslation { r: [0.05, 0.0, 0.0], ..FixedTranslation::default() };
        /// The piston's slide in the cylinder.
        component cylinder: Prismatic = Prismatic { n: [0.0, -1.0, 0.0], axisflange: true, ..Prismatic::default() };
        /// To the next cylinder along the block.
        component mounting: FixedTranslation = FixedTranslation { r: [0.2, 0.0, 0.0], ..FixedTranslation::default() };
        /// The cylinder's axis.
        component cylinder_inclination: FixedRotation = FixedRotation { r: [0.15, 0.0, 0.0], rotation_type: RotationType::TwoAxesVectors, n_y: [0.0, self.inclination.cos(), self.inclination.sin()], ..FixedRotation::default() };
        /// The crank's angle.
        component crank_angle1: FixedRotation = FixedRotation { rotation_type: RotationType::TwoAxesVectors, n_y: [0.0, self.crank_offset.cos(), self.crank_offset.sin()], ..FixedRotation::default() };
        /// Back to the crankshaft's frame.
        component crank_angle2: FixedRotation = FixedRotation { rotation_type: RotationType::TwoAxesVectors, n_y: [0.0, self.crank_offset.cos(), -self.crank_offset.sin()], ..FixedRotation::default() };
        /// The cylinder's top.
        component cylinder_top: FixedTranslation = FixedTranslation { r: [0.0, TOP, 0.0], ..FixedTranslation::default() };
        /// The gas force.
        component gas_force: GasForce2 = GasForce2 { L: CYLINDER_LENGTH, d: BORE, ..GasForce2::default() };
        equation {
            connect(b1.frame_a, mid.frame_b);
            connect(connecting_rod.frame_a, b1.frame_b);
            connect(cylinder.frame_b, piston.frame_b);
            connect(crank1.frame_a, crank_angle1.frame_b);
            connect(b2.frame_a, piston.frame_a);
            connect(connecting_rod.frame_b, b2.frame_b);
            connect(crank4.frame_b, crank_angle2.frame_a);
            connect(cylinder_inclination.frame_b, cylinder_top.frame_a);
            connect(crank1.frame_b, crank2.frame_a);
            connect(crank3.frame_b, crank4.frame_a);
            connect(crank3.frame_a, crank2.frame_b);
            connect(crank2.frame_b, mid.frame_a);
            connect(cylinder_top.frame_b, cylinder.frame_a);
            connect(cylinder_inclination.frame_a, cylinder_a);
            connect(mounting.frame_a, cylinder_a);
            connect(mounting.frame_b, cylinder_b);
            connect(crank_angle1.frame_a, crank_a);
            connect(crank_angle2.frame_b, crank_b);
            connect(cylinder.axis, gas_force.flange_b);
            connect(cylinder.support, gas_force.flange_a);
        }
    }
}

/// The engine (MSL `EngineV6`): the crankshaft on a bearing along x, six cylinders, the
/// load inertia (1 kg m2, its angle and speed always states) behind a torque sensor,
/// the load torque `-100 (w / 200)^2` N m, and the sensed torque filtered (2nd-order
/// critical damping at 5 Hz, starting steady).
pub fn engine() -> System {
    let mut m = System::new("engine_v6");
    let world = m.add_typed("world", &World::default());
    let bearing = m.add_typed(
        "bearing",
        &Revolute {
            n: [1.0, 0.0, 0.0],
            axisflange: true,
            ..Default::default()
        },
    );
    m.connect_handles(&world.frame_b, &bearing.frame_a);
    let (mut crank, mut block) = (bearing.frame_b, world.frame_b);
    for (k, &(offset, inclination)) in CYLINDERS.iter().enumerate() {
        let c = m.add_typed(
            &format!("cylinder{}", k + 1),
            &Cylinder {
                inclination: inclination.to_radians(),
                crank_offset: offset.to_radians(),
            },
        );
        m.connect_handles(&crank, &c.crank_a);
        m.connect_handles(&block, &c.cylinder_a);
        (crank, block) = (c.crank_b, c.cylinder_b);
    }
    let load = m.add_typed(
        "load",
        &Inertia {
            J: 1.0,
            state_priority: StateSelect::Always.priority(),
            ..Default::default()
        },
    );
    let brake = m.add_typed(
        "load2",
        &QuadraticSpeedDependentTorque {
            tau_nominal: -100.0,
            w_nominal: 200.0,
            ..Default::default()
        },
    );
    let sensor = m.add_typed("torque_sensor", &TorqueSensor::default());
    let filter = m.add_typed(
        "filter",
        &CriticalDamping {
            n: 2,
            f: 5.0,
            init: Init::SteadyState,
            ..Default::default()
        },
    );
    m.connect_handles(&brake.flange, &load.flange_b);
    m.connect_handles(&sensor.flange_b, &load.flange_a);
    m.connect_handles(&sensor.tau, &filter.u);
    m.connect_handles(&sensor.flange_a, &bearing.axis);
    m
}

/// The piston's travel `s` (from the cylinder top) of a cylinder with `offset` and
/// `inclination` \[rad\] at the crank angle `phi`: the slider-crank's closed form.
pub fn piston_travel(phi: f64, offset: f64, inclination: f64) -> f64 {
    let theta = phi + offset - inclination;
    TOP - PISTON - (CRANK * theta.cos() + (ROD * ROD - (CRANK * theta.sin()).powi(2)).sqrt())
}

/// Values by name.
pub type Named = Vec<(String, f64)>;

/// The start: load angle 0 and speed 10 rad/s (MSL), and the pistons' travel as
/// guesses.
pub fn start() -> (Named, Named) {
    let values = vec![("load.phi".to_string(), 0.0), ("load.w".to_string(), 10.0)];
    let guesses = CYLINDERS
        .iter()
        .enumerate()
        .map(|(k, &(offset, inclination))| {
            (
                format!("cylinder{}.cylinder.s", k + 1),
                piston_travel(0.0, offset.to_radians(), inclination.to_radians()),
            )
        })
        .collect();
    (values, guesses)
}

/// Solves the engine compiled as `ssys` from [`start`] over `(0, t_end)`.
pub fn run(
    ssys: &SimplifiedSystem,
    t_end: f64,
    options: &SolverOptions,
) -> Result<Solution, multibody::Error> {
    let (values, guesses) = start();
    let values: Vec<(&str, f64)> = values.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    let guesses: Vec<(&str, f64)> = guesses.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    DaeProblem::new_with_guesses(ssys, &values, &guesses, (0.0, t_end))?.solve(options)
}

#[allow(dead_code)]
fn main() -> Result<(), multibody::Error> {
    let model = engine();
    let t0 = Instant::now();
    let ssys = structural_simplify(&model)?;
    let compile_s = t0.elapsed().as_secs_f64();
    println!("{}", ssys.statistics());
    let t1 = Instant::now();
    let sol = run(&ssys, 1.01, &SolverOptions::default())?;
    let solve_s = t1.elapsed().as_secs_f64();
    println!(
        "{{\"compile_s\": {compile_s:.4}, \"solve_s\": {solve_s:.4}, \"steps\": {}, \"events\": {}, \"speed_rpm_at_1.01_s\": {:.1}}}",
        sol.statistics().steps,
        sol.events().len(),
        sol.final_value("load.w")? * 60.0 / (2.0 * PI)
    );
    Figure::new()
        .title("EngineV6")
        .panel(&sol, &["load.w"])
        .panel(&sol, &["torque_sensor.tau", "filter.y"])
        .save("engine_v6.png")?;
    println!("wrote engine_v6.png");
    let gif = run(
        &ssys,
        0.3,
        &SolverOptions::default().with_output_interval(0.0, 0.3, 0.005),
    )?;
    let options = RenderOptions {
        camera: [1.6, 0.9, 1.4],
        look_at: [0.6, 0.2, 0.0],
        times: Some((0..=60).map(|k| 0.005 * f64::from(k)).collect()),
        ..RenderOptions::default()
    };
    render(&model, &gif, "engine_v6.gif", &options)?;
    println!("wrote engine_v6.gif");
    Ok(())
}
