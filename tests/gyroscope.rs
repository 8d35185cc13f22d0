//! The seed's gyroscope: a heavy symmetric top with three choices of orientation states
//! starts in the same state, keeps its three invariants (energy, angular momentum about
//! the vertical and about the symmetry axis) to the tolerance, and all three choices
//! follow the same motion.

#[path = "../examples/gyroscope.rs"]
#[allow(dead_code)]
mod gyroscope_example;
use gyroscope_example::{
    CHOICES, G, I_AXIAL, LENGTH, MASS, SPIN, TILT, axis, invariants, row, solve, top,
};
use multibody::prelude::*;

#[test]
fn the_three_orientation_choices_start_alike_keep_the_invariants_and_agree() {
    // The invariants at the start, in closed form: spin about the axis, no other
    // rotation; the axis tilted by TILT from the vertical.
    let energy = 0.5 * I_AXIAL * SPIN * SPIN + MASS * G * LENGTH * TILT.cos();
    let vertical = I_AXIAL * SPIN * TILT.cos();
    let axial = I_AXIAL * SPIN;
    // The first choice's symmetry axis, which the others follow.
    let mut first: Option<Vec<[f64; 3]>> = None;
    for (name, states, sequence) in CHOICES {
        let ssys = structural_simplify(&top(states, sequence)).unwrap();
        let sol = solve(&ssys, 1e-8).unwrap();
        let inv = invariants(&sol);
        for (k, (got, want)) in inv[0].iter().zip([energy, vertical, axial]).enumerate() {
            assert!(
                (got - want).abs() < 1e-10,
                "{name}: invariant {k} at t = 0: {got} vs {want}"
            );
        }
        let reference = first.get_or_insert_with(|| axis(&sol));
        let r = row(&sol, reference);
        // Energy is about 19 J, the momenta 0.7 kg m2/s: conserved to about the
        // tolerance relative to their sizes over 10 s.
        assert!(
            r.drift[0] < 1e-4 * energy,
            "{name}: energy drifts {}",
            r.drift[0]
        );
        assert!(
            r.drift[1] < 1e-4 * axial,
            "{name}: vertical momentum drifts {}",
            r.drift[1]
        );
        assert!(
            r.drift[2] < 1e-4 * axial,
            "{name}: axial momentum drifts {}",
            r.drift[2]
        );
        assert!(r.error < 1e-4, "{name}: the axis differs by {}", r.error);
    }
}
