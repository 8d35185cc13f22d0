//! Malformed models and inputs: each gives an error of the right kind whose message names
//! the offending component, variable, parameter or option, and none panics.

#![allow(missing_docs)]

use multibody::Error;
use multibody::blocks::Constant;
use multibody::joints::{Prismatic, Revolute, Universal, UniversalSpherical};
use multibody::parts::{
    Body, BodyBox, BodyCylinder, BodyShape, FixedRotation, FixedTranslation, OrientationStates,
    RotationType,
};
use multibody::prelude::*;
use multibody::rotational::{
    Damper, Fixed, Flange, Inertia, Position, Spring, SpringDamper, Torque,
};
use multibody::sensors::RelativeAngles;
use multibody::world::World;

// ---------------------------------------------------------------------------------------
// Helpers: the phase an error comes from, and what its message must name.

/// Which phase failed.
#[derive(Debug, PartialEq, Clone, Copy)]
enum Phase {
    Model,
    Simplify,
    Init,
    Solve,
    Solution,
    Plot,
}

fn phase(e: &Error) -> Phase {
    match e {
        Error::Model(_) => Phase::Model,
        Error::Simplify(_) => Phase::Simplify,
        Error::Init(_) => Phase::Init,
        Error::Solve(_) => Phase::Solve,
        Error::Solution(_) => Phase::Solution,
        Error::Plot(_) => Phase::Plot,
        Error::Codegen(_) => panic!("unexpected codegen error: {e}"),
    }
}

/// Asserts `r` failed in `expected`, with a message containing every needle.
#[track_caller]
fn assert_err<T: std::fmt::Debug>(r: Result<T, Error>, expected: Phase, needles: &[&str]) {
    let e = r.expect_err("an error");
    let text = e.to_string();
    assert_eq!(phase(&e), expected, "wrong phase for: {text}");
    for n in needles {
        assert!(text.contains(n), "`{n}` is not in: {text}");
    }
}

/// Simplifies, sets up and solves `model` over `span` with `values` and `options`.
fn run(
    model: &(impl AsRef<System> + ?Sized),
    values: &[(&str, f64)],
    span: (f64, f64),
    options: &SolverOptions,
) -> Result<Solution, Error> {
    let ssys = structural_simplify(model)?;
    DaeProblem::new(&ssys, values, span)?.solve(options)
}

fn run_default(model: &(impl AsRef<System> + ?Sized)) -> Result<Solution, Error> {
    run(model, &[], (0.0, 1.0), &SolverOptions::default())
}

system! {
    /// A world and a pendulum on a revolute joint with axis `n`.
    fn pendulum_with_axis(n: [f64; 3]) -> PendulumWithAxis {
        name: "pendulum";
        world = World::default();
        j1 = Revolute { n };
        body = Body { m: 1.0, r_CM: [0.5, 0.0, 0.0] };
        connect(world.frame_b, j1.frame_a);
        connect(j1.frame_b, body.frame_a);
    }
}

/// A world and a body hanging from a revolute joint, the body being `part`.
fn hanging(part: &dyn Component) -> System {
    let mut m = System::new("hanging");
    m.add("world", &World::default());
    m.add("j1", &Revolute::default());
    m.add("part", part);
    m.connect("world.frame_b", "j1.frame_a");
    m.connect("j1.frame_b", "part.frame_a");
    m
}

system! {
    /// A spring and an inertia on a fixed flange: phi'' = -c phi.
    fn oscillator() -> Oscillator {
        name: "osc";
        fixed = Fixed::default();
        spring = Spring { c: 4.0 };
        inertia = Inertia { J: 1.0, phi_start: 1.0 };
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, inertia.flange_a);
    }
}

fn osc_problem_err(values: &[(&str, f64)], guesses: &[(&str, f64)], span: (f64, f64)) -> Error {
    let ssys = structural_simplify(&oscillator()).unwrap();
    DaeProblem::new_with_guesses(&ssys, values, guesses, span).unwrap_err()
}

fn osc_solve(options: SolverOptions) -> Result<Solution, Error> {
    run(&oscillator(), &[], (0.0, 1.0), &options)
}

// ---------------------------------------------------------------------------------------
// Structural parameters a component rejects (the model does not compile).

#[test]
fn a_zero_revolute_axis_names_the_joint_and_the_axis() {
    assert_err(
        run_default(&pendulum_with_axis([0.0, 0.0, 0.0])),
        Phase::Model,
        &["MultiBody.Joints.Revolute `j1`", "the axis n = [0, 0, 0]"],
    );
}

#[test]
fn a_nan_revolute_axis_is_not_finite_rather_than_zero() {
    let e = run_default(&pendulum_with_axis([f64::NAN, 0.0, 1.0]));
    assert_err(
        e,
        Phase::Model,
        &[
            "`j1`",
            "structural parameter `n` = [NaN, 0, 1] is not finite",
        ],
    );
}

#[test]
fn an_infinite_axis_is_not_finite() {
    assert_err(
        run_default(&pendulum_with_axis([0.0, f64::INFINITY, 0.0])),
        Phase::Model,
        &["`j1`", "`n` = [0, inf, 0] is not finite"],
    );
}

#[test]
fn a_zero_prismatic_axis_names_the_joint() {
    let m = system! {
        name: "slider";
        world = World::default();
        slide = Prismatic { n: [0.0, 0.0, 0.0] };
        body = Body::default();
        connect(world.frame_b, slide.frame_a);
        connect(slide.frame_b, body.frame_a);
    };
    assert_err(
        run_default(&m),
        Phase::Model,
        &["MultiBody.Joints.Prismatic `slide`", "axis n = [0, 0, 0]"],
    );
}

