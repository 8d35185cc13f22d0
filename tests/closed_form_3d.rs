//! 3-D motions with closed-form trajectories: a spherical pendulum in steady conical
//! motion, and the torque-free motion of an axisymmetric rigid body. Each is compared
//! with its closed form at many times, so a wrong inertia, mass, gravity, sign or
//! rotation convention fails (not only invariants, which a wrong model may also keep).

use multibody::joints::Spherical;
use multibody::parts::{Body, OrientationStates};
use multibody::prelude::*;
use multibody::world::World;

const G: f64 = 9.80665;

/// Tolerances far below the comparisons' (1e-6 on quantities of order 1).
fn tight() -> SolverOptions {
    SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        ..SolverOptions::default()
    }
}

/// `T` of `frame` at every reported time: `t[i][j][k]` is `T[i+1,j+1]` at time k.
fn matrix(sol: &Solution, frame: &str) -> Vec<Vec<Vec<f64>>> {
    (1..=3)
        .map(|i| {
            (1..=3)
                .map(|j| sol.get(format!("{frame}.R.T[{i},{j}]")).unwrap())
                .collect()
        })
        .collect()
}

/// The conical pendulum: a 1 kg body on a ball joint at the world origin, its centre of
/// mass L = 1 m below the joint (r_CM = -L y in the body frame, gravity along -y), with
/// the default isotropic inertia 0.001 kg m2 about the centre of mass.
///
/// Steady conical motion: the rod at a constant angle theta from the downward vertical,
/// the whole body turning about the world's y axis at Omega. For a rigid rotation at
/// constant w = Omega y, dL/dt = w x L with L = J w + m r x (w x r): the isotropic J
/// drops out (w x J w = 0), and the balance with the gravity torque r x m g is the
/// point mass's, Omega^2 = g / (L cos theta).
///
/// The joint's Cardan sequence [2, 3, 1] makes this motion phi = (Omega t, theta, 0): a
/// turn about y (azimuth), then about the new z (tilt). The rod direction in the world
/// is then -T' y = (sin theta cos(Omega t), -cos theta, -sin theta sin(Omega t)).
#[test]
fn spherical_pendulum_in_steady_conical_motion() {
    let l = 1.0;
    let model = system! {
        name: "conical_pendulum";
        world = World::default();
        joint = Spherical { state: true, sequence: [2, 3, 1], orientation_states: OrientationStates::Cardan };
        body = Body { m: 1.0, r_CM: [0.0, -1.0, 0.0] };
        connect(world.frame_b, joint.frame_a);
        connect(joint.frame_b, body.frame_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    assert_eq!(ssys.states().len(), 6, "{:?}", ssys.states());
    let theta: f64 = 0.6;
    let omega = (G / (l * theta.cos())).sqrt(); // 3.447 rad/s, period 1.823 s
    let period = 2.0 * std::f64::consts::PI / omega;
    let t_end = 4.0 * period;
    let start = [
        ("joint.phi[1]", 0.0),
        ("joint.phi[2]", theta),
        ("joint.phi[3]", 0.0),
        ("joint.phi_d[1]", omega),
        ("joint.phi_d[2]", 0.0),
        ("joint.phi_d[3]", 0.0),
    ];
    let options = SolverOptions {
        output_times: Some((0..=400).map(|k| k as f64 * t_end / 400.0).collect()),
        ..tight()
    };
    let sol = DaeProblem::new(&ssys, &start, (0.0, t_end))
        .unwrap()
        .solve(&options)
        .unwrap();
    let phi: Vec<Vec<f64>> = (1..=3)
        .map(|i| sol.get(format!("joint.phi[{i}]")).unwrap())
        .collect();
    let t_b = matrix(&sol, "body.frame_a");
    // rtol 1e-10 over four periods of a stable motion: errors of order 1e-9. 1e-6
    // leaves margin; a 1 % error in g, m L^2 or Omega shows as a nutation of 0.015 rad
    // or an azimuth error of 0.25 rad by the end.
    let tol = 1e-6;
    for (k, &t) in sol.t().iter().enumerate() {
        assert!(
            (phi[0][k] - omega * t).abs() < tol,
            "azimuth {} at {t}",
            phi[0][k]
        );
        assert!(
            (phi[1][k] - theta).abs() < tol,
            "polar angle {} at {t}",
            phi[1][k]
        );
        assert!(phi[2][k].abs() < tol, "third angle {} at {t}", phi[2][k]);
        let rod = [-t_b[1][0][k], -t_b[1][1][k], -t_b[1][2][k]];
        let expected = [
            theta.sin() * (omega * t).cos(),
            -theta.cos(),
            -theta.sin() * (omega * t).sin(),
        ];
        for i in 0..3 {
            assert!(
                (rod[i] - expected[i]).abs() < tol,
                "rod direction {rod:?} vs {expected:?} at {t}"
            );
        }
        // The body turns about the world's vertical at Omega: w resolved in the body
        // frame is T (0, Omega, 0).
        for i in 0..3 {
            let w = sol.get(format!("body.w_a[{}]", i + 1)).unwrap()[k];
            assert!(
                (w - omega * t_b[i][1][k]).abs() < tol,
                "w_a[{}] = {w} at {t}",
                i + 1
            );
        }
    }
}

/// Torque-free motion of an axisymmetric body, I1 = I2 = 0.1, I3 = 0.3, from
/// w0 = (0.5, 0, 2) in the body frame (which starts aligned with the world).
///
/// Euler's equations: I1 w1' = (I1 - I3) w2 w3, I1 w2' = (I3 - I1) w3 w1, I3 w3' = 0,
/// so w3 = 2 and (w1, w2) = 0.5 (cos(Omega t), sin(Omega t)) with
/// Omega = (I3 - I1) / I1 w3 = 4 rad/s.
///
/// In the world the angular momentum L = I w0 = (0.05, 0, 0.6) is fixed, and the
/// symmetry axis e3 turns about it: w = L / I1 - (I3 - I1) / I1 w3 e3, so
/// der(e3) = w x e3 = (L / I1) x e3, a rotation about L at |L| / I1 = 6.02 rad/s.
#[test]
fn axisymmetric_free_body_precesses_in_closed_form() {
    let (i1, i3) = (0.1f64, 0.3f64);
    let w0 = [0.5, 0.0, 2.0];
    let omega = (i3 - i1) / i1 * w0[2];
    let l = [i1 * w0[0], i1 * w0[1], i3 * w0[2]];
    let l_norm = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
    let lh = l.map(|x| x / l_norm);
    let rate = l_norm / i1;
    // e3(t) by Rodrigues' formula from e3(0) = (0, 0, 1).
    let e3 = |t: f64| -> [f64; 3] {
        let (c, s) = ((rate * t).cos(), (rate * t).sin());
        let x = [0.0, 0.0, 1.0];
        let cross = [
            lh[1] * x[2] - lh[2] * x[1],
            lh[2] * x[0] - lh[0] * x[2],
            lh[0] * x[1] - lh[1] * x[0],
        ];
        let dot = lh[2];
        std::array::from_fn(|i| x[i] * c + cross[i] * s + lh[i] * dot * (1.0 - c))
    };
    for states in [OrientationStates::Cardan, OrientationStates::Quaternion] {
        let model = system! {
            name: "axisymmetric";
            world = World { g: 0.0 };
            body = Body { m: 2.0, I_11: 0.1, I_22: 0.1, I_33: 0.3, orientation_states: states };
        };
        let ssys = structural_simplify(&model).unwrap();
        // At zero Cardan angles their rates are the body-frame angular velocity.
        let start: Vec<(&str, f64)> = match states {
            OrientationStates::Cardan => vec![
                ("body.phi_d[1]", w0[0]),
                ("body.phi_d[2]", w0[1]),
                ("body.phi_d[3]", w0[2]),
            ],
            OrientationStates::Quaternion => vec![
                ("body.w_a[1]", w0[0]),
                ("body.w_a[2]", w0[1]),
                ("body.w_a[3]", w0[2]),
            ],
        };
        let options = SolverOptions {
            output_times: Some((0..=500).map(|k| k as f64 * 0.02).collect()),
            ..tight()
        };
        let sol = DaeProblem::new(&ssys, &start, (0.0, 10.0))
            .unwrap()
            .solve(&options)
            .unwrap();
        let w = sol
            .get_many(&["body.w_a[1]", "body.w_a[2]", "body.w_a[3]"])
            .unwrap();
        let t_b = matrix(&sol, "body.frame_a");
        // rtol 1e-10 over 6.4 turns of (w1, w2) and 9.6 of e3: errors near 1e-8; 1e-6
        // leaves margin. Swapping I1 and I3 reverses the turn (Omega = -1.33), and a
        // 1 % error in Omega shifts (w1, w2) by 0.2 by t = 10.
        let tol = 1e-6;
        for (k, &t) in sol.t().iter().enumerate() {
            let expected = [w0[0] * (omega * t).cos(), w0[0] * (omega * t).sin(), w0[2]];
            for i in 0..3 {
                assert!(
                    (w[i][k] - expected[i]).abs() < tol,
                    "{states:?}: w_a = ({}, {}, {}) vs {expected:?} at {t}",
                    w[0][k],
                    w[1][k],
                    w[2][k]
                );
            }
            // The body's third axis in the world is the third row of T.
            let axis = [t_b[2][0][k], t_b[2][1][k], t_b[2][2][k]];
            let e = e3(t);
            for i in 0..3 {
                assert!(
                    (axis[i] - e[i]).abs() < tol,
                    "{states:?}: e3 = {axis:?} vs {e:?} at {t}"
                );
            }
        }
    }
}
