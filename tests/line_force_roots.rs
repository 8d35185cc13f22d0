//! Line forces whose frame is a root parallel to the world (`fixed_rotation_at_frame_a`,
//! `fixed_rotation_at_frame_b`, MSL `fixedRotationAtFrame_a/b`): a mass hanging on a
//! spring whose own frame fixes the body's orientation, and MSL's
//! `Examples.Elementary.ThreeSprings` (springs meeting at a point without a body),
//! checked against closed forms and invariants.

#![allow(missing_docs)]

#[path = "support/mechanics.rs"]
mod mechanics;

use mechanics::{MassProps, body_energy, dot, relative_drift, rotation, vector};
use multibody::forces::{Damper, Spring, SpringDamperParallel};
use multibody::parts::{Body, FixedTranslation};
use multibody::prelude::*;
use multibody::world::World;

const G: f64 = 9.80665;

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    std::array::from_fn(|i| a[i] - b[i])
}

fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

fn solve(
    model: &System,
    values: &[(&str, f64)],
    guesses: &[(&str, f64)],
    t_end: f64,
    n: usize,
) -> Solution {
    let ssys = structural_simplify(model).unwrap_or_else(|e| panic!("{e}"));
    let options = SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        output_times: Some((0..=n).map(|k| k as f64 * t_end / n as f64).collect()),
        ..SolverOptions::default()
    };
    DaeProblem::new_with_guesses(&ssys, values, guesses, (0.0, t_end))
        .and_then(|p| p.solve(&options))
        .unwrap_or_else(|e| panic!("{e}"))
}

/// A body of mass m on a spring (zero unstretched length) from the world's origin, no
/// gravity; the spring's `frame_b`, at the body, is a root parallel to the world, so the
/// body keeps the world's orientation (it has no orientation states; without the flag
/// it would be a free body carrying them). The force is -c r: an isotropic oscillator,
/// r(t) = r0 cos(wt) + v0 / w sin(wt), w = sqrt(c / m), period 2 pi / w, with
/// m |v|^2 / 2 + c |r|^2 / 2 conserved.
#[test]
fn a_mass_on_a_spring_whose_frame_b_is_a_root() {
    let (c, m): (f64, f64) = (8.0, 2.0);
    let w = (c / m).sqrt();
    let model = system! {
        name: "spring_root";
        world = World { g: 0.0 };
        spring = Spring { c, fixed_rotation_at_frame_b: true };
        body = Body { m, r_CM: [0.0, 0.0, 0.0], I_11: 0.1, I_22: 0.2, I_33: 0.3 };
        connect(world.frame_b, spring.frame_a);
        connect(spring.frame_b, body.frame_a);
    }
    .into_system();
    let ssys = structural_simplify(&model).unwrap_or_else(|e| panic!("{e}"));
    // Three positions and three velocities: no orientation states.
    assert_eq!(ssys.states().len(), 6, "{:?}", ssys.states());
    let (r0, v0) = ([1.0, 0.2, -0.3], [0.1, 1.5, 0.4]);
    let period = 2.0 * std::f64::consts::PI / w;
    let values = [
        ("body.r_0[1]", r0[0]),
        ("body.r_0[2]", r0[1]),
        ("body.r_0[3]", r0[2]),
        ("body.v_0[1]", v0[0]),
        ("body.v_0[2]", v0[1]),
        ("body.v_0[3]", v0[2]),
    ];
    let sol = solve(&model, &values, &[], 2.0 * period, 400);
    let (r, v) = (vector(&sol, "body.r_0"), vector(&sol, "body.v_0"));
    let t_body = rotation(&sol, "body.frame_a");
    let energy0 = 0.5 * m * dot(v0, v0) + 0.5 * c * dot(r0, r0);
    // rtol 1e-10 over two periods: errors up to 2e-9 m, the energy off by 4e-9.
    let tol = 1e-7;
    for (k, &t) in sol.t().iter().enumerate() {
        let (cw, sw) = ((w * t).cos(), (w * t).sin());
        for i in 0..3 {
            let expected = r0[i] * cw + v0[i] / w * sw;
            assert!(
                (r[k][i] - expected).abs() < tol,
                "r_0[{i}] at {t}: {} vs {expected}",
                r[k][i]
            );
            for j in 0..3 {
                let id = if i == j { 1.0 } else { 0.0 };
                assert_eq!(t_body[k][i][j], id, "body turned at {t}");
            }
        }
        let energy = 0.5 * m * dot(v[k], v[k]) + 0.5 * c * dot(r[k], r[k]);
        assert!(
            (energy - energy0).abs() < 1e-8 * energy0,
            "energy at {t}: {energy} vs {energy0}"
        );
    }
    // After each period the body is back where it started.
    let last = r.last().unwrap();
    assert!(norm(sub(*last, r0)) < tol, "after two periods: {last:?}");
}

