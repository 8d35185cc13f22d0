//! Causalization: which equation computes which unknown, in which order.
//!
//! The equations are matched to the unknowns and sorted into blocks (BLT). A block of
//! one equation that is linear in its unknown becomes an assignment; a nonlinear one an
//! iteration variable. A larger block is torn: equations linear in a variable with a
//! coefficient that cannot vanish become assignments, the rest residuals. A linear block
//! is then solved inside the compiled functions: its torn system by a dense LU when
//! tearing leaves few variables, otherwise the whole block by a sparse LU (the
//! acceleration block of a multibody chain: linear cost in its length). A nonlinear
//! block leaves its tearing variables to the solver.

use crate::hash::{HashMap, HashSet};

use crate::codegen::Stmt;
use crate::expr::{Arena, Id, IdIndex, LinearSolve, Node};
use crate::structure::BipartiteGraph;
use crate::structure::blt::blt_flat;
use crate::structure::dm::dulmage_mendelsohn;
use crate::structure::matching::maximum_matching;
use crate::structure::tearing::{TearingEquation, tear_with_priority};

use super::pre_eliminate::{LinearRow, PreEliminated, back_substitution, pre_eliminate};

/// Limits deciding where linear blocks are solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LinearBlockLimits {
    /// A linear block with more equations than this is not torn for a dense solve
    /// (default 400).
    pub max_inline_size: usize,
    /// A linear block whose tearing leaves more iteration variables than this is not
    /// solved by a dense LU (its cost grows with their cube; default 24).
    pub max_inline_tearing: usize,
    /// With `sparse_inline`, a torn linear block is solved densely only while its
    /// tearing variables times its assigned unknowns (the sensitivities the dense form
    /// computes) stay at most this (default 2000: a 20-link pendulum torn to 20
    /// variables of 229 is solved faster by the sparse LU).
    pub max_inline_sensitivities: usize,
    /// Linear blocks beyond the limits above are solved inside the compiled
    /// functions by a sparse LU of the whole block (`true`, the default), or left to the
    /// solver as algebraic unknowns of the DAE (`false`). Solving inside keeps IDA's
    /// Newton iteration on the states only: on a 20-link pendulum it needed 40 % fewer
    /// iterations and a third of the Jacobians of the DAE form.
    pub sparse_inline: bool,
    /// Before a block goes to the sparse LU, its unknowns with coefficients that cannot
    /// vanish are eliminated symbolically where that adds at most this many entries
    /// (Markowitz cost); `None` keeps the whole block for the LU (default `Some(8)`).
    pub pre_elimination_fill: Option<usize>,
}

impl Default for LinearBlockLimits {
    fn default() -> Self {
        LinearBlockLimits {
            max_inline_size: 400,
            max_inline_tearing: 24,
            max_inline_sensitivities: 2000,
            sparse_inline: true,
            pre_elimination_fill: Some(8),
        }
    }
}

/// How a block is solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlockKind {
    /// One equation, solved explicitly.
    Explicit,
    /// Linear, solved inside the compiled functions (torn, dense LU).
    LinearInline,
    /// Linear, solved inside the compiled functions by a sparse LU.
    LinearSparse,
    /// Linear, left to the solver (all its unknowns are iteration variables).
    LinearSolver,
    /// Nonlinear; its tearing variables are iteration variables.
    Nonlinear,
}

/// Statistics of one block of size > 1 (or a nonlinear scalar).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BlockInfo {
    /// How it is solved.
    pub kind: BlockKind,
    /// Number of equations (and unknowns).
    pub size: usize,
    /// Number of tearing variables.
    pub torn: usize,
}

/// The result of causalization.
#[derive(Clone, Debug, Default)]
pub struct Schedule {
    /// Steps in execution order.
    pub steps: Vec<Stmt>,
    /// Unknown leaves that are inputs to the steps (iteration variables).
    pub iteration: Vec<Id>,
    /// Residual expressions (as many as iteration variables) with their equation.
    pub residuals: Vec<(Id, usize)>,
    /// The blocks that are not plain assignments.
    pub blocks: Vec<BlockInfo>,
    /// Per equation: the unknown its scalar block solved it for and how, when it is
    /// linear in it (`None` for equations of larger blocks and nonlinear ones). A later
    /// causalization of the same equations in an extending arena (the initialization)
    /// reuses these instead of solving again.
    pub solved_for: Vec<Option<SolvedFor>>,
}

