//! BodyBox and BodyCylinder with an offset shape (`r_shape`, `length_direction`,
//! `length`): their mass, centre of mass and inertia against MSL's formulas evaluated by
//! hand here (outer products of the principal axes, not the library's matrices), the
//! same numbers read back from the compiled model, a physical pendulum's period, and a
//! tumbling spherical pendulum against a plain `Body` given the hand-computed
//! properties.

#![allow(missing_docs)]

#[path = "support/mechanics.rs"]
mod mechanics;

use mechanics::{MassProps, body_energy, relative_drift, rotation, vector};
use multibody::joints::{Revolute, Spherical};
use multibody::parts::{Body, BodyBox, BodyCylinder, OrientationStates};
use multibody::prelude::*;
use multibody::world::World;

const G: f64 = 9.80665;
const PI: f64 = std::f64::consts::PI;

type V3 = [f64; 3];
type M3 = [[f64; 3]; 3];

fn norm(a: V3) -> f64 {
    mechanics::dot(a, a).sqrt()
}

/// `sum_k d_k e_k e_k'`: the inertia whose principal axes are the unit vectors `e_k`
/// with moments `d_k`.
fn from_principal(axes: [V3; 3], d: V3) -> M3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| (0..3).map(|k| d[k] * axes[k][i] * axes[k][j]).sum())
    })
}

fn assert_close(what: &str, got: f64, want: f64, tol: f64) {
    assert!(
        (got - want).abs() <= tol,
        "{what}: {got}, expected {want} (tolerance {tol:e})"
    );
}

fn assert_props(what: &str, got: &MassProps, want: &MassProps, rel: f64) {
    assert_close(&format!("{what} m"), got.m, want.m, rel * want.m);
    for i in 0..3 {
        assert_close(
            &format!("{what} r_cm[{i}]"),
            got.r_cm[i],
            want.r_cm[i],
            1e-15,
        );
        for j in 0..3 {
            let tol = rel * (want.inertia[0][0] + want.inertia[1][1] + want.inertia[2][2]);
            assert_close(
                &format!("{what} I[{i}][{j}]"),
                got.inertia[i][j],
                want.inertia[i][j],
                tol,
            );
        }
    }
}

fn props_of(p: multibody::parts::MassProperties) -> MassProps {
    MassProps {
        m: p.m,
        r_cm: p.r_cm,
        inertia: p.inertia,
    }
}

// ---------------------------------------------------------------------------------------
// The shapes and their mass properties by hand.

/// A box with every default of the new parameters in play: r = (0.3, 0.4, 0), so
/// |r| = 0.5 and the principal axes are e_x = (0.6, 0.8, 0), e_z = e_x x (0, 1, 0)
/// normalized = (0, 0, 1), e_y = e_z x e_x = (-0.8, 0.6, 0); r_shape = (0.1, 0, 0.05),
/// so length_direction = r - r_shape = (0.2, 0.4, -0.05) and length = |r - r_shape|
/// = 0.45; width = length / 20 = 0.0225, height = width; a hollow 0.01 x 0.008.
fn offset_box() -> BodyBox {
    BodyBox {
        r: [0.3, 0.4, 0.0],
        r_shape: [0.1, 0.0, 0.05],
        inner_width: 0.01,
        inner_height: Some(0.008),
        orientation_states: OrientationStates::Quaternion,
        ..Default::default()
    }
}

fn offset_box_by_hand() -> MassProps {
    let (l, w, h, wi, hi, rho) = (0.45, 0.0225, 0.0225, 0.01, 0.008, 7700.0);
    let (mo, mi) = (rho * l * w * h, rho * l * wi * hi);
    let d = [
        (mo * (w * w + h * h) - mi * (wi * wi + hi * hi)) / 12.0,
        (mo * (l * l + h * h) - mi * (l * l + hi * hi)) / 12.0,
        (mo * (l * l + w * w) - mi * (l * l + wi * wi)) / 12.0,
    ];
    MassProps {
        m: mo - mi,
        // r_shape + (r - r_shape) / 2.
        r_cm: [0.2, 0.2, 0.025],
        inertia: from_principal([[0.6, 0.8, 0.0], [-0.8, 0.6, 0.0], [0.0, 0.0, 1.0]], d),
    }
}