#[test]
fn a_zero_universal_axis_names_the_joint_inside_it() {
    let m = hanging(&Universal {
        n_a: [0.0, 0.0, 0.0],
        ..Default::default()
    });
    // The universal joint's first revolute joint carries the axis.
    let mut m2 = System::new("universal");
    m2.add("world", &World::default());
    m2.add(
        "u",
        &Universal {
            n_a: [0.0, 0.0, 0.0],
            ..Default::default()
        },
    );
    m2.add("body", &Body::default());
    m2.connect("world.frame_b", "u.frame_a");
    m2.connect("u.frame_b", "body.frame_a");
    assert_err(run_default(&m2), Phase::Model, &["`u.", "[0, 0, 0]"]);
    // A universal joint is no body: connecting its frame_a to j1 still fails at the axis.
    assert_err(run_default(&m), Phase::Model, &["[0, 0, 0]"]);
}

#[test]
fn a_repeated_axis_in_a_body_sequence_is_rejected() {
    let body = Body {
        sequence_angle_states: [1, 1, 2],
        ..Default::default()
    };
    let mut m = System::new("free");
    m.add("world", &World::default());
    m.add("body", &body);
    assert_err(
        run_default(&m),
        Phase::Model,
        &[
            "MultiBody.Parts.Body `body`",
            "sequence_angle_states = [1, 1, 2]",
        ],
    );
}

#[test]
fn an_axis_0_in_a_body_sequence_is_rejected() {
    let body = Body {
        sequence_angle_states: [0, 2, 3],
        ..Default::default()
    };
    let mut m = System::new("free");
    m.add("world", &World::default());
    m.add("body", &body);
    assert_err(
        run_default(&m),
        Phase::Model,
        &["`body`", "sequence_angle_states = [0, 2, 3]"],
    );
}

#[test]
fn a_box_of_zero_length_names_the_box() {
    let m = hanging(&BodyBox {
        r: [0.0, 0.0, 0.0],
        ..Default::default()
    });
    assert_err(
        run_default(&m),
        Phase::Model,
        &[
            "MultiBody.Parts.BodyBox `part`",
            "`length_direction` = [0.0, 0.0, 0.0] must be a finite, non-zero vector",
        ],
    );
}

#[test]
fn a_cylinder_of_zero_length_names_the_cylinder() {
    let m = hanging(&BodyCylinder {
        r: [0.0, 0.0, 0.0],
        ..Default::default()
    });
    assert_err(
        run_default(&m),
        Phase::Model,
        &[
            "MultiBody.Parts.BodyCylinder `part`",
            "`length_direction` = [0.0, 0.0, 0.0] must be a finite, non-zero vector",
        ],
    );
}

#[test]
fn a_box_of_negative_width_is_rejected() {
    let m = hanging(&BodyBox {
        r: [0.5, 0.0, 0.0],
        width: Some(-0.1),
        ..Default::default()
    });
    assert_err(
        run_default(&m),
        Phase::Model,
        &["`part`", "`width` = -0.1 must be positive"],
    );
}

#[test]
fn a_tube_wider_inside_than_outside_is_rejected() {
    let m = hanging(&BodyCylinder {
        r: [0.5, 0.0, 0.0],
        diameter: Some(0.1),
        inner_diameter: 0.2,
        ..Default::default()
    });
    assert_err(
        run_default(&m),
        Phase::Model,
        &["`part`", "`inner_diameter` = 0.2", "diameter = 0.1"],
    );
}

#[test]
fn a_box_of_zero_density_is_rejected() {
    let m = hanging(&BodyBox {
        r: [0.5, 0.0, 0.0],
        density: 0.0,
        ..Default::default()
    });
    assert_err(
        run_default(&m),
        Phase::Model,
        &["`part`", "`density` = 0 must be positive"],
    );
}

#[test]
fn a_fixed_rotation_about_a_zero_axis_is_rejected() {
    let m = system! {
        name: "rotated";
        world = World::default();
        rot = FixedRotation { n: [0.0, 0.0, 0.0], angle: 30.0 };
        connect(world.frame_b, rot.frame_a);
    };
    assert_err(
        run_default(&m),
        Phase::Model,
        &["MultiBody.Parts.FixedRotation `rot`", "axis n = [0, 0, 0]"],
    );
}

#[test]
fn a_fixed_rotation_sequence_with_a_repeated_axis_is_rejected() {
    let m = system! {
        name: "rotated";
        world = World::default();
        rot = FixedRotation {
            rotation_type: RotationType::PlanarRotationSequence,
            sequence: [2, 2, 1],
        };
        connect(world.frame_b, rot.frame_a);
    };
    assert_err(
        run_default(&m),
        Phase::Model,
        &["`rot`", "sequence = [2, 2, 1]"],
    );
}

#[test]
fn a_relative_angles_sensor_with_a_bad_sequence_is_rejected() {
    let m = system! {
        name: "sensed";
        world = World::default();
        j1 = Revolute::default();
        body = Body { r_CM: [0.5, 0.0, 0.0] };
        angles = RelativeAngles { sequence: [3, 3, 1] };
        connect(world.frame_b, j1.frame_a);
        connect(j1.frame_b, body.frame_a);
        connect(world.frame_b, angles.frame_a);
        connect(body.frame_a, angles.frame_b);
    };
    assert_err(
        run_default(&m),
        Phase::Model,
        &["MultiBody.Sensors.RelativeAngles `angles`", "[3, 3, 1]"],
    );
}

