//! Closed kinematic loops: the seed tutorial's planar four-bar (closed by
//! `RevolutePlanarLoopConstraint`) and its spatial four-bar closed by a cut joint.
//! Assertions are closed forms (loop-closure kinematics, the spatial four-bar's
//! prismatic stroke and energy), a hand-written minimal-coordinate model of the planar
//! one, energy balances, agreement between formulations of one mechanism, and the
//! unknown counts the seed's users assert.

#[path = "../examples/fourbar.rs"]
#[allow(dead_code)]
mod fourbar_example;

#[path = "../examples/fourbar_cutjoint.rs"]
#[allow(dead_code)]
mod fourbar_cutjoint_example;

use multibody::prelude::*;

const G: f64 = 9.80665;

/// Total mechanical energy of BodyShapes with m = 1, r_CM = r/2 and inertia
/// diag(0.001) (the defaults), at every reported time.
fn energy(sol: &Solution, bodies: &[(&str, [f64; 3])]) -> Vec<f64> {
    let get = |name: String| sol.get(&name).unwrap();
    let mut e = vec![0.0; sol.t().len()];
    for (b, r) in bodies {
        let r_cm = [r[0] / 2.0, r[1] / 2.0, r[2] / 2.0];
        let t: Vec<Vec<Vec<f64>>> = (1..=3)
            .map(|i| {
                (1..=3)
                    .map(|j| get(format!("{b}.frame_a.R.T[{i},{j}]")))
                    .collect()
            })
            .collect();
        let w: Vec<Vec<f64>> = (1..=3).map(|i| get(format!("{b}.body.w_a[{i}]"))).collect();
        let v0: Vec<Vec<f64>> = (1..=3).map(|i| get(format!("{b}.body.v_0[{i}]"))).collect();
        let r0: Vec<Vec<f64>> = (1..=3)
            .map(|i| get(format!("{b}.frame_a.r_0[{i}]")))
            .collect();
        for (k, ek) in e.iter_mut().enumerate() {
            let w = [w[0][k], w[1][k], w[2][k]];
            // w x r_CM in frame_a, then resolved in the world (T' v).
            let wxr = [
                w[1] * r_cm[2] - w[2] * r_cm[1],
                w[2] * r_cm[0] - w[0] * r_cm[2],
                w[0] * r_cm[1] - w[1] * r_cm[0],
            ];
            let to_world = |v: [f64; 3]| -> [f64; 3] {
                std::array::from_fn(|i| (0..3).map(|j| t[j][i][k] * v[j]).sum())
            };
            let wxr0 = to_world(wxr);
            let v_cm: Vec<f64> = (0..3).map(|i| v0[i][k] + wxr0[i]).collect();
            let y_cm = r0[1][k] + to_world(r_cm)[1];
            *ek += 0.5 * v_cm.iter().map(|v| v * v).sum::<f64>()
                + 0.5 * 0.001 * w.iter().map(|v| v * v).sum::<f64>()
                + G * y_cm;
        }
    }
    e
}

/// The planar four-bar in minimal coordinates, written by hand: with j1 and j5 both at
/// the origin the loop is a rhombus of side L, and on the branch the model starts on
/// (a parallelogram) b3 = -b1 and b4 = -b2. With alpha = j1.phi (the angle of b1) and
/// beta = j1.phi + j2.phi + pi/2 (that of b2), a = alpha', b = beta', c = cos(beta -
/// alpha), s = sin(beta - alpha), each bar of mass 1, centre of mass at its middle and
/// inertia J = 0.001 about it:
///   centres of mass: b1 u1/2, b2 u1 + u2/2, b3 u2 + u1/2, b4 u2/2 (u_i = L e(angle)),
///   T = 1/2 (3/2 L^2 + 2 J)(a^2 + b^2) + L^2 c a b,  V = 2 g L (sin alpha + sin beta).
/// The dampers (d = 0.1) on j1 (rate a) and j2 (rate b - a) give the generalized forces
/// Q_alpha = -d a + d (b - a), Q_beta = -d (b - a). Lagrange's equations:
///   M11 a' + L^2 c b' - L^2 s b^2 + 2 g L cos alpha = Q_alpha,
///   L^2 c a' + M22 b' + L^2 s a^2 + 2 g L cos beta = Q_beta,  M11 = M22 = 3/2 L^2 + 2 J.
/// Returns the derivative of (alpha, beta, a, b).
fn rhombus_rhs(y: [f64; 4]) -> [f64; 4] {
    let (l, d, j) = (1.5f64, 0.1, 0.001);
    let (alpha, beta, a, b) = (y[0], y[1], y[2], y[3]);
    let (c, s) = ((beta - alpha).cos(), (beta - alpha).sin());
    let m11 = 1.5 * l * l + 2.0 * j;
    let m12 = l * l * c;
    let r1 = -d * a + d * (b - a) + l * l * s * b * b - 2.0 * G * l * alpha.cos();
    let r2 = -d * (b - a) - l * l * s * a * a - 2.0 * G * l * beta.cos();
    let det = m11 * m11 - m12 * m12;
    [
        a,
        b,
        (m11 * r1 - m12 * r2) / det,
        (m11 * r2 - m12 * r1) / det,
    ]
}