/// An equation solved for one unknown (see [`Schedule::solved_for`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SolvedFor {
    /// The equation's residual.
    pub residual: Id,
    /// The unknown (a leaf).
    pub unknown: Id,
    /// The solution and its coefficient, as [`Arena::solve_linear`] gave them.
    pub solve: LinearSolve,
}

/// Causalization failed: the system is structurally singular.
#[derive(Clone, Debug, PartialEq)]
pub struct Singular {
    /// Equations with nothing left to determine.
    pub over_equations: Vec<usize>,
    /// Unknowns those equations determine more than once.
    pub over_unknowns: Vec<Id>,
    /// Unknowns no equation determines.
    pub under_unknowns: Vec<Id>,
}

/// Source of fresh leaves for temporaries, and the parameter values that decide which
/// coefficients can vanish.
pub struct Temporaries<'p> {
    /// The next free variable index for a temporary leaf.
    pub next: u32,
    /// Values of the parameters (by index).
    pub params: &'p [f64],
    /// Leaves that tearing must not choose as tearing variables unless nothing else
    /// works (the entries of orientation matrices: they are computed from the joint
    /// coordinates, never iterated on).
    pub never_tear: &'p HashSet<Id>,
    /// State priority of leaves (absent: 0): among equally good tearing variables the
    /// higher one is chosen (a loop is iterated on a joint coordinate rather than on an
    /// internal vector).
    pub tear_priority: &'p HashMap<Id, f64>,
}

impl Temporaries<'_> {
    fn fresh(&mut self, arena: &mut Arena) -> Id {
        let v = arena.var(self.next);
        self.next += 1;
        v
    }
}

/// Whether `coefficient` cannot vanish: a nonzero constant, or an expression of
/// parameters only that is nonzero for the parameter values `params` (the defaults:
/// products of inertia are 0 by default, masses are not; a NaN value marks a parameter
/// that may take any value).
pub fn safe_coefficient(arena: &Arena, coefficient: Id, params: &[f64]) -> bool {
    if let Some(c) = arena.as_const(coefficient) {
        return c != 0.0 && c.is_finite();
    }
    // Parameters without a value (NaN: those that events change) make it unsafe.
    let only_params = arena.leaves(coefficient).iter().all(|&l| {
        matches!(arena.node(l), Node::Param(j) if params.get(*j as usize).is_some_and(|v| v.is_finite()))
    });
    if !only_params {
        return false;
    }
    let v = arena.eval(coefficient, &|n: &Node| match n {
        Node::Param(j) => params.get(*j as usize).copied(),
        _ => None,
    });
    matches!(v, Some(v) if v != 0.0 && v.is_finite())
}

/// Causalizes `equations` (residuals) for the `unknowns` (leaves); every other leaf is
/// known.
pub fn causalize(
    arena: &mut Arena,
    equations: &[Id],
    unknowns: &[Id],
    limits: LinearBlockLimits,
    temps: &mut Temporaries<'_>,
) -> Result<Schedule, Singular> {
    let index = IdIndex::new(unknowns);
    let g = incidence_graph(arena, equations.iter().copied(), &index, unknowns.len());
    causalize_graph(arena, equations, unknowns, &g, &[], limits, temps)
}

/// The incidence of `residuals` in the unknowns `index` numbers (`n_unknowns` of them):
/// row `e` lists the unknowns residual `e` contains, ascending. Room is left for more
/// rows (the initialization adds some).
pub(crate) fn incidence_graph(
    arena: &Arena,
    residuals: impl ExactSizeIterator<Item = Id>,
    index: &IdIndex,
    n_unknowns: usize,
) -> BipartiteGraph {
    // Room for a few unknowns per equation.
    let n = residuals.len();
    let mut g = BipartiteGraph::with_capacity(n_unknowns, n, 4 * n);
    let (mut leaves, mut vars) = (Vec::new(), Vec::new());
    for r in residuals {
        arena.leaves_into(r, &mut leaves);
        vars.clear();
        vars.extend(leaves.iter().filter_map(|&l| index.get(l)));
        g.add_equation_from(&mut vars);
    }
    g
}

