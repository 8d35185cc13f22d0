//! Rolling wheels against closed forms: a disk on a steady circle with a constant lean
//! (as a root joint and as a contact on a chain of joints), the invariants of a wheel
//! rolling freely, and MSL's wheel set pulled by a force.

#[path = "common/mod.rs"]
mod common;

use multibody::Expr;
use multibody::joints::{Prismatic, Revolute, RollingContact};
use multibody::parts::{Body, RollingWheel};
use multibody::prelude::*;
use multibody::world::World;

const G: f64 = 9.80665;

use common::tight_options as options;

/// The steady circle of a uniform disk (m 1, R 0.5, I_axis = m R^2 / 2, I_long =
/// m R^2 / 4) whose centre runs on a circle of radius rho = 1.5 at speed v, leaning by
/// theta = 0.3 towards its centre: steady when v^2 = g rho^2 tan(theta) / (rho (1 +
/// I_axis / (m R^2)) + I_long / (m R) sin(theta)), with yaw rate v / rho and spin
/// (rho + R sin theta) v / (rho R).
struct SteadyDisk {
    m: f64,
    r: f64,
    rho: f64,
    theta: f64,
    i_axis: f64,
    i_long: f64,
    v: f64,
    omega: f64,
    spin: f64,
}

fn steady_disk() -> SteadyDisk {
    let (m, r, rho, theta): (f64, f64, f64, f64) = (1.0, 0.5, 1.5, 0.3);
    let (i_axis, i_long) = (m * r * r / 2.0, m * r * r / 4.0);
    let v = (G * rho * rho * theta.tan()
        / (rho * (1.0 + i_axis / (m * r * r)) + i_long / (m * r) * theta.sin()))
    .sqrt();
    let omega = v / rho;
    let spin = omega * (rho + r * theta.sin()) / r;
    SteadyDisk {
        m,
        r,
        rho,
        theta,
        i_axis,
        i_long,
        v,
        omega,
        spin,
    }
}

#[test]
fn a_disk_leaning_into_a_circle_rolls_on_it() {
    // The disk as a root joint (see `steady_disk`).
    let SteadyDisk {
        m,
        r,
        rho,
        theta,
        i_axis,
        i_long,
        v,
        omega,
        spin,
    } = steady_disk();
    let model = system! {
        name: "disk";
        world = World { n: [0.0, 0.0, -1.0] };
        wheel = RollingWheel {
            radius: r, m, I_axis: i_axis, I_long: i_long,
            angles_start: [0.0, -theta, 0.0],
            der_angles_start: [omega, 0.0, spin],
        };
    };
    let ssys = structural_simplify(&model).unwrap();
    let period = 2.0 * std::f64::consts::PI / omega;
    let sol = DaeProblem::builder(&ssys, (0.0, period))
        .build()
        .unwrap()
        .solve(&options(period, 40))
        .unwrap();
    // It starts heading along x at speed v.
    let v0 = sol.at("wheel.rollingWheel.v_0[1]", 0.0).unwrap();
    assert!((v0.abs() - v).abs() < 1e-9, "{v0} vs {v}");
    let sign = v0.signum();
    for k in 0..=40 {
        let t = k as f64 * period / 40.0;
        let x = sol.at("wheel.rollingWheel.x", t).unwrap();
        let y = sol.at("wheel.rollingWheel.y", t).unwrap();
        let z = sol.at("wheel.rollingWheel.z", t).unwrap();
        // The circle's centre is on the side the disk leans to (+y).
        let radius = (x * x + (y - rho).powi(2)).sqrt();
        assert!((radius - rho).abs() < 1e-7, "radius {radius} at {t}");
        assert!((z - r * theta.cos()).abs() < 1e-9, "height {z} at {t}");
        let heading = sign * omega * t;
        assert!((x - rho * heading.sin()).abs() < 1e-6, "x {x} at {t}");
    }
}

