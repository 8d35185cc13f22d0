//! Ensembles: one compiled model solved for many values in parallel gives, in input
//! order, what solving each alone gives; a bad entry fails alone.

use multibody::joints::Revolute;
use multibody::parts::{Body, FixedTranslation};
use multibody::prelude::*;
use multibody::world::World;
use multibody::{EnsembleOptions, solve_ensemble};

/// A pendulum of a point mass on a massless link of tunable length `link.r[1]`.
fn pendulum() -> System {
    system! {
        name: "pendulum";
        world = World::default();
        joint = Revolute::default();
        link = FixedTranslation { r: [1.0, 0.0, 0.0] };
        bob = Body { m: 1.0, I_11: 0.0, I_22: 0.0, I_33: 0.0 };
        connect(world.frame_b, joint.frame_a);
        connect(joint.frame_b, link.frame_a);
        connect(link.frame_b, bob.frame_a);
    }
    .into()
}

#[test]
fn an_ensemble_gives_each_solution_in_input_order() {
    let ssys = structural_simplify(&pendulum()).unwrap();
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
    let ssys = structural_simplify(&pendulum()).unwrap();
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
