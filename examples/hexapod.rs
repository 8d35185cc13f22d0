//! The seed's hexapod (seed `001`, Exercise 2): a Stewart platform. A base triangle of
//! side `LB` = 3.8 m and a platform triangle of side `LP` = 1.9 m (turned by 60 degrees)
//! `H_START` = 2 m above it, joined by six legs (`Leg`: a universal joint at the base, a
//! prismatic actuator, a spherical joint at the platform); each base corner carries the
//! legs to the two nearest platform corners. The actuators are position-driven to the
//! lengths that put the platform where `LegLength` says: at rest (the static scenario,
//! whose actuator forces hold the platform's weight) or heaving and rolling (the
//! trajectory scenario: the legs follow the inverse kinematics of that motion, the model
//! solves the forward kinematics).
//!
//! `cargo run --release --example hexapod` prints the translation statistics and the
//! actuator forces of both scenarios, writes `hexapod.png` and `hexapod.gif`, and
//! prints the statistics of the trajectory scenario with force-controlled legs
//! (`ControlledLeg`: a PID per actuator; 18 states, as the seed's translation log).

use multibody::blocks::{RealInput, RealOutput};
use multibody::interfaces::Frame;
use multibody::joints::{Prismatic, Spherical, Universal};
use multibody::nalgebra::{Matrix6, Vector3, Vector6};
use multibody::parts::{Body, FixedTranslation, OrientationStates};
use multibody::prelude::*;
use multibody::translational::{Force, Position};
use multibody::world::World;

/// Side of the base triangle \[m\] (seed `Basis.Lb`).
pub const LB: f64 = 3.8;
/// Side of the platform triangle \[m\] (seed `Platform.Lp`).
pub const LP: f64 = 1.9;
/// Height of the platform above the base at the start \[m\] (seed `h_start`).
pub const H_START: f64 = 2.0;
/// Mass of the platform \[kg\].
pub const M_PLATFORM: f64 = 100.0;
/// Centre of mass of the platform from its centre, in its frame \[m\] (off centre, so
/// that the legs carry unequal loads).
pub const CM: [f64; 3] = [0.2, 0.0, 0.1];
/// Moment of inertia of the platform about x through its centre of mass \[kg m2\].
pub const I_ROLL: f64 = 30.0;
/// Gravity of the world \[m/s2\].
pub const G: f64 = 9.80665;

/// Corner `k` (0, 1, 2) of the base in the world: on the circle of radius `LB / sqrt(3)`
/// at 0, 120 and 240 degrees about the vertical (y), in the plane y = 0.
pub fn base_corner(k: usize) -> [f64; 3] {
    let r = LB / 3f64.sqrt();
    let a = (120.0 * k as f64).to_radians();
    [r * a.cos(), 0.0, r * a.sin()]
}

/// Corner `k` of the platform in the platform's frame (its centre): radius
/// `LP / sqrt(3)` at 60, 180 and 300 degrees.
pub fn platform_corner(k: usize) -> [f64; 3] {
    let r = LP / 3f64.sqrt();
    let a = (60.0 + 120.0 * k as f64).to_radians();
    [r * a.cos(), 0.0, r * a.sin()]
}

/// The legs: (base corner, platform corner) of each. Base corner `k` carries the legs to
/// platform corners `k` (at +60 degrees) and `k + 2` (at -60 degrees).
pub const LEGS: [(usize, usize); 6] = [(0, 0), (0, 2), (1, 1), (1, 0), (2, 2), (2, 1)];

/// The prescribed motion of the platform: heave `heave sin(2 pi f t)` above `H_START`
/// and roll (about x) `roll sin(2 pi f t)`.
#[derive(Clone, Copy, Debug)]
pub struct Motion {
    /// Heave amplitude \[m\].
    pub heave: f64,
    /// Roll amplitude \[rad\].
    pub roll: f64,
    /// Frequency \[Hz\].
    pub f: f64,
}

impl Motion {
    /// At rest at `H_START`.
    pub const REST: Motion = Motion {
        heave: 0.0,
        roll: 0.0,
        f: 0.0,
    };

    /// Centre of the platform and its roll angle at `t`.
    pub fn pose(&self, t: f64) -> ([f64; 3], f64) {
        let s = (2.0 * PI * self.f * t).sin();
        ([0.0, H_START + self.heave * s, 0.0], self.roll * s)
    }

    /// Corner `k` of the platform in the world at `t`.
    pub fn corner(&self, k: usize, t: f64) -> [f64; 3] {
        let (c, roll) = self.pose(t);
        let p = platform_corner(k);
        let (s, co) = roll.sin_cos();
        [
            c[0] + p[0],
            c[1] + p[1] * co - p[2] * s,
            c[2] + p[1] * s + p[2] * co,
        ]
    }