#[test]
fn a_wheel_rolling_freely_keeps_its_energy() {
    // MSL Examples.Elementary.RollingWheel: a wheel (R 0.3, m 2, I_axis 0.06, I_long
    // 0.12) starts upright at (0.2, 0.2) spinning at 5 rad/s and leaning over at 1 rad/s;
    // it rolls without slip, so its energy stays (9.03399 J), and its path matches an
    // independent quaternion model of the same wheel (to 1e-4).
    let model = system! {
        name: "wheel";
        world = World { n: [0.0, 0.0, -1.0] };
        wheel = RollingWheel {
            radius: 0.3, m: 2.0, I_axis: 0.06, I_long: 0.12,
            x_start: 0.2, y_start: 0.2,
            der_angles_start: [0.0, 1.0, 5.0],
        };
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::builder(&ssys, (0.0, 4.0))
        .build()
        .unwrap()
        .solve(&options(4.0, 400))
        .unwrap();
    let energy = |t: f64| {
        let get = |n: &str| sol.at(n, t).unwrap();
        let v2: f64 = (1..=3)
            .map(|i| get(&format!("wheel.rollingWheel.v_0[{i}]")).powi(2))
            .sum();
        let w: Vec<f64> = (1..=3)
            .map(|i| get(&format!("wheel.body.w_a[{i}]")))
            .collect();
        let rot = 0.12 * w[0] * w[0] + 0.06 * w[1] * w[1] + 0.12 * w[2] * w[2];
        0.5 * 2.0 * v2 + 0.5 * rot + 2.0 * G * get("wheel.rollingWheel.z")
    };
    let e0 = energy(0.0);
    assert!((e0 - 9.03399).abs() < 1e-5, "{e0}");
    for k in 1..=40 {
        let t = 0.1 * k as f64;
        assert!((energy(t) - e0).abs() < 1e-6, "energy {} at {t}", energy(t));
    }
    for (t, x, y, z) in [
        (1.0, 0.700579, -0.709359, 0.242466),
        (2.0, -0.839391, -0.432619, 0.219211),
        (4.0, 0.163003, -2.237614, 0.260848),
    ] {
        let got = [
            sol.at("wheel.rollingWheel.x", t).unwrap(),
            sol.at("wheel.rollingWheel.y", t).unwrap(),
            sol.at("wheel.rollingWheel.z", t).unwrap(),
        ];
        for (g, want) in got.iter().zip([x, y, z]) {
            assert!(
                (g - want).abs() < 1e-4,
                "{got:?} at {t}, want {:?}",
                (x, y, z)
            );
        }
    }
}

/// The force of MSL's RollingWheelSetPulling: (1, 0, 0) N until 1 s, then turning
/// linearly to (0, 2, 0) N at 2 s, resolved in world.
fn pull(t: Expr) -> Vec3 {
    let ramp = t - 1.0;
    Vec3::new(
        if_else(lt(t, 1.0), 1.0, if_else(lt(t, 2.0), 1.0 - ramp, 0.0)),
        if_else(lt(t, 1.0), 0.0, if_else(lt(t, 2.0), 2.0 * ramp, 2.0)),
        0.0,
    )
}

#[test]
fn msl_rolling_wheel_set_pulling() {
    // MSL Examples.Elementary.RollingWheelSetPulling (with a point mass where MSL's body
    // has the default inertia 0.001): a wheel set pulled by a force at a point 0.2 m
    // ahead of its axle, first straight ahead, then turning sideways. Until 1 s it runs
    // straight, x = 0.1 + t^2 / (2 * 3.01); then it turns. Values against the reduced
    // equations of motion (Gibbs-Appell in the forward speed and the yaw rate, checked
    // against a Lagrange-multiplier form in all five coordinates).
    let model = system! {
        name: "pulling";
        world = World { n: [0.0, 0.0, -1.0] };
        wheel_set = multibody::parts::RollingWheelSet {
            R_wheel: 0.1, m_wheel: 0.5, I_wheelAxis: 0.01, I_wheelLong: 0.02, track: 0.5,
            x_start: 0.1, y_start: 0.1,
        };
        body = multibody::parts::Body { m: 0.01, I_11: 0.0, I_22: 0.0, I_33: 0.0, radius: 0.0 };
        ahead = multibody::parts::FixedTranslation { r: [0.2, 0.0, 0.0] };
        force = multibody::forces::WorldForce::default();
        input = multibody::blocks::RealExpression3 { expression: pull };
        connect(ahead.frame_a, wheel_set.frameMiddle);
        connect(ahead.frame_b, body.frame_a);
        connect(force.frame_b, ahead.frame_b);
        connect(input.y, force.force);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::builder(&ssys, (0.0, 3.0))
        .build()
        .unwrap()
        .solve(&options(3.0, 300))
        .unwrap();
    let names = [
        "x",
        "y",
        "phi",
        "theta1",
        "theta2",
        "der_theta1",
        "der_theta2",
    ];
    for (t, want) in [
        (
            1.0,
            [0.266113, 0.1, 0.0, 1.661130, 1.661130, 3.322259, 3.322259],
        ),
        (
            2.0,
            [
                0.712379, 0.136118, 0.286985, 5.436727, 6.871652, 3.225716, 7.498874,
            ],
        ),
        (
            3.0,
            [
                1.049941, 0.710074, 1.776675, 9.079947, 17.963322, 5.829206, 14.690852,
            ],
        ),
    ] {
        for (name, w) in names.iter().zip(want) {
            let got = sol.at(format!("wheel_set.{name}").as_str(), t).unwrap();
            assert!((got - w).abs() < 2e-6, "{name}({t}) = {got}, want {w}");
        }
    }
    let x = sol.at("wheel_set.x", 0.5).unwrap();
    assert!((x - 0.1 - 0.25 / (2.0 * 3.01)).abs() < 1e-9, "{x}");
}

#[test]
fn a_rolling_contact_on_a_chain_of_joints_rolls_on_the_circle() {
    // The disk of the first test, now carried by joints (x, y, z slides, yaw, lean and
    // spin revolutes) with a RollingContact: the same steady circle.
    let SteadyDisk {
        m,
        r,
        rho,
        theta,
        i_axis,
        i_long,
        omega,
        spin,
        ..
    } = steady_disk();
    let model = system! {
        name: "chain_disk";
        world = World { n: [0.0, 0.0, -1.0] };
        px = Prismatic { n: [1.0, 0.0, 0.0] };
        py = Prismatic { n: [0.0, 1.0, 0.0] };
        pz = Prismatic { n: [0.0, 0.0, 1.0], state_priority: -100.0 };
        yaw = Revolute { n: [0.0, 0.0, 1.0] };
        lean = Revolute { n: [1.0, 0.0, 0.0] };
        spin = Revolute { n: [0.0, 1.0, 0.0] };
        wheel = Body { m, I_11: i_long, I_22: i_axis, I_33: i_long };
        contact = RollingContact { radius: r };
        connect(world.frame_b, px.frame_a);
        connect(px.frame_b, py.frame_a);
        connect(py.frame_b, pz.frame_a);
        connect(pz.frame_b, yaw.frame_a);
        connect(yaw.frame_b, lean.frame_a);
        connect(lean.frame_b, spin.frame_a);
        connect(spin.frame_b, wheel.frame_a);
        connect(spin.frame_b, contact.frame_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    let period = 2.0 * std::f64::consts::PI / omega;
    let start = [
        ("px.s", 0.0),
        ("py.s", 0.0),
        ("yaw.phi", 0.0),
        ("lean.phi", -theta),
        ("spin.phi", 0.0),
        ("yaw.w", omega),
        ("lean.w", 0.0),
        ("spin.w", spin),
    ];
    let sol = DaeProblem::new(&ssys, &start, (0.0, period))
        .unwrap()
        .solve(&options(period, 40))
        .unwrap();
    for k in 0..=40 {
        let t = k as f64 * period / 40.0;
        let (x, y, z) = (
            sol.at("px.s", t).unwrap(),
            sol.at("py.s", t).unwrap(),
            sol.at("pz.s", t).unwrap(),
        );
        let radius = (x * x + (y - rho).powi(2)).sqrt();
        assert!((radius - rho).abs() < 1e-7, "radius {radius} at {t}");
        assert!((z - r * theta.cos()).abs() < 1e-9, "height {z} at {t}");
    }
}

#[test]
fn a_wheel_set_driven_by_equal_torques_runs_straight() {
    // Equal torques tau on both wheels (R 0.1, m 0.5, I_axis 0.01; reactions on the
    // axle's support): no turn, and the axle accelerates at 2 tau / (R M) with
    // M = 2 m + 2 I_axis / R^2 = 3 kg, the wheels turning at u / R.
    let tau = 0.3;
    let model = system! {
        name: "driven_set";
        world = World { n: [0.0, 0.0, -1.0] };
        wheel_set = multibody::parts::RollingWheelSet {
            R_wheel: 0.1, m_wheel: 0.5, I_wheelAxis: 0.01, I_wheelLong: 0.02, track: 0.5,
        };
        drive1 = multibody::rotational::Torque { use_support: true };
        drive2 = multibody::rotational::Torque { use_support: true };
        torque = multibody::blocks::Constant { k: tau };
        connect(torque.y, drive1.tau);
        connect(torque.y, drive2.tau);
        connect(drive1.flange, wheel_set.axis1);
        connect(drive2.flange, wheel_set.axis2);
        connect(drive1.support, wheel_set.support);
        connect(drive2.support, wheel_set.support);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::builder(&ssys, (0.0, 2.0))
        .build()
        .unwrap()
        .solve(&options(2.0, 20))
        .unwrap();
    let a = 2.0 * tau / (0.1 * 3.0);
    for k in 1..=20 {
        let t = 0.1 * k as f64;
        let get = |n: &str| sol.at(n, t).unwrap();
        assert!(
            (get("wheel_set.x") - 0.5 * a * t * t).abs() < 1e-8,
            "x at {t}"
        );
        assert!(get("wheel_set.y").abs() < 1e-10 && get("wheel_set.phi").abs() < 1e-10);
        for speed in ["wheel_set.der_theta1", "wheel_set.der_theta2"] {
            assert!((get(speed) - a * t / 0.1).abs() < 1e-7, "{speed} at {t}");
        }
    }
}