/// Classical RK4 of `rhombus_rhs` with step `h` from `y0` at t = 0, sampled at `times`
/// (multiples of `h`).
fn rhombus_rk4(y0: [f64; 4], h: f64, times: &[f64]) -> Vec<[f64; 4]> {
    let add =
        |y: [f64; 4], k: [f64; 4], f: f64| -> [f64; 4] { std::array::from_fn(|i| y[i] + f * k[i]) };
    let mut y = y0;
    let mut steps_done = 0usize;
    times
        .iter()
        .map(|&t| {
            let target = (t / h).round() as usize;
            assert!(
                (target as f64 * h - t).abs() < 1e-9,
                "{t} is not a multiple of {h}"
            );
            while steps_done < target {
                let k1 = rhombus_rhs(y);
                let k2 = rhombus_rhs(add(y, k1, h / 2.0));
                let k3 = rhombus_rhs(add(y, k2, h / 2.0));
                let k4 = rhombus_rhs(add(y, k3, h));
                y = std::array::from_fn(|i| {
                    y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
                });
                steps_done += 1;
            }
            y
        })
        .collect()
}

#[test]
fn planar_fourbar_dissipates_energy_and_keeps_its_loop_closed() {
    let ssys = structural_simplify(&fourbar_example::fourbar()).unwrap();
    // Two degrees of freedom: two angles and two speeds (the dampers' relative
    // coordinates, MSL's preferred states, equal to -j1.phi and -j2.phi), plus the two
    // loop angles iterated by IDA.
    assert_eq!(ssys.states().len(), 4, "{:?}", ssys.states());
    assert!(!ssys.unknowns().iter().any(|u| u.contains(".R.T[")));
    // At rtol 1e-8 IDA fails at t = 1.539 s, where the rhombus folds flat and the
    // closure's Jacobian in the loop angles it iterates on is singular (static state
    // selection); at rtol 1e-7 it steps across.
    let options = SolverOptions {
        rtol: 1e-7,
        atol: 1e-9,
        ..SolverOptions::default()
    };
    let sol = DaeProblem::new(&ssys, &[("j1.phi", 0.1)], (0.0, 10.0))
        .unwrap()
        .solve(&options.with_output_interval(0.0, 10.0, 0.001))
        .unwrap();
    let get = |name: &str| sol.get(name).unwrap();
    let (j1, j2, j3, j5) = (get("j1.phi"), get("j2.phi"), get("j3.phi"), get("j5.phi"));
    // The start: j1 as given, the rest at their start values (0, at rest).
    assert!((j1[0] - 0.1).abs() < 1e-9);
    assert!(j2[0].abs() < 1e-12 && get("j1.w")[0].abs() < 1e-12 && get("j2.w")[0].abs() < 1e-12);
    let l = 1.5;
    let bodies = [
        ("b1", [l, 0.0, 0.0]),
        ("b2", [0.0, l, 0.0]),
        ("b3", [-l, 0.0, 0.0]),
        ("b4", [0.0, -l, 0.0]),
    ];
    // Loop closure in closed form. The rhombus stays a parallelogram (b3 = -b1,
    // b4 = -b2): j3 = -j2 and j5 = -(j1 + j2), and the joint between b3 and b4 sits at
    // the end of b2 moved to the origin, L (-sin(j1 + j2), cos(j1 + j2)). Outputs are
    // projected onto the constraints (SolverOptions::project_outputs): round-off, so
    // 1e-9 (without projection the residual reaches 2e-4 next to the folding points).
    let (ax, ay) = (get("j4.frame_a.r_0[1]"), get("j4.frame_a.r_0[2]"));
    let (bx, by) = (get("j4.frame_b.r_0[1]"), get("j4.frame_b.r_0[2]"));
    for k in 0..sol.t().len() {
        let t = sol.t()[k];
        let q = j1[k] + j2[k];
        let residuals = [
            j3[k] + j2[k],
            j5[k] + q,
            ax[k] + l * q.sin(),
            ay[k] - l * q.cos(),
            (ax[k] - bx[k]).hypot(ay[k] - by[k]),
        ];
        for (i, r) in residuals.iter().enumerate() {
            assert!(r.abs() < 1e-9, "closure residual {i} = {r} at {t}");
        }
    }
    // The run covers the singular configurations: the rhombus stretches to a line
    // (j2 = -pi/2) and folds flat (j2 = -3 pi/2, b2 back on b1) more than once.
    assert!(j2.iter().cloned().fold(f64::MAX, f64::min) < -3.0 * std::f64::consts::PI);
    // Energy balance: kinetic plus potential energy plus the work of the dampers,
    // int 0.1 (j1.w^2 + j2.w^2) dt (trapezoid on the 1 ms grid), stays at its start.
    // Of the 32 J at the start the dampers take 42 J over the run. At rtol 1e-7 the
    // balance holds to 6e-4 J (the trapezoid adds 1e-4; at rtol 1e-6 it is 1e-2 J, an
    // integration error that depends on the order of the unknowns); 3e-3 J is 7e-5 of
    // the work, while a 1 % error in a damping constant or a mass moves it by 0.4 J or
    // more.
    let e = energy(&sol, &bodies);
    let (w1, w2) = (get("j1.w"), get("j2.w"));
    let power: Vec<f64> = (0..w1.len())
        .map(|k| 0.1 * (w1[k] * w1[k] + w2[k] * w2[k]))
        .collect();
    let mut work = 0.0;
    for k in 1..e.len() {
        work += 0.5 * (sol.t()[k] - sol.t()[k - 1]) * (power[k] + power[k - 1]);
        let balance = e[k] + work - e[0];
        assert!(
            balance.abs() < 3e-3,
            "energy balance off by {balance} J at {}",
            sol.t()[k]
        );
    }
    assert!(work > 40.0, "the dampers took only {work} J");

    // The dynamics against the hand-written minimal-coordinate model above, integrated
    // by RK4 at h = 1e-4 (its error is below 1e-12: h = 1e-3 gives the same digits),
    // up to 1 s: before the first singular configuration (j2 = -pi/2 at 1.09 s), so
    // the library can run at rtol 1e-8. By then j1 has turned by 2.6 rad and the
    // speeds reach 5 rad/s; the two agree to 8e-7, and 1e-5 leaves margin while the
    // bars' inertia J alone (0.06 % of M11) moves j1 by 4e-3 and j1.w by 3e-2 at 1 s.
    let times: Vec<f64> = (0..=100).map(|k| k as f64 * 0.01).collect();
    let tight = SolverOptions {
        rtol: 1e-8,
        atol: 1e-10,
        output_times: Some(times.clone()),
        ..SolverOptions::default()
    };
    let sol = DaeProblem::new(&ssys, &[("j1.phi", 0.1)], (0.0, 1.0))
        .unwrap()
        .solve(&tight)
        .unwrap();
    let half_pi = std::f64::consts::FRAC_PI_2;
    let reference = rhombus_rk4([0.1, 0.1 + half_pi, 0.0, 0.0], 1e-4, sol.t());
    let got = ["j1.phi", "j2.phi", "j1.w", "j2.w"].map(|n| sol.get(n).unwrap());
    for (k, y) in reference.iter().enumerate() {
        // j1 = alpha, j2 = beta - alpha - pi/2, and their rates.
        let expected = [y[0], y[1] - y[0] - half_pi, y[2], y[3] - y[2]];
        for i in 0..4 {
            assert!(
                (got[i][k] - expected[i]).abs() < 1e-5,
                "{} = {} vs {} (minimal coordinates) at {}",
                ["j1.phi", "j2.phi", "j1.w", "j2.w"][i],
                got[i][k],
                expected[i],
                sol.t()[k]
            );
        }
    }
}