/// A box beside the line from frame_a to frame_b, with MSL's quirk visible: r along x,
/// the box from r_shape = (0, 0.05, 0) along length_direction = (2, 0, 0) (any length)
/// for length 0.5 (given; the default would be |r - r_shape|), width 0.04 along
/// width_direction (0, 0, 1), height 0.03. The centre of mass follows
/// length_direction: (0.25, 0.05, 0); the principal axes follow r and width_direction:
/// e_x = (1, 0, 0), e_z = e_x x (0, 0, 1) = (0, -1, 0), e_y = e_z x e_x = (0, 0, 1).
fn beside_box() -> BodyBox {
    BodyBox {
        r: [0.5, 0.0, 0.0],
        r_shape: [0.0, 0.05, 0.0],
        length_direction: Some([2.0, 0.0, 0.0]),
        length: Some(0.5),
        width: Some(0.04),
        height: Some(0.03),
        width_direction: [0.0, 0.0, 1.0],
        ..Default::default()
    }
}

fn beside_box_by_hand() -> MassProps {
    let (l, w, h, rho) = (0.5, 0.04, 0.03, 7700.0);
    let m = rho * l * w * h;
    let d = [
        m * (w * w + h * h) / 12.0,
        m * (l * l + h * h) / 12.0,
        m * (l * l + w * w) / 12.0,
    ];
    MassProps {
        m,
        r_cm: [0.25, 0.05, 0.0],
        inertia: from_principal([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]], d),
    }
}

/// A tube: r = (0, -0.4, 0.3) (|r| = 0.5, axis e_x = (0, -0.8, 0.6); with the y axis
/// (0, 1, 0): e_z = e_x x (0, 1, 0) normalized = (-1, 0, 0), e_y = e_z x e_x
/// = (0, 0.6, 0.8)); r_shape = (0.12, 0, 0), so length = |(-0.12, -0.4, 0.3)| = 0.5140..
/// and the centre of mass is at (r + r_shape) / 2 = (0.06, -0.2, 0.15); diameter 0.08,
/// inner diameter 0.05.
fn offset_tube() -> BodyCylinder {
    BodyCylinder {
        r: [0.0, -0.4, 0.3],
        r_shape: [0.12, 0.0, 0.0],
        diameter: Some(0.08),
        inner_diameter: 0.05,
        orientation_states: OrientationStates::Quaternion,
        ..Default::default()
    }
}

fn offset_tube_by_hand() -> MassProps {
    let l = (0.12f64 * 0.12 + 0.4 * 0.4 + 0.3 * 0.3).sqrt();
    let (ro, ri, rho) = (0.04, 0.025, 7700.0);
    let mo = rho * PI * l * ro * ro;
    let mi = rho * PI * l * ri * ri;
    let axial = (mo * ro * ro - mi * ri * ri) / 2.0;
    let across = (mo * (l * l + 3.0 * ro * ro) - mi * (l * l + 3.0 * ri * ri)) / 12.0;
    MassProps {
        m: mo - mi,
        r_cm: [0.06, -0.2, 0.15],
        inertia: from_principal(
            [[0.0, -0.8, 0.6], [0.0, 0.6, 0.8], [-1.0, 0.0, 0.0]],
            [axial, across, across],
        ),
    }
}

/// The mass properties the components compute agree with MSL's formulas by hand, to
/// rounding (1e-14 relative; the centre of mass to 1e-15 m).
#[test]
fn offset_box_and_cylinder_mass_properties_match_msl_by_hand() {
    let cases = [
        (
            "offset box",
            props_of(offset_box().mass_properties()),
            offset_box_by_hand(),
        ),
        (
            "box beside r",
            props_of(beside_box().mass_properties()),
            beside_box_by_hand(),
        ),
        (
            "offset tube",
            props_of(offset_tube().mass_properties()),
            offset_tube_by_hand(),
        ),
    ];
    for (what, got, want) in &cases {
        assert_props(what, got, want, 1e-14);
    }
    // Without r_shape the defaults are the old ones: the centre of mass at r / 2.
    let plain = BodyBox {
        r: [0.2, -0.4, 0.4],
        ..Default::default()
    }
    .mass_properties();
    for (i, want) in [0.1, -0.2, 0.2].into_iter().enumerate() {
        assert_close("plain box r_cm", plain.r_cm[i], want, 1e-15);
    }
    let (l, w) = (0.6, 0.03);
    assert_close("plain box m", plain.m, 7700.0 * l * w * w, 1e-12);
}