/// A body whose centre of mass is off its frame (r_CM = (0.2, 0, 0)) hanging on a spring
/// (zero unstretched length) from the world's origin, gravity -y, with the spring's
/// `frame_b` a root: the body cannot turn, so its frame moves like a point mass along
/// the vertical line, y(t) = y_eq + (y0 - y_eq) cos(wt), y_eq = -m g / c, and the torque
/// that holds it parallel comes through `frame_b`, not zeroed under the flag. The
/// body's Euler equation with w = 0 gives that torque: the frame torque on the body,
/// -spring.frame_b.t, is r_CM x m (a - g) = (0, 0, x_cm m (y'' + g)).
#[test]
fn the_root_frame_takes_the_torque_that_holds_the_body() {
    let (c, m, x_cm): (f64, f64, f64) = (50.0, 0.5, 0.2);
    let w = (c / m).sqrt();
    let model = system! {
        name: "spring_torque";
        world = World::default();
        spring = Spring { c, fixed_rotation_at_frame_b: true };
        body = Body { m, r_CM: [x_cm, 0.0, 0.0] };
        connect(world.frame_b, spring.frame_a);
        connect(spring.frame_b, body.frame_a);
    }
    .into_system();
    let y0 = -0.3;
    let y_eq = -m * G / c;
    let sol = solve(&model, &[("body.r_0[2]", y0)], &[], 2.0, 200);
    let r = vector(&sol, "body.r_0");
    let torque = vector(&sol, "spring.frame_b.t");
    let tol = 1e-7;
    for (k, &t) in sol.t().iter().enumerate() {
        let y = y_eq + (y0 - y_eq) * (w * t).cos();
        assert!((r[k][1] - y).abs() < tol, "y at {t}: {} vs {y}", r[k][1]);
        assert!(
            r[k][0].abs() < tol && r[k][2].abs() < tol,
            "left the line at {t}"
        );
        // The body's Euler equation with w = 0: the frame torque on the body,
        // -spring.frame_b.t, equals r_CM x m (a - g); a = y'' ey, g = -G ey, so about z:
        // x_cm m (y'' + G).
        let y_dd = -w * w * (y0 - y_eq) * (w * t).cos();
        let tz = -torque[k][2];
        assert!(
            (tz - x_cm * m * (y_dd + G)).abs() < 1e-6,
            "frame torque at {t}: {tz} vs {}",
            x_cm * m * (y_dd + G)
        );
        assert!(torque[k][0].abs() < 1e-9 && torque[k][1].abs() < 1e-9);
    }
}

