//! Where a linear algebraic loop is solved: torn and solved by a dense LU inside the
//! compiled functions (the default), handed to IDA as algebraic unknowns, or solved
//! inside by a sparse LU; in every case the solution must be the analytic one.

use crate::model::{System, Variable};
use crate::solve::{DaeProblem, SolverOptions};

use super::*;
use crate::codegen::Stmt;

const R1: f64 = 1.0;
const R2: f64 = 2.0;
const R3: f64 = 3.0;
const C: f64 = 0.5;

/// A capacitor (voltage `x`, `x(0) = 1`) discharging through `R1` into `R2 || R3`:
///
/// ```text
///   R1 i1 + vm = x          (source branch)
///   vm = R2 (i1 - i2)       (shunt)
///   vm = R3 i2              (load)
///   C der(x) = -i1
/// ```
///
/// The first three equations form one linear block of three unknowns (`i1`, `i2`,
/// `vm`) that tearing reduces to one tearing variable (`vm`: `i1` from the first, `i2`
/// from the third, the second a residual). Analytic solution: with
/// `Req = R1 + R2 R3 / (R2 + R3)`, `i1 = x / Req`, `vm = x - R1 i1`, `i2 = vm / R3`,
/// `x(t) = exp(-t / (C Req))`.
fn network(name: &str) -> System {
    let mut s = System::new(name);
    let x = s.variable(Variable::new("x").start(1.0).fixed(true));
    let i1 = s.var("i1");
    let i2 = s.var("i2");
    let vm = s.var("vm");
    let r1 = s.param("R1", R1);
    let r2 = s.param("R2", R2);
    let r3 = s.param("R3", R3);
    let c = s.param("C", C);
    s.equation(r1 * i1 + vm, x);
    s.equation(vm, r2 * (i1 - i2));
    s.equation(vm, r3 * i2);
    s.equation(c * x.der(), -i1);
    s
}

const REQ: f64 = R1 + R2 * R3 / (R2 + R3);

/// `(i1, i2, vm)` for a capacitor voltage `x`.
fn analytic_loop(x: f64) -> (f64, f64, f64) {
    let i1 = x / REQ;
    let vm = x - R1 * i1;
    (i1, vm / R3, vm)
}

/// Simplifies the network with `limits`, solves it on `[0, 2]`, and checks the loop
/// against the analytic solution at every output (and the state against `exp`).
fn solve_and_check(ssys: &SimplifiedSystem) {
    // The analytic solution also satisfies the three loop equations as written.
    let (i1, i2, vm) = analytic_loop(0.7);
    assert!((R1 * i1 + vm - 0.7).abs() < 1e-15);
    assert!((vm - R2 * (i1 - i2)).abs() < 1e-15);
    assert!((vm - R3 * i2).abs() < 1e-15);

    let prob = DaeProblem::new(ssys, &[], (0.0, 2.0)).unwrap();
    let opts = SolverOptions {
        rtol: 1e-10,
        atol: 1e-12,
        ..SolverOptions::default()
    }
    .with_output_interval(0.0, 2.0, 0.25);
    let sol = prob.solve(&opts).unwrap();
    let s = sol.get_many(&["x", "i1", "i2", "vm", "der(x)"]).unwrap();
    assert!(sol.t().len() >= 9, "{:?}", sol.t());
    for (k, &t) in sol.t().iter().enumerate() {
        let x = s[0][k];
        let exact_x = (-t / (C * REQ)).exp();
        assert!((x - exact_x).abs() < 1e-7, "x({t}) = {x}, exact {exact_x}");
        let (i1, i2, vm) = analytic_loop(x);
        for (name, got, want) in [
            ("i1", s[1][k], i1),
            ("i2", s[2][k], i2),
            ("vm", s[3][k], vm),
        ] {
            assert!(
                (got - want).abs() < 1e-9,
                "{name}({t}) = {got}, analytic {want} (x = {x})"
            );
        }
        assert!(
            (s[4][k] + i1 / C).abs() < 1e-9,
            "der(x)({t}) = {}, analytic {}",
            s[4][k],
            -i1 / C
        );
    }
}