/// Whether `g` is the incidence of `equations` in `unknowns` (what [`causalize`]
/// reads; checked in debug builds when a caller brings its own graph).
fn incidence_matches(arena: &Arena, equations: &[Id], unknowns: &[Id], g: &BipartiteGraph) -> bool {
    let own = incidence_graph(arena, equations.iter().copied(), &IdIndex::new(unknowns), 0);
    own.eq_vars == g.eq_vars
}

/// [`causalize`] with the incidence of `equations` in `unknowns` already built: row `e`
/// of `g` lists the unknowns (indices into `unknowns`) that equation `e` contains, as
/// [`causalize`] would find them. Initialization has that graph from completing its
/// conditions, and reading every residual again is a pass over the whole arena.
///
/// `reuse[e]` (possibly shorter than `equations`): how an earlier causalization solved
/// equation `e`, from [`Schedule::solved_for`], in this arena or the one it extends. It
/// is used when equation `e` has the same residual and is again solved for the same
/// unknown, and gives what solving again would (the arena interns every node once).
pub fn causalize_graph(
    arena: &mut Arena,
    equations: &[Id],
    unknowns: &[Id],
    g: &BipartiteGraph,
    reuse: &[Option<SolvedFor>],
    limits: LinearBlockLimits,
    temps: &mut Temporaries<'_>,
) -> Result<Schedule, Singular> {
    debug_assert_eq!(g.n_vars, unknowns.len());
    debug_assert!(
        incidence_matches(arena, equations, unknowns, g),
        "the incidence given to causalize_graph is not the residuals'"
    );
    let m = maximum_matching(g, None, None);
    if !m.is_perfect() || equations.len() != unknowns.len() {
        let dm = dulmage_mendelsohn(g, &m, None);
        let mut over = dm.over_eqs.clone();
        if over.is_empty() {
            over = dm.unmatched_eqs.clone();
        }
        return Err(Singular {
            over_equations: over,
            over_unknowns: dm.over_vars.iter().map(|&v| unknowns[v]).collect(),
            under_unknowns: dm.under_vars.iter().map(|&v| unknowns[v]).collect(),
        });
    }
    // Mostly one step per equation (a scalar block each); sized once, as the steps of a
    // large model otherwise grow by copying through several doublings.
    let mut out = Schedule {
        steps: Vec::with_capacity(equations.len()),
        solved_for: vec![None; equations.len()],
        ..Schedule::default()
    };
    for block in blt_flat(g, &m).iter() {
        let (eqs, vars) = (block.eqs, block.vars);
        if eqs.len() == 1 {
            let (e, x) = (eqs[0], unknowns[vars[0]]);
            let known = reuse.get(e).copied().flatten();
            scalar_block(arena, equations[e], e, x, known, temps.params, &mut out);
        } else {
            let block_eqs: Vec<Id> = eqs.iter().map(|&e| equations[e]).collect();
            let block_vars: Vec<Id> = vars.iter().map(|&v| unknowns[v]).collect();
            solve_block(arena, &block_eqs, eqs, &block_vars, limits, temps, &mut out);
        }
    }
    super::reroot::reroot_iteration_variables(arena, &mut out, temps.tear_priority, temps.params);
    Ok(out)
}

/// Equation `e` (residual `r`) alone determines `x`. `known`: how an earlier
/// causalization solved it, taken when it is for the same residual and unknown; the
/// solution (when `r` is linear in `x`) is recorded in `out.solved_for`.
fn scalar_block(
    arena: &mut Arena,
    r: Id,
    e: usize,
    x: Id,
    known: Option<SolvedFor>,
    params: &[f64],
    out: &mut Schedule,
) {
    let solved = match known {
        Some(k) if k.residual == r && k.unknown == x => Some(k.solve),
        _ => arena.solve_linear(r, x),
    };
    if let Some(solve) = solved {
        out.solved_for[e] = Some(SolvedFor {
            residual: r,
            unknown: x,
            solve,
        });
    }
    match solved {
        Some(sol) if safe_coefficient(arena, sol.coefficient, params) => {
            out.steps.push(Stmt::Assign {
                target: x,
                expr: sol.solution,
                equation: e,
            });
        }
        Some(sol) => {
            let mut map = HashMap::default();
            map.insert(x, arena.zero());
            let c = arena.substitute_leaves(r, &map);
            out.steps.push(Stmt::LinearSolve {
                targets: vec![x],
                a: vec![sol.coefficient],
                c: vec![c],
            });
            out.blocks.push(BlockInfo {
                kind: BlockKind::LinearInline,
                size: 1,
                torn: 1,
            });
        }
        None => {
            out.iteration.push(x);
            out.residuals.push((r, e));
            out.blocks.push(BlockInfo {
                kind: BlockKind::Nonlinear,
                size: 1,
                torn: 1,
            });
        }
    }
}