#[test]
fn a_rod_of_zero_length_is_rejected() {
    let m = hanging(&UniversalSpherical {
        rRod_ia: [0.0, 0.0, 0.0],
        ..Default::default()
    });
    assert_err(
        run_default(&m),
        Phase::Model,
        &["`part`", "rRod_ia = [0, 0, 0]"],
    );
}

#[test]
fn a_rod_along_the_universal_axis_is_rejected() {
    let m = hanging(&UniversalSpherical {
        n1_a: [0.0, 0.0, 1.0],
        rRod_ia: [0.0, 0.0, 2.0],
        ..Default::default()
    });
    assert_err(
        run_default(&m),
        Phase::Model,
        &[
            "`part`",
            "n1_a = [0, 0, 1]",
            "not parallel to rRod_ia = [0, 0, 2]",
        ],
    );
}

#[test]
fn a_nan_start_angle_names_the_inertia() {
    let m = system! {
        name: "osc";
        fixed = Fixed::default();
        spring = Spring::default();
        inertia = Inertia { phi_start: f64::NAN };
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, inertia.flange_a);
    };
    assert_err(
        run_default(&m),
        Phase::Model,
        &["Rotational.Inertia `inertia`", "`phi_start` = NaN"],
    );
}

component! {
    /// A component whose structural parameter must be positive.
    pub struct Picky {
        structural k: f64 = 1.0;
        variable x: Real;
        equation {
            assert(k > 0.0, format!("k = {k} must be positive"));
            der(x) = -k * x;
        }
    }
}

#[test]
fn a_user_components_structural_assertion_names_it() {
    let m = system! {
        name: "picky";
        p = Picky { k: -2.0 };
    };
    assert_err(
        run_default(&m),
        Phase::Model,
        &["`p`", "k = -2 must be positive"],
    );
}

component! {
    /// A component asserting a condition on a variable (not supported).
    pub struct WatchesVariable {
        variable x(start = 1.0): Real;
        equation {
            assert(x.ge(0.0), "x must stay positive");
            der(x) = -x;
        }
    }
}

#[test]
fn an_assertion_on_a_variable_is_refused_by_name() {
    let m = system! {
        name: "watch";
        w = WatchesVariable::default();
    };
    assert_err(
        run_default(&m),
        Phase::Model,
        &["w: the assertion `w.x >= 0` refers to variables"],
    );
}

// ---------------------------------------------------------------------------------------
// Tunable parameters a component rejects (checked when the problem sets their values).

#[test]
fn a_negative_mass_names_the_body_and_its_value() {
    let m = hanging(&Body {
        m: -1.0,
        r_CM: [0.5, 0.0, 0.0],
        ..Default::default()
    });
    assert_err(
        run_default(&m),
        Phase::Init,
        &["parameter `part.m` = -1 is below its minimum 0"],
    );
}

#[test]
fn a_negative_mass_given_to_the_problem_is_rejected_too() {
    let m = hanging(&Body {
        r_CM: [0.5, 0.0, 0.0],
        ..Default::default()
    });
    assert_err(
        run(
            &m,
            &[("part.m", -2.0)],
            (0.0, 1.0),
            &SolverOptions::default(),
        ),
        Phase::Init,
        &["parameter `part.m` = -2 is below its minimum 0"],
    );
}

#[test]
fn a_negative_principal_moment_is_not_a_physical_inertia() {
    let m = hanging(&Body {
        I_11: -0.1,
        r_CM: [0.5, 0.0, 0.0],
        ..Default::default()
    });
    assert_err(
        run_default(&m),
        Phase::Init,
        &["`part`", "positive semi-definite", "part.I_11 = -0.1"],
    );
}

#[test]
fn an_indefinite_inertia_is_rejected() {
    // Positive diagonal, but the product of inertia makes one principal moment negative
    // (0.001 - 0.01 < 0).
    let m = hanging(&Body {
        I_21: 0.01,
        r_CM: [0.5, 0.0, 0.0],
        ..Default::default()
    });
    assert_err(
        run_default(&m),
        Phase::Init,
        &["`part`", "positive semi-definite", "part.I_21 = 0.01"],
    );
}

#[test]
fn a_negative_mass_inside_a_body_shape_names_the_inner_body() {
    let m = hanging(&BodyShape {
        r: [0.5, 0.0, 0.0],
        m: -3.0,
        ..Default::default()
    });
    assert_err(
        run_default(&m),
        Phase::Init,
        &["parameter `part.body.m` = -3 is below its minimum 0"],
    );
}

#[test]
fn a_point_mass_with_zero_inertia_is_accepted() {
    let sol = run_default(&hanging(&Body {
        I_11: 0.0,
        I_22: 0.0,
        I_33: 0.0,
        r_CM: [0.5, 0.0, 0.0],
        ..Default::default()
    }))
    .expect("a point mass is physical");
    assert!(sol.final_value("j1.phi").unwrap().is_finite());
}

#[test]
fn a_negative_moment_of_inertia_is_below_its_minimum() {
    let m = system! {
        name: "osc";
        fixed = Fixed::default();
        spring = Spring::default();
        inertia = Inertia { J: -0.5 };
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, inertia.flange_a);
    };
    assert_err(
        run_default(&m),
        Phase::Init,
        &["parameter `inertia.J` = -0.5 is below its minimum 0"],
    );
}

