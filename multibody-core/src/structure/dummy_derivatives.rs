//! Static state selection by dummy derivatives (Mattsson and Soederlind, 1993).
//!
//! After index reduction every differentiated equation removes one degree of freedom
//! from the derivative chains it touches. Level by level, from the highest
//! differentiated equations down, as many derivative slots as there are equations are
//! chosen (a structurally nonsingular selection) to become *dummy derivatives*: plain
//! algebraic unknowns. A slot whose derivative slot is not a dummy is a state.
//!
//! The choice honours preferences: candidates are tried in order of the state priority
//! of the slot that would lose its state status (lowest first), then declaration rank
//! (latest first), and a candidate is kept when the selection stays matchable: the greedy
//! algorithm on the transversal matroid, so the states kept have the best priorities
//! that any valid selection allows.

use super::pantelides::IndexReduction;

/// Ranking of one slot as a state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StateRank {
    /// Preference for staying a state (higher stays); [`ALWAYS`] and above must stay.
    pub priority: f64,
    /// Declaration order of the variable behind the slot (later ones are dropped first).
    pub declaration: usize,
}

/// Priority from which a state is a hard requirement (Modelica's `StateSelect.always`).
pub const ALWAYS: f64 = 1000.0;

/// One level of the selection (for reports and tests).
#[derive(Clone, Debug, PartialEq)]
pub struct SelectionLevel {
    /// Equations of this level.
    pub equations: Vec<usize>,
    /// Derivative slots that could be made dummies.
    pub candidates: Vec<usize>,
    /// The slots made dummies, one per equation.
    pub dummies: Vec<usize>,
}

/// The result of state selection.
#[derive(Clone, Debug, PartialEq)]
pub struct StateSelection {
    /// Per slot: whether it is a dummy derivative (an algebraic unknown).
    pub dummy: Vec<bool>,
    /// Slots that are states (their derivative slot exists and is not a dummy),
    /// ascending.
    pub states: Vec<usize>,
    /// The levels, highest derivatives first.
    pub levels: Vec<SelectionLevel>,
}

/// Why no valid selection exists.
#[derive(Clone, Debug, PartialEq)]
pub enum SelectionError {
    /// A level's equations cannot be matched to its candidates.
    Singular {
        /// The level's equations.
        equations: Vec<usize>,
        /// Its candidates.
        candidates: Vec<usize>,
    },
    /// Slots marked `always` that must lose their state status.
    AlwaysViolated(Vec<usize>),
}

/// Selects dummy derivatives for an index reduction of a system whose first
/// `n_original` equations are the original ones. `rank[v]` ranks slot `v` as a state.
pub fn dummy_derivatives(
    red: &IndexReduction,
    n_original: usize,
    rank: &[StateRank],
) -> Result<StateSelection, SelectionError> {
    dummy_derivatives_with_intermediates(red, n_original, rank, &[])
}

/// [`dummy_derivatives`] for systems with implicit derivatives: `intermediates[v]` marks
/// the slots that implicit derivatives contain (the angular velocities in the
/// derivative of an orientation matrix). They are derivatives of nothing, so a level's
/// equations that contain them reach the candidates only through the equations that
/// determine them (the joints' propagation of angular velocity, differentiated one time
/// less than the level's equations): where the plain selection fails, those equations
/// and intermediates join the level's matching.
pub fn dummy_derivatives_with_intermediates(
    red: &IndexReduction,
    n_original: usize,
    rank: &[StateRank],
    intermediates: &[bool],
) -> Result<StateSelection, SelectionError> {
    dummy_derivatives_with_definitions(red, n_original, rank, intermediates, &[])
}

/// [`dummy_derivatives_with_intermediates`] knowing which original equations define an
/// intermediate (`defines[e]`, a joint's propagation of angular velocity): where the
/// companions of a level would include other equations that merely contain
/// intermediates (a wheel's rolling constraint, which has no counterpart a level
/// lower), the selection is tried again with the defining ones alone.
pub fn dummy_derivatives_with_definitions(
    red: &IndexReduction,
    n_original: usize,
    rank: &[StateRank],
    intermediates: &[bool],
    defines: &[bool],
) -> Result<StateSelection, SelectionError> {
    let context = Context {
        intermediates,
        defines,
    };
    match select_levels(red, n_original, rank, &context, false) {
        Err(first @ SelectionError::Singular { .. }) => {
            // A dummy whose antiderivative is no derivative (an angular acceleration,
            // the derivative of an intermediate) leaves the next level without the
            // candidate it needs: try again with the derivatives of derivatives first
            // on the levels above the last.
            select_levels(red, n_original, rank, &context, true).map_err(|_| first)
        }
        other => other,
    }
}

/// What the companions of a level are made of.
struct Context<'a> {
    /// Per slot: whether it is an intermediate.
    intermediates: &'a [bool],
    /// Per original equation: whether it defines an intermediate (empty: unknown).
    defines: &'a [bool],
}