/// The prismatic coordinate of the spatial four-bars (`fourbar_cutjoint`,
/// `fourbar_analytic`) as a function of the crank angle `phi = j1.phi`, in closed form.
/// j1 turns b1 about the world x axis (MSL: T = [1, 0, 0; 0, c, s; 0, -s, c]), so b1's
/// end is at A = T' (0, 0.5, 0.1) = (0, 0.5 c - 0.1 s, 0.5 s + 0.1 c); b2's end is at
/// B = (1.2 + s_p, 0.2, 0) (b0, then j2 along x, then b2). The rod (b3, or the
/// UniversalSpherical's rRod_ia = (-1, 0.3, 0.1)) keeps |A - B|^2 = 1.1, and with
/// A_y^2 + A_z^2 = 0.26:
///   (1.2 + s_p)^2 = 1.1 - (0.2 - A_y)^2 - A_z^2 = 0.8 + 0.4 A_y,
/// on the branch through s_p(0) = -0.2 (the other, near -2.2, never meets it: the root
/// stays above sqrt(0.8 - 0.4 sqrt(0.26)) = 0.77). Returns (s_p, d s_p / d phi).
fn prismatic_of_crank(phi: f64) -> (f64, f64) {
    let a_y = 0.5 * phi.cos() - 0.1 * phi.sin();
    let d_a_y = -0.5 * phi.sin() - 0.1 * phi.cos();
    let root = (0.8 + 0.4 * a_y).sqrt();
    (-1.2 + root, 0.2 * d_a_y / root)
}