fn solve_block(
    arena: &mut Arena,
    block_eqs: &[Id],
    eq_ids: &[usize],
    vars: &[Id],
    limits: LinearBlockLimits,
    temps: &mut Temporaries<'_>,
    out: &mut Schedule,
) {
    let k = vars.len();
    let var_set: HashSet<Id> = vars.iter().copied().collect();
    let local: HashMap<Id, usize> = vars.iter().enumerate().map(|(i, &v)| (v, i)).collect();
    let mut linear = true;
    let mut teqs = Vec::with_capacity(k);
    // Per equation: the coefficient of each block unknown it contains (the sparse path
    // reuses them as matrix entries).
    let mut coefficients: Vec<Vec<(usize, Id)>> = Vec::with_capacity(k);
    // Equations linear in the block's unknowns (the common case) give every
    // coefficient from one walk; the others one derivative per unknown.
    let forms = arena.linear_coefficients(block_eqs, &|l| local.get(&l).copied());
    for (&r, form) in block_eqs.iter().zip(forms) {
        let mut tv = Vec::new();
        let mut row = Vec::new();
        for l in arena.leaves(r) {
            let Some(&j) = local.get(&l) else { continue };
            let (coef, depends) = match &form {
                Some(coefficients) => {
                    let coef = coefficients.iter().find(|c| c.0 == j).map(|c| c.1);
                    (coef.unwrap_or_else(|| arena.zero()), false)
                }
                None => {
                    let coef = arena.diff(r, l);
                    (coef, arena.contains_any(coef, &var_set))
                }
            };
            if depends {
                linear = false;
            }
            let solvable = !depends && safe_coefficient(arena, coef, temps.params);
            tv.push((j, solvable));
            row.push((j, coef));
        }
        teqs.push(TearingEquation { vars: tv });
        coefficients.push(row);
    }
    let tearable: Vec<bool> = vars.iter().map(|v| !temps.never_tear.contains(v)).collect();
    let priority: Vec<f64> = vars
        .iter()
        .map(|v| temps.tear_priority.get(v).copied().unwrap_or(0.0))
        .collect();
    let t = tear_with_priority(k, &teqs, Some(&tearable), Some(&priority));
    let torn: Vec<Id> = t.torn_vars.iter().map(|&j| vars[j]).collect();
    let assignments: Vec<(usize, Id)> = t.assignments.iter().map(|&(e, j)| (e, vars[j])).collect();
    if linear {
        let too_big = k > limits.max_inline_size || torn.len() > limits.max_inline_tearing;
        // Many sensitivities make the dense form slower than the sparse LU, not
        // impossible: they decide between the two inline forms only.
        let too_many_sensitivities =
            torn.len() * (k - torn.len()) > limits.max_inline_sensitivities;
        if limits.sparse_inline && (too_big || too_many_sensitivities) {
            let left = sparse_linear(
                arena,
                block_eqs,
                coefficients,
                eq_ids,
                vars,
                limits,
                temps,
                out,
            );
            out.blocks.push(BlockInfo {
                kind: BlockKind::LinearSparse,
                size: k,
                torn: left,
            });
            return;
        }
        if too_big {
            for (i, &v) in vars.iter().enumerate() {
                let _ = i;
                out.iteration.push(v);
            }
            for (i, &r) in block_eqs.iter().enumerate() {
                out.residuals.push((r, eq_ids[i]));
            }
            out.blocks.push(BlockInfo {
                kind: BlockKind::LinearSolver,
                size: k,
                torn: k,
            });
            return;
        }
        inline_linear(
            arena,
            block_eqs,
            eq_ids,
            &torn,
            &assignments,
            &t.residual_eqs,
            temps,
            out,
        );
        out.blocks.push(BlockInfo {
            kind: BlockKind::LinearInline,
            size: k,
            torn: torn.len(),
        });
        return;
    }
    for &v in &torn {
        out.iteration.push(v);
    }
    for &(e, x) in &assignments {
        let sol = arena
            .solve_linear(block_eqs[e], x)
            .expect("tearing assigns only solvable equations");
        out.steps.push(Stmt::Assign {
            target: x,
            expr: sol.solution,
            equation: eq_ids[e],
        });
    }
    for &e in &t.residual_eqs {
        out.residuals.push((block_eqs[e], eq_ids[e]));
    }
    out.blocks.push(BlockInfo {
        kind: BlockKind::Nonlinear,
        size: k,
        torn: torn.len(),
    });
}