    /// Length of leg `i` at `t` (inverse kinematics).
    pub fn leg_length(&self, i: usize, t: f64) -> f64 {
        let (b, p) = (base_corner(LEGS[i].0), self.corner(LEGS[i].1, t));
        ((p[0] - b[0]).powi(2) + (p[1] - b[1]).powi(2) + (p[2] - b[2]).powi(2)).sqrt()
    }
}

component! {
    /// The length of a leg from the base point `b` (world) to the platform point `p`
    /// (platform frame) while the platform heaves by `heave sin(2 pi f t)` above `h`
    /// and rolls by `roll sin(2 pi f t)` about x: the inverse kinematics of the motion.
    pub struct LegLength {
        /// Base point in the world \[m\].
        parameter b: [f64; 3] = [0.0, 0.0, 0.0];
        /// Platform point in the platform's frame \[m\].
        parameter p: [f64; 3] = [0.0, 0.0, 0.0];
        /// Height of the platform's centre at rest \[m\].
        parameter h: f64 = 2.0;
        /// Heave amplitude \[m\].
        parameter heave: f64 = 0.0;
        /// Roll amplitude \[rad\].
        parameter roll: f64 = 0.0;
        /// Frequency \[Hz\].
        parameter f: f64 = 0.0;
        /// The leg's length \[m\].
        connector y: RealOutput;
        equation {
            let s = sin(2.0 * PI * f * time);
            let angle = roll * s;
            let x = p[0] - b[0];
            let yy = h + heave * s + p[1] * cos(angle) - p[2] * sin(angle) - b[1];
            let z = p[1] * sin(angle) + p[2] * cos(angle) - b[2];
            y = sqrt(x * x + yy * yy + z * z);
        }
    }
}

component! {
    /// A leg of the hexapod (seed `Leg`): a universal joint at the base (`frame_a`;
    /// axes x, then z), a prismatic actuator along the leg (y after the universal joint)
    /// driven exactly to the length `length`, and a spherical joint at the platform
    /// (`frame_b`). Massless: the actuator's force `actuator.f` carries the platform.
    pub struct Leg {
        /// At the base.
        connector frame_a: Frame;
        /// At the platform.
        connector frame_b: Frame;
        /// The length to drive the leg to \[m\].
        connector length: RealInput;
        /// The universal joint at the base.
        component universal: Universal = Universal { n_a: [1.0, 0.0, 0.0], n_b: [0.0, 0.0, 1.0], ..Universal::default() };
        /// The actuator.
        component actuator: Prismatic = Prismatic { n: [0.0, 1.0, 0.0], axisflange: true, ..Prismatic::default() };
        /// The spherical joint at the platform.
        component ball: Spherical = Spherical::default();
        /// The position drive of the actuator.
        component drive: Position = Position { exact: true, ..Position::default() };
        equation {
            connect(frame_a, universal.frame_a);
            connect(universal.frame_b, actuator.frame_a);
            connect(actuator.frame_b, ball.frame_a);
            connect(ball.frame_b, frame_b);
            connect(drive.flange, actuator.axis);
            connect(length, drive.s_ref);
        }
    }
}

component! {
    /// A leg whose actuator is force-controlled to the length `length`: the force
    /// `held + kp e + kd e'` on the length error `e = length - actuator.s`, with
    /// `held' = ki e` (PID). Its states are the actuator's length and speed and the
    /// controller's integral: six such legs give the seed's 18 states.
    pub struct ControlledLeg {
        /// Proportional gain \[N/m\], default 1e6.
        parameter kp: f64 = 1.0e6;
        /// Integral gain \[N/(m s)\], default 2e7.
        parameter ki: f64 = 2.0e7;
        /// Derivative gain \[N s/m\], default 2e4.
        parameter kd: f64 = 2.0e4;
        /// The force the integral holds at the start \[N\], default 0.
        structural force_start: f64 = 0.0;
        /// The actuator's length at the start \[m\], default 1.
        structural s_start: f64 = 1.0;
        /// The actuator's speed at the start \[m/s\], default 0.
        structural v_start: f64 = 0.0;
        /// At the base.
        connector frame_a: Frame;
        /// At the platform.
        connector frame_b: Frame;
        /// The length to drive the leg to \[m\].
        connector length: RealInput;
        /// The universal joint at the base (its angles follow from the lengths: not
        /// states).
        component universal: Universal = Universal { n_a: [1.0, 0.0, 0.0], n_b: [0.0, 0.0, 1.0], state_priority: StateSelect::Avoid.priority(), ..Universal::default() };
        /// The actuator.
        component actuator: Prismatic = Prismatic { n: [0.0, 1.0, 0.0], axisflange: true, s_start: self.s_start, v_start: self.v_start, ..Prismatic::default() };
        /// The spherical joint at the platform.
        component ball: Spherical = Spherical::default();
        /// The actuator's force.
        component force: Force = Force::default();
        /// The controller's integral term \[N\].
        variable held(start = force_start, fixed = true): Real;
        equation {
            connect(frame_a, universal.frame_a);
            connect(universal.frame_b, actuator.frame_a);
            connect(actuator.frame_b, ball.frame_a);
            connect(ball.frame_b, frame_b);
            connect(force.flange, actuator.axis);
            der(held) = ki * (length - actuator.s);
            force.f = held + kp * (length - actuator.s) + kd * (der(length) - actuator.v);
        }
    }
}