#[test]
fn cut_joint_fourbar_has_j1_as_its_only_states() {
    let ssys = structural_simplify(&fourbar_cutjoint_example::fourbar_cutjoint()).unwrap();
    assert_eq!(ssys.states(), ["j1.phi", "j1.w"]);
    // The choice in a loop depends on the configuration: j1 is chosen among the loop's
    // joint angles (the solver watches it and would change to dynamic states).
    let groups = ssys.state_candidates();
    assert_eq!(groups.len(), 1, "{groups:?}");
    assert_eq!(groups[0].chosen, ["j1.phi"]);
    for j in ["j1.phi", "j2.s", "j3.phi", "j4.phi", "j5.phi"] {
        assert!(groups[0].candidates.iter().any(|c| c == j), "{groups:?}");
    }
    assert!(ssys.warnings().is_empty(), "{:?}", ssys.warnings());
    let u = ssys.unknowns();
    // Multibody.jl: 8 unknowns (2 states + 6 joint angles). Tearing here also solves
    // j2.s from the closure equation that is linear in it, so 7 remain (Dymola's
    // Fourbar1 needs 5: it also solves two angles in closed form).
    assert_eq!(u.len(), 7, "{u:?}");
    assert_eq!(u[0], "j1.phi");
    assert_eq!(u[6], "j1.w");
    for name in &u[1..6] {
        assert!(name.ends_with(".phi"), "{name} is not a joint angle");
    }
    assert_eq!(
        ssys.mass_matrix_diagonal(),
        [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]
    );
    let sol = DaeProblem::new(&ssys, &[], (0.0, 1.4399))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    // The cut joint's orientation residue stays closed: frame_b.R = Rz(phi) frame_a.R.
    let phi = sol.get("j5.phi").unwrap();
    let entries = |frame: &str| -> Vec<Vec<Vec<f64>>> {
        (1..=3)
            .map(|i| {
                (1..=3)
                    .map(|j| sol.get(format!("j5.{frame}.R.T[{i},{j}]")).unwrap())
                    .collect()
            })
            .collect()
    };
    let (ta, tb) = (entries("frame_a"), entries("frame_b"));
    let mut worst: f64 = 0.0;
    for k in 0..sol.t().len() {
        let (c, s) = (phi[k].cos(), phi[k].sin());
        let rz = [[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]];
        for i in 0..3 {
            for j in 0..3 {
                let expected: f64 = (0..3).map(|m| rz[i][m] * ta[m][j][k]).sum();
                worst = worst.max((expected - tb[i][j][k]).abs());
            }
        }
    }
    // Projected outputs: round-off (4e-5 at the default tolerance without projection).
    assert!(worst < 1e-9, "orientation residue {worst}");
    // Outputs at the integrator's own steps. The prismatic coordinate follows the
    // crank in closed form (`prismatic_of_crank`) at every one: projected outputs, so
    // round-off (measured 1e-15); a transposed crank rotation (A_y = 0.5 c + 0.1 s)
    // would miss by up to 0.045.
    let s = sol.get("j2.s").unwrap();
    let crank = sol.get("j1.phi").unwrap();
    assert!((s[0] + 0.2).abs() < 1e-12);
    for k in 0..s.len() {
        let expected = prismatic_of_crank(crank[k]).0;
        assert!(
            (s[k] - expected).abs() < 1e-10,
            "j2.s = {} vs {expected} at j1.phi = {}",
            s[k],
            crank[k]
        );
    }
    // The crank turns almost twice (12.37 rad), more than once, so the prismatic joint
    // sweeps its whole stroke, -1.2 + sqrt(0.8 -+ 0.4 sqrt(0.26)) = -0.427964 ..
    // -0.198022 (at A_y = -+ |(A_y, A_z)|); the steps sample its flat ends to 1e-4.
    assert!(crank[crank.len() - 1] > 2.0 * std::f64::consts::PI);
    let (s_min, s_max) = (
        -1.2 + (0.8 - 0.4 * 0.26f64.sqrt()).sqrt(),
        -1.2 + (0.8 + 0.4 * 0.26f64.sqrt()).sqrt(),
    );
    let lowest = s.iter().cloned().fold(f64::MAX, f64::min);
    let highest = s.iter().cloned().fold(f64::MIN, f64::max);
    assert!(
        lowest >= s_min - 1e-12 && lowest < s_min + 1e-4,
        "{lowest} vs {s_min}"
    );
    assert!(
        highest <= s_max + 1e-12 && highest > s_max - 1e-4,
        "{highest} vs {s_max}"
    );
}

