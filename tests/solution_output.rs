//! What a solution gives back besides trajectories: the CSV export and the report of
//! the start values that the initialization assumed.

#[path = "support/analytic.rs"]
mod analytic;

use analytic::{damped, tight};
use multibody::blocks::{Constant, FirstOrder, Init};
use multibody::prelude::*;
use multibody::translational::{Damper, Fixed, Mass, Spring};

/// The start values the initialization assumed, sorted by name.
fn assumed_by_name(prob: &DaeProblem<'_>) -> Vec<(String, f64)> {
    let mut assumed = prob.init_report().assumed.clone();
    assumed.sort_by(|a, b| a.0.cmp(&b.0));
    assumed
}

system! {
    fn mass_spring(c: f64, d: f64, m: f64, s0: f64, v0: f64) -> MassSpring {
        name: "mass_spring";
        fixed = Fixed::default();
        spring = Spring { c };
        damper = Damper { d };
        mass = Mass { m, s_start: s0, v_start: v0 };
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, mass.flange_a);
        connect(fixed.flange, damper.flange_a);
        connect(damper.flange_b, mass.flange_a);
    }
}

/// A file in the temporary directory, removed when dropped.
struct TempFile(std::path::PathBuf);

impl TempFile {
    fn new(tag: &str) -> TempFile {
        let p = std::env::temp_dir().join(format!(
            "multibody_solution_output_{}_{tag}.csv",
            std::process::id()
        ));
        let _ = std::fs::remove_file(&p);
        TempFile(p)
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

/// Header and rows of a CSV file of plain numbers.
fn read_csv(path: &std::path::Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines
        .next()
        .expect("a header")
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse::<f64>().unwrap()).collect())
        .collect();
    (header, rows)
}

#[test]
fn csv_export_round_trips_the_named_variables_at_the_output_times() {
    let (m, c, d, s0) = (2.0, 50.0, 1.5, 0.1);
    let ssys = structural_simplify(&mass_spring(c, d, m, s0, 0.0)).unwrap();
    let opts = tight().with_output_interval(0.0, 2.0, 0.1);
    let sol = DaeProblem::new(&ssys, &[], (0.0, 2.0))
        .unwrap()
        .solve(&opts)
        .unwrap();
    let names = ["mass.s", "mass.v", "spring.f", "damper.v_rel"];
    let file = TempFile::new("named");
    sol.write_csv(&file.0, &names).unwrap();
    let (header, rows) = read_csv(&file.0);
    assert_eq!(
        header,
        ["time", "mass.s", "mass.v", "spring.f", "damper.v_rel"]
    );
    // One row per reported time: t0 and the 20 output times.
    assert_eq!(rows.len(), 21);
    assert_eq!(rows.len(), sol.t().len());
    let series = sol.get_many(&names).unwrap();
    for (k, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), 5, "row {k}");
        // Numbers are written in the shortest form that reads back exactly.
        assert_eq!(row[0], sol.t()[k], "time of row {k}");
        assert!((row[0] - 0.1 * k as f64).abs() < 1e-12, "time of row {k}");
        for (j, s) in series.iter().enumerate() {
            assert_eq!(row[j + 1], s[k], "{} at row {k}", names[j]);
        }
        // And they are the physics: the analytic position, the spring law f = c s, and
        // the damper's relative velocity is the mass's velocity.
        let t = row[0];
        let exact = damped(m, d, c, s0, 0.0, t);
        assert!(
            (row[1] - exact).abs() <= 1e-6 * exact.abs().max(1e-3),
            "s({t}) = {}, exact {exact}",
            row[1]
        );
        assert!((row[3] - c * row[1]).abs() < 1e-12, "spring force at {t}");
        assert!((row[4] - row[2]).abs() < 1e-12, "relative velocity at {t}");
    }
}

#[test]
fn csv_export_without_names_writes_every_variable() {
    let ssys = structural_simplify(&mass_spring(50.0, 1.5, 2.0, 0.1, 0.0)).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 0.5))
        .unwrap()
        .solve(&tight().with_output_interval(0.0, 0.5, 0.25))
        .unwrap();
    let file = TempFile::new("all");
    sol.write_csv_all(&file.0).unwrap();
    let (header, rows) = read_csv(&file.0);
    assert_eq!(header[0], "time");
    let names: Vec<&str> = sol.names().iter().map(|n| &**n).collect();
    assert_eq!(header[1..], names);
    assert!(header.iter().any(|h| h == "fixed.flange.f"));
    assert_eq!(rows.len(), 3);
    for (j, name) in sol.names().iter().enumerate() {
        let s = sol.get(name).unwrap();
        for (k, row) in rows.iter().enumerate() {
            // NaN never equals itself; no variable of this model is NaN.
            assert_eq!(row[j + 1], s[k], "{name} at row {k}");
        }
    }
    // The fixed flange's position is its parameter s0 = 0 throughout, and the
    // reaction force balances spring and damper: f_fixed = c s + d v.
    let col = |n: &str| 1 + sol.names().iter().position(|x| &**x == n).unwrap();
    for row in &rows {
        assert_eq!(row[col("fixed.flange.s")], 0.0);
        let (s, v) = (row[col("mass.s")], row[col("mass.v")]);
        assert!((row[col("fixed.flange.f")] - (50.0 * s + 1.5 * v)).abs() < 1e-12);
    }
}

