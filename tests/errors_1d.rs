//! Bad models give errors that name the variables and equations involved.

#![allow(missing_docs)]

use multibody::blocks::Constant;
use multibody::prelude::*;
use multibody::rotational::{Fixed, Flange, Inertia, Position, Spring};

component! {
    /// A component that forgets an equation: `y` is determined by nothing.
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
fn unbalanced_model_names_the_undetermined_variable() {
    let model = system! {
        name: "unbalanced";
        fixed = Fixed::default();
        part = Forgetful::default();
        connect(fixed.flange, part.flange);
    };
    let err = structural_simplify(&model).unwrap_err().to_string();
    assert!(err.contains("model `unbalanced` is not balanced"), "{err}");
    assert!(err.contains("equations for"), "{err}");
    assert!(err.contains("part.y"), "{err}");
}

#[test]
fn an_inertia_fixed_at_both_flanges_is_structurally_singular() {
    let model = system! {
        name: "fixed_twice";
        left = Fixed::default();
        right = Fixed { phi0: 0.0 };
        inertia = Inertia::default();
        connect(left.flange, inertia.flange_a);
        connect(inertia.flange_b, right.flange);
    };
    let err = structural_simplify(&model).unwrap_err().to_string();
    assert!(err.contains("structurally singular"), "{err}");
    // The angle is fixed twice (the connection of the two fixed angles relates two
    // parameters only), so one torque is left undetermined.
    assert!(
        err.contains("reduces to 0 = left.phi0 - right.phi0: no unknown is left in it"),
        "{err}"
    );
    assert!(
        err.contains("left.flange.tau") && err.contains("right.flange.tau"),
        "{err}"
    );
}

#[test]
fn two_position_sources_fighting_over_one_flange_are_named() {
    let model = system! {
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
    let err = structural_simplify(&model).unwrap_err().to_string();
    assert!(err.contains("structurally singular"), "{err}");
    // Each position source forces the angle to its reference: the references end up
    // equated, and the torques of the sources are left undetermined.
    assert!(err.contains("reduces to 0 = -ref1.k + ref2.k"), "{err}");
    assert!(
        err.contains("pos1.flange.tau") && err.contains("pos2.flange.tau"),
        "{err}"
    );
}

component! {
    /// `z` from `z^2 = x - 5`: no real solution while `x < 5`.
    pub struct Impossible {
        variable x(start = 1.0, fixed = true): Real;
        variable z(start = 1.0): Real;
        equation {
            der(x) = 1.0;
            z * z = x - 5.0;
        }
    }
}

#[test]
fn failed_initialization_names_the_residual_and_the_iteration_variable() {
    let model = system! {
        name: "impossible";
        part = Impossible::default();
    };
    let ssys = structural_simplify(&model).unwrap();
    let err = DaeProblem::new(&ssys, &[], (0.0, 1.0))
        .unwrap_err()
        .to_string();
    assert!(err.contains("initialization did not converge"), "{err}");
    assert!(err.contains("in part: part.z^2 = part.x - 5"), "{err}");
    assert!(err.contains("part.z = "), "{err}");
}

#[test]
fn unknown_names_get_suggestions() {
    let model = system! {
        name: "osc";
        fixed = Fixed::default();
        spring = Spring { c: 1.0 };
        inertia = Inertia { phi_start: 1.0 };
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, inertia.flange_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    let err = DaeProblem::new(&ssys, &[("inertia.pi", 1.0)], (0.0, 1.0))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("no variable or parameter `inertia.pi`"),
        "{err}"
    );
    assert!(err.contains("inertia.phi"), "{err}");
    let sol = DaeProblem::new(&ssys, &[], (0.0, 1.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    let err = sol.get("inertia.ww").unwrap_err().to_string();
    assert!(err.contains("did you mean `inertia.w`"), "{err}");
}

#[test]
fn conflicting_fixed_start_values_are_over_determined() {
    let model = system! {
        name: "osc";
        fixed = Fixed::default();
        spring = Spring { c: 1.0 };
        inertia = Inertia::default();
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, inertia.flange_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    // phi and the spring's relative angle are the same thing: fixing both is too much.
    let err = DaeProblem::new(
        &ssys,
        &[
            ("inertia.phi", 1.0),
            ("spring.phi_rel", 2.0),
            ("inertia.w", 0.0),
        ],
        (0.0, 1.0),
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("over-determined"), "{err}");
    assert!(err.contains("fixed start value of inertia.phi"), "{err}");
    assert!(err.contains("fixed start value of spring.phi_rel"), "{err}");
}

#[test]
fn solver_failure_says_when_and_why() {
    component! {
        /// Blows up in finite time: `der(x) = x^2`, x(0) = 1 -> x = 1/(1 - t).
        pub struct BlowUp {
            variable x(start = 1.0, fixed = true): Real;
            equation { der(x) = x * x; }
        }
    }
    let model = system! { name: "blowup"; part = BlowUp::default(); };
    let ssys = structural_simplify(&model).unwrap();
    let err = DaeProblem::new(&ssys, &[], (0.0, 2.0))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("model `blowup`: the solver failed at t = "),
        "{text}"
    );
    let multibody::Error::Solve(e) = err else {
        panic!("expected a solver error: {text}")
    };
    assert!(e.t > 0.99 && e.t < 1.0, "failure time {}", e.t);
    // Why: x grows without bound towards t = 1, so the local error estimate does too and
    // IDA shrinks the step until it gives up: its error-test failure, in words.
    assert_eq!(e.flag, "IDA_ERR_FAIL", "{text}");
    let reason =
        "error test failed repeatedly (step size became too small; stiff or discontinuous?)";
    assert!(e.message.starts_with(reason), "{}", e.message);
    assert!(
        text.ends_with(&format!(": {}", e.message)) && text.contains(reason),
        "{text}"
    );
    // SUNDIALS' own message is kept, with the step size it reached.
    assert!(
        e.message.contains("[SUNDIALS: ") && e.message.contains("the error test failed repeatedly"),
        "{}",
        e.message
    );
}