#[test]
fn a_structural_parameter_given_to_the_problem_says_so() {
    let m = pendulum_with_axis([0.0, 0.0, 1.0]);
    assert_err(
        run(&m, &[("j1.n", 1.0)], (0.0, 1.0), &SolverOptions::default()),
        Phase::Init,
        &["`j1.n` is a structural parameter, fixed when the model was built"],
    );
    assert_err(
        run(
            &m,
            &[("j1.n[2]", 1.0)],
            (0.0, 1.0),
            &SolverOptions::default(),
        ),
        Phase::Init,
        &["`j1.n[2]` is a structural parameter, fixed when the model was built"],
    );
}

#[test]
fn two_outputs_connected_are_named() {
    let m = system! {
        name: "clash";
        s1 = Constant { k: 1.0 };
        s2 = Constant { k: 2.0 };
        torque = Torque::default();
        inertia = Inertia::default();
        connect(s1.y, s2.y);
        connect(s1.y, torque.tau);
        connect(torque.flange, inertia.flange_a);
    };
    assert_err(
        run_default(&m),
        Phase::Model,
        &["in `connect(s1.y, s2.y)`: `s1.y` and `s2.y` are both outputs"],
    );
}

#[test]
fn an_input_connected_to_nothing_is_named() {
    // The torque source's input is left open: one equation short, and the message says
    // which input is connected to nothing.
    let m = system! {
        name: "driven";
        torque = Torque::default();
        inertia = Inertia::default();
        connect(torque.flange, inertia.flange_a);
    };
    assert_err(
        run_default(&m),
        Phase::Model,
        &[
            "is not balanced",
            "inputs connected to nothing: torque.tau (connect an output to each",
        ],
    );
}

#[test]
fn a_negative_stiffness_or_damping_is_below_its_minimum() {
    // MSL: c(final min = 0), d(final min = 0) on springs and dampers.
    let m = system! {
        name: "osc";
        fixed = Fixed::default();
        spring = Spring { c: -4.0 };
        inertia = Inertia::default();
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, inertia.flange_a);
    };
    assert_err(
        run_default(&m),
        Phase::Init,
        &["parameter `spring.c` = -4 is below its minimum 0"],
    );
    let m = system! {
        name: "osc";
        fixed = Fixed::default();
        damper = multibody::rotational::Damper { d: -1.0 };
        inertia = Inertia::default();
        connect(fixed.flange, damper.flange_a);
        connect(damper.flange_b, inertia.flange_a);
    };
    assert_err(
        run_default(&m),
        Phase::Init,
        &["parameter `damper.d` = -1 is below its minimum 0"],
    );
}

#[test]
fn a_nan_parameter_default_names_the_parameter() {
    let m = system! {
        name: "osc";
        fixed = Fixed::default();
        spring = Spring { c: f64::NAN };
        inertia = Inertia::default();
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, inertia.flange_a);
    };
    assert_err(
        run_default(&m),
        Phase::Init,
        &["parameter `spring.c` evaluates to NaN"],
    );
}

#[test]
fn an_infinite_vector_parameter_names_its_element() {
    let mut m = System::new("translated");
    m.add("world", &World::default());
    m.add(
        "rod",
        &FixedTranslation {
            r: [f64::INFINITY, 0.0, 0.0],
            ..Default::default()
        },
    );
    m.add("j1", &Revolute::default());
    m.add("body", &Body::default());
    m.connect("world.frame_b", "rod.frame_a");
    m.connect("rod.frame_b", "j1.frame_a");
    m.connect("j1.frame_b", "body.frame_a");
    assert_err(
        run_default(&m),
        Phase::Init,
        &["`rod.r[1]` evaluates to inf"],
    );
}

// ---------------------------------------------------------------------------------------
// Values, guesses and time spans given to a problem.

#[test]
fn a_nan_parameter_value_names_the_parameter() {
    let e = osc_problem_err(&[("spring.c", f64::NAN)], &[], (0.0, 1.0));
    assert_err::<()>(Err(e), Phase::Init, &["NaN", "`spring.c`", "not finite"]);
}

#[test]
fn an_infinite_start_value_names_the_variable() {
    let e = osc_problem_err(&[("inertia.phi", f64::INFINITY)], &[], (0.0, 1.0));
    assert_err::<()>(Err(e), Phase::Init, &["inf", "`inertia.phi`"]);
}

#[test]
fn a_name_given_twice_is_rejected() {
    let e = osc_problem_err(&[("spring.c", 1.0), ("spring.c", 2.0)], &[], (0.0, 1.0));
    assert_err::<()>(Err(e), Phase::Init, &["`spring.c` is given twice"]);
}

#[test]
fn an_unknown_value_name_gets_a_suggestion() {
    let e = osc_problem_err(&[("spring.k", 1.0)], &[], (0.0, 1.0));
    assert_err::<()>(
        Err(e),
        Phase::Init,
        &[
            "has no variable or parameter `spring.k`",
            "did you mean",
            "`spring.c`",
        ],
    );
}

#[test]
fn a_guess_for_a_parameter_says_it_is_a_parameter() {
    let e = osc_problem_err(&[], &[("spring.c", 2.0)], (0.0, 1.0));
    let text = e.to_string();
    assert!(text.contains("`spring.c` is a parameter"), "{text}");
    assert!(
        !text.contains("did you mean"),
        "no contradictory suggestion: {text}"
    );
}

#[test]
fn a_nan_guess_names_the_variable() {
    let e = osc_problem_err(&[], &[("inertia.w", f64::NAN)], (0.0, 1.0));
    assert_err::<()>(Err(e), Phase::Init, &["guess NaN", "`inertia.w`"]);
}

