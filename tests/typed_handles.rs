//! Typed access end to end: `system!` gives back the handle of every instance, and
//! results, start values, guesses, parameters, units and plots take a handle's field
//! (`m.j1.phi`) as well as a path. Checked against closed forms and against the same
//! quantities read by path or computed another way.

#![allow(missing_docs)]

#[path = "../examples/fourbar.rs"]
#[allow(dead_code)]
mod fourbar_example;

use multibody::joints::Revolute;
use multibody::parts::BodyShape;
use multibody::prelude::*;
use multibody::rotational::{Fixed, Inertia, Spring};
use multibody::world::World;

system! {
    /// A torsional oscillator of stiffness `c` on an inertia of 1 kg.m2.
    fn oscillator(c: f64) -> Oscillator {
        name: "oscillator";
        fixed = Fixed::default();
        spring = Spring { c };
        inertia: Inertia = Inertia::default();
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, inertia.flange_a);
    }
}

fn tight() -> SolverOptions {
    SolverOptions {
        rtol: 1e-9,
        atol: 1e-11,
        ..SolverOptions::default()
    }
}

#[test]
fn values_parameters_and_results_by_handle_match_the_closed_form() {
    let m = oscillator(4.0);
    let ssys = structural_simplify(&m).unwrap();
    // Start value and a parameter set by handle: phi = 0.5 cos(3 t).
    let sol = DaeProblem::builder(&ssys, (0.0, 2.0))
        .value(m.inertia.phi, 0.5)
        .value(m.spring.c, 9.0)
        .build()
        .unwrap()
        .solve(&tight())
        .unwrap();
    let phi = sol.get(m.inertia.phi).unwrap();
    for (t, p) in sol.t().iter().zip(&phi) {
        assert!((p - 0.5 * (3.0 * t).cos()).abs() < 1e-6, "phi({t}) = {p}");
    }
    // The same series by path; the parameter as set, by handle and by path.
    assert_eq!(sol.get("inertia.phi").unwrap(), phi);
    assert_eq!(sol.parameter(m.spring.c).unwrap(), 9.0);
    assert_eq!(sol.parameter("spring.c").unwrap(), 9.0);
    // A parameter read as a series is constant.
    assert!(sol.get(m.spring.c).unwrap().iter().all(|&c| c == 9.0));
    // Several at once, and at a time between the reported ones.
    let [w, a] =
        <[Vec<f64>; 2]>::try_from(sol.get_many(&[m.inertia.w, m.inertia.a]).unwrap()).unwrap();
    let k = sol.t().len() / 2;
    let t = sol.t()[k];
    assert!((w[k] + 1.5 * (3.0 * t).sin()).abs() < 1e-6);
    assert!((a[k] + 4.5 * (3.0 * t).cos()).abs() < 1e-5);
    // Time reads like a variable, as in Modelica.
    assert_eq!(sol.get("time").unwrap(), sol.t());
    assert!((sol.at("time", 1.234).unwrap() - 1.234).abs() < 1e-12);
    let at = sol.at(m.inertia.phi, 1.234).unwrap();
    assert!((at - 0.5 * (3.0f64 * 1.234).cos()).abs() < 1e-5);
}

#[test]
fn handles_name_their_full_paths_and_are_copies() {
    let m = fourbar_example::fourbar();
    assert_eq!(m.j1.phi.name().as_deref(), Some("j1.phi"));
    assert_eq!(m.b1.body.m.name().as_deref(), Some("b1.body.m"));
    assert_eq!(m.damper1.d.name().as_deref(), Some("damper1.d"));
    let h = *m.handles();
    let copied = h.j2;
    assert_eq!(copied.w.name().as_deref(), Some("j2.w"));
    assert_eq!(m.system().name, "fourbar");
}

