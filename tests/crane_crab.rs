//! The crane crab (`examples/crane_crab.rs`): its swing frequency against the closed
//! form, and the conservation of momentum along the rail and of energy.

#[path = "../examples/crane_crab.rs"]
#[allow(dead_code)]
mod crane_crab_example;

use crane_crab_example::{M_LOAD, M_TROLLEY, ROPE, crane_crab};
use multibody::linearize;
use multibody::prelude::*;

#[test]
fn the_crane_crab_swings_at_the_closed_form_frequency() {
    let ssys = structural_simplify(&crane_crab()).unwrap();
    let at_rest = DaeProblem::builder(&ssys, (0.0, 1.0))
        .value("rail.s", 0.0)
        .value("rail.v", 0.0)
        .value("hook.phi", 0.0)
        .value("hook.w", 0.0)
        .build()
        .unwrap();
    let lin = linearize(&ssys, &at_rest.operating_point(), &[], &[]).unwrap();
    // w^2 = g (M + m) / (M l), and the free translation (two zero eigenvalues).
    let w2 = 9.80665 * (M_TROLLEY + M_LOAD) / (M_TROLLEY * ROPE);
    let mut swing: Vec<f64> = lin
        .eigenvalues()
        .iter()
        .map(|e| e.im.abs())
        .filter(|&w| w > 1e-6)
        .collect();
    swing.sort_by(f64::total_cmp);
    assert_eq!(swing.len(), 2, "{:?}", lin.eigenvalues());
    for w in swing {
        assert!((w * w - w2).abs() < 1e-9 * w2, "{w} vs {}", w2.sqrt());
    }
    // Swung out by 0.3 rad: the momentum along the rail stays 0, the energy stays.
    let sol = DaeProblem::builder(&ssys, (0.0, 5.0))
        .value("rail.s", 0.0)
        .value("rail.v", 0.0)
        .value("hook.phi", 0.3)
        .value("hook.w", 0.0)
        .build()
        .unwrap()
        .solve(&SolverOptions {
            rtol: 1e-10,
            atol: 1e-12,
            output_times: Some((0..=50).map(|k| 0.1 * k as f64).collect()),
            ..SolverOptions::default()
        })
        .unwrap();
    let energy = |t: f64| {
        let get = |n: &str| sol.at(n, t).unwrap();
        let (v, phi, w) = (get("rail.v"), get("hook.phi"), get("hook.w"));
        let (vx, vy) = (v + ROPE * w * phi.cos(), ROPE * w * phi.sin());
        0.5 * M_TROLLEY * v * v + 0.5 * M_LOAD * (vx * vx + vy * vy)
            - M_LOAD * 9.80665 * ROPE * phi.cos()
    };
    let e0 = energy(0.0);
    for k in 1..=50 {
        let t = 0.1 * k as f64;
        let get = |n: &str| sol.at(n, t).unwrap();
        let (v, phi, w) = (get("rail.v"), get("hook.phi"), get("hook.w"));
        let momentum = M_TROLLEY * v + M_LOAD * (v + ROPE * w * phi.cos());
        assert!(momentum.abs() < 1e-8, "momentum {momentum} at {t}");
        assert!((energy(t) - e0).abs() < 1e-8, "energy at {t}");
    }
}