#[test]
fn the_spatial_loop_cut_anywhere_has_the_same_unknowns() {
    // Multibody.jl: cutting j5 gives 8 unknowns, any other joint 17. Here every choice,
    // and none (automatic breaking at a connection), gives j1's two states and five
    // loop angles.
    for cut in [
        Some("j2"),
        None,
        Some("j3"),
        Some("j4"),
        Some("j5"),
        Some("rev"),
        Some("rev1"),
    ] {
        let ssys = structural_simplify(&fourbar_cutjoint_example::fourbar_with_cut(cut))
            .unwrap_or_else(|e| panic!("cut {cut:?}: {e}"));
        assert_eq!(ssys.states(), ["j1.phi", "j1.w"], "cut {cut:?}");
        assert_eq!(
            ssys.unknowns().len(),
            7,
            "cut {cut:?}: {:?}",
            ssys.unknowns()
        );
        assert!(
            !ssys.unknowns().iter().any(|u| u.contains(".R.T[")),
            "cut {cut:?}"
        );
    }
}

#[test]
fn the_spatial_loop_cut_anywhere_moves_the_same() {
    // The same mechanism, its loop closed at different joints (or broken at a
    // connection): different equations, one motion. At rtol 1e-10 the choices agree
    // to 2.2e-7 (to 2e-6 at rtol 1e-9 and 3e-8 at 1e-11: the differences are the
    // integration's error, shrinking with it), so 2e-6. What differs between the
    // runs is where the loop's constraint forces and torques are carried: a cut joint
    // or a breaking that dropped or mis-resolved one would show here.
    let options = SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        ..SolverOptions::default()
    }
    .with_output_interval(0.0, 1.4399, 0.01);
    let run = |cut: Option<&str>| {
        let ssys = structural_simplify(&fourbar_cutjoint_example::fourbar_with_cut(cut)).unwrap();
        DaeProblem::new(&ssys, &[], (0.0, 1.4399))
            .unwrap()
            .solve(&options)
            .unwrap()
    };
    let reference = run(Some("j5"));
    for cut in [
        None,
        Some("j2"),
        Some("j3"),
        Some("j4"),
        Some("rev"),
        Some("rev1"),
    ] {
        let sol = run(cut);
        assert_eq!(sol.t(), reference.t());
        for name in ["j1.phi", "j1.w", "j2.s", "j2.v"] {
            let (a, b) = (sol.get(name).unwrap(), reference.get(name).unwrap());
            let worst = a
                .iter()
                .zip(&b)
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max);
            assert!(worst < 2e-6, "cut {cut:?}: {name} differs by {worst}");
        }
    }
}

