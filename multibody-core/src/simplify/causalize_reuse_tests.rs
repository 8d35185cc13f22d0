//! A second causalization of the same equations (the initialization's) reuses how the
//! first solved each one, and only where the residual and the unknown are the same.

use crate::codegen::Stmt;
use crate::expr::{Arena, Id, LinearSolve};
use crate::hash::{HashMap, HashSet};
use crate::structure::BipartiteGraph;

use super::causalize::{
    LinearBlockLimits, Schedule, SolvedFor, Temporaries, causalize, causalize_graph,
};

/// `x + y - 3 = 0` and `2 y - p = 0` in the unknowns `x`, `y` (`p` a parameter): `y`
/// from the second equation, then `x` from the first.
struct Pair {
    arena: Arena,
    x: Id,
    y: Id,
    residuals: [Id; 2],
}

fn pair() -> Pair {
    let mut arena = Arena::new();
    let (x, y, p) = (arena.var(0), arena.var(1), arena.param(0));
    let (two, three) = (arena.constant(2.0), arena.constant(3.0));
    let xy = arena.add(x, y);
    let r0 = arena.sub(xy, three);
    let two_y = arena.mul(two, y);
    let r1 = arena.sub(two_y, p);
    Pair {
        arena,
        x,
        y,
        residuals: [r0, r1],
    }
}

/// Causalizes the pair: by `causalize` (reading the residuals) without `reuse`, by
/// `causalize_graph` with the pair's incidence and `reuse` with it.
fn schedule(s: &mut Pair, reuse: Option<&[Option<SolvedFor>]>) -> Schedule {
    let (never_tear, tear_priority) = (HashSet::default(), HashMap::default());
    let mut temps = Temporaries {
        next: 2,
        params: &[4.0],
        never_tear: &never_tear,
        tear_priority: &tear_priority,
    };
    let (unknowns, limits) = ([s.x, s.y], LinearBlockLimits::default());
    let result = match reuse {
        None => causalize(&mut s.arena, &s.residuals, &unknowns, limits, &mut temps),
        Some(reuse) => {
            let mut g = BipartiteGraph::new(2);
            g.add_equation(vec![0, 1]);
            g.add_equation(vec![1]);
            let (arena, residuals) = (&mut s.arena, &s.residuals);
            causalize_graph(arena, residuals, &unknowns, &g, reuse, limits, &mut temps)
        }
    };
    result.expect("the pair is regular")
}

/// [`schedule`] through `causalize_graph` with `reuse`.
fn with_reuse(s: &mut Pair, reuse: &[Option<SolvedFor>]) -> Schedule {
    schedule(s, Some(reuse))
}

#[test]
fn the_first_causalization_records_how_it_solved_each_equation() {
    let mut s = pair();
    let first = schedule(&mut s, None);
    let [r0, r1] = s.residuals;
    let x_from_r0 = s.arena.solve_linear(r0, s.x).unwrap();
    let y_from_r1 = s.arena.solve_linear(r1, s.y).unwrap();
    assert_eq!(
        first.solved_for,
        vec![
            Some(SolvedFor {
                residual: r0,
                unknown: s.x,
                solve: x_from_r0
            }),
            Some(SolvedFor {
                residual: r1,
                unknown: s.y,
                solve: y_from_r1
            }),
        ]
    );
    // Reusing them gives exactly the first schedule.
    let again = with_reuse(&mut s, &first.solved_for);
    assert_eq!(again.steps, first.steps);
    assert_eq!(again.solved_for, first.solved_for);
}

#[test]
fn a_recorded_solution_is_taken_only_for_the_same_residual_and_unknown() {
    let mut s = pair();
    let plain = with_reuse(&mut s, &[]);
    let ([r0, r1], x, y) = (s.residuals, s.x, s.y);
    // A made-up solution y = 7 for the second equation: taken when residual and
    // unknown match (which shows the reuse happens) ...
    let seven = s.arena.constant(7.0);
    let two = s.arena.constant(2.0);
    let made_up = LinearSolve {
        solution: seven,
        coefficient: two,
    };
    let reused = with_reuse(
        &mut s,
        &[
            None,
            Some(SolvedFor {
                residual: r1,
                unknown: y,
                solve: made_up,
            }),
        ],
    );
    assert!(reused.steps.contains(&Stmt::Assign {
        target: y,
        expr: seven,
        equation: 1
    }));
    // ... and ignored for another residual or another unknown.
    for other in [
        SolvedFor {
            residual: r0,
            unknown: y,
            solve: made_up,
        },
        SolvedFor {
            residual: r1,
            unknown: x,
            solve: made_up,
        },
    ] {
        let ignored = with_reuse(&mut s, &[None, Some(other)]);
        assert_eq!(ignored.steps, plain.steps);
    }
}
