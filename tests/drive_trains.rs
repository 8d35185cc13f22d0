//! Drive trains on moving bodies (Mounting1D, Rotor1D, BevelGear1D) and the ideal gear
//! between two shafts (GearConstraint), against closed forms and the conservation of
//! angular momentum.

#[path = "common/mod.rs"]
mod common;

use std::f64::consts::PI;

use multibody::blocks::{Constant, RealExpression3, Sine};
use multibody::joints::{GearConstraint, Revolute};
use multibody::parts::{BevelGear1D, Body, BodyCylinder, Mounting1D, Rotor1D};
use multibody::prelude::*;
use multibody::rotational::{Speed, Torque};
use multibody::world::World;

use common::tight_options as tight;

#[test]
fn a_motor_on_a_free_carrier_turns_it_backwards() {
    // A motor torque sin(2 pi t) between a rotor (J about x, Rotor1D) and its housing
    // (Mounting1D) on a carrier free to turn about x (inertia I, which includes the
    // rotor's, as Rotor1D asks). The rotor's absolute speed is int(tau) / J, the
    // carrier's -int(tau) / (I - J), so the angular momentum about x, I w_c + J w, stays
    // 0, w being the rotor's speed relative to the carrier, int(tau) (1/J + 1/(I - J)),
    // with int(tau) = (1 - cos 2 pi t) / (2 pi).
    let (j, i) = (0.5, 3.0);
    let model = system! {
        name: "free_carrier";
        world = World { g: 0.0 };
        joint = Revolute { n: [1.0, 0.0, 0.0], w_start: 0.0 };
        carrier = Body { m: 1.0, I_11: i, I_22: 1.0, I_33: 1.0 };
        rotor = Rotor1D { J: j, n: [1.0, 0.0, 0.0] };
        mounting = Mounting1D { n: [1.0, 0.0, 0.0] };
        motor = Torque { use_support: true };
        sine = Sine { amplitude: 1.0, f: 1.0 };
        connect(world.frame_b, joint.frame_a);
        connect(joint.frame_b, carrier.frame_a);
        connect(joint.frame_b, rotor.frame_a);
        connect(joint.frame_b, mounting.frame_a);
        connect(sine.y, motor.tau);
        connect(motor.flange, rotor.flange_a);
        connect(motor.support, mounting.flange_b);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::builder(&ssys, (0.0, 1.5))
        .value(model.joint.phi, 0.0)
        .value(model.joint.w, 0.0)
        .value(model.rotor.phi, 0.0)
        .value(model.rotor.w, 0.0)
        .build()
        .unwrap()
        .solve(&tight(1.5, 30))
        .unwrap();
    for t in [0.3, 0.8, 1.5] {
        let integral = (1.0 - (2.0 * PI * t).cos()) / (2.0 * PI);
        let carrier = sol.at("joint.w", t).unwrap();
        let rotor = sol.at("rotor.w", t).unwrap();
        assert!(
            (carrier + integral / (i - j)).abs() < 1e-8,
            "carrier {carrier} at {t}"
        );
        assert!(
            (rotor - integral * (1.0 / j + 1.0 / (i - j))).abs() < 1e-8,
            "rotor {rotor} at {t}"
        );
        assert!((i * carrier + j * rotor).abs() < 1e-8, "momentum at {t}");
    }
}

/// A carrier turning about z at `omega`, with a rotor of inertia `j` spinning about x at
/// `w`: as a Rotor1D, or (`rigid`) as a body on a revolute joint.
fn spinning_on_a_turntable(j: f64, w: f64, omega: f64, rigid: bool) -> (f64, f64) {
    let mut model: System = system! {
        name: "turntable";
        world = World { g: 0.0 };
        table = Revolute { n: [0.0, 0.0, 1.0], axisflange: true };
        drive = Speed { exact: true };
        rate = Constant { k: omega };
        connect(world.frame_b, table.frame_a);
        connect(rate.y, drive.w_ref);
        connect(drive.flange, table.axis);
    }
    .into();
    if rigid {
        model.add(
            "spin",
            &Revolute {
                n: [1.0, 0.0, 0.0],
                w_start: w,
                ..Revolute::default()
            },
        );
        model.add(
            "rotor",
            &Body {
                m: 0.0,
                I_11: j,
                I_22: 0.0,
                I_33: 0.0,
                ..Body::default()
            },
        );
        model.connect("table.frame_b", "spin.frame_a");
        model.connect("spin.frame_b", "rotor.frame_a");
    } else {
        model.add(
            "rotor",
            &Rotor1D {
                J: j,
                n: [1.0, 0.0, 0.0],
                w_start: w,
                ..Rotor1D::default()
            },
        );
        model.connect("table.frame_b", "rotor.frame_a");
    }
    let ssys = structural_simplify(&model).unwrap();
    let speed = if rigid { "spin.w" } else { "rotor.w" };
    let sol = DaeProblem::builder(&ssys, (0.0, 1.0))
        .value(speed, w)
        .build()
        .unwrap()
        .solve(&tight(1.0, 10))
        .unwrap();
    (
        sol.at("table.frame_b.t[2]", 0.7).unwrap(),
        sol.at(speed, 0.7).unwrap(),
    )
}

#[test]
fn a_rotor_on_a_turntable_has_the_gyroscopic_torque_of_a_rigid_one() {
    // The carrier turns at omega about z, the rotor spins at w about x: its angular
    // momentum j w x turns with the carrier, which takes the torque omega z x j w x =
    // j w omega y from the table's joint (the joint's cut torque at frame_b is its
    // negative). A rigid body on a revolute joint gives the same.
    let (j, w, omega) = (0.2, 10.0, 3.0);
    let (t_rotor, w_rotor) = spinning_on_a_turntable(j, w, omega, false);
    let (t_rigid, w_rigid) = spinning_on_a_turntable(j, w, omega, true);
    assert!((t_rotor + j * w * omega).abs() < 1e-8, "{t_rotor}");
    assert!((t_rigid - t_rotor).abs() < 1e-8, "{t_rigid} vs {t_rotor}");
    assert!((w_rotor - w).abs() < 1e-9 && (w_rigid - w).abs() < 1e-9);
}

#[test]
fn a_bevel_gear_on_a_free_carrier_keeps_its_ratio_and_the_angular_momentum() {
    // A motor on a carrier free to turn about z drives rotor a (about x) and, through a
    // bevel gear of ratio 2, rotor b (about z). Nothing outside acts about z: the
    // carrier's momentum (its inertia includes rotor b's) and rotor b's relative spin
    // cancel, I w_c + J_b w_b = 0, while w_a = 2 w_b.
    let (i, j_a, j_b) = (4.0, 0.3, 0.7);
    let model = system! {
        name: "bevel";
        world = World { g: 0.0 };
        joint = Revolute { n: [0.0, 0.0, 1.0] };
        carrier = Body { m: 1.0, I_11: 1.0, I_22: 1.0, I_33: i };
        mounting = Mounting1D { n: [1.0, 0.0, 0.0] };
        motor = Torque { use_support: true };
        sine = Sine { amplitude: 2.0, f: 0.5 };
        rotor_a = Rotor1D { J: j_a, n: [1.0, 0.0, 0.0] };
        gear = BevelGear1D { ratio: 2.0, n_a: [1.0, 0.0, 0.0], n_b: [0.0, 0.0, 1.0] };
        rotor_b = Rotor1D { J: j_b, n: [0.0, 0.0, 1.0] };
        connect(world.frame_b, joint.frame_a);
        connect(joint.frame_b, carrier.frame_a);
        connect(joint.frame_b, mounting.frame_a);
        connect(joint.frame_b, rotor_a.frame_a);
        connect(joint.frame_b, gear.frame_a);
        connect(joint.frame_b, rotor_b.frame_a);
        connect(sine.y, motor.tau);
        connect(motor.support, mounting.flange_b);
        connect(motor.flange, rotor_a.flange_a);
        connect(rotor_a.flange_b, gear.flange_a);
        connect(gear.flange_b, rotor_b.flange_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::builder(&ssys, (0.0, 2.0))
        .value(model.joint.phi, 0.0)
        .value(model.joint.w, 0.0)
        .value(model.rotor_a.phi, 0.0)
        .value(model.rotor_a.w, 0.0)
        .build()
        .unwrap()
        .solve(&tight(2.0, 20))
        .unwrap();
    let mut moved = 0.0f64;
    for k in 1..=20 {
        let t = 0.1 * k as f64;
        let (w_c, w_a, w_b) = (
            sol.at("joint.w", t).unwrap(),
            sol.at("rotor_a.w", t).unwrap(),
            sol.at("rotor_b.w", t).unwrap(),
        );
        assert!((w_a - 2.0 * w_b).abs() < 1e-9, "ratio at {t}");
        assert!(
            (i * w_c + j_b * w_b).abs() < 1e-8,
            "momentum at {t}: {w_c} {w_b}"
        );
        moved = moved.max(w_c.abs());
    }
    assert!(moved > 0.1, "the carrier turns: {moved}");
}

/// The torque of MSL's GearConstraint example: 2 sin(2 pi t) about x.
fn drive(t: Expr) -> Vec3 {
    Vec3::new(2.0 * sin(2.0 * PI * t), 0.0, 0.0)
}

#[test]
fn msl_gear_constraint_example() {
    // MSL Examples.Rotational3DEffects.GearConstraint: a torque 2 sin(2 pi t) on cylinder
    // 1 (shaft a, about x) geared 10:1 to cylinder 2 (shaft b): J_eff = J1 + J2 / 100,
    // w_a = 2 (1 - cos 2 pi t) / (2 pi J_eff), phi_b = phi_a / 10; beside it the same
    // drive train in 1-D. No power flows into the gear.
    let model = system! {
        name: "gear_constraint";
        world = World { g: 0.0 };
        gear = GearConstraint { ratio: 10.0, check_total_power: true };
        cyl1 = BodyCylinder { r: [0.4, 0.0, 0.0], diameter: Some(0.1) };
        cyl2 = BodyCylinder { r: [0.4, 0.0, 0.0], diameter: Some(0.2) };
        torque = multibody::forces::WorldTorque::default();
        input = RealExpression3 { expression: drive };
        connect(world.frame_b, gear.bearing);
        connect(cyl1.frame_b, gear.frame_a);
        connect(gear.frame_b, cyl2.frame_a);
        connect(torque.frame_b, cyl1.frame_a);
        connect(input.y, torque.torque);
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::builder(&ssys, (0.0, 5.0))
        .value(model.gear.phi_b, 0.0)
        .value(model.gear.w_b, 0.0)
        .build()
        .unwrap()
        .solve(&tight(5.0, 500))
        .unwrap();
    let j1 = 7700.0 * PI * 0.05f64.powi(2) * 0.4 * 0.05f64.powi(2) / 2.0;
    let j2 = 7700.0 * PI * 0.1f64.powi(2) * 0.4 * 0.1f64.powi(2) / 2.0;
    let j_eff = j1 + j2 / 100.0;
    for t in [0.25, 0.5, 1.0, 3.3, 5.0] {
        let phi_a = 2.0 * (t - (2.0 * PI * t).sin() / (2.0 * PI)) / (2.0 * PI * j_eff);
        let phi_b = sol.at("gear.phi_b", t).unwrap();
        assert!(
            (phi_b - phi_a / 10.0).abs() < 1e-7 * phi_a.max(1.0),
            "phi_b({t}) = {phi_b}"
        );
        let power = sol.at("gear.totalPower", t).unwrap();
        assert!(power.abs() < 1e-7, "power {power} at {t}");
    }
    assert!((j_eff - 0.0350758820).abs() < 1e-9, "{j_eff}");
}

#[test]
fn msl_gyroscopic_effects() {
    // MSL Examples.Rotational3DEffects.GyroscopicEffects: a heavy top, a rod on a
    // spherical joint with a cylinder spinning at 10 rad/s on a 45-degree bracket: once
    // with the spinning cylinder as a body on a revolute joint, once as a rigid cylinder
    // with a Rotor1D for its spin. Both move alike, and as an independent quaternion
    // model of the top (cylinder 2's frame at t = 1 and 5 s; Multibody.jl's port asserts
    // the same t = 5 position to about 1e-7).
    let model = system! {
        name: "gyroscopic";
        world = World::default();
        spherical1 = multibody::joints::Spherical { state: true };
        cyl1 = BodyCylinder { r: [0.25, 0.0, 0.0], diameter: Some(0.05) };
        rotation1 = multibody::parts::FixedRotation { n: [0.0, 1.0, 0.0], angle: 45.0 };
        revolute = Revolute { n: [1.0, 0.0, 0.0] };
        translation1 = multibody::parts::FixedTranslation { r: [-0.1, 0.0, 0.0] };
        cyl2 = BodyCylinder { r: [0.2, 0.0, 0.0], diameter: Some(0.1) };
        fixed = multibody::parts::Fixed::default();
        spherical2 = multibody::joints::Spherical { state: true };
        cyl3 = BodyCylinder { r: [0.25, 0.0, 0.0], diameter: Some(0.05) };
        rotation2 = multibody::parts::FixedRotation { n: [0.0, 1.0, 0.0], angle: 45.0 };
        translation2 = multibody::parts::FixedTranslation { r: [-0.1, 0.0, 0.0] };
        cyl4 = BodyCylinder { r: [0.2, 0.0, 0.0], diameter: Some(0.1) };
        rotor = Rotor1D { J: 7700.0 * PI * 0.05f64.powi(2) * 0.2 * 0.05f64.powi(2) / 2.0, n: [1.0, 0.0, 0.0] };
        connect(world.frame_b, spherical1.frame_a);
        connect(spherical1.frame_b, cyl1.frame_a);
        connect(cyl1.frame_b, rotation1.frame_a);
        connect(rotation1.frame_b, revolute.frame_a);
        connect(revolute.frame_b, translation1.frame_a);
        connect(translation1.frame_b, cyl2.frame_a);
        connect(fixed.frame_b, spherical2.frame_a);
        connect(spherical2.frame_b, cyl3.frame_a);
        connect(cyl3.frame_b, rotation2.frame_a);
        connect(rotation2.frame_b, translation2.frame_a);
        connect(translation2.frame_b, cyl4.frame_a);
        connect(rotation2.frame_b, rotor.frame_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    let mut values = vec![
        ("revolute.phi", 0.0),
        ("revolute.w", 10.0),
        ("rotor.phi", 0.0),
        ("rotor.w", 10.0),
    ];
    let names: Vec<String> = ["spherical1", "spherical2"]
        .iter()
        .flat_map(|s| {
            (1..=3).flat_map(move |i| [format!("{s}.q_v[{i}]"), format!("{s}.w_rel[{i}]")])
        })
        .collect();
    values.extend(names.iter().map(|n| (n.as_str(), 0.0)));
    let sol = DaeProblem::new(&ssys, &values, (0.0, 5.0))
        .unwrap()
        .solve(&tight(5.0, 50))
        .unwrap();
    for (t, want) in [
        (1.0, [0.17054709, -0.06609863, 0.06073978]),
        (5.0, [-0.03573672, -0.18824501, 0.02076933]),
    ] {
        for i in 0..3 {
            let upper = sol
                .at(format!("cyl2.frame_a.r_0[{}]", i + 1).as_str(), t)
                .unwrap();
            let lower = sol
                .at(format!("cyl4.frame_a.r_0[{}]", i + 1).as_str(), t)
                .unwrap();
            assert!(
                (upper - want[i]).abs() < 2e-7,
                "upper r_0[{i}] {upper} at {t}"
            );
            assert!(
                (lower - upper).abs() < 1e-7,
                "lower r_0[{i}] {lower} vs {upper} at {t}"
            );
        }
    }
}