#[test]
fn a_guess_for_an_unknown_name_gets_a_suggestion() {
    let e = osc_problem_err(&[], &[("inertia.ww", 0.0)], (0.0, 1.0));
    assert_err::<()>(Err(e), Phase::Init, &["`inertia.ww`", "`inertia.w`"]);
}

#[test]
fn a_guess_given_twice_is_rejected() {
    let e = osc_problem_err(&[], &[("inertia.w", 0.0), ("inertia.w", 1.0)], (0.0, 1.0));
    assert_err::<()>(
        Err(e),
        Phase::Init,
        &["`inertia.w` is given twice in the guesses"],
    );
}

#[test]
fn an_evaluated_parameter_cannot_be_changed_per_problem() {
    let ssys = multibody::structural_simplify_with(
        &oscillator(),
        &multibody::SimplifyOptions {
            evaluate_parameters: true,
            ..Default::default()
        },
    )
    .unwrap();
    let e = DaeProblem::new(&ssys, &[("spring.c", 2.0)], (0.0, 1.0)).unwrap_err();
    assert_err::<()>(
        Err(e),
        Phase::Init,
        &["parameter `spring.c` was evaluated at compile time"],
    );
}

#[test]
fn a_reversed_time_span_is_rejected() {
    let e = osc_problem_err(&[], &[], (1.0, 0.0));
    assert_err::<()>(
        Err(e),
        Phase::Init,
        &["time span (1, 0) must be finite and increasing"],
    );
}

#[test]
fn an_empty_time_span_is_rejected() {
    let e = osc_problem_err(&[], &[], (1.0, 1.0));
    assert_err::<()>(Err(e), Phase::Init, &["must be finite and increasing"]);
}

#[test]
fn a_nan_time_span_is_rejected() {
    let e = osc_problem_err(&[], &[], (0.0, f64::NAN));
    assert_err::<()>(Err(e), Phase::Init, &["time span (0, NaN)"]);
}

#[test]
fn an_infinite_time_span_is_rejected() {
    let e = osc_problem_err(&[], &[], (0.0, f64::INFINITY));
    assert_err::<()>(Err(e), Phase::Init, &["time span (0, inf)"]);
}

#[test]
fn a_span_of_1e_minus_300_seconds_is_too_short() {
    let e = osc_problem_err(&[], &[], (0.0, 1e-300));
    assert_err::<()>(
        Err(e),
        Phase::Init,
        &["time span (0, 1e-300) is too short to integrate"],
    );
}

#[test]
fn a_span_lost_in_the_rounding_of_a_large_start_time_is_too_short() {
    let e = osc_problem_err(&[], &[], (1e10, 1e10 + 1e-6));
    assert_err::<()>(Err(e), Phase::Init, &["too short to integrate"]);
}

// ---------------------------------------------------------------------------------------
// Solver options.

#[test]
fn a_negative_rtol_is_rejected() {
    assert_err(
        osc_solve(SolverOptions {
            rtol: -1e-6,
            ..Default::default()
        }),
        Phase::Solve,
        &["SolverOptions::rtol = -1e-6"],
    );
}

#[test]
fn rtol_and_atol_both_zero_are_rejected() {
    assert_err(
        osc_solve(SolverOptions {
            rtol: 0.0,
            atol: 0.0,
            ..Default::default()
        }),
        Phase::Solve,
        &["rtol and atol are both zero"],
    );
}

#[test]
fn a_nan_atol_is_rejected() {
    assert_err(
        osc_solve(SolverOptions {
            atol: f64::NAN,
            ..Default::default()
        }),
        Phase::Solve,
        &["SolverOptions::atol = NaN"],
    );
}

#[test]
fn an_rtol_below_machine_precision_is_rejected() {
    assert_err(
        osc_solve(SolverOptions {
            rtol: 1e-300,
            ..Default::default()
        }),
        Phase::Solve,
        &["rtol = 1e-300 is below the precision"],
    );
}

#[test]
fn a_zero_max_step_is_rejected() {
    assert_err(
        osc_solve(SolverOptions {
            max_step: Some(0.0),
            ..Default::default()
        }),
        Phase::Solve,
        &["SolverOptions::max_step = 0 must be a positive, finite number"],
    );
}

#[test]
fn a_nan_max_step_is_rejected() {
    assert_err(
        osc_solve(SolverOptions {
            max_step: Some(f64::NAN),
            ..Default::default()
        }),
        Phase::Solve,
        &["max_step = NaN"],
    );
}

#[test]
fn a_negative_initial_step_is_rejected() {
    assert_err(
        osc_solve(SolverOptions {
            initial_step: Some(-0.1),
            ..Default::default()
        }),
        Phase::Solve,
        &["initial_step = -0.1"],
    );
}

#[test]
fn a_nan_output_time_is_rejected() {
    assert_err(
        osc_solve(SolverOptions {
            output_times: Some(vec![0.5, f64::NAN]),
            ..Default::default()
        }),
        Phase::Solve,
        &["output time NaN", "time span [0, 1]"],
    );
}

#[test]
fn an_output_time_outside_the_span_is_rejected() {
    assert_err(
        osc_solve(SolverOptions {
            output_times: Some(vec![0.5, 2.0]),
            ..Default::default()
        }),
        Phase::Solve,
        &["output time 2 ", "not in the time span [0, 1]"],
    );
}