/// The selection of [`dummy_derivatives_with_intermediates`]; with `prefer_chains`, the
/// candidates whose antiderivatives are derivatives themselves go first on every level
/// but the last.
fn select_levels(
    red: &IndexReduction,
    n_original: usize,
    rank: &[StateRank],
    context: &Context<'_>,
    prefer_chains: bool,
) -> Result<StateSelection, SelectionError> {
    let n_slots = red.var_diff.len();
    let anti = red.antiderivative_var();
    let counts = red.differentiation_counts(n_original);
    let max_level = counts.iter().copied().max().unwrap_or(0);
    let var_eqs_of = |e: usize| &red.graph.eq_vars[e];
    let mut dummy = vec![false; n_slots];
    let mut levels = Vec::new();
    let mut previous: Vec<usize> = Vec::new();
    let mut violated = Vec::new();

    for level in 1..=max_level {
        // Equations differentiated at least `level` times, taken `counts - level + 1`
        // times differentiated.
        let mut equations = Vec::new();
        for (e, &m) in counts.iter().enumerate() {
            if m >= level {
                let mut cur = e;
                for _ in 0..(m - level + 1) {
                    cur = red.eq_diff[cur].expect("counted derivative");
                }
                equations.push(cur);
            }
        }
        let mut candidates: Vec<usize> = if level == 1 {
            let mut c: Vec<usize> = equations
                .iter()
                .flat_map(|&e| var_eqs_of(e).iter().copied())
                .filter(|&v| red.var_diff[v].is_none() && anti[v].is_some())
                .collect();
            c.sort_unstable();
            c.dedup();
            c
        } else {
            let mut c: Vec<usize> = previous
                .iter()
                .filter_map(|&v| anti[v])
                .filter(|&a| anti[a].is_some())
                .collect();
            c.sort_unstable();
            c.dedup();
            c
        };
        // Greedy on the transversal matroid: lowest priority of the antiderivative
        // first, then the lowest priority found further down its chain (so a preferred
        // position keeps its velocity too), then the latest declared.
        let key = |v: usize| {
            let a = anti[v].expect("candidates are derivatives");
            let mut chain = rank[a].priority;
            let mut b = a;
            while let Some(c) = anti[b] {
                chain = chain.max(rank[c].priority);
                b = c;
            }
            (rank[a].priority, chain, rank[a].declaration)
        };
        // Each key computed once (it walks a derivative chain and reads the ranks,
        // scattered in a large model), then sorted with its candidate.
        let mut keyed: Vec<((f64, f64, usize), usize)> =
            candidates.iter().map(|&v| (key(v), v)).collect();
        // With `prefer_chains`, a candidate that can pass its status down a level.
        let chained = |v: usize| {
            !prefer_chains || level == max_level || anti[v].and_then(|a| anti[a]).is_some()
        };
        keyed.sort_by(|&(kx, x), &(ky, y)| {
            chained(y)
                .cmp(&chained(x))
                .then(kx.0.total_cmp(&ky.0))
                .then(kx.1.total_cmp(&ky.1))
                .then(ky.2.cmp(&kx.2))
                .then(y.cmp(&x))
        });
        candidates.clear();
        candidates.extend(keyed.iter().map(|&(_, v)| v));
        let mut selected = select(&equations, &candidates, |e| var_eqs_of(e));
        if selected.len() < equations.len() && level >= 2 {
            // The level's equations may reach their candidates only through
            // intermediate unknowns of the same order that equations outside the level
            // determine (a frame's angular velocity, propagated from the joints' speeds,
            // is what the derivative of a loop's position constraint contains).
            let companions = |defines: &[bool]| {
                select_with_companions(
                    red,
                    &anti,
                    (&counts, defines),
                    level,
                    &equations,
                    &candidates,
                    context.intermediates,
                )
            };
            let alternative = companions(&[]).or_else(|| {
                (!context.defines.is_empty())
                    .then(|| companions(context.defines))
                    .flatten()
            });
            if let Some(alternative) = alternative {
                selected = alternative;
            }
        }
        if selected.len() < equations.len() {
            return Err(SelectionError::Singular {
                equations,
                candidates,
            });
        }
        for &v in &selected {
            dummy[v] = true;
            let a = anti[v].expect("candidate");
            if rank[a].priority >= ALWAYS {
                violated.push(a);
            }
        }
        let mut dummies = selected.clone();
        dummies.sort_unstable();
        levels.push(SelectionLevel {
            equations,
            candidates,
            dummies,
        });
        previous = selected;
    }
    if !violated.is_empty() {
        violated.sort_unstable();
        violated.dedup();
        return Err(SelectionError::AlwaysViolated(violated));
    }
    let states = (0..n_slots)
        .filter(|&v| red.var_diff[v].is_some_and(|d| !dummy[d]))
        .collect();
    Ok(StateSelection {
        dummy,
        states,
        levels,
    })
}

