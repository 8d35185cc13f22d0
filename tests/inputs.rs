//! The model's inputs: signal inputs left open (or variables named in
//! `SimplifyOptions::inputs`) driven at solve time by closures or tables, without
//! compiling again, against closed forms; linearized as inputs; and the errors.

use multibody::prelude::*;
use multibody::rotational::{Brake, Inertia, Position, Torque, friction_mode};
use multibody::{InputSignal, SimplifyOptions, linearize, structural_simplify_with};

fn tight() -> SolverOptions {
    SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        ..Default::default()
    }
}

fn driven_inertia(j: f64) -> System {
    system! {
        name: "driven";
        torque = Torque::default();
        inertia = Inertia { J: j };
        connect(torque.flange, inertia.flange_a);
    }
    .into()
}

#[test]
fn an_open_torque_input_is_driven_by_functions_of_time_without_recompiling() {
    let j = 2.0;
    let model = driven_inertia(j);
    let options = SimplifyOptions {
        open_inputs: true,
        ..Default::default()
    };
    let ssys = structural_simplify_with(&model, &options).unwrap();
    assert_eq!(ssys.inputs(), ["torque.tau"]);
    // J phi'' = sin t from rest: phi = (t - sin t) / J.
    let sol = DaeProblem::builder(&ssys, (0.0, 3.0))
        .input("torque.tau", |t: f64| t.sin())
        .build()
        .unwrap()
        .solve(&tight())
        .unwrap();
    for t in [0.5, 1.7, 3.0] {
        let phi = sol.at("inertia.phi", t).unwrap();
        assert!((phi - (t - t.sin()) / j).abs() < 1e-8, "phi({t}) = {phi}");
        assert!((sol.at("torque.tau", t).unwrap() - t.sin()).abs() < 1e-14);
    }
    // The same compiled model with a table (a ramp to 1 at t = 1, then off): w = 1/(2J).
    let ramp = InputSignal::table(vec![(0.0, 0.0), (1.0, 1.0), (1.0, 0.0)]);
    let sol = DaeProblem::builder(&ssys, (0.0, 3.0))
        .input_signal("torque.tau", ramp)
        .build()
        .unwrap()
        .solve(&tight())
        .unwrap();
    let w = sol.final_value("inertia.w").unwrap();
    assert!((w - 0.5 / j).abs() < 1e-8, "w = {w}");
    // And with a constant value: the input is a parameter of the compiled model, which
    // linearization takes as an input (B = 1/J into the speed).
    let problem = DaeProblem::builder(&ssys, (0.0, 3.0))
        .value("torque.tau", 1.0)
        .build()
        .unwrap();
    let w = problem
        .solve(&tight())
        .unwrap()
        .final_value("inertia.w")
        .unwrap();
    assert!((w - 3.0 / j).abs() < 1e-8, "w = {w}");
    let lin = linearize(
        &ssys,
        &problem.operating_point(),
        &["torque.tau"],
        &["inertia.w"],
    )
    .unwrap();
    let k = lin.states.iter().position(|s| s == "inertia.w").unwrap();
    assert!((lin.b[(k, 0)] - 1.0 / j).abs() < 1e-12, "{lin:?}");
}

#[test]
fn specialized_parameters_leave_a_driven_input_free() {
    let model = driven_inertia(4.0);
    let options = SimplifyOptions {
        inputs: vec!["torque.tau".into()],
        ..Default::default()
    };
    let ssys = structural_simplify_with(&model, &options).unwrap();
    let sol = DaeProblem::builder(&ssys, (0.0, 2.0))
        .input("torque.tau", |t: f64| 3.0 * t * t)
        .build()
        .unwrap()
        .solve(&SolverOptions {
            specialize_parameters: true,
            ..tight()
        })
        .unwrap();
    // w = t^3 / J.
    let w = sol.final_value("inertia.w").unwrap();
    assert!((w - 8.0 / 4.0).abs() < 1e-8, "w = {w}");
}

