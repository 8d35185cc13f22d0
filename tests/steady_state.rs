//! Steady states against closed forms, and the errors of steady states that are not
//! unique.

#![allow(missing_docs)]

use multibody::blocks::Constant;
use multibody::joints::Revolute;
use multibody::parts::Body;
use multibody::prelude::*;
use multibody::rotational::{self, Damper, Inertia};
use multibody::translational::{Fixed, Force, Mass, Spring};
use multibody::world::World;
use multibody::{SteadyStateOptions, linearize, steady_state};

#[test]
fn a_pendulum_held_by_a_torque_rests_where_gravity_balances_it() {
    // 2 N.m on a 1 kg pendulum of 0.5 m (zero at horizontal): m g l cos(phi) = 2.
    let model = system! {
        name: "held";
        world = World::default();
        rev = Revolute { n: [0.0, 0.0, 1.0], axisflange: true };
        body = Body { m: 1.0, r_CM: [0.5, 0.0, 0.0] };
        tau = Constant { k: 2.0 };
        torque = rotational::Torque::default();
        connect(world.frame_b, rev.frame_a);
        connect(rev.frame_b, body.frame_a);
        connect(tau.y, torque.tau);
        connect(torque.flange, rev.axis);
    };
    let ssys = structural_simplify(&model).unwrap();
    let point = steady_state(
        &ssys,
        &[],
        &[("rev.phi", 1.0)],
        &[],
        &SteadyStateOptions::default(),
    )
    .unwrap();
    let names = ssys.unknowns();
    let phi = point.u[names.iter().position(|n| n == "rev.phi").unwrap()];
    let w = point.u[names.iter().position(|n| n == "rev.w").unwrap()];
    let exact = (2.0f64 / (9.80665 * 0.5)).acos();
    assert!(
        (phi - exact).abs() < 1e-10 && w.abs() < 1e-12,
        "{phi} {w}, exact {exact}"
    );
    // Above the horizontal the balance is unstable: lambda^2 = m g l sin(phi) / I.
    let lin = linearize(&ssys, &point, &[], &[]).unwrap();
    let lambda = (9.80665 * 0.5 * exact.sin() / 0.251).sqrt();
    let ev = lin.eigenvalues();
    assert!(
        (ev[0].re + lambda).abs() < 1e-8 && (ev[1].re - lambda).abs() < 1e-8,
        "{ev:?}"
    );
}

#[test]
fn a_steady_motion_with_a_cyclic_angle() {
    // 3 N.m against a damper of 0.5 N.m.s/rad: the inertia turns at 6 rad/s, its angle
    // growing (a free rate, its value fixed).
    let model = system! {
        name: "spinning";
        inertia = Inertia { J: 2.0 };
        damper = Damper { d: 0.5 };
        ground = rotational::Fixed::default();
        tau = Constant { k: 3.0 };
        torque = rotational::Torque::default();
        connect(tau.y, torque.tau);
        connect(torque.flange, inertia.flange_a);
        connect(inertia.flange_b, damper.flange_b);
        connect(damper.flange_a, ground.flange);
    };
    let ssys = structural_simplify(&model).unwrap();
    let states = ssys.states();
    let angle = states
        .iter()
        .find(|s| s.ends_with("phi") || s.ends_with("phi_rel"))
        .unwrap();
    let point = steady_state(
        &ssys,
        &[(angle.as_str(), 0.0)],
        &[],
        &[(angle.as_str(), f64::NAN)],
        &SteadyStateOptions::default(),
    )
    .unwrap();
    let names = ssys.unknowns();
    let k = names.iter().position(|n| n == angle).unwrap();
    assert!((point.up[k].abs() - 6.0).abs() < 1e-10, "{}", point.up[k]);
    // Linearized around the steady motion: the angle's integrator (0) and the speed's
    // decay -d / J.
    let lin = linearize(&ssys, &point, &[], &[]).unwrap();
    let ev = lin.eigenvalues();
    assert!(
        (ev[0].re + 0.25).abs() < 1e-12 && ev[1].norm() < 1e-12,
        "{ev:?}"
    );
}

#[test]
fn a_spring_balances_a_force_and_a_free_mass_has_no_unique_rest() {
    let model = system! {
        name: "spring";
        wall = Fixed::default();
        spring = Spring { c: 2.0 };
        mass = Mass { m: 1.0 };
        f = Constant { k: 3.0 };
        force = Force::default();
        connect(wall.flange, spring.flange_a);
        connect(spring.flange_b, mass.flange_a);
        connect(f.y, force.f);
        connect(force.flange, mass.flange_b);
    };
    let ssys = structural_simplify(&model).unwrap();
    let point = steady_state(&ssys, &[], &[], &[], &SteadyStateOptions::default()).unwrap();
    let names = ssys.unknowns();
    let s = point.u[names.iter().position(|n| n == "mass.s").unwrap()];
    assert!((s - 1.5).abs() < 1e-10, "{s}");
    // Without the spring, any position is at rest: not unique, naming the position.
    let free = system! {
        name: "free";
        mass = Mass { m: 1.0 };
    };
    let ssys = structural_simplify(&free).unwrap();
    let err = steady_state(&ssys, &[], &[], &[], &SteadyStateOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("not unique") && err.contains("mass.s"),
        "{err}"
    );
}