/// The selection of a level (`level >= 2`) seen through intermediates: the marked
/// slots its equations contain, together with the *companions*, the equations
/// differentiated exactly `level - 1` times that contain them (taken undifferentiated:
/// they are of the level's order), closed transitively. Intermediates are matched
/// first, then candidates in order; the selection holds when every equation is matched
/// and the candidates kept are as many as the level's equations.
fn select_with_companions(
    red: &IndexReduction,
    anti: &[Option<usize>],
    (counts, defines): (&[usize], &[bool]),
    level: usize,
    equations: &[usize],
    candidates: &[usize],
    marked: &[bool],
) -> Option<Vec<usize>> {
    use crate::hash::HashSet;
    let is_candidate: HashSet<usize> = candidates.iter().copied().collect();
    // An angular velocity that alias elimination merged with a joint's speed is a
    // derivative (of the joint angle): not an intermediate.
    let is_intermediate = |v: usize| {
        !is_candidate.contains(&v) && marked.get(v).copied().unwrap_or(false) && anti[v].is_none()
    };
    // (With `defines`, only the equations that define an intermediate.)
    let companions_pool: Vec<usize> = (0..counts.len())
        .filter(|&e| counts[e] == level - 1 && defines.get(e).copied().unwrap_or(true))
        .collect();
    let mut rows: Vec<usize> = equations.to_vec();
    let mut intermediates: HashSet<usize> = HashSet::default();
    let mut in_rows: HashSet<usize> = rows.iter().copied().collect();
    loop {
        let before = (rows.len(), intermediates.len());
        for &e in &rows {
            for &v in &red.graph.eq_vars[e] {
                if is_intermediate(v) {
                    intermediates.insert(v);
                }
            }
        }
        for &e in &companions_pool {
            if !in_rows.contains(&e)
                && red.graph.eq_vars[e]
                    .iter()
                    .any(|v| intermediates.contains(v))
            {
                in_rows.insert(e);
                rows.push(e);
            }
        }
        if (rows.len(), intermediates.len()) == before {
            break;
        }
    }
    if intermediates.is_empty() {
        return None;
    }
    let mut columns: Vec<usize> = intermediates.iter().copied().collect();
    columns.sort_unstable();
    let n_intermediate = columns.len();
    columns.extend_from_slice(candidates);
    let kept = select(&rows, &columns, |e| &red.graph.eq_vars[e]);
    let chosen: Vec<usize> = kept
        .into_iter()
        .filter(|v| is_candidate.contains(v))
        .collect();
    let matched_intermediates = rows.len() - chosen.len();
    (chosen.len() == equations.len() && matched_intermediates <= n_intermediate).then_some(chosen)
}

/// Greedy matroid selection: each candidate in order is kept when an augmenting path
/// from it reaches an unmatched equation of `equations`. Returns the kept candidates.
fn select<'a>(
    equations: &[usize],
    candidates: &[usize],
    vars_of: impl Fn(usize) -> &'a [usize],
) -> Vec<usize> {
    use std::collections::VecDeque;

    // Candidate of each slot (dense: a large model's selection reads it in order).
    let n_slots = candidates.iter().max().map_or(0, |&v| v + 1);
    let mut cand_index = vec![usize::MAX; n_slots];
    for (i, &v) in candidates.iter().enumerate() {
        cand_index[v] = i;
    }
    let candidate_of = |v: usize| cand_index.get(v).copied().filter(|&c| c != usize::MAX);
    // Candidate -> local equations containing it, in increasing order.
    let cand_eqs = super::Rows::grouped(candidates.len(), || {
        equations.iter().enumerate().flat_map(|(le, &e)| {
            vars_of(e)
                .iter()
                .filter_map(move |&v| candidate_of(v).map(|c| (c, le)))
        })
    });
    let mut eq_match: Vec<Option<usize>> = vec![None; equations.len()];
    let mut cand_match: Vec<Option<usize>> = vec![None; candidates.len()];
    let mut parent: Vec<usize> = vec![0; equations.len()];
    let mut visited: Vec<bool> = vec![false; equations.len()];
    let mut touched: Vec<usize> = Vec::new();
    let mut kept = Vec::new();
    let mut queue = VecDeque::new();
    for c in 0..candidates.len() {
        if kept.len() == equations.len() {
            break;
        }
        // Reset only what the last search visited (a full fill is quadratic).
        for &le in &touched {
            visited[le] = false;
        }
        touched.clear();
        queue.clear();
        queue.push_back(c);
        let mut found = None;
        'bfs: while let Some(x) = queue.pop_front() {
            for &le in &cand_eqs[x] {
                if visited[le] {
                    continue;
                }
                visited[le] = true;
                touched.push(le);
                parent[le] = x;
                match eq_match[le] {
                    None => {
                        found = Some(le);
                        break 'bfs;
                    }
                    Some(y) => queue.push_back(y),
                }
            }
        }
        let Some(mut le) = found else { continue };
        loop {
            let x = parent[le];
            let old = cand_match[x];
            cand_match[x] = Some(le);
            eq_match[le] = Some(x);
            if x == c {
                break;
            }
            le = old.expect("an inner candidate of the path is matched");
        }
        kept.push(candidates[c]);
    }
    kept
}

#[cfg(test)]
#[path = "dummy_derivatives_tests.rs"]
mod tests;