#[test]
fn zero_max_steps_are_rejected() {
    assert_err(
        osc_solve(SolverOptions {
            max_steps: 0,
            ..Default::default()
        }),
        Phase::Solve,
        &["max_steps must be at least 1"],
    );
}

#[test]
fn too_few_points_are_reported_as_such() {
    assert_err(
        osc_solve(SolverOptions {
            max_points: 1,
            ..Default::default()
        }),
        Phase::Solve,
        &["max_points must be at least 2"],
    );
    assert_err(
        osc_solve(SolverOptions {
            max_points: 5,
            ..Default::default()
        }),
        Phase::Solve,
        &["more than 5 reported points (SolverOptions::max_points)"],
    );
}

#[test]
fn too_many_steps_between_points_name_the_option() {
    assert_err(
        osc_solve(SolverOptions {
            max_steps: 3,
            output_times: Some(vec![1.0]),
            ..Default::default()
        }),
        Phase::Solve,
        &["more than SolverOptions::max_steps = 3 steps"],
    );
}

// ---------------------------------------------------------------------------------------
// Values a solution cannot report.

component! {
    /// `y = sqrt(1 - time)`: NaN after t = 1.
    pub struct SqrtOfShrinking {
        variable x(start = 0.0): Real;
        variable y: Real;
        equation {
            der(x) = 1.0;
            y = (1.0 - x).sqrt();
        }
    }
}

#[test]
fn a_square_root_of_a_negative_number_is_reported_with_its_time() {
    let m = system! {
        name: "sqrt";
        s = SqrtOfShrinking::default();
    };
    let sol = run(&m, &[], (0.0, 2.0), &SolverOptions::default()).expect("the states are fine");
    assert_err(
        sol.get("s.y").map_err(Error::from),
        Phase::Solution,
        &["`s.y` is NaN at t = 1."],
    );
    // Before t = 1 the values exist.
    let y = sol.sample(&["s.y"], &[0.75]).unwrap()[0][0];
    assert!((y - 0.5).abs() < 1e-6, "{y}");
    assert_err(
        sol.sample(&["s.y"], &[1.5]).map_err(Error::from),
        Phase::Solution,
        &["`s.y` is NaN at t = 1.5"],
    );
    assert_err(
        sol.final_value("s.y").map_err(Error::from),
        Phase::Solution,
        &["`s.y` is NaN at t = 2"],
    );
}

component! {
    /// `y = 1 / x` with `x(0) = 0`: infinite at the start.
    pub struct Reciprocal {
        variable x(start = 0.0, fixed = true): Real;
        variable y: Real;
        equation {
            der(x) = 1.0;
            y = 1.0 / x;
        }
    }
}

#[test]
fn a_division_by_zero_at_the_start_is_reported() {
    let m = system! {
        name: "reciprocal";
        r = Reciprocal::default();
    };
    let sol = run_default(&m).expect("the state is fine");
    assert_err(
        sol.get("r.y").map_err(Error::from),
        Phase::Solution,
        &["`r.y` is inf at t = 0"],
    );
    let y = sol.sample(&["r.y"], &[0.5]).unwrap()[0][0];
    assert!((y - 2.0).abs() < 1e-6, "{y}");
}

#[test]
fn point_gravity_at_the_bodys_own_position_is_reported() {
    // A free body at the centre of a point-gravity field: its gravity acceleration is
    // 0/0 there.
    let m = system! {
        name: "centre";
        world = World { point_gravity: 1.0 };
        body = Body::default();
    };
    assert_err(
        run_default(&m),
        Phase::Init,
        &["model `centre`", "body.a_0[1]", "non-finite solution"],
    );
}

#[test]
fn an_unknown_variable_gets_suggestions() {
    let sol = osc_solve(SolverOptions::default()).unwrap();
    assert_err(
        sol.get("inertia.phii").map_err(Error::from),
        Phase::Solution,
        &["no variable `inertia.phii`", "`inertia.phi`"],
    );
}

#[test]
fn an_unknown_parameter_gets_suggestions() {
    let sol = osc_solve(SolverOptions::default()).unwrap();
    assert_err(
        sol.parameter("spring.cc").map_err(Error::from),
        Phase::Solution,
        &["no parameter `spring.cc`", "`spring.c`"],
    );
}

#[test]
fn a_time_outside_the_solution_is_rejected() {
    let sol = osc_solve(SolverOptions::default()).unwrap();
    assert_err(
        sol.sample(&["inertia.phi"], &[1.5]).map_err(Error::from),
        Phase::Solution,
        &["t = 1.5 is outside the solved interval [0, 1]"],
    );
    assert_err(
        sol.at("inertia.phi", f64::NAN).map_err(Error::from),
        Phase::Solution,
        &["t = NaN"],
    );
}

#[test]
fn unknowns_past_the_last_point_are_none() {
    let sol = osc_solve(SolverOptions::default()).unwrap();
    let n = sol.t().len();
    assert!(sol.unknowns_at(n - 1).is_some());
    assert!(sol.unknowns_at(n).is_none());
    assert!(sol.unknowns_at(usize::MAX).is_none());
}

#[test]
fn an_unwritable_csv_path_is_named() {
    let sol = osc_solve(SolverOptions::default()).unwrap();
    let path = "no/such/directory/out.csv";
    assert_err(
        sol.write_csv(path, &["inertia.phi"]).map_err(Error::from),
        Phase::Solution,
        &["cannot write `no/such/directory/out.csv`"],
    );
}