#[test]
fn the_tutorial_fourbar_runs_by_handle_and_reads_derivatives_by_name() {
    let m = fourbar_example::fourbar();
    let ssys = structural_simplify(&m).unwrap();
    let sol = DaeProblem::builder(&ssys, (0.0, 2.0))
        .value(m.j1.phi, 0.1)
        .guess(m.j2.phi, 0.0)
        .build()
        .unwrap()
        .solve(&tight().with_output_interval(0.0, 2.0, 0.01))
        .unwrap();
    assert_eq!(sol.get(m.j1.phi).unwrap()[0], 0.1);
    // Every derivative that the reduced equations print can be read, and it agrees with
    // the variable the model defines as that derivative (the integrator's derivative of
    // a state against the observed function).
    let printed: Vec<String> = ssys
        .equations()
        .iter()
        .filter_map(|e| {
            e.strip_prefix("der(")?
                .split_once(')')
                .map(|(x, _)| x.to_string())
        })
        .collect();
    assert!(!printed.is_empty());
    for x in &printed {
        assert!(
            sol.get(format!("der({x})")).is_ok(),
            "der({x}) is not readable"
        );
    }
    for (state, derivative) in [("j1.phi", "j1.w"), ("j1.w", "j1.a"), ("j2.phi", "j2.w")] {
        let Ok(d) = sol.get(format!("der({state})")) else {
            continue;
        };
        let v = sol.get(derivative).unwrap();
        let scale = v.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (k, (a, b)) in d.iter().zip(&v).enumerate() {
            assert!(
                (a - b).abs() < 1e-6 * scale,
                "der({state}) = {a}, {derivative} = {b} at t = {}",
                sol.t()[k]
            );
        }
    }
    // Units come from the components' declarations.
    assert_eq!(sol.unit(m.j1.phi).as_deref(), Some("rad"));
    assert_eq!(sol.unit(m.j1.w).as_deref(), Some("rad/s"));
    assert_eq!(sol.unit("der(j1.w)").as_deref(), Some("rad/s2"));
    assert_eq!(sol.unit(m.j1.tau).as_deref(), Some("N.m"));
    assert_eq!(sol.unit("b1.frame_b.r_0[1]").as_deref(), Some("m"));
}

#[test]
fn a_derivative_that_is_not_computed_is_an_error_naming_the_computed_ones() {
    let m = oscillator(4.0);
    let ssys = structural_simplify(&m).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 0.1))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    let states = ssys.states();
    let e = sol.get("der(spring.tau)").unwrap_err().to_string();
    assert!(e.contains("der(spring.tau)"), "{e}");
    assert!(
        states.iter().any(|s| e.contains(&format!("der({s})"))),
        "{e} names no derivative of {states:?}"
    );
}

#[test]
fn derivatives_of_aliases_of_states_are_readable() {
    // With a damper, MSL's relative states win: inertia.phi and the flanges' angles are
    // aliases of damper.phi_rel, and their derivatives are the inertia's speed.
    let m = system! {
        name: "damped";
        fixed = Fixed::default();
        spring = Spring { c: 4.0 };
        damper = multibody::rotational::Damper { d: 0.4 };
        inertia = Inertia { phi_start: 1.0 };
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, inertia.flange_a);
        connect(fixed.flange, damper.flange_a);
        connect(damper.flange_b, inertia.flange_a);
    };
    let ssys = structural_simplify(&m).unwrap();
    assert_eq!(ssys.states(), ["damper.phi_rel", "damper.w_rel"]);
    let sol = DaeProblem::new(&ssys, &[], (0.0, 2.0))
        .unwrap()
        .solve(&tight())
        .unwrap();
    let w = sol.get(m.inertia.w).unwrap();
    assert!(w.iter().any(|x| x.abs() > 0.5), "the inertia moves");
    for name in [
        "der(inertia.phi)",
        "der(inertia.flange_a.phi)",
        "der(spring.flange_b.phi)",
        "der(damper.flange_b.phi)",
    ] {
        let d = sol.get(name).unwrap();
        for (a, b) in d.iter().zip(&w) {
            assert!((a - b).abs() < 1e-9, "{name} = {a}, inertia.w = {b}");
        }
    }
    // And the acceleration: der(inertia.w) = -(c phi + d w) / J.
    let (phi, a) = (
        sol.get(m.inertia.phi).unwrap(),
        sol.get("der(inertia.w)").unwrap(),
    );
    for k in 0..phi.len() {
        let exact = -(4.0 * phi[k] + 0.4 * w[k]);
        assert!(
            (a[k] - exact).abs() < 1e-8,
            "der(inertia.w) = {}, {exact}",
            a[k]
        );
    }
}

#[test]
fn a_close_but_wrong_name_suggests_the_sub_component_path() {
    let m = system! {
        name: "pendulum";
        world = World::default();
        j1 = Revolute::default();
        b1 = BodyShape { m: 1.0, r: [1.0, 0.0, 0.0] };
        connect(world.frame_b, j1.frame_a);
        connect(j1.frame_b, b1.frame_a);
    };
    let ssys = structural_simplify(&m).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 0.1))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    for e in [
        sol.get("b1.m").unwrap_err().to_string(),
        sol.parameter("b1.m").unwrap_err().to_string(),
    ] {
        assert!(e.contains("did you mean `b1.body.m`"), "{e}");
    }
    let e = sol.get("j1.omega").unwrap_err().to_string();
    assert!(e.contains("`j1.w`") || e.contains("`j1.phi`"), "{e}");
    assert!(!e.contains("b1."), "{e}");
}