/// How the actuators are driven.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Drive {
    /// Exactly to the lengths (`Leg`): no states.
    Exact,
    /// Force-controlled to the lengths (`ControlledLeg`), the integrals starting at the
    /// static balance's forces.
    Controlled,
}

/// The hexapod with the platform moving as `motion` (`Motion::REST`: the static
/// scenario), its actuators driven exactly.
pub fn hexapod(motion: Motion) -> System {
    hexapod_driven(motion, Drive::Exact)
}

/// The hexapod with the platform moving as `motion`, its actuators driven as `drive`.
pub fn hexapod_driven(motion: Motion, drive: Drive) -> System {
    let mut m = System::new("hexapod");
    let world = m.add_typed("world", &World::default());
    let platform = m.add_typed(
        "platform",
        &Body {
            m: M_PLATFORM,
            r_CM: CM,
            I_11: I_ROLL,
            I_22: 60.0,
            I_33: 30.0,
            orientation_states: OrientationStates::Cardan,
            // The legs determine the platform's orientation.
            orientation_state_priority: StateSelect::Avoid.priority(),
            ..Default::default()
        },
    );
    let base: Vec<_> = (0..3)
        .map(|k| {
            m.add_typed(
                &format!("base{}", k + 1),
                &FixedTranslation {
                    r: base_corner(k),
                    ..Default::default()
                },
            )
        })
        .collect();
    let corners: Vec<_> = (0..3)
        .map(|k| {
            m.add_typed(
                &format!("corner{}", k + 1),
                &FixedTranslation {
                    r: platform_corner(k),
                    ..Default::default()
                },
            )
        })
        .collect();
    for b in &base {
        m.connect_handles(&world.frame_b, &b.frame_a);
    }
    for c in &corners {
        m.connect_handles(&platform.frame_a, &c.frame_a);
    }
    let held = static_leg_forces();
    for (i, &(b, p)) in LEGS.iter().enumerate() {
        let name = format!("leg{}", i + 1);
        let (frame_a, frame_b, input) = match drive {
            Drive::Exact => {
                let leg = m.add_typed(&name, &Leg::default());
                (leg.frame_a, leg.frame_b, leg.length)
            }
            Drive::Controlled => {
                // The speed at the start by a central difference of the inverse
                // kinematics.
                let dt = 1e-6;
                let speed = (motion.leg_length(i, dt) - motion.leg_length(i, -dt)) / (2.0 * dt);
                let leg = m.add_typed(
                    &name,
                    &ControlledLeg {
                        force_start: held[i],
                        s_start: motion.leg_length(i, 0.0),
                        v_start: speed,
                        ..ControlledLeg::default()
                    },
                );
                (leg.frame_a, leg.frame_b, leg.length)
            }
        };
        let length = m.add_typed(
            &format!("length{}", i + 1),
            &LegLength {
                b: base_corner(b),
                p: platform_corner(p),
                h: H_START,
                heave: motion.heave,
                roll: motion.roll,
                f: motion.f,
            },
        );
        m.connect_handles(&base[b].frame_b, &frame_a);
        m.connect_handles(&frame_b, &corners[p].frame_b);
        m.connect_handles(&length.y, &input);
    }
    m
}