/// The planar four-bar with `j4` a plain revolute joint: five parallel revolute joints.
fn planar_fourbar_without_loop_constraint() -> System {
    let mut model = fourbar_example::fourbar().into_system();
    assert!(model.replace("j4", &multibody::joints::Revolute::default()));
    model
}

#[test]
fn planar_loop_of_revolute_joints_is_diagnosed() {
    let Err(err) = structural_simplify(&planar_fourbar_without_loop_constraint()) else {
        panic!("a planar loop of revolute joints is singular");
    };
    let err = err.to_string();
    for joint in ["j1", "j2", "j3", "j4", "j5"] {
        assert!(
            err.contains(&format!("`{joint}`")),
            "{joint} not named: {err}"
        );
    }
    assert!(err.contains("RevolutePlanarLoopConstraint"), "{err}");
}

#[test]
fn planar_loop_with_redundancy_removed_matches_the_loop_constraint_version() {
    use multibody::{PlanarLoops, SimplifyOptions, structural_simplify_with};
    let options = SimplifyOptions {
        planar_loops: PlanarLoops::RemoveRedundant,
        ..SimplifyOptions::default()
    };
    let automatic =
        structural_simplify_with(&planar_fourbar_without_loop_constraint(), &options).unwrap();
    let reference = structural_simplify(&fourbar_example::fourbar()).unwrap();
    // Both integrated far below the comparison's tolerance (their states differ).
    let tight = SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        output_times: Some((1..=100).map(|k| k as f64 * 0.01).collect()),
        ..SolverOptions::default()
    };
    let solve = |ssys: &SimplifiedSystem| {
        DaeProblem::new(ssys, &[("j1.phi", 0.1)], (0.0, 1.0))
            .unwrap()
            .solve(&tight)
            .unwrap()
    };
    let (a, b) = (solve(&automatic), solve(&reference));
    // j4.phi exists only in the automatic version: the model's variables all stay.
    assert!(a.get("j4.phi").is_ok());
    let mut worst: f64 = 0.0;
    for name in ["j1.phi", "j2.phi", "j3.phi", "j1.w", "j2.w", "j3.w"] {
        let (x, y) = (a.get(name).unwrap(), b.get(name).unwrap());
        for (p, q) in x.iter().zip(&y) {
            worst = worst.max((p - q).abs());
        }
    }
    assert!(worst < 1e-6, "the two versions differ by {worst}");
}

#[test]
fn planar_loops_are_found_from_the_geometry_only() {
    use multibody::loops::planar_loops;
    let loops = planar_loops(&planar_fourbar_without_loop_constraint());
    assert_eq!(loops, [["j1", "j2", "j3", "j4", "j5"]]);
    // Closed by the loop constraint: nothing to report.
    assert!(planar_loops(&fourbar_example::fourbar()).is_empty());
    // The spatial four-bar's axes are not parallel.
    for cut in [None, Some("j5")] {
        assert!(planar_loops(&fourbar_cutjoint_example::fourbar_with_cut(cut)).is_empty());
    }
}

#[path = "../examples/fourbar_analytic.rs"]
#[allow(dead_code)]
mod fourbar_analytic_example;