/// The same numbers reach the model: the parameters of the inner `body`, read from a
/// solution of a pendulum built with each shape.
#[test]
fn the_compiled_body_carries_the_hand_computed_properties() {
    let model = system! {
        name: "shapes_on_joints";
        world = World::default();
        j1 = Revolute { n: [0.0, 0.0, 1.0] };
        boxed = offset_box();
        j2 = Revolute { n: [0.0, 0.0, 1.0] };
        tube = offset_tube();
        connect(world.frame_b, j1.frame_a);
        connect(j1.frame_b, boxed.frame_a);
        connect(world.frame_b, j2.frame_a);
        connect(j2.frame_b, tube.frame_a);
    };
    let ssys = structural_simplify(&model).unwrap_or_else(|e| panic!("{e}"));
    let sol = DaeProblem::new(&ssys, &[], (0.0, 0.01))
        .and_then(|p| p.solve(&SolverOptions::default()))
        .unwrap_or_else(|e| panic!("{e}"));
    for (name, want) in [
        ("boxed", offset_box_by_hand()),
        ("tube", offset_tube_by_hand()),
    ] {
        let p = |s: &str| sol.parameter(format!("{name}.body.{s}").as_str()).unwrap();
        let got = MassProps {
            m: p("m"),
            r_cm: [p("r_CM[1]"), p("r_CM[2]"), p("r_CM[3]")],
            inertia: [
                [p("I_11"), p("I_21"), p("I_31")],
                [p("I_21"), p("I_22"), p("I_32")],
                [p("I_31"), p("I_32"), p("I_33")],
            ],
        };
        assert_props(name, &got, &want, 1e-14);
    }
}

// ---------------------------------------------------------------------------------------
// Dynamics.

/// The offset box as a physical pendulum about z through frame_a, gravity -y. Its
/// centre of mass is at d = |(0.2, 0.2)| = 0.2828.. from the axis, so for a small
/// amplitude the period is T = 2 pi sqrt(I_pivot / (m g d)), I_pivot = I_zz + m d^2
/// (Steiner), with the hand-computed m and I_zz. The equilibrium is the centre of mass
/// straight below the axis: phi_eq = -pi/2 - atan2(0.2, 0.2) = -3 pi / 4.
///
/// Amplitude theta0 = 1e-3 rad: the period is T (1 + theta0^2 / 16) to O(theta0^4); the
/// zero crossings, located by linear interpolation between 1 ms samples of a motion
/// that is linear at its crossings, match it to 1e-9 relative (measured: 3e-10); a
/// centre of mass at r / 2 instead (ignoring r_shape) changes T by 5 %, a moment of
/// inertia off by 1e-6 changes it by 5e-7.
#[test]
fn offset_box_swings_with_the_physical_pendulum_period() {
    let p = offset_box_by_hand();
    let d2 = p.r_cm[0] * p.r_cm[0] + p.r_cm[1] * p.r_cm[1];
    let theta0: f64 = 1e-3;
    let period = 2.0
        * PI
        * ((p.inertia[2][2] + p.m * d2) / (p.m * G * d2.sqrt())).sqrt()
        * (1.0 + theta0 * theta0 / 16.0);
    let phi_eq = -0.75 * PI;
    let model = system! {
        name: "box_pendulum";
        world = World::default();
        j = Revolute { n: [0.0, 0.0, 1.0] };
        boxed = offset_box();
        connect(world.frame_b, j.frame_a);
        connect(j.frame_b, boxed.frame_a);
    };
    let t_end = 3.2 * period;
    let n = (t_end / 1e-3) as usize;
    let ssys = structural_simplify(&model).unwrap_or_else(|e| panic!("{e}"));
    let options = SolverOptions {
        rtol: 1e-11,
        atol: 1e-13,
        output_times: Some((0..=n).map(|k| k as f64 * t_end / n as f64).collect()),
        ..SolverOptions::default()
    };
    let sol = DaeProblem::new(&ssys, &[("j.phi", phi_eq + theta0)], (0.0, t_end))
        .and_then(|pr| pr.solve(&options))
        .unwrap_or_else(|e| panic!("{e}"));
    let (t, phi) = (sol.t(), sol.get("j.phi").unwrap());
    let crossings: Vec<f64> = (1..t.len())
        .filter_map(|k| {
            let (a, b) = (phi[k - 1] - phi_eq, phi[k] - phi_eq);
            (a > 0.0 && b <= 0.0).then(|| t[k - 1] + (t[k] - t[k - 1]) * a / (a - b))
        })
        .collect();
    assert!(crossings.len() >= 3, "too few crossings: {crossings:?}");
    for pair in crossings.windows(2) {
        let measured = pair[1] - pair[0];
        assert!(
            ((measured - period) / period).abs() < 1e-9,
            "period {measured}, expected {period}"
        );
    }
}