#[test]
fn an_unwritable_plot_path_is_named() {
    let sol = osc_solve(SolverOptions::default()).unwrap();
    assert_err(
        plot(&sol, &["inertia.phi"], "no/such/directory/out.png"),
        Phase::Plot,
        &["no/such/directory"],
    );
}

#[test]
fn a_plot_of_60000_by_60000_pixels_is_refused_before_drawing() {
    let sol = osc_solve(SolverOptions::default()).unwrap();
    let options = PlotOptions {
        width: 60_000,
        height: 60_000,
        ..Default::default()
    };
    let dir = std::env::temp_dir().join("multibody_malformed_plot");
    std::fs::create_dir_all(&dir).unwrap();
    assert_err(
        plot_figure(&sol, &[&["inertia.phi"]], dir.join("huge.png"), &options),
        Phase::Plot,
        &["60000x60000 is too large"],
    );
}

#[test]
fn a_plot_of_an_unknown_variable_names_it() {
    let sol = osc_solve(SolverOptions::default()).unwrap();
    assert_err(
        plot(&sol, &["inertia.psi"], "unused.png"),
        Phase::Solution,
        &["no variable `inertia.psi`"],
    );
}

// ---------------------------------------------------------------------------------------
// Structure: declarations, connections and balance.

component! {
    /// A component that forgets an equation.
    pub struct Forgetful {
        connector flange: Flange;
        variable x: Real;
        variable y: Real;
        equation {
            x = flange.phi;
            flange.tau = 0.0;
        }
    }
}

#[test]
fn a_forgotten_equation_names_the_undetermined_variable() {
    let m = system! {
        name: "unbalanced";
        fixed = Fixed::default();
        part = Forgetful::default();
        connect(fixed.flange, part.flange);
    };
    assert_err(run_default(&m), Phase::Model, &["not balanced", "part.y"]);
}

#[test]
fn an_inertia_held_by_two_fixed_flanges_is_structurally_singular() {
    let m = system! {
        name: "held";
        left = Fixed::default();
        right = Fixed::default();
        inertia = Inertia::default();
        connect(left.flange, inertia.flange_a);
        connect(inertia.flange_b, right.flange);
    };
    assert_err(
        run_default(&m),
        Phase::Simplify,
        &[
            "structurally singular",
            "left.flange.tau",
            "right.flange.tau",
        ],
    );
}

#[test]
fn two_position_sources_on_one_flange_are_named() {
    let m = system! {
        name: "fight";
        ref1 = Constant { k: 1.0 };
        ref2 = Constant { k: 2.0 };
        pos1 = Position { exact: true };
        pos2 = Position { exact: true };
        inertia = Inertia::default();
        connect(ref1.y, pos1.phi_ref);
        connect(ref2.y, pos2.phi_ref);
        connect(pos1.flange, inertia.flange_a);
        connect(pos2.flange, inertia.flange_b);
    };
    assert_err(
        run_default(&m),
        Phase::Simplify,
        &["pos1.flange.tau", "pos2.flange.tau"],
    );
}

#[test]
fn an_unconnected_signal_input_is_undetermined() {
    let m = system! {
        name: "undriven";
        torque = Torque::default();
        inertia = Inertia::default();
        connect(torque.flange, inertia.flange_a);
    };
    assert_err(
        run_default(&m),
        Phase::Model,
        &["not balanced", "torque.tau"],
    );
}

#[test]
fn a_connection_of_a_flange_with_a_frame_names_both() {
    let mut m = System::new("mixed");
    m.add("world", &World::default());
    m.add("inertia", &Inertia::default());
    m.connect("world.frame_b", "inertia.flange_a");
    assert_err(
        run_default(&m),
        Phase::Model,
        &["cannot connect `world.frame_b`", "with `inertia.flange_a`"],
    );
}

#[test]
fn a_misspelt_connector_gets_a_suggestion() {
    let mut m = System::new("misspelt");
    m.add("fixed", &Fixed::default());
    m.add("inertia", &Inertia::default());
    m.connect("fixed.flange", "inertia.flang_a");
    assert_err(
        run_default(&m),
        Phase::Model,
        &["`inertia.flang_a` is not a connector", "`inertia.flange_a`"],
    );
}

#[test]
fn a_component_added_twice_under_one_name_is_a_duplicate() {
    let mut m = System::new("twice");
    m.add("inertia", &Inertia::default());
    m.add("inertia", &Inertia::default());
    assert_err(
        run_default(&m),
        Phase::Model,
        &["`inertia.phi` is declared twice"],
    );
}

#[test]
fn an_equation_on_an_undeclared_variable_names_it_and_the_equation() {
    let mut m = oscillator().into_system();
    let ghost = m.v("inertia.ghost");
    m.equation(ghost, 1.0);
    assert_err(
        run_default(&m),
        Phase::Model,
        &[
            "unknown variable `inertia.ghost`",
            "model: inertia.ghost = 1",
        ],
    );
}

#[test]
fn an_undeclared_parameter_names_it() {
    let mut m = oscillator().into_system();
    let x = m.var("x");
    let k = m.p("spring.cc");
    m.equation(x.der(), k * x);
    assert_err(
        run_default(&m),
        Phase::Model,
        &["unknown parameter `spring.cc`", "`spring.c`"],
    );
}

#[test]
fn two_equations_for_one_variable_and_none_for_another_are_named() {
    let mut m = System::new("conflict");
    let x = m.var("x");
    let y = m.var("y");
    m.equation(x, 1.0);
    m.equation(x, 2.0);
    let _ = y;
    assert_err(
        run_default(&m),
        Phase::Simplify,
        &[
            "structurally singular",
            "no equation determines y",
            "model: x = 2",
        ],
    );
}