#[test]
fn an_input_table_engages_a_brake_through_its_events() {
    // The brake's normal force ramps from 0 at 1 s to its maximum at 2 s: the braking
    // torque 0.8 * 10 * 0.3 r(t) = 2.4 r(t) N.m takes 1.2 N.m.s by 2 s (w = 6 - 0.4) and
    // stops the 3 kg.m2 inertia at 2 + 5.6 * 3 / 2.4 = 9 s, where it sticks.
    let model = system! {
        name: "brake";
        inertia = Inertia { J: 3.0, w_start: 6.0, state_priority: 20.0 };
        brake = Brake { fn_max: 10.0, mu_pos: vec![[0.0, 0.3]], cgeo: 0.8 };
        connect(inertia.flange_b, brake.flange_a);
    };
    let options = SimplifyOptions {
        inputs: vec!["brake.f_normalized".into()],
        ..Default::default()
    };
    let ssys = structural_simplify_with(&model, &options).unwrap();
    let press = InputSignal::table(vec![(1.0, 0.0), (2.0, 1.0)]);
    let sol = DaeProblem::builder(&ssys, (0.0, 12.0))
        .input_signal("brake.f_normalized", press)
        .build()
        .unwrap()
        .solve(&tight())
        .unwrap();
    for (t, w) in [
        (0.5, 6.0),
        (1.5, 6.0 - 0.1),
        (5.0, 3.2),
        (8.5, 0.4),
        (11.0, 0.0),
    ] {
        let got = sol.at("inertia.w", t).unwrap();
        assert!((got - w).abs() < 1e-7, "w({t}) = {got}, exact {w}");
    }
    let engaged = &sol.events()[0];
    assert_eq!(engaged.condition, "brake.f_n <= 0");
    assert!((engaged.t - 1.0).abs() < 1e-8, "{engaged:?}");
    let stuck = sol.events().iter().find(|e| e.t > 2.0).unwrap();
    assert!((stuck.t - 9.0).abs() < 1e-7, "{stuck:?}");
    assert_eq!(sol.at("brake.mode", 10.0).unwrap(), friction_mode::STUCK);
}

#[test]
fn errors_name_the_input() {
    let model = driven_inertia(1.0);
    let named = |inputs: &[&str]| SimplifyOptions {
        inputs: inputs.iter().map(|s| s.to_string()).collect(),
        ..Default::default()
    };
    let message = |e: multibody::Error| e.to_string();
    // An input that is not a variable of the model.
    let e = structural_simplify_with(&model, &named(&["inertia.phy"])).unwrap_err();
    assert!(
        message(e).contains("`inertia.phy` in SimplifyOptions::inputs (did you mean `inertia.phi`")
    );
    let e = structural_simplify_with(&model, &named(&["torque.tau", "torque.tau"])).unwrap_err();
    assert!(message(e).contains("input `torque.tau` is named twice"));
    // Left open without being an input: unbalanced, and the message says how to make it one.
    let e = multibody::structural_simplify(&model).unwrap_err();
    assert!(message(e).contains("inputs connected to nothing: torque.tau"));
    // A position source that follows its input exactly differentiates it.
    let exact = system! {
        name: "exact";
        source = Position { exact: true };
        inertia = Inertia::default();
        connect(source.flange, inertia.flange_a);
    };
    let e = structural_simplify_with(&exact, &named(&["source.phi_ref"])).unwrap_err();
    let text = message(e);
    assert!(
        text.contains("index reduction has to differentiate")
            && text.contains("input `source.phi_ref`"),
        "{text}"
    );
    // Filtered, it does not.
    let filtered = system! {
        name: "filtered";
        source = Position::default();
        inertia = Inertia::default();
        connect(source.flange, inertia.flange_a);
    };
    assert!(structural_simplify_with(&filtered, &named(&["source.phi_ref"])).is_ok());

    let ssys = structural_simplify_with(&model, &named(&["torque.tau"])).unwrap();
    let build = |b: multibody::ProblemBuilder| b.build().map(|_| ()).map_err(message);
    let e = build(DaeProblem::builder(&ssys, (0.0, 1.0)).input("inertia.w", |t: f64| t));
    assert!(
        e.unwrap_err()
            .contains("`inertia.w` is not an input of the model: its inputs are torque.tau")
    );
    let e = build(
        DaeProblem::builder(&ssys, (0.0, 1.0))
            .value("torque.tau", 1.0)
            .input("torque.tau", |t: f64| t),
    );
    assert!(e.unwrap_err().contains("given both a value and a signal"));
    let e = build(DaeProblem::builder(&ssys, (0.0, 1.0)).input_signal(
        "torque.tau",
        InputSignal::table(vec![(1.0, 0.0), (0.5, 1.0)]),
    ));
    assert!(e.unwrap_err().contains("the times of its table decrease"));
    // A value the signal does not have is an error at the time it occurs.
    let e = DaeProblem::builder(&ssys, (0.0, 1.0))
        .input("torque.tau", |t: f64| if t > 0.5 { f64::NAN } else { 1.0 })
        .build()
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap_err();
    let text = message(e);
    assert!(
        text.contains("the input `torque.tau` is NaN at t = 0.5"),
        "{text}"
    );
}