/// A linear torn block solved inside: with the torn unknowns `t`, every assigned unknown
/// is affine in `t`, `x_a = alpha_a + sum_j beta_aj t_j`; temporaries hold `alpha` and
/// `beta`, the residuals give `A t + c = 0`, and the assignments run again with the
/// solved `t`.
#[allow(clippy::too_many_arguments)]
fn inline_linear(
    arena: &mut Arena,
    block_eqs: &[Id],
    eq_ids: &[usize],
    torn: &[Id],
    assignments: &[(usize, Id)],
    residual_eqs: &[usize],
    temps: &mut Temporaries<'_>,
    out: &mut Schedule,
) {
    let solutions: Vec<(Id, Id, usize)> = assignments
        .iter()
        .map(|&(e, x)| {
            let sol = arena
                .solve_linear(block_eqs[e], x)
                .expect("tearing assigns only solvable equations");
            (x, sol.solution, eq_ids[e])
        })
        .collect();
    let r = torn.len();
    if r == 0 {
        for &(x, f, e) in &solutions {
            out.steps.push(Stmt::Assign {
                target: x,
                expr: f,
                equation: e,
            });
        }
        return;
    }
    let zero = arena.zero();
    // alpha: the assignments at t = 0.
    let mut alpha_map: HashMap<Id, Id> = torn.iter().map(|&t| (t, zero)).collect();
    for &(x, f, _) in &solutions {
        let v = arena.substitute_leaves(f, &alpha_map);
        let a = if arena.as_const(v).is_some() {
            v
        } else {
            let tmp = temps.fresh(arena);
            out.steps.push(Stmt::Assign {
                target: tmp,
                expr: v,
                equation: usize::MAX,
            });
            tmp
        };
        alpha_map.insert(x, a);
    }
    // beta: sensitivities of each assigned unknown to each torn unknown.
    let assigned: Vec<Id> = solutions.iter().map(|s| s.0).collect();
    let partials: Vec<Vec<(usize, Id)>> = solutions
        .iter()
        .map(|&(_, f, _)| {
            let leaves: HashSet<Id> = arena.leaves(f).into_iter().collect();
            assigned
                .iter()
                .enumerate()
                .filter(|(_, x)| leaves.contains(x))
                .map(|(b, &x)| (b, arena.diff(f, x)))
                .collect()
        })
        .collect();
    let mut beta: Vec<Vec<Id>> = vec![Vec::with_capacity(solutions.len()); r];
    for (j, &tj) in torn.iter().enumerate() {
        for (a, &(_, f, _)) in solutions.iter().enumerate() {
            let mut terms = vec![(1.0, arena.diff(f, tj))];
            for &(b, p) in &partials[a] {
                let prod = arena.mul(p, beta[j][b]);
                terms.push((1.0, prod));
            }
            let v = arena.linear_combination(0.0, &terms);
            let bj = if arena.as_const(v).is_some() {
                v
            } else {
                let tmp = temps.fresh(arena);
                out.steps.push(Stmt::Assign {
                    target: tmp,
                    expr: v,
                    equation: usize::MAX,
                });
                tmp
            };
            beta[j].push(bj);
        }
    }
    // A t + c = 0 from the residual equations.
    let mut a_entries = Vec::with_capacity(r * r);
    let mut c = Vec::with_capacity(r);
    for &e in residual_eqs {
        let res = block_eqs[e];
        let leaves: HashSet<Id> = arena.leaves(res).into_iter().collect();
        let res_partials: Vec<(usize, Id)> = assigned
            .iter()
            .enumerate()
            .filter(|(_, x)| leaves.contains(x))
            .map(|(b, &x)| (b, arena.diff(res, x)))
            .collect();
        for (j, &tj) in torn.iter().enumerate() {
            let mut terms = vec![(1.0, arena.diff(res, tj))];
            for &(b, p) in &res_partials {
                let prod = arena.mul(p, beta[j][b]);
                terms.push((1.0, prod));
            }
            a_entries.push(arena.linear_combination(0.0, &terms));
        }
        c.push(arena.substitute_leaves(res, &alpha_map));
    }
    out.steps.push(Stmt::LinearSolve {
        targets: torn.to_vec(),
        a: a_entries,
        c,
    });
    for &(x, f, e) in &solutions {
        out.steps.push(Stmt::Assign {
            target: x,
            expr: f,
            equation: e,
        });
    }
}

