//! 3-D mechanisms without loops: unknown counts that Multibody.jl's tests assert,
//! analytic motions, invariants, and errors.

use multibody::forces::WorldForce;
use multibody::joints::{FreeMotion, Revolute, Spherical};
use multibody::parts::{Body, BodyBox, BodyCylinder, Fixed, OrientationStates};
use multibody::prelude::*;
use multibody::world::World;

const G: f64 = 9.80665;

fn tight() -> SolverOptions {
    SolverOptions {
        rtol: 1e-9,
        atol: 1e-11,
        ..SolverOptions::default()
    }
}

/// Entries of orientation matrices are never unknowns.
fn assert_no_orientation_unknowns(ssys: &SimplifiedSystem) {
    for u in ssys.unknowns() {
        assert!(
            !u.contains(".R.T["),
            "orientation matrix entry {u} is an unknown"
        );
    }
}

#[test]
fn a_body_fixed_to_the_world_has_no_unknowns() {
    let model = system! {
        name: "fixed_body";
        world = World::default();
        body = Body { m: 2.0, r_CM: [0.1, 0.2, 0.3] };
        connect(world.frame_b, body.frame_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    assert_eq!(ssys.unknowns().len(), 0, "{:?}", ssys.unknowns());
    let sol = DaeProblem::new(&ssys, &[], (0.0, 1.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    // The world holds the weight: frame_a.f = -m g (resolved in the world = frame_a).
    let f = sol.final_value("body.frame_a.f[2]").unwrap();
    assert!((f - 2.0 * G).abs() < 1e-12, "{f}");
    // and its moment: t = r_CM x f.
    let t1 = sol.final_value("body.frame_a.t[1]").unwrap();
    assert!((t1 - (0.2 * 0.0 - 0.3 * 2.0 * G)).abs() < 1e-12, "{t1}");
}

#[test]
fn spherical_pendulum_with_joint_states_has_six_unknowns() {
    let model = system! {
        name: "spherical_pendulum";
        world = World::default();
        joint = Spherical { state: true, orientation_states: OrientationStates::Cardan };
        body = Body { m: 1.0, r_CM: [0.5, 0.0, 0.0] };
        connect(world.frame_b, joint.frame_a);
        connect(joint.frame_b, body.frame_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    assert_eq!(ssys.unknowns().len(), 6, "{:?}", ssys.unknowns());
    assert_eq!(ssys.states().len(), 6);
    assert_no_orientation_unknowns(&ssys);
    let sol = DaeProblem::new(
        &ssys,
        &[("joint.phi[1]", 0.3), ("joint.phi[2]", 0.2)],
        (0.0, 3.0),
    )
    .unwrap()
    .solve(&tight())
    .unwrap();
    // The distance of the centre of mass from the pivot stays 0.5 and energy is kept.
    let e = energy_pendulum(&sol, "body", 1.0);
    let (e0, emax) = (e[0], e.iter().fold(0.0f64, |m, &x| m.max((x - e[0]).abs())));
    assert!(emax < 1e-6 * e0.abs().max(1.0), "energy drift {emax}");
}

/// Kinetic plus potential energy of a body whose `frame_a` sits at a fixed pivot, with
/// its centre of mass at `{0.5, 0, 0}` and inertia 0.001 about it.
fn energy_pendulum(sol: &Solution, body: &str, m: f64) -> Vec<f64> {
    let names: Vec<String> = ["w_a[1]", "w_a[2]", "w_a[3]", "frame_a.R.T[1,2]"]
        .iter()
        .map(|s| format!("{body}.{s}"))
        .collect();
    let refs: Vec<&str> = names.iter().map(|s| s.as_str()).collect();
    let v = sol.get_many(&refs).unwrap();
    (0..sol.t().len())
        .map(|k| {
            let (w1, w2, w3) = (v[0][k], v[1][k], v[2][k]);
            // v_cm = w x r_cm with r_cm = 0.5 x: |v_cm|^2 = 0.25 (w2^2 + w3^2).
            0.5 * m * 0.25 * (w2 * w2 + w3 * w3)
                + 0.5 * 0.001 * (w1 * w1 + w2 * w2 + w3 * w3)
                + m * G * 0.5 * v[3][k]
        })
        .collect()
}

#[test]
fn free_motion_and_a_free_body_have_twelve_unknowns() {
    for states in [OrientationStates::Cardan, OrientationStates::Quaternion] {
        let expected = if states == OrientationStates::Cardan {
            12
        } else {
            13
        };
        let with_joint = system! {
            name: "free_motion";
            world = World::default();
            joint = FreeMotion { orientation_states: states };
            body = Body { m: 1.0 };
            connect(world.frame_b, joint.frame_a);
            connect(joint.frame_b, body.frame_a);
        };
        let ssys = structural_simplify(&with_joint).unwrap();
        assert_eq!(
            ssys.unknowns().len(),
            expected,
            "{states:?}: {:?}",
            ssys.unknowns()
        );
        assert_no_orientation_unknowns(&ssys);
        let lone = system! {
            name: "free_body";
            world = World::default();
            body = Body { m: 1.0, orientation_states: states };
        };
        let ssys = structural_simplify(&lone).unwrap();
        assert_eq!(
            ssys.unknowns().len(),
            expected,
            "{states:?}: {:?}",
            ssys.unknowns()
        );
        assert_no_orientation_unknowns(&ssys);
    }
}

#[test]
fn free_fall_follows_g_t_squared_over_two() {
    let model = system! {
        name: "free_fall";
        world = World::default();
        body = Body { m: 3.0 };
    };
    let ssys = structural_simplify(&model).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 2.0))
        .unwrap()
        .solve(&tight())
        .unwrap();
    for &t in &[0.5, 1.0, 2.0] {
        let y = sol.at("body.r_0[2]", t).unwrap();
        assert!((y + G * t * t / 2.0).abs() < 1e-8, "y({t}) = {y}");
        assert!(sol.at("body.r_0[1]", t).unwrap().abs() < 1e-12);
    }
}

#[test]
fn a_tumbling_body_keeps_its_energy_and_angular_momentum() {
    for states in [OrientationStates::Cardan, OrientationStates::Quaternion] {
        let model = system! {
            name: "tumbling";
            world = World { g: 0.0 };
            body = Body {
                m: 1.0,
                I_11: 0.1,
                I_22: 0.2,
                I_33: 0.3,
                I_21: 0.01,
                orientation_states: states,
            };
        };
        let ssys = structural_simplify(&model).unwrap();
        // Spin mostly about the intermediate axis (unstable): a demanding motion.
        let start: Vec<(&str, f64)> = match states {
            OrientationStates::Cardan => vec![
                ("body.phi_d[1]", 0.1),
                ("body.phi_d[2]", 3.0),
                ("body.phi_d[3]", 0.2),
            ],
            OrientationStates::Quaternion => vec![
                ("body.w_a[1]", 0.1),
                ("body.w_a[2]", 3.0),
                ("body.w_a[3]", 0.2),
            ],
        };
        let sol = DaeProblem::new(&ssys, &start, (0.0, 10.0))
            .unwrap()
            .solve(&tight())
            .unwrap();
        let w = sol
            .get_many(&["body.w_a[1]", "body.w_a[2]", "body.w_a[3]"])
            .unwrap();
        let inertia = [[0.1, 0.01, 0.0], [0.01, 0.2, 0.0], [0.0, 0.0, 0.3]];
        let t_names: Vec<String> = (1..=3)
            .flat_map(|i| (1..=3).map(move |j| format!("body.frame_a.R.T[{i},{j}]")))
            .collect();
        let t_refs: Vec<&str> = t_names.iter().map(|s| s.as_str()).collect();
        let tm = sol.get_many(&t_refs).unwrap();
        let mut e0 = None;
        let mut l0: Option<[f64; 3]> = None;
        for k in 0..sol.t().len() {
            let wk = [w[0][k], w[1][k], w[2][k]];
            let iw: Vec<f64> = (0..3)
                .map(|i| (0..3).map(|j| inertia[i][j] * wk[j]).sum())
                .collect();
            let e = 0.5 * (0..3).map(|i| wk[i] * iw[i]).sum::<f64>();
            // Angular momentum in the world: T' (I w).
            let l: Vec<f64> = (0..3)
                .map(|j| (0..3).map(|i| tm[3 * i + j][k] * iw[i]).sum())
                .collect();
            let e0 = *e0.get_or_insert(e);
            let l0 = *l0.get_or_insert([l[0], l[1], l[2]]);
            assert!(
                (e - e0).abs() < 1e-6 * e0,
                "{states:?}: energy {e} vs {e0} at {}",
                sol.t()[k]
            );
            for i in 0..3 {
                assert!(
                    (l[i] - l0[i]).abs() < 1e-5,
                    "{states:?}: L[{i}] {} vs {} at {}",
                    l[i],
                    l0[i],
                    sol.t()[k]
                );
            }
        }
    }
}

#[test]
fn box_and_cylinder_masses_match_the_msl_table() {
    // MODELS.md, computed with MSL's rules (density 7700).
    // To 1e-9 relative, or to the last digit the table prints.
    let rel = |a: f64, b: f64| {
        (((a - b) / b).abs()).min(if (a - b).abs() <= 0.5e-10 { 0.0 } else { 1.0 })
    };
    let p = BodyBox {
        r: [0.5, 0.0, 0.0],
        width: Some(0.06),
        ..Default::default()
    }
    .mass_properties();
    assert!(rel(p.m, 13.86) < 1e-9, "{}", p.m);
    assert!(rel(p.inertia[0][0], 0.008316) < 1e-9, "{:?}", p.inertia);
    assert!(rel(p.inertia[1][1], 0.292908) < 1e-9, "{:?}", p.inertia);
    for (r, m, ia, ip) in [
        ([0.0, 0.5, 0.1], 7.709164080, 0.0024091138, 0.1682364453),
        ([0.0, 0.2, 0.0], 3.023782929, 0.00094493217, 0.0105517425),
        ([-1.0, 0.3, 0.1], 15.85685145, 0.0049552661, 1.45602235),
    ] {
        let c = BodyCylinder {
            r,
            diameter: Some(0.05),
            ..Default::default()
        };
        let p = c.mass_properties();
        assert!(rel(p.m, m) < 1e-9, "m {} vs {m}", p.m);
        // Axial and perpendicular inertias: the eigenvalues, via the axis direction.
        let l = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        let e = [r[0] / l, r[1] / l, r[2] / l];
        let axial: f64 = (0..3)
            .map(|i| (0..3).map(|j| e[i] * p.inertia[i][j] * e[j]).sum::<f64>())
            .sum();
        let trace = p.inertia[0][0] + p.inertia[1][1] + p.inertia[2][2];
        let perp = (trace - axial) / 2.0;
        assert!(rel(axial, ia) < 1e-8, "axial {axial} vs {ia}");
        assert!(rel(perp, ip) < 1e-9, "perp {perp} vs {ip}");
    }
}

#[test]
fn undamped_double_pendulum_keeps_its_energy() {
    let model = system! {
        name: "double";
        world = World::default();
        rev1 = Revolute { n: [0.0, 0.0, 1.0] };
        body1 = BodyBox { r: [0.5, 0.0, 0.0], width: Some(0.06) };
        rev2 = Revolute { n: [0.0, 0.0, 1.0] };
        body2 = BodyBox { r: [0.5, 0.0, 0.0], width: Some(0.06) };
        connect(world.frame_b, rev1.frame_a);
        connect(rev1.frame_b, body1.frame_a);
        connect(body1.frame_b, rev2.frame_a);
        connect(rev2.frame_b, body2.frame_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    assert_eq!(ssys.states(), ["rev1.phi", "rev2.phi", "rev1.w", "rev2.w"]);
    assert_no_orientation_unknowns(&ssys);
    // A tree's joint coordinates are valid states everywhere: no warning.
    assert!(ssys.warnings().is_empty(), "{:?}", ssys.warnings());
    let sol = DaeProblem::new(&ssys, &[("rev1.phi", 1.0), ("rev2.phi", -0.5)], (0.0, 10.0))
        .unwrap()
        .solve(&tight())
        .unwrap();
    let m = BodyBox {
        r: [0.5, 0.0, 0.0],
        width: Some(0.06),
        ..Default::default()
    }
    .mass_properties();
    let mut energies = vec![0.0; sol.t().len()];
    for b in ["body1", "body2"] {
        let mut names = Vec::new();
        for n in [
            "v_0[1]", "v_0[2]", "v_0[3]", "w_a[1]", "w_a[2]", "w_a[3]", "r_0[2]",
        ] {
            names.push(format!("{b}.body.{n}"));
        }
        for i in 1..=3 {
            for j in 1..=3 {
                names.push(format!("{b}.frame_a.R.T[{i},{j}]"));
            }
        }
        let refs: Vec<&str> = names.iter().map(|s| s.as_str()).collect();
        let s = sol.get_many(&refs).unwrap();
        for (k, e) in energies.iter_mut().enumerate() {
            let v = [s[0][k], s[1][k], s[2][k]];
            let w = [s[3][k], s[4][k], s[5][k]];
            let t = |i: usize, j: usize| s[7 + 3 * (i - 1) + (j - 1)][k];
            // Velocity of the centre of mass (r_CM = {0.25, 0, 0} in frame_a).
            let wxr = [0.0, w[2] * 0.25, -w[1] * 0.25];
            let vcm: Vec<f64> = (0..3)
                .map(|j| v[j] + (1..=3).map(|i| t(i, j + 1) * wxr[i - 1]).sum::<f64>())
                .collect();
            let ycm = s[6][k] + t(1, 2) * 0.25;
            let iw: f64 = (0..3)
                .map(|i| (0..3).map(|j| w[i] * m.inertia[i][j] * w[j]).sum::<f64>())
                .sum();
            *e += 0.5 * m.m * vcm.iter().map(|x| x * x).sum::<f64>() + 0.5 * iw + m.m * G * ycm;
        }
    }
    let drift = energies
        .iter()
        .fold(0.0f64, |d, &e| d.max((e - energies[0]).abs()));
    assert!(
        drift < 1e-5 * energies[0].abs().max(1.0),
        "energy drift {drift}"
    );
}

#[test]
fn a_body_fixed_twice_is_two_roots_fighting() {
    let model = system! {
        name: "fixed_twice";
        world = World::default();
        fixed = Fixed { r: [1.0, 0.0, 0.0] };
        body = multibody::parts::BodyShape { r: [1.0, 0.0, 0.0] };
        connect(world.frame_b, body.frame_a);
        connect(fixed.frame_b, body.frame_b);
    };
    let err = structural_simplify(&model).unwrap_err().to_string();
    assert!(err.contains("two roots fight"), "{err}");
    assert!(
        err.contains("world.frame_b.R") && err.contains("fixed.frame_b.R"),
        "{err}"
    );
}

#[test]
fn a_floating_joint_is_reported() {
    let model = system! {
        name: "floating";
        world = World::default();
        joint = Revolute::default();
        link = multibody::parts::FixedTranslation { r: [1.0, 0.0, 0.0] };
        connect(joint.frame_b, link.frame_a);
    };
    let err = structural_simplify(&model).unwrap_err().to_string();
    assert!(err.contains("is not determined"), "{err}");
    assert!(err.contains("joint.frame_a.R"), "{err}");
}

#[test]
fn an_inconsistent_initial_position_names_the_variables() {
    let model = system! {
        name: "pendulum";
        world = World::default();
        rev = Revolute { n: [0.0, 0.0, 1.0] };
        body = Body { m: 1.0, r_CM: [0.5, 0.0, 0.0] };
        connect(world.frame_b, rev.frame_a);
        connect(rev.frame_b, body.frame_a);
        force = WorldForce::default();
        connect(force.frame_b, body.frame_a);
    };
    let _ = model;
    let model = system! {
        name: "pendulum";
        world = World::default();
        rev = Revolute { n: [0.0, 0.0, 1.0] };
        link = multibody::parts::BodyShape { r: [1.0, 0.0, 0.0] };
        connect(world.frame_b, rev.frame_a);
        connect(rev.frame_b, link.frame_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    // The tip of a 1 m link cannot be 2 m from the pivot.
    let err = DaeProblem::new(
        &ssys,
        &[("link.frame_b.r_0[1]", 2.0), ("rev.w", 0.0)],
        (0.0, 1.0),
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("initialization did not converge"), "{err}");
    // The angle that would have to reach the impossible position, the equation that
    // fails, and the conditions that contradict it.
    assert!(
        err.contains("iteration variables (last values): rev.phi"),
        "{err}"
    );
    assert!(
        err.contains("in link.translation: link.translation.frame_b.r_0[1] ="),
        "{err}"
    );
    assert!(
        err.contains("initial conditions in force:") && err.contains("link.frame_b.r_0[1] = 2"),
        "{err}"
    );
}