#[test]
fn csv_export_of_an_unknown_name_fails_without_writing() {
    let ssys = structural_simplify(&mass_spring(50.0, 1.5, 2.0, 0.1, 0.0)).unwrap();
    let sol = DaeProblem::new(&ssys, &[], (0.0, 0.1))
        .unwrap()
        .solve(&SolverOptions::default())
        .unwrap();
    let file = TempFile::new("unknown");
    let err = sol
        .write_csv(&file.0, &["mass.s", "mass.ss"])
        .unwrap_err()
        .to_string();
    assert!(err.contains("no variable `mass.ss`"), "{err}");
    assert!(err.contains("did you mean `mass.s`"), "{err}");
    assert!(!file.0.exists());
}

#[test]
fn assumed_start_values_are_reported_by_name_and_value() {
    // Undamped mass on a spring: states mass.s and mass.v, whose start values (not
    // fixed) complete the initial conditions.
    let (m, c, s0, v0) = (0.5, 8.0, 0.25, -0.5);
    let model = system! {
        name: "mass_on_spring";
        fixed = Fixed::default();
        spring = Spring { c };
        mass = Mass { m, s_start: s0, v_start: v0 };
        connect(fixed.flange, spring.flange_a);
        connect(spring.flange_b, mass.flange_a);
    };
    let ssys = structural_simplify(&model).unwrap();
    assert_eq!(ssys.states(), ["mass.s", "mass.v"]);
    let prob = DaeProblem::new(&ssys, &[], (0.0, 2.0)).unwrap();
    assert_eq!(
        assumed_by_name(&prob),
        [("mass.s".to_string(), s0), ("mass.v".to_string(), v0)]
    );
    assert_eq!(prob.initial_unknowns(), [s0, v0]);
    let sol = prob.solve(&tight()).unwrap();
    assert_eq!(sol.init_report(), prob.init_report());
    // The assumed values are the initial conditions: s = s0 cos(w t) + v0/w sin(w t).
    for &t in &[0.3, 1.0, 2.0] {
        let exact = damped(m, 0.0, c, s0, v0, t);
        let got = sol.at("mass.s", t).unwrap();
        assert!((got - exact).abs() < 1e-7, "s({t}) = {got}, exact {exact}");
    }

    // A given value is fixed, not assumed: only the velocity is left to its start.
    let prob = DaeProblem::new(&ssys, &[("mass.s", 0.4)], (0.0, 2.0)).unwrap();
    assert_eq!(prob.init_report().assumed, [("mass.v".to_string(), v0)]);
    assert_eq!(prob.initial_unknowns(), [0.4, v0]);

    // Both given: nothing is assumed.
    let prob = DaeProblem::new(&ssys, &[("mass.s", 0.4), ("mass.v", 1.0)], (0.0, 2.0)).unwrap();
    assert!(prob.init_report().assumed.is_empty());
}

#[test]
fn start_values_of_non_states_are_assumed_before_states_without_one() {
    // With the damper, the states are the damper's preferred s_rel and v_rel, which have
    // no start value; the mass's s and v have one (s_start, v_start) and a derivative,
    // so they are the ones assumed.
    let (m, c, d, s0, v0) = (2.0, 50.0, 1.5, 0.1, 0.3);
    let ssys = structural_simplify(&mass_spring(c, d, m, s0, v0)).unwrap();
    assert_eq!(ssys.states(), ["damper.s_rel", "damper.v_rel"]);
    let prob = DaeProblem::new(&ssys, &[], (0.0, 2.0)).unwrap();
    assert_eq!(
        assumed_by_name(&prob),
        [("mass.s".to_string(), s0), ("mass.v".to_string(), v0)]
    );
    // The states start from them: s_rel = s - 0 (fixed at 0, L = 0), v_rel = v.
    assert_eq!(prob.initial_unknowns(), [s0, v0]);
    let sol = prob.solve(&tight()).unwrap();
    for &t in &[0.5, 1.0, 2.0] {
        let exact = damped(m, d, c, s0, v0, t);
        let got = sol.at("mass.s", t).unwrap();
        assert!(
            (got - exact).abs() <= 1e-6 * exact.abs().max(1e-3),
            "s({t}) = {got}, exact {exact}"
        );
    }
}

// `FirstOrder` and `Integrator` declare `connector y(start = y_start)`, as MSL's
// `extends SISO(y(start = y_start))`: with `Init::NoInit` the state starts there.
#[test]
fn first_order_block_without_initialization_starts_at_y_start() {
    // MSL: `extends SISO(y(start = y_start))` and initType = NoInit: y_start is the
    // start value of the state y, used when nothing else fixes it (as for the inertia
    // and mass states above). T y' + y = k u from y(0) = y_start:
    // y = k u + (y_start - k u) exp(-t / T).
    let (u, k, tc, y0) = (1.0, 2.0, 0.5, 0.7);
    let model = system! {
        name: "first_order_noinit";
        source = Constant { k: u };
        lag = FirstOrder { k, T: tc, y_start: y0, init: Init::NoInit };
        connect(source.y, lag.u);
    };
    let ssys = structural_simplify(&model).unwrap();
    let prob = DaeProblem::new(&ssys, &[], (0.0, 2.0)).unwrap();
    assert_eq!(
        prob.init_report().assumed.len(),
        1,
        "{:?}",
        prob.init_report()
    );
    assert_eq!(
        prob.init_report().assumed[0].1,
        y0,
        "{:?}",
        prob.init_report()
    );
    let sol = prob.solve(&tight()).unwrap();
    for &t in &[0.0, 0.5, 2.0] {
        let exact = k * u + (y0 - k * u) * (-t / tc).exp();
        let got = sol.at("lag.y", t).unwrap();
        assert!((got - exact).abs() < 1e-8, "y({t}) = {got}, exact {exact}");
    }
}