/// Guesses for the joint angles of the legs and the platform's position at the start
/// of `motion`: the universal joint's angles that point a leg from its base corner to
/// its platform corner.
pub fn guesses(motion: Motion) -> Vec<(String, f64)> {
    let mut g = Vec::new();
    for (i, &(b, p)) in LEGS.iter().enumerate() {
        let (b, p) = (base_corner(b), motion.corner(p, 0.0));
        let d: Vec<f64> = (0..3).map(|j| p[j] - b[j]).collect();
        let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        // The leg's axis after rotations phi_a about x and phi_b about z:
        // (-sin phi_b, cos phi_b cos phi_a, cos phi_b sin phi_a).
        let phi_b = (-d[0] / l).asin();
        let phi_a = d[2].atan2(d[1]);
        g.push((format!("leg{}.universal.phi_a", i + 1), phi_a));
        g.push((format!("leg{}.universal.phi_b", i + 1), phi_b));
        // The same angles by the names the controlled legs' tearing uses.
        g.push((format!("leg{}.universal.revolute_a.axis.phi", i + 1), phi_a));
        g.push((format!("leg{}.universal.revolute_b.axis.phi", i + 1), phi_b));
        g.push((format!("leg{}.actuator.s", i + 1), l));
    }
    let (c, _) = motion.pose(0.0);
    for (j, v) in c.iter().enumerate() {
        g.push((format!("platform.r_0[{}]", j + 1), *v));
        g.push((format!("platform.frame_a.r_0[{}]", j + 1), *v));
    }
    for k in 0..3 {
        for (j, v) in motion.corner(k, 0.0).iter().enumerate() {
            g.push((format!("corner{}.frame_b.r_0[{}]", k + 1, j + 1), *v));
        }
    }
    g
}

/// The forces along the legs (positive pushing the platform away from the base) whose
/// sum and moment about the world point `about` are `load` (force, then moment), with
/// the platform posed as `motion` at `t`: the 6 x 6 system of the legs' lines of
/// action.
pub fn leg_forces(motion: Motion, t: f64, about: [f64; 3], load: [f64; 6]) -> [f64; 6] {
    let mut a = Matrix6::zeros();
    for (i, &(b, p)) in LEGS.iter().enumerate() {
        let (b, p) = (base_corner(b), motion.corner(p, t));
        let u = Vector3::from(p) - Vector3::from(b);
        let u = u / u.norm();
        let m = (Vector3::from(p) - Vector3::from(about)).cross(&u);
        for j in 0..3 {
            a[(j, i)] = u[j];
            a[(3 + j, i)] = m[j];
        }
    }
    let f = a
        .lu()
        .solve(&Vector6::from(load))
        .expect("the legs' lines of action are independent");
    f.into()
}

/// The independent static balance of the platform at rest: the forces along the legs
/// that hold its weight, `(0, m g, 0)`, and balance its moment about the platform's
/// centre, `CM x (0, -m g, 0)`.
pub fn static_leg_forces() -> [f64; 6] {
    let w = M_PLATFORM * G;
    leg_forces(
        Motion::REST,
        0.0,
        [0.0, H_START, 0.0],
        [0.0, w, 0.0, -CM[2] * w, 0.0, CM[0] * w],
    )
}

#[allow(dead_code)]
fn main() -> Result<(), multibody::Error> {
    let ssys = structural_simplify(&hexapod(Motion::REST))?;
    println!("{}", ssys.statistics());
    let guesses = guesses(Motion::REST);
    let named: Vec<(&str, f64)> = guesses.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    let sol = DaeProblem::new_with_guesses(&ssys, &[], &named, (0.0, 1.0))?
        .solve(&SolverOptions::default())?;
    let balance = static_leg_forces();
    for i in 0..6 {
        println!(
            "leg{}: actuator force {:.3} N (static balance {:.3} N)",
            i + 1,
            sol.final_value(format!("leg{}.actuator.f", i + 1).as_str())?,
            balance[i]
        );
    }
    let motion = Motion {
        heave: 0.2,
        roll: 0.1,
        f: 0.5,
    };
    let model = hexapod(motion);
    let ssys = structural_simplify(&model)?;
    println!("{}", ssys.statistics());
    let guesses = self::guesses(motion);
    let named: Vec<(&str, f64)> = guesses.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    let sol = DaeProblem::new_with_guesses(&ssys, &[], &named, (0.0, 4.0))?
        .solve(&SolverOptions::default().with_output_interval(0.0, 4.0, 0.02))?;
    Figure::new()
        .title("Hexapod: platform heaving and rolling")
        .panel(&sol, &["platform.r_0[2]"])
        .panel(
            &sol,
            &["leg1.actuator.s", "leg2.actuator.s", "leg3.actuator.s"],
        )
        .panel(
            &sol,
            &["leg1.actuator.f", "leg2.actuator.f", "leg3.actuator.f"],
        )
        .save("hexapod.png")?;
    println!("wrote hexapod.png");
    let options = RenderOptions {
        camera: [5.0, 4.0, 6.0],
        look_at: [0.0, 1.0, 0.0],
        times: Some((0..=80).map(|k| 0.05 * f64::from(k)).collect()),
        ..RenderOptions::default()
    };
    render(&model, &sol, "hexapod.gif", &options)?;
    println!("wrote hexapod.gif");
    // The legs force-controlled to the same lengths: 18 states, as the seed's.
    let ssys = structural_simplify(&hexapod_driven(motion, Drive::Controlled))?;
    println!("force-controlled legs:\n{}", ssys.statistics());
    Ok(())
}
