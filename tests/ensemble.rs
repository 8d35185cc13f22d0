//! Ensembles: one compiled model solved for many values in parallel gives, in input
//! order, what solving each alone gives; a bad entry fails alone.

#[path = "support/small_models.rs"]
mod small_models;

use multibody::prelude::*;
use multibody::{EnsembleOptions, solve_ensemble};
use small_models::point_pendulum;

#[test]
fn an_ensemble_gives_each_solution_in_input_order() {
    let ssys = structural_simplify(&point_pendulum()).unwrap();
    let values: Vec<Vec<(String, f64)>> = (0..24)
        .map(|k| {
            vec![
                ("link.r[1]".to_string(), 0.5 + 0.05 * k as f64),
                ("joint.phi".to_string(), -0.3),
                ("joint.w".to_string(), 0.0),
            ]
        })
        .collect();
    let options = SolverOptions::default();
    for threads in [1, 2] {
        let ensemble = EnsembleOptions { threads };
        let solutions = solve_ensemble(&ssys, (0.0, 2.0), &values, &options, &ensemble).unwrap();
        assert_eq!(solutions.len(), values.len());
        for (v, s) in values.iter().zip(&solutions) {
            let named: Vec<(&str, f64)> = v.iter().map(|(n, x)| (n.as_str(), *x)).collect();
            let alone = DaeProblem::new(&ssys, &named, (0.0, 2.0))
                .unwrap()
                .solve(&options)
                .unwrap();
            let s = s.as_ref().unwrap();
            assert_eq!(s.t(), alone.t());
            assert_eq!(
                s.get("joint.phi").unwrap(),
                alone.get("joint.phi").unwrap(),
                "length {}",
                v[0].1
            );
        }
    }
}

#[test]
fn a_bad_entry_fails_alone() {
    let ssys = structural_simplify(&point_pendulum()).unwrap();
    let values = vec![
        vec![("link.r[1]".to_string(), 0.7)],
        vec![("link.rr[1]".to_string(), 0.7)],
        vec![("link.r[1]".to_string(), 0.9)],
    ];
    let solutions = solve_ensemble(
        &ssys,
        (0.0, 1.0),
        &values,
        &SolverOptions::default(),
        &EnsembleOptions::default(),
    )
    .unwrap();
    assert!(solutions[0].is_ok() && solutions[2].is_ok());
    let message = solutions[1].as_ref().unwrap_err().to_string();
    assert!(message.contains("link.rr[1]"), "{message}");
}