/// A linear block solved inside by a sparse LU: `A` holds the coefficients of the
/// block's unknowns in its equations (`coefficients`, by equation), `c` the equations
/// with the unknowns set to zero. Emits the sparse LU solve of the block after symbolic
/// pre-elimination, and the back substitution of the eliminated unknowns; returns how
/// many unknowns the LU keeps.
#[allow(clippy::too_many_arguments)]
fn sparse_linear(
    arena: &mut Arena,
    block_eqs: &[Id],
    coefficients: Vec<Vec<(usize, Id)>>,
    eq_ids: &[usize],
    vars: &[Id],
    limits: LinearBlockLimits,
    temps: &mut Temporaries<'_>,
    out: &mut Schedule,
) -> usize {
    let zero = arena.zero();
    let zeros: HashMap<Id, Id> = vars.iter().map(|&v| (v, zero)).collect();
    let mut memo = HashMap::default();
    let rows: Vec<LinearRow> = block_eqs
        .iter()
        .zip(coefficients)
        .map(|(&r, mut entries)| {
            entries.retain(|&(_, a)| arena.as_const(a) != Some(0.0));
            let c = arena.substitute_leaves_memo(r, &zeros, &mut memo);
            LinearRow { entries, c }
        })
        .collect();
    let params = temps.params;
    let mut compact = |arena: &mut Arena, e: Id| -> Id {
        // A sum of more than two terms becomes a temporary computed before the solve.
        match arena.node(e) {
            Node::Sum(ts, _) if ts.len() > 2 => {
                let t = temps.fresh(arena);
                out.steps.push(Stmt::Assign {
                    target: t,
                    expr: e,
                    equation: usize::MAX,
                });
                t
            }
            _ => e,
        }
    };
    let reduced = match limits.pre_elimination_fill {
        Some(fill) => pre_eliminate(arena, rows, vars.len(), params, fill, &mut compact),
        None => PreEliminated {
            eliminations: Vec::new(),
            rows: rows.into_iter().enumerate().collect(),
            vars: (0..vars.len()).collect(),
        },
    };
    if !reduced.vars.is_empty() {
        let position: HashMap<usize, usize> = reduced
            .vars
            .iter()
            .enumerate()
            .map(|(p, &j)| (j, p))
            .collect();
        let mut entries = Vec::new();
        let mut c = Vec::with_capacity(reduced.rows.len());
        for (row, (_, r)) in reduced.rows.iter().enumerate() {
            for &(j, a) in &r.entries {
                entries.push((row, position[&j], a));
            }
            c.push(r.c);
        }
        out.steps.push(Stmt::SparseLinearSolve {
            targets: reduced.vars.iter().map(|&j| vars[j]).collect(),
            entries,
            c,
        });
    }
    for e in reduced.eliminations.iter().rev() {
        let value = back_substitution(arena, e, vars);
        out.steps.push(Stmt::Assign {
            target: vars[e.var],
            expr: value,
            equation: eq_ids[e.row],
        });
    }
    reduced.vars.len()
}