#[test]
fn analytic_fourbar_iterates_on_the_prismatic_coordinate() {
    let ssys = structural_simplify(&fourbar_analytic_example::fourbar_analytic()).unwrap();
    // Multibody.jl and the seed: 3 unknowns, diagonal [1, 0, 1]; the rod length is the one
    // nonlinear equation, iterated on j2.s (not solved as a quadratic in closed form).
    assert_eq!(ssys.unknowns(), ["j1.phi", "j2.s", "j1.w"]);
    assert_eq!(ssys.mass_matrix_diagonal(), [1.0, 0.0, 1.0]);
    let options = SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        ..SolverOptions::default()
    }
    .with_output_interval(0.0, 1.4399, 0.01);
    let analytic = DaeProblem::new(&ssys, &[], (0.0, 1.4399))
        .unwrap()
        .solve(&options)
        .unwrap();
    let get = |name: &str| analytic.get(name).unwrap();
    let (crank, w, s, v) = (get("j1.phi"), get("j1.w"), get("j2.s"), get("j2.v"));
    // The mechanism has one degree of freedom and no losses, so its motion follows in
    // closed form from the crank angle. Kinematics: s and v = ds/dphi w from
    // `prismatic_of_crank`. Energy (the rod is massless): b1 (1 kg, centre of mass
    // (0, 0.25, 0.05) from the crank axis, inertia 0.001) turns about x with
    // I = 0.001 + 0.25^2 + 0.05^2 = 0.066 and height 0.25 cos - 0.05 sin; b2 (1 kg)
    // slides at v on a level line. So
    //   1/2 (0.066 + (ds/dphi)^2) w^2 + g (0.25 cos phi - 0.05 sin phi) = E0,
    // with w(0) = j1.w_start = 5.235987755983: w = sqrt(2 (E0 - V(phi)) / M(phi)) > 0.
    let inertia = |phi: f64| 0.066 + prismatic_of_crank(phi).1.powi(2);
    let height = |phi: f64| G * (0.25 * phi.cos() - 0.05 * phi.sin());
    let w0 = 5.235987755983;
    let e0 = 0.5 * inertia(0.0) * w0 * w0 + height(0.0);
    assert!(crank[crank.len() - 1] > 12.0, "the crank turns about twice");
    for k in 0..crank.len() {
        let t = analytic.t()[k];
        let (s_expected, ds) = prismatic_of_crank(crank[k]);
        let w_expected = (2.0 * (e0 - height(crank[k])) / inertia(crank[k])).sqrt();
        // s and v: projected outputs, round-off (1e-15 measured).
        assert!(
            (s[k] - s_expected).abs() < 1e-10,
            "j2.s = {} vs {s_expected} at {t}",
            s[k]
        );
        assert!(
            (v[k] - ds * w[k]).abs() < 1e-10,
            "j2.v = {} vs {} at {t}",
            v[k],
            ds * w[k]
        );
        // w: the integration's error, 3e-8 at rtol 1e-10 (1.3e-6 at 1e-8: it converges
        // to the closed form); 1e-6 leaves margin. The speed swings between 5.1 and
        // 13.3 rad/s: leaving out b2's mass misses by 0.9, a 1 % error in b1's inertia
        // about the axis by 0.06.
        assert!(
            (w[k] - w_expected).abs() < 1e-6,
            "j1.w = {} vs {w_expected} at {t}",
            w[k]
        );
    }
    // The rod keeps its length: |b1.frame_b.r_0 - b2.frame_b.r_0| = |rRod_ia|.
    let length = (1.0f64 + 0.09 + 0.01).sqrt();
    let p: Vec<Vec<f64>> = ["b1.frame_b.r_0", "b2.frame_b.r_0"]
        .iter()
        .flat_map(|f| (1..=3).map(move |i| format!("{f}[{i}]")))
        .map(|n| analytic.get(&n).unwrap())
        .collect();
    for k in 0..crank.len() {
        let d: f64 = (0..3)
            .map(|i| (p[i][k] - p[3 + i][k]).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!(
            (d - length).abs() < 1e-6,
            "rod length {d} at {}",
            analytic.t()[k]
        );
    }
}

#[test]
fn a_loop_that_cannot_close_names_its_joints_and_asks_for_guesses() {
    use multibody::joints::{Revolute, RevolutePlanarLoopConstraint};
    use multibody::parts::BodyShape;
    use multibody::world::World;
    // b3 and b4 together reach 1 m from the origin; with j1 and j2 at 0 the end of b2 is
    // 2.1 m away: no configuration closes the loop.
    let model = system! {
        name: "short_fourbar";
        world = World::default();
        j1 = Revolute::default();
        j2 = Revolute::default();
        j3 = Revolute::default();
        j4 = RevolutePlanarLoopConstraint::default();
        j5 = Revolute::default();
        b1 = BodyShape { r: [1.5, 0.0, 0.0] };
        b2 = BodyShape { r: [0.0, 1.5, 0.0] };
        b3 = BodyShape { r: [-0.5, 0.0, 0.0] };
        b4 = BodyShape { r: [0.0, -0.5, 0.0] };
        connect(world.frame_b, j1.frame_a);
        connect(j1.frame_b, b1.frame_a);
        connect(b1.frame_b, j2.frame_a);
        connect(j2.frame_b, b2.frame_a);
        connect(b2.frame_b, j3.frame_a);
        connect(j3.frame_b, b3.frame_a);
        connect(b3.frame_b, j4.frame_a);
        connect(j4.frame_b, b4.frame_a);
        connect(b4.frame_b, j5.frame_a);
        connect(j5.frame_b, world.frame_b);
    };
    let ssys = structural_simplify(&model).unwrap();
    let start = [
        ("j1.phi", 0.0),
        ("j2.phi", 0.0),
        ("j1.w", 0.0),
        ("j2.w", 0.0),
    ];
    let Err(err) = DaeProblem::new(&ssys, &start, (0.0, 1.0)) else {
        panic!("the loop cannot close");
    };
    let err = err.to_string();
    assert!(err.contains("did not converge"), "{err}");
    assert!(
        err.contains("`j3`, `j5`") || err.contains("`j5`, `j3`"),
        "{err}"
    );
    assert!(err.contains("new_with_guesses"), "{err}");
}

