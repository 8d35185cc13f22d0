//! Golden tests of index reduction on the Cartesian pendulum and double pendulum.

use super::*;

/// The Cartesian pendulum after derivative aliasing. Slots: 0 x, 1 y, 2 vx = der(x),
/// 3 vy = der(y), 4 lambda, 5 der(vx), 6 der(vy). Equations: 0 `der(vx) = -lambda x`,
/// 1 `der(vy) = -lambda y - g`, 2 `x^2 + y^2 = L^2`.
pub(crate) fn pendulum() -> (BipartiteGraph, Vec<Option<usize>>) {
    let mut g = BipartiteGraph::new(7);
    g.add_equation(vec![5, 4, 0]);
    g.add_equation(vec![6, 4, 1]);
    g.add_equation(vec![0, 1]);
    let var_diff = vec![Some(2), Some(3), Some(5), Some(6), None, None, None];
    (g, var_diff)
}

#[test]
fn cartesian_pendulum_differentiates_the_constraint_twice() {
    let (g, var_diff) = pendulum();
    let r = pantelides(&g, &var_diff).unwrap();
    // The constraint (2) is differentiated into 3, and 3 into 4; nothing else.
    assert_eq!(r.eq_diff, vec![None, None, Some(3), Some(4), None]);
    assert_eq!(r.differentiation_counts(3), vec![0, 0, 2]);
    // No new slots: every derivative the constraint needs exists already.
    assert_eq!(r.var_diff.len(), 7);
    // 3 = d/dt(x^2 + y^2): x, y, vx, vy; 4 adds der(vx), der(vy).
    assert_eq!(r.graph.eq_vars[3], vec![0, 1, 2, 3]);
    assert_eq!(r.graph.eq_vars[4], vec![0, 1, 2, 3, 5, 6]);
    // Highest-order equations matched to highest-derivative slots.
    assert_eq!(r.matching.eq_to_var[0], Some(4));
    assert_eq!(r.matching.eq_to_var[1], Some(6));
    assert_eq!(r.matching.eq_to_var[4], Some(5));
    assert_eq!(r.matching.eq_to_var[2], None);
    assert_eq!(r.matching.eq_to_var[3], None);
}

#[test]
fn index_one_system_is_left_alone() {
    // x' = -x + y, 0 = y - sin(t): slots 0 x, 1 y, 2 der(x).
    let mut g = BipartiteGraph::new(3);
    g.add_equation(vec![0, 1, 2]);
    g.add_equation(vec![1]);
    let r = pantelides(&g, &[Some(2), None, None]).unwrap();
    assert_eq!(r.eq_diff, vec![None, None]);
    assert_eq!(r.matching.eq_to_var, vec![Some(2), Some(1)]);
}

#[test]
fn a_prescribed_position_is_differentiated_once() {
    // der(x1) = x2 (not aliased), 0 = x1 - sin(t): slots 0 x1, 1 x2, 2 der(x1).
    // x2 takes the first equation; the constraint on x1 must be differentiated once so
    // that der(x1) is determined (x1 stops being a state).
    let mut g = BipartiteGraph::new(3);
    g.add_equation(vec![1, 2]); // der(x1) - x2
    g.add_equation(vec![0]); // x1 - sin(t)
    let r = pantelides(&g, &[Some(2), None, None]).unwrap();
    assert_eq!(r.differentiation_counts(2), vec![0, 1]);
    assert_eq!(r.graph.eq_vars[2], vec![0, 2]);
    assert_eq!(r.matching.eq_to_var, vec![Some(1), None, Some(2)]);
}

#[test]
fn new_derivative_slots_are_created_when_needed() {
    // 0 = x1 - sin(t), 0 = x2 - x1 with der(x2) in a third equation for y:
    // y = der(x2). Slots 0 x1, 1 x2, 2 y, 3 der(x2). x1 has no derivative slot yet.
    let mut g = BipartiteGraph::new(4);
    g.add_equation(vec![0]); // x1 - sin(t)
    g.add_equation(vec![0, 1]); // x2 - x1
    g.add_equation(vec![2, 3]); // y - der(x2)
    let r = pantelides(&g, &[None, Some(3), None, None]).unwrap();
    // y takes its equation; x2 - x1 differentiates (needs der(x1), created) and then
    // x1 - sin(t) differentiates to determine der(x1).
    assert_eq!(r.differentiation_counts(3), vec![1, 1, 0]);
    assert_eq!(r.var_diff.len(), 5);
    assert_eq!(r.var_diff[0], Some(4));
}

#[test]
fn double_pendulum_differentiates_both_constraints_twice() {
    // Slots: x1 y1 x2 y2 (0..4), their velocities (4..8), accelerations (8..12),
    // lambda1 lambda2 (12, 13).
    let mut g = BipartiteGraph::new(14);
    let var_diff: Vec<Option<usize>> = (0..8)
        .map(|i| Some(i + 4))
        .chain((8..14).map(|_| None))
        .collect();
    // Newton: accelerations from the two rod forces.
    g.add_equation(vec![8, 12, 13, 0, 2]); // der(vx1)
    g.add_equation(vec![9, 12, 13, 1, 3]); // der(vy1)
    g.add_equation(vec![10, 13, 0, 2]); // der(vx2)
    g.add_equation(vec![11, 13, 1, 3]); // der(vy2)
    g.add_equation(vec![0, 1]); // rod 1
    g.add_equation(vec![0, 1, 2, 3]); // rod 2
    let r = pantelides(&g, &var_diff).unwrap();
    assert_eq!(r.differentiation_counts(6), vec![0, 0, 0, 0, 2, 2]);
    assert_eq!(r.graph.n_eqs(), 10);
    assert_eq!(r.var_diff.len(), 14);
}

#[test]
fn structurally_singular_system_is_reported() {
    // Two equations in x alone, y in none: no differentiation helps.
    let mut g = BipartiteGraph::new(3);
    g.add_equation(vec![0]);
    g.add_equation(vec![0, 2]);
    let err = pantelides(&g, &[Some(2), None, None]).unwrap_err();
    assert_eq!(err.equations, vec![0, 1]);
    assert_eq!(err.overdetermined, vec![0]);
    assert_eq!(err.undetermined, vec![1]);
}