fn simplify(name: &str, limits: LinearBlockLimits) -> SimplifiedSystem {
    structural_simplify_with(
        &network(name),
        &SimplifyOptions {
            linear_blocks: limits,
            ..SimplifyOptions::default()
        },
    )
    .unwrap()
}

fn loop_targets(ssys: &SimplifiedSystem) -> Vec<String> {
    let mut out = Vec::new();
    for step in &ssys.sorted.schedule.steps {
        if let Stmt::LinearSolve { targets, .. } | Stmt::SparseLinearSolve { targets, .. } = step {
            out.extend(targets.iter().map(|&t| ssys.leaf_name(t)));
        }
    }
    out
}

#[test]
fn default_limits_solve_the_loop_inside_the_residual() {
    let ssys = simplify("lin_default", LinearBlockLimits::default());
    let st = ssys.statistics();
    assert_eq!(st.alias_variables, 0, "{st}");
    assert_eq!(st.states, 1, "{st}");
    // The block of 3, torn down to 1 tearing variable, dense LU inside.
    assert_eq!(st.linear_inline, vec![(3, 1)], "{st}");
    assert!(st.linear_solver.is_empty(), "{st}");
    assert!(st.linear_sparse.is_empty(), "{st}");
    assert_eq!(st.algebraic, 0, "{st}");
    assert_eq!(ssys.unknowns(), vec!["x"]);
    assert_eq!(ssys.mass_matrix_diagonal(), &[1.0]);
    // One dense solve for the single tearing variable.
    let dense: Vec<usize> = ssys
        .sorted
        .schedule
        .steps
        .iter()
        .filter_map(|s| match s {
            Stmt::LinearSolve { targets, a, c } => {
                assert_eq!((a.len(), c.len()), (targets.len().pow(2), targets.len()));
                Some(targets.len())
            }
            _ => None,
        })
        .collect();
    assert_eq!(dense, vec![1]);
    assert_eq!(loop_targets(&ssys), vec!["vm"]);
    solve_and_check(&ssys);
}

#[test]
fn block_above_the_size_limit_goes_to_ida_without_sparse_inline() {
    let ssys = simplify(
        "lin_ida_size",
        LinearBlockLimits {
            max_inline_size: 2,
            sparse_inline: false,
            ..LinearBlockLimits::default()
        },
    );
    check_ida_form(&ssys);
}

#[test]
fn block_above_the_tearing_limit_goes_to_ida_without_sparse_inline() {
    let ssys = simplify(
        "lin_ida_tearing",
        LinearBlockLimits {
            max_inline_tearing: 0,
            sparse_inline: false,
            ..LinearBlockLimits::default()
        },
    );
    check_ida_form(&ssys);
}

/// The three loop unknowns are algebraic unknowns of the DAE (mass 0) after the
/// position-level states (none) and before the velocity-level state `x` (mass 1).
fn check_ida_form(ssys: &SimplifiedSystem) {
    let st = ssys.statistics();
    assert_eq!(st.linear_solver, vec![3], "{st}");
    assert!(st.linear_inline.is_empty(), "{st}");
    assert!(st.linear_sparse.is_empty(), "{st}");
    assert_eq!(st.algebraic, 3, "{st}");
    assert_eq!(st.states, 1, "{st}");
    let unknowns = ssys.unknowns();
    assert_eq!(unknowns.len(), 4, "{unknowns:?}");
    assert_eq!(unknowns[3], "x");
    let mut loop_vars = unknowns[..3].to_vec();
    loop_vars.sort();
    assert_eq!(loop_vars, vec!["i1", "i2", "vm"]);
    assert_eq!(ssys.mass_matrix_diagonal(), &[0.0, 0.0, 0.0, 1.0]);
    assert!(loop_targets(ssys).is_empty());
    // Consistent initialization solves the loop: u0 agrees with the analytic values.
    let prob = DaeProblem::new(ssys, &[], (0.0, 1.0)).unwrap();
    let u0 = prob.initial_unknowns();
    let (i1, i2, vm) = analytic_loop(1.0);
    for (k, name) in unknowns.iter().enumerate().take(3) {
        let want = match name.as_str() {
            "i1" => i1,
            "i2" => i2,
            _ => vm,
        };
        assert!(
            (u0[k] - want).abs() < 1e-9,
            "{name}(0) = {}, analytic {want}",
            u0[k]
        );
    }
    assert_eq!(u0[3], 1.0);
    solve_and_check(ssys);
}