/// MSL `Examples.Elementary.ThreeSprings` (MSL 4.x, where `spring3` has
/// `fixedRotationAtFrame_b = true`): springs 1 and 3 from two bars on the world meet
/// spring 2 at a point with no body; spring 2 carries body1 (m = 0.8, r_CM =
/// (0, -0.2, 0), inertia 0.1), starting at rest at (0.5, -0.3, 0). Without the flag the
/// junction has no orientation (an error naming it); with it, the model runs, and
///
/// - the massless junction is in equilibrium at every instant: the tensions
///   c_i (L_i - 0.1) along the three springs, from the positions alone, sum to zero;
/// - the total energy (body, gravity, the three springs) is conserved.
#[test]
fn msl_three_springs_meet_at_a_point_without_a_body() {
    let build = |flag: bool| {
        system! {
            name: "three_springs";
            world = World::default();
            body1 = Body { m: 0.8, r_CM: [0.0, -0.2, 0.0], I_11: 0.1, I_22: 0.1, I_33: 0.1 };
            bar1 = FixedTranslation { r: [0.3, 0.0, 0.0] };
            spring1 = Spring { s_unstretched: 0.1, c: 20.0 };
            bar2 = FixedTranslation { r: [0.0, 0.0, 0.3] };
            spring2 = Spring { s_unstretched: 0.1, c: 40.0 };
            spring3 = Spring { s_unstretched: 0.1, c: 20.0, fixed_rotation_at_frame_b: flag };
            connect(world.frame_b, bar1.frame_a);
            connect(world.frame_b, bar2.frame_a);
            connect(bar1.frame_b, spring1.frame_a);
            connect(bar2.frame_b, spring3.frame_a);
            connect(spring2.frame_b, body1.frame_a);
            connect(spring3.frame_b, spring1.frame_b);
            connect(spring2.frame_a, spring1.frame_b);
        }
        .into_system()
    };
    let e = structural_simplify(&build(false))
        .map(|_| ())
        .expect_err("no root at the junction");
    let text = e.to_string();
    assert!(
        text.contains("spring1.frame_b.R") && text.contains("not determined"),
        "{text}"
    );

    let model = build(true);
    let values = [
        ("body1.r_0[1]", 0.5),
        ("body1.r_0[2]", -0.3),
        ("body1.r_0[3]", 0.0),
    ];
    // MSL's start of spring1.lineForce.r_rel_0, (-0.2, -0.2, 0.2), from bar1's end.
    let guesses = [
        ("spring1.frame_b.r_0[1]", 0.1),
        ("spring1.frame_b.r_0[2]", -0.2),
        ("spring1.frame_b.r_0[3]", 0.2),
    ];
    let sol = solve(&model, &values, &guesses, 5.0, 500);
    let node = vector(&sol, "spring1.frame_b.r_0");
    let body = vector(&sol, "body1.r_0");
    let (a1, a3) = ([0.3, 0.0, 0.0], [0.0, 0.0, 0.3]);
    let props = MassProps {
        m: 0.8,
        r_cm: [0.0, -0.2, 0.0],
        inertia: [[0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [0.0, 0.0, 0.1]],
    };
    let mut energy = body_energy(&sol, "body1", props, G, [0.0, -1.0, 0.0]);
    let mut moved = 0.0f64;
    for k in 0..sol.t().len() {
        // Each spring pulls the junction towards its other end with its tension.
        let mut sum = [0.0; 3];
        let mut spring_energy = 0.0;
        for (other, c) in [(a1, 20.0), (a3, 20.0), (body[k], 40.0)] {
            let d = sub(other, node[k]);
            let l = norm(d);
            let f = c * (l - 0.1);
            for i in 0..3 {
                sum[i] += f * d[i] / l;
            }
            spring_energy += 0.5 * c * (l - 0.1) * (l - 0.1);
        }
        // The junction is solved to rounding (measured: 1e-14 N).
        assert!(
            norm(sum) < 1e-10,
            "junction force {sum:?} at {}",
            sol.t()[k]
        );
        energy[k] += spring_energy;
        moved = moved.max(norm(sub(body[k], body[0])));
    }
    let drift = relative_drift(&energy, 0.8 * G * 0.5);
    // Measured: 3e-10 at rtol 1e-10.
    assert!(drift < 1e-8, "energy drift {drift:e}");
    assert!(moved > 0.1, "the body barely moved: {moved}");
}

/// `Damper` and `SpringDamperParallel` take the flags too: a body on a damper and a
/// spring-damper in parallel from the world's origin, moving along a line (no gravity),
/// at s = s_unstretched + x: m x'' = -c x - (d1 + d2) x', the underdamped oscillator in
/// closed form. The body's frame is the root of either the damper (its `frame_b`), or
/// of the spring-damper connected the other way round (its `frame_a`), and the body
/// keeps the world's orientation.
#[test]
fn damper_and_spring_damper_take_the_flags() {
    let (c, d1, d2, m, s_un): (f64, f64, f64, f64, f64) = (18.0, 0.7, 0.5, 2.0, 1.0);
    let e = [2.0 / 3.0, -1.0 / 3.0, 2.0 / 3.0];
    let (x0, u0) = (0.5, -0.4);
    let values = [
        ("body.r_0[1]", e[0] * (s_un + x0)),
        ("body.r_0[2]", e[1] * (s_un + x0)),
        ("body.r_0[3]", e[2] * (s_un + x0)),
        ("body.v_0[1]", e[0] * u0),
        ("body.v_0[2]", e[1] * u0),
        ("body.v_0[3]", e[2] * u0),
    ];
    let delta = (d1 + d2) / (2.0 * m);
    let wd = (c / m - delta * delta).sqrt();
    for root_in_damper in [true, false] {
        let mut model = system! {
            name: "damped_root";
            world = World { g: 0.0 };
            damper = Damper { d: d1, fixed_rotation_at_frame_b: root_in_damper };
            parallel = SpringDamperParallel {
                c,
                d: d2,
                s_unstretched: s_un,
                fixed_rotation_at_frame_a: !root_in_damper,
            };
            body = Body { m };
            connect(world.frame_b, damper.frame_a);
            connect(damper.frame_b, body.frame_a);
        }
        .into_system();
        model.connect("body.frame_a", "parallel.frame_a");
        model.connect("parallel.frame_b", "world.frame_b");
        let sol = solve(&model, &values, &[], 4.0, 400);
        let r = vector(&sol, "body.r_0");
        let t_body = rotation(&sol, "body.frame_a");
        for (k, &t) in sol.t().iter().enumerate() {
            let x = (-delta * t).exp()
                * (x0 * (wd * t).cos() + (u0 + delta * x0) / wd * (wd * t).sin());
            for i in 0..3 {
                assert!(
                    (r[k][i] - e[i] * (s_un + x)).abs() < 1e-8,
                    "root in damper {root_in_damper}: r_0[{i}] at {t}"
                );
                assert_eq!(t_body[k][i][i], 1.0, "body turned at {t}");
            }
        }
    }
}