/// The initialization system is torn like the DAE: it iterates on joint coordinates,
/// never on entries of orientation matrices (which the joints compute from them). The
/// planar four-bar closes its loop through j3 and j5 (j1 is given); the spatial one
/// through the joint coordinates of its loop.
#[test]
fn initialization_iterates_on_joint_coordinates_only() {
    for (model, overrides, expected) in [
        (
            fourbar_example::fourbar().into_system(),
            vec![("j1.phi", 0.1)],
            vec!["j3.phi", "j5.phi"],
        ),
        (
            fourbar_cutjoint_example::fourbar_cutjoint().into_system(),
            vec![],
            vec!["rev1.phi", "rev.phi", "j3.phi", "j4.phi", "j5.phi"],
        ),
    ] {
        let ssys = structural_simplify(&model).unwrap();
        let prob = DaeProblem::new(&ssys, &overrides, (0.0, 1.0)).unwrap();
        let report = prob.init_report();
        assert!(
            !report.iteration_variables.is_empty(),
            "{}: a loop needs iteration",
            ssys.name()
        );
        // (In the order tearing picks them: compared as sets.)
        let mut got = report.iteration_variables.clone();
        got.sort();
        let mut expected = expected;
        expected.sort();
        assert_eq!(got, expected, "{}", ssys.name());
        for v in &report.iteration_variables {
            assert!(
                !v.contains(".R.") && !v.contains(".T["),
                "{}: iterates on {v}: {:?}",
                ssys.name(),
                report.iteration_variables
            );
        }
    }
}

#[test]
fn initialization_keeps_the_loop_angles_within_half_a_turn_of_their_starts() {
    // With j1 and j2 given, the planar four-bar's other angles are found by Newton from
    // their start values (0). Without care, Newton's first steps carry them whole turns
    // away (j5 = 7.35 where 1.07 is the same configuration). Every angle must come out
    // within half a turn of its start, and the loop closed.
    let ssys = structural_simplify(&fourbar_example::fourbar()).unwrap();
    for (j1, j2) in [
        (0.5, 1.0),
        (0.5, 2.0),
        (1.0, 2.0),
        (2.0, -2.5),
        (-2.0, -2.5),
    ] {
        let problem = DaeProblem::new(&ssys, &[("j1.phi", j1), ("j2.phi", j2)], (0.0, 0.01))
            .unwrap_or_else(|e| panic!("({j1}, {j2}): {e}"));
        let sol = problem.solve(&SolverOptions::default()).unwrap();
        for name in ["j1.phi", "j2.phi", "j3.phi", "j5.phi"] {
            let phi = sol.get(name).unwrap()[0];
            assert!(
                phi.abs() <= std::f64::consts::PI,
                "({j1}, {j2}): {name} = {phi}, more than half a turn from its start 0"
            );
        }
        // Closed: the sum of the loop's rotations is a whole number of turns (the
        // planar loop constraint j4 takes the rest), and the given angles are kept.
        let get = |n: &str| sol.get(n).unwrap()[0];
        assert!((get("j1.phi") - j1).abs() < 1e-12 && (get("j2.phi") - j2).abs() < 1e-12);
        let end = sol
            .sample(&["j4.frame_a.r_0[1]", "j4.frame_a.r_0[2]"], &[0.0])
            .unwrap();
        let other = sol
            .sample(&["j4.frame_b.r_0[1]", "j4.frame_b.r_0[2]"], &[0.0])
            .unwrap();
        for i in 0..2 {
            assert!(
                (end[i][0] - other[i][0]).abs() < 1e-9,
                "({j1}, {j2}) open by {}",
                end[i][0] - other[i][0]
            );
        }
    }
}