#[test]
fn a_world_under_another_name_is_one_line_that_says_so() {
    let renamed = system! {
        name: "pendulum";
        earth = World::default();
        j1 = Revolute::default();
        b1 = BodyShape { m: 1.0, r: [1.0, 0.0, 0.0] };
        connect(earth.frame_b, j1.frame_a);
        connect(j1.frame_b, b1.frame_a);
    };
    let e = structural_simplify(&renamed).unwrap_err().to_string();
    assert_eq!(
        e,
        "model `pendulum` has no instance `world` (MultiBody.World), which its components \
         refer to by that name; the model has one named `earth`: name it `world`"
    );
    let without = system! {
        name: "pendulum";
        j1 = Revolute::default();
        b1 = BodyShape { m: 1.0, r: [1.0, 0.0, 0.0] };
        connect(j1.frame_b, b1.frame_a);
    };
    let e = structural_simplify(&without).unwrap_err().to_string();
    assert!(e.ends_with(": add one named `world`"), "{e}");
    assert!(!e.contains('\n') && e.len() < 200, "{e}");
}

#[test]
fn plots_take_handles() {
    let m = oscillator(4.0);
    let ssys = structural_simplify(&m).unwrap();
    let sol = DaeProblem::builder(&ssys, (0.0, 1.0))
        .value(m.inertia.phi, 1.0)
        .build()
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    let path = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("typed_plot.png");
    plot(&sol, &[m.inertia.phi, m.inertia.w], &path).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    let plain_height = png_height(&bytes);
    // A figure title given before the panels and kept through `options`: a band over
    // the panels makes the image taller.
    Figure::new()
        .title("Oscillator")
        .panel(&sol, &[m.inertia.phi])
        .panel(&sol, &[m.inertia.w])
        .options(PlotOptions {
            columns: 2,
            ..PlotOptions::default()
        })
        .save(&path)
        .unwrap();
    let titled = std::fs::read(&path).unwrap();
    assert!(
        png_height(&titled) > plain_height / 2,
        "two panels side by side"
    );
    let untitled = path.with_file_name("typed_plot_untitled.png");
    Figure::new()
        .panel(&sol, &[m.inertia.phi])
        .panel(&sol, &[m.inertia.w])
        .options(PlotOptions {
            columns: 2,
            ..PlotOptions::default()
        })
        .save(&untitled)
        .unwrap();
    let untitled_bytes = std::fs::read(&untitled).unwrap();
    assert!(png_height(&titled) > png_height(&untitled_bytes));
    std::fs::remove_file(&path).ok();
    std::fs::remove_file(&untitled).ok();
    // Two solutions compared panel by panel: each panel labels both curves, and its y
    // axis carries the unit.
    let stiff = DaeProblem::builder(&ssys, (0.0, 1.0))
        .value(m.inertia.phi, 1.0)
        .value(m.spring.c, 16.0)
        .build()
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    let panels = Figure::new()
        .labelled_panel(&sol, &[m.inertia.phi], "c = 4")
        .overlay(&stiff, &[m.inertia.phi], "c = 16")
        .labelled_panel(&sol, &[m.inertia.w], "c = 4")
        .overlay(&stiff, &[m.inertia.w], "c = 16")
        .into_panels()
        .unwrap();
    let labels: Vec<Vec<&str>> = panels
        .iter()
        .map(|p| p.series.iter().map(|s| s.label.as_str()).collect())
        .collect();
    assert_eq!(
        labels,
        [
            ["inertia.phi (c = 4)", "inertia.phi (c = 16)"],
            ["inertia.w (c = 4)", "inertia.w (c = 16)"]
        ]
    );
    assert_eq!(panels[0].y_label, "[rad]");
    assert_eq!(panels[1].y_label, "[rad/s]");
    // The stiffer spring's curve is the other solution's: phi = cos(4 t) at the end.
    let last = panels[0].series[1].y.last().copied().unwrap();
    assert!((last - 4.0f64.cos()).abs() < 1e-4, "{last}");
}

/// The height of a PNG image, from its IHDR chunk.
fn png_height(bytes: &[u8]) -> u32 {
    u32::from_be_bytes(bytes[20..24].try_into().unwrap())
}
