//! Golden tests of dummy-derivative state selection.

use super::*;
use crate::structure::BipartiteGraph;
use crate::structure::pantelides::pantelides;

fn ranks(n: usize, decl: &[usize], prio: &[(usize, f64)]) -> Vec<StateRank> {
    let mut r: Vec<StateRank> = (0..n)
        .map(|v| StateRank {
            priority: 0.0,
            declaration: decl.get(v).copied().unwrap_or(v),
        })
        .collect();
    for &(v, p) in prio {
        r[v].priority = p;
    }
    r
}

#[test]
fn cartesian_pendulum_keeps_x_and_vx_without_priorities() {
    let (g, vd) = crate::structure::pantelides::tests::pendulum();
    let red = pantelides(&g, &vd).unwrap();
    // Declaration order x, y, vx, vy, lambda; der(vx), der(vy) rank with vx, vy.
    let rank = ranks(7, &[0, 1, 2, 3, 4, 2, 3], &[]);
    let sel = dummy_derivatives(&red, 3, &rank).unwrap();
    // Two levels: the twice-differentiated constraint picks der(vy), once picks vy.
    assert_eq!(sel.levels.len(), 2);
    assert_eq!(sel.levels[0].equations, vec![4]);
    assert_eq!(sel.levels[0].dummies, vec![6]);
    assert_eq!(sel.levels[1].equations, vec![3]);
    assert_eq!(sel.levels[1].dummies, vec![3]);
    assert_eq!(sel.states, vec![0, 2]);
}

#[test]
fn cartesian_pendulum_honours_a_priority_on_y() {
    let (g, vd) = crate::structure::pantelides::tests::pendulum();
    let red = pantelides(&g, &vd).unwrap();
    let rank = ranks(7, &[0, 1, 2, 3, 4, 2, 3], &[(1, 10.0)]);
    let sel = dummy_derivatives(&red, 3, &rank).unwrap();
    assert_eq!(sel.states, vec![1, 3]);
    assert!(sel.dummy[5] && sel.dummy[2]);
}

#[test]
fn always_that_cannot_be_honoured_is_an_error() {
    let (g, vd) = crate::structure::pantelides::tests::pendulum();
    let red = pantelides(&g, &vd).unwrap();
    // Both x and y demanded as states: only one can be.
    let rank = ranks(
        7,
        &[0, 1, 2, 3, 4, 2, 3],
        &[(0, ALWAYS), (1, ALWAYS), (2, ALWAYS), (3, ALWAYS)],
    );
    let err = dummy_derivatives(&red, 3, &rank).unwrap_err();
    assert!(
        matches!(err, SelectionError::AlwaysViolated(ref v) if !v.is_empty()),
        "{err:?}"
    );
}

#[test]
fn index_one_system_has_all_candidates_as_states() {
    let mut g = BipartiteGraph::new(3);
    g.add_equation(vec![0, 1, 2]);
    g.add_equation(vec![1]);
    let red = pantelides(&g, &[Some(2), None, None]).unwrap();
    let sel = dummy_derivatives(&red, 2, &ranks(3, &[], &[])).unwrap();
    assert!(sel.levels.is_empty());
    assert_eq!(sel.states, vec![0]);
}

#[test]
fn double_pendulum_keeps_four_states() {
    let mut g = BipartiteGraph::new(14);
    let var_diff: Vec<Option<usize>> = (0..8)
        .map(|i| Some(i + 4))
        .chain((8..14).map(|_| None))
        .collect();
    g.add_equation(vec![8, 12, 13, 0, 2]);
    g.add_equation(vec![9, 12, 13, 1, 3]);
    g.add_equation(vec![10, 13, 0, 2]);
    g.add_equation(vec![11, 13, 1, 3]);
    g.add_equation(vec![0, 1]);
    g.add_equation(vec![0, 1, 2, 3]);
    let red = pantelides(&g, &var_diff).unwrap();
    let decl: Vec<usize> = (0..14)
        .map(|v| if (8..12).contains(&v) { v - 4 } else { v })
        .collect();
    let sel = dummy_derivatives(&red, 6, &ranks(14, &decl, &[])).unwrap();
    // Positions x1, x2 and velocities vx1, vx2 stay (y's are declared later).
    assert_eq!(sel.states, vec![0, 2, 4, 6]);
}

/// A crank whose tip is held in place, with its orientation as an implicit slot: slots
/// phi 0, w 1, der(w) 2, the orientation entry T 3 (implicit, its derivative contains
/// the frame's angular velocity wf 4), the tip position x 5 and the constraint force
/// lam 6. Equations: T = f(phi) (a definition), wf = w (the joint's propagation of
/// angular velocity), x = h(T), 0 = x - c, der(w) = F(phi, w, lam).
fn held_crank() -> crate::structure::pantelides::IndexReduction {
    use crate::structure::pantelides::pantelides_with_implicit;
    let mut g = BipartiteGraph::new(7);
    g.add_equation(vec![0, 3]);
    g.add_equation(vec![1, 4]);
    g.add_equation(vec![3, 5]);
    g.add_equation(vec![5]);
    g.add_equation(vec![0, 1, 2, 6]);
    let var_diff = [Some(1), Some(2), None, None, None, None, None];
    let implicit = vec![vec![], vec![], vec![], vec![3, 4], vec![], vec![], vec![]];
    let definitions = [true, false, false, false, false];
    pantelides_with_implicit(&g, &var_diff, &implicit, &definitions).unwrap()
}

#[test]
fn a_constraint_reaches_the_joint_speed_only_through_the_angular_velocity() {
    let red = held_crank();
    let n = red.var_diff.len();
    let rank = ranks(n, &[], &[(0, 3.0), (1, 3.0)]);
    // Seen directly, the velocity-level constraint contains wf and der(x), not w: no
    // selection demotes the crank's angle, which the constraint fixes.
    assert!(matches!(
        dummy_derivatives(&red, 5, &rank),
        Err(SelectionError::Singular { .. })
    ));
    // With wf marked as an intermediate, its propagation equation (differentiated one
    // time less) joins the level: w and der(w) become dummies, nothing is a state.
    let mut marked = vec![false; n];
    marked[4] = true;
    let sel = dummy_derivatives_with_intermediates(&red, 5, &rank, &marked).unwrap();
    assert!(sel.states.is_empty(), "{:?}", sel.states);
    assert!(sel.dummy[1] && sel.dummy[2]);
}