/// The offset box and the offset tube, each tumbling on a spherical joint at the world
/// origin, next to a plain `Body` with the hand-computed m, r_CM and inertia on its own
/// spherical joint, started alike: the orientations and the centre-of-mass paths agree
/// (a wrong off-diagonal inertia element or centre of mass separates them within the
/// first swing), and the energy of each, computed from the hand-computed properties, is
/// conserved.
#[test]
fn tumbling_shapes_match_a_body_with_the_hand_computed_properties() {
    for (shape, props) in [
        (&offset_box() as &dyn Component, offset_box_by_hand()),
        (&offset_tube() as &dyn Component, offset_tube_by_hand()),
    ] {
        let i = props.inertia;
        let reference = Body {
            m: props.m,
            r_CM: props.r_cm,
            I_11: i[0][0],
            I_22: i[1][1],
            I_33: i[2][2],
            I_21: i[1][0],
            I_31: i[2][0],
            I_32: i[2][1],
            orientation_states: OrientationStates::Quaternion,
            ..Default::default()
        };
        let mut model = System::new("tumbling");
        model.add("world", &World::default());
        model.add("ball", &Spherical::default());
        model.add("shape", shape);
        model.add("ref_ball", &Spherical::default());
        model.add("reference", &reference);
        model.connect("world.frame_b", "ball.frame_a");
        model.connect("ball.frame_b", "shape.frame_a");
        model.connect("world.frame_b", "ref_ball.frame_a");
        model.connect("ref_ball.frame_b", "reference.frame_a");
        let w0 = [1.5, -2.0, 3.0];
        let mut start = Vec::new();
        for (k, w) in w0.iter().enumerate() {
            start.push((format!("shape.body.w_a[{}]", k + 1), *w));
            start.push((format!("reference.w_a[{}]", k + 1), *w));
        }
        let start: Vec<(&str, f64)> = start.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        let t_end = 2.0;
        let n = 200;
        let ssys = structural_simplify(&model).unwrap_or_else(|e| panic!("{e}"));
        let options = SolverOptions {
            rtol: 1e-10,
            atol: 1e-12,
            output_times: Some((0..=n).map(|k| k as f64 * t_end / n as f64).collect()),
            ..SolverOptions::default()
        };
        let sol = DaeProblem::new(&ssys, &start, (0.0, t_end))
            .and_then(|p| p.solve(&options))
            .unwrap_or_else(|e| panic!("{e}"));
        let (t_shape, t_ref) = (
            rotation(&sol, "shape.frame_a"),
            rotation(&sol, "reference.frame_a"),
        );
        let (w_shape, w_ref) = (
            vector(&sol, "shape.body.w_a"),
            vector(&sol, "reference.w_a"),
        );
        // Both integrate the same equations, so they agree to rounding (measured:
        // 1e-12); the energy drifts by 2e-9 at rtol 1e-10.
        let tol = 1e-9;
        for k in 0..sol.t().len() {
            for r in 0..3 {
                assert_close("w_a", w_shape[k][r], w_ref[k][r], tol);
                for c in 0..3 {
                    assert_close("R.T", t_shape[k][r][c], t_ref[k][r][c], tol);
                }
            }
        }
        // It did tumble: the last orientation is far from the start.
        assert!(t_ref.last().unwrap()[0][0] < 0.9, "barely turned");
        let energy = body_energy(&sol, "shape.body", props, G, [0.0, -1.0, 0.0]);
        let e_scale = props.m * G * norm(props.r_cm) + energy[0].abs();
        let drift = relative_drift(&energy, e_scale);
        assert!(drift < 2e-8, "energy drift {drift:e}");
    }
}