#[test]
fn block_above_the_limits_is_solved_by_sparse_lu_inside() {
    let ssys = simplify(
        "lin_sparse",
        LinearBlockLimits {
            max_inline_size: 2,
            sparse_inline: true,
            pre_elimination_fill: None,
            ..LinearBlockLimits::default()
        },
    );
    let st = ssys.statistics();
    assert_eq!(st.linear_sparse, vec![(3, 3)], "{st}");
    assert!(st.linear_inline.is_empty(), "{st}");
    assert!(st.linear_solver.is_empty(), "{st}");
    assert_eq!(st.algebraic, 0, "{st}");
    assert_eq!(ssys.unknowns(), vec!["x"]);
    assert_eq!(ssys.mass_matrix_diagonal(), &[1.0]);
    // One sparse solve of the whole block: the structural non-zeros of the 3x3 matrix
    // are the 2 + 3 + 2 incidences of the three equations.
    let sparse: Vec<(usize, usize)> = ssys
        .sorted
        .schedule
        .steps
        .iter()
        .filter_map(|s| match s {
            Stmt::SparseLinearSolve {
                targets, entries, ..
            } => Some((targets.len(), entries.len())),
            _ => None,
        })
        .collect();
    assert_eq!(sparse, vec![(3, 7)]);
    let mut targets = loop_targets(&ssys);
    targets.sort();
    assert_eq!(targets, vec!["i1", "i2", "vm"]);
    solve_and_check(&ssys);
}

/// With symbolic pre-elimination (the default) the three coefficients are parameters
/// that are nonzero for their defaults: `i1` goes from the source branch and `i2` from
/// the load (original coefficients `R1` and `R3`). That leaves `vm` alone in the shunt
/// equation with the coefficient `1 + R2/R1 + R2/R3`, which elimination made: a sum of
/// parameters that could vanish for other values, so it is no pivot and the LU solves
/// this one unknown at run time.
#[test]
fn pre_elimination_leaves_one_unknown_for_the_lu() {
    let ssys = simplify(
        "lin_pre",
        LinearBlockLimits {
            max_inline_size: 2,
            sparse_inline: true,
            ..LinearBlockLimits::default()
        },
    );
    let st = ssys.statistics();
    assert_eq!(st.linear_sparse, vec![(3, 1)], "{st}");
    assert!(
        st.to_string()
            .contains("sparse LU: sizes {3} before and {1} after pre-elimination"),
        "{st}"
    );
    let solved: Vec<usize> = ssys
        .sorted
        .schedule
        .steps
        .iter()
        .filter_map(|s| match s {
            Stmt::SparseLinearSolve { targets, .. } => Some(targets.len()),
            _ => None,
        })
        .collect();
    assert_eq!(solved, vec![1], "{:?}", ssys.sorted.schedule.steps);
    assert_eq!(ssys.unknowns(), vec!["x"]);
    solve_and_check(&ssys);
}

/// Tearing leaves one variable (`vm`) and two assignments: two sensitivities. With a
/// budget below that the block goes to the sparse path (where pre-elimination leaves
/// one unknown to the LU); with the default it is torn and solved densely.
#[test]
fn sensitivity_budget_decides_between_dense_and_sparse() {
    let dense = simplify("lin_budget_dense", LinearBlockLimits::default());
    assert_eq!(dense.statistics().linear_inline, vec![(3, 1)]);
    let sparse = simplify(
        "lin_budget_sparse",
        LinearBlockLimits {
            max_inline_sensitivities: 1,
            ..LinearBlockLimits::default()
        },
    );
    let st = sparse.statistics();
    assert!(st.linear_inline.is_empty(), "{st}");
    assert_eq!(st.linear_sparse, vec![(3, 1)], "{st}");
    solve_and_check(&sparse);
}