#[test]
fn conflicting_fixed_start_values_are_over_determined() {
    // Two rigidly connected inertias whose angles are both fixed at different values.
    let m = system! {
        name: "conflict";
        i1 = Inertia { phi_start: 1.0 };
        i2 = Inertia { phi_start: 2.0 };
        connect(i1.flange_b, i2.flange_a);
    };
    let mut m = m.into_system();
    m.set_start("i1.phi", 1.0);
    let ssys = structural_simplify(&m).unwrap();
    let e = DaeProblem::new(&ssys, &[("i1.phi", 1.0), ("i2.phi", 2.0)], (0.0, 1.0)).unwrap_err();
    assert_err::<()>(Err(e), Phase::Init, &["i1.phi", "i2.phi"]);
}

#[test]
fn an_initial_equation_that_contradicts_a_fixed_start_is_named() {
    let mut m = oscillator().into_system();
    let phi = m.v("inertia.phi");
    m.initial_equation(phi, 3.0);
    let ssys = structural_simplify(&m).unwrap();
    let e = DaeProblem::new(&ssys, &[("inertia.phi", 1.0)], (0.0, 1.0)).unwrap_err();
    assert_err::<()>(Err(e), Phase::Init, &["over-determined", "inertia.phi"]);
}

#[test]
fn an_expression_of_a_dropped_model_is_named_where_it_is_used() {
    let donor = oscillator();
    let e = Expr::var("inertia.phi").sin() * 2.0;
    drop(donor);
    let mut m = oscillator().into_system();
    // Put by hand into the fields (the builder calls would have copied it while the
    // donor lived).
    let x = m.var("x");
    m.equations
        .push(multibody_core::model::Equation { lhs: x, rhs: e });
    assert_err(
        run_default(&m),
        Phase::Model,
        &["uses an expression of a model that was dropped"],
    );
}

#[test]
fn an_over_constrained_loop_of_two_universal_joints_is_named_without_a_panic() {
    // A free body, a universal joint to a second body, and a second universal joint
    // closing onto a rigid offset of the first body: the name table of the singularity
    // message must cover the derivatives index reduction made.
    let m = system! {
        name: "universal_loop";
        world = World::default();
        b1 = Body { r_CM: [0.1, 0.0, 0.0], orientation_states: OrientationStates::Cardan };
        u1 = Universal::default();
        b2 = Body { r_CM: [0.2, 0.0, 0.0] };
        ft = FixedTranslation { r: [0.0, 0.3, 0.0] };
        u2 = Universal::default();
        connect(b1.frame_a, u1.frame_a);
        connect(u1.frame_b, b2.frame_a);
        connect(b1.frame_a, ft.frame_a);
        connect(ft.frame_b, u2.frame_a);
        connect(u2.frame_b, b2.frame_a);
    };
    // The second universal joint takes 4 degrees of freedom from a loop that has 2.
    assert_err(
        run_default(&m),
        Phase::Simplify,
        &[
            "`b1.phi[1]`",
            "must be states",
            "leave fewer degrees of freedom",
        ],
    );
}

#[test]
fn a_model_that_blows_up_reports_when() {
    // x' = x^2 from 1 reaches infinity at t = 1.
    let mut m = System::new("blowup");
    let x = m.variable(Variable::new("x").start(1.0).fixed(true));
    m.equation(x.der(), x * x);
    assert_err(
        run(&m, &[], (0.0, 2.0), &SolverOptions::default()),
        Phase::Solve,
        &["model `blowup`: the solver failed at t = 0.99"],
    );
}

#[test]
fn a_spring_damper_with_nan_damping_names_it() {
    let m = system! {
        name: "sd";
        fixed = Fixed::default();
        sd = SpringDamper { c: 1.0, d: f64::NAN };
        inertia = Inertia { phi_start: 1.0 };
        connect(fixed.flange, sd.flange_a);
        connect(sd.flange_b, inertia.flange_a);
    };
    assert_err(run_default(&m), Phase::Init, &["`sd.d` evaluates to NaN"]);
}

#[test]
fn a_free_vector_of_nans_as_a_start_value_names_its_element() {
    let mut m = System::new("vector");
    for k in 1..=3 {
        let v = m.var(&format!("v[{k}]"));
        m.equation(v.der(), -v);
    }
    let ssys = structural_simplify(&m).unwrap();
    let e = DaeProblem::new(&ssys, &[("v[2]", f64::NAN)], (0.0, 1.0)).unwrap_err();
    assert_err::<()>(Err(e), Phase::Init, &["`v[2]`"]);
}

#[test]
fn a_damper_alone_between_two_free_inertias_solves() {
    // Not malformed: a control for the corpus (relative states of a free pair).
    let m = system! {
        name: "pair";
        i1 = Inertia { J: 1.0, w_start: 1.0 };
        d = Damper { d: 0.5 };
        i2 = Inertia { J: 2.0 };
        connect(i1.flange_b, d.flange_a);
        connect(d.flange_b, i2.flange_a);
    };
    let sol = run(&m, &[], (0.0, 2.0), &SolverOptions::default()).unwrap();
    // Momentum J1 w1 + J2 w2 = 1 is conserved.
    let (w1, w2) = (
        sol.final_value("i1.w").unwrap(),
        sol.final_value("i2.w").unwrap(),
    );
    assert!((w1 + 2.0 * w2 - 1.0).abs() < 1e-6, "{w1} {w2}");
}