// ---------------------------------------------------------------------------------------
// Bad input.

fn hanging(part: &dyn Component) -> System {
    let mut m = System::new("hanging");
    m.add("world", &World::default());
    m.add("j1", &Revolute::default());
    m.add("part", part);
    m.connect("world.frame_b", "j1.frame_a");
    m.connect("j1.frame_b", "part.frame_a");
    m
}

#[track_caller]
fn assert_rejected(part: &dyn Component, needles: &[&str]) {
    let e = structural_simplify(&hanging(part))
        .map(|_| ())
        .expect_err("the part must be rejected");
    assert!(matches!(e, multibody::Error::Model(_)), "wrong phase: {e}");
    let text = e.to_string();
    for n in needles {
        assert!(text.contains(n), "`{n}` is not in: {text}");
    }
}

#[test]
fn a_shape_without_a_length_direction_is_rejected() {
    // r = r_shape: the default length direction r - r_shape is zero.
    assert_rejected(
        &BodyBox {
            r: [0.2, 0.0, 0.0],
            r_shape: [0.2, 0.0, 0.0],
            length: Some(0.1),
            ..Default::default()
        },
        &[
            "MultiBody.Parts.BodyBox `part`",
            "`length_direction` = [0.0, 0.0, 0.0]",
        ],
    );
    assert_rejected(
        &BodyCylinder {
            length_direction: Some([0.0; 3]),
            ..Default::default()
        },
        &["MultiBody.Parts.BodyCylinder `part`", "`length_direction`"],
    );
}

#[test]
fn a_shape_of_negative_or_nan_size_is_rejected() {
    assert_rejected(
        &BodyBox {
            length: Some(-0.5),
            ..Default::default()
        },
        &["BodyBox `part`", "`length` = -0.5 must be positive"],
    );
    assert_rejected(
        &BodyCylinder {
            r_shape: [f64::NAN, 0.0, 0.0],
            ..Default::default()
        },
        &[
            "BodyCylinder `part`",
            "`r_shape` = [NaN, 0.0, 0.0] must be finite",
        ],
    );
    assert_rejected(
        &BodyBox {
            height: Some(f64::NAN),
            ..Default::default()
        },
        &["BodyBox `part`", "`height` = NaN must be positive"],
    );
    assert_rejected(
        &BodyBox {
            width: Some(0.05),
            inner_width: 0.06,
            ..Default::default()
        },
        &[
            "BodyBox `part`",
            "`inner_width` = 0.06 must be in [0, width = 0.05]",
        ],
    );
}

/// MSL's bounds on the hollow are non-strict for the box (a box hollowed to nothing is
/// accepted, with zero mass) and strict for the cylinder.
#[test]
fn msl_bounds_on_the_hollow() {
    let hollow = BodyBox {
        r: [0.5, 0.0, 0.0],
        width: Some(0.04),
        inner_width: 0.04,
        inner_height: Some(0.02),
        ..Default::default()
    };
    let p = hollow.mass_properties();
    assert_close("hollow box m", p.m, 7700.0 * 0.5 * 0.04 * 0.02, 1e-12);
    assert!(structural_simplify(&hanging(&hollow)).is_ok());
    assert_rejected(
        &BodyCylinder {
            diameter: Some(0.05),
            inner_diameter: 0.05,
            ..Default::default()
        },
        &[
            "BodyCylinder `part`",
            "`inner_diameter` = 0.05 must be in [0, diameter = 0.05)",
        ],
    );
}
