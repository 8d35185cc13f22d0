//! Greedy tearing of one algebraic block (Cellier / Elmqvist–Otter style).
//!
//! Repeatedly: if an unassigned equation has exactly one unknown left and can be
//! solved for it, assign it (lowest equation index first); otherwise tear the
//! unknown that appears in the most unassigned equations. Counters and heaps
//! keep every step cheap, so blocks with ~10^4 equations are torn quickly.

use std::cmp::{Ordering, Reverse};
use std::collections::BinaryHeap;

/// One equation of a block: the block variables it contains, and for each whether the
/// equation can be solved for it explicitly (linear in it with a coefficient that cannot vanish).
#[derive(Clone, Debug)]
pub struct TearingEquation {
    /// `(variable, solvable)` pairs; variables are block-local indices `< n_vars`.
    pub vars: Vec<(usize, bool)>,
}

/// Result of tearing one block.
#[derive(Clone, Debug, PartialEq)]
pub struct Tearing {
    /// iteration (tearing) variables
    pub torn_vars: Vec<usize>,
    /// equations left as residuals (as many as torn_vars), indices into the block's equation list
    pub residual_eqs: Vec<usize>,
    /// (equation index, variable) solved explicitly, in evaluation order: each uses only torn
    /// vars and earlier assigned vars
    pub assignments: Vec<(usize, usize)>,
}

/// How many equally ranked tearing candidates get the (more expensive) tie-break evaluation.
const TIE_LIMIT: usize = 64;

#[derive(Clone, Copy, PartialEq, Eq)]
enum VarState {
    Unknown,
    Assigned,
    Torn,
}

/// A total order on `f64` priorities.
#[derive(Clone, Copy, PartialEq)]
struct Prio(f64);
impl Eq for Prio {}
impl PartialOrd for Prio {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Prio {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// Heap key of a tearing candidate: tearable, priority, live equation count, lowest index.
type Cand = (bool, Prio, usize, Reverse<usize>);

struct State<'a> {
    eq_vars: Vec<Vec<(usize, bool)>>,
    var_eqs: Vec<Vec<usize>>,
    status: Vec<VarState>,
    eq_done: Vec<bool>,
    /// unknown variables left in each equation, and the sum of their indices
    count: Vec<usize>,
    sum: Vec<usize>,
    /// unassigned equations containing each variable
    live: Vec<usize>,
    ready: BinaryHeap<Reverse<usize>>,
    cands: BinaryHeap<Cand>,
    tearable: Option<&'a [bool]>,
    priority: Option<&'a [f64]>,
    out: Tearing,
}

impl State<'_> {
    fn solvable(&self, e: usize, v: usize) -> bool {
        let vars = &self.eq_vars[e];
        vars.binary_search_by_key(&v, |p| p.0)
            .is_ok_and(|i| vars[i].1)
    }

    fn cand(&self, v: usize) -> Cand {
        let tearable = self
            .tearable
            .is_none_or(|t| t.get(v).copied().unwrap_or(true));
        let prio = self.priority.and_then(|p| p.get(v).copied()).unwrap_or(0.0);
        (tearable, Prio(prio), self.live[v], Reverse(v))
    }

    /// `v` stops being unknown: update the equations containing it.
    fn remove_unknown(&mut self, v: usize) {
        for i in 0..self.var_eqs[v].len() {
            let e = self.var_eqs[v][i];
            if self.eq_done[e] {
                continue;
            }
            self.count[e] -= 1;
            self.sum[e] -= v;
            if self.count[e] == 1 && self.solvable(e, self.sum[e]) {
                self.ready.push(Reverse(e));
            }
        }
    }

    fn assign(&mut self, e: usize, v: usize) {
        self.eq_done[e] = true;
        self.status[v] = VarState::Assigned;
        self.out.assignments.push((e, v));
        for i in 0..self.eq_vars[e].len() {
            let u = self.eq_vars[e][i].0;
            self.live[u] -= 1;
            if self.status[u] == VarState::Unknown {
                let c = self.cand(u);
                self.cands.push(c);
            }
        }
        self.remove_unknown(v);
    }

    fn tear_var(&mut self, v: usize) {
        self.status[v] = VarState::Torn;
        self.out.torn_vars.push(v);
        self.remove_unknown(v);
    }

    fn is_current(&self, c: &Cand) -> bool {
        let v = c.3.0;
        self.status[v] == VarState::Unknown && self.live[v] == c.2
    }

    /// Equations that tearing `v` would leave with exactly one solvable unknown.
    fn tie_score(&self, v: usize) -> usize {
        self.var_eqs[v]
            .iter()
            .filter(|&&e| !self.eq_done[e] && self.count[e] == 2)
            .filter(|&&e| self.solvable(e, self.sum[e] - v))
            .count()
    }

    /// The next tearing variable, or `None` when no unknown is left.
    fn pick_tear(&mut self) -> Option<usize> {
        let best = loop {
            let c = self.cands.pop()?;
            if self.is_current(&c) {
                break c;
            }
        };
        let mut tied = vec![best];
        while tied.len() < TIE_LIMIT {
            match self.cands.peek() {
                Some(c) if (c.0, c.1, c.2) == (best.0, best.1, best.2) => {
                    let c = self.cands.pop().expect("peeked");
                    if self.is_current(&c) {
                        tied.push(c);
                    }
                }
                _ => break,
            }
        }
        // `tied` is in ascending variable order; keep the first best score.
        let mut chosen = 0;
        let mut chosen_score = self.tie_score(tied[0].3.0);
        for (i, c) in tied.iter().enumerate().skip(1) {
            let s = self.tie_score(c.3.0);
            if s > chosen_score {
                chosen = i;
                chosen_score = s;
            }
        }
        let pick = tied.swap_remove(chosen);
        self.cands.extend(tied);
        if !pick.0 {
            log::warn!(
                "tearing: no tearable variable left, tearing forbidden variable {}",
                pick.3.0
            );
        }
        Some(pick.3.0)
    }
}

/// Tears one block. `n_vars` block variables are numbered `0..n_vars` and
/// `eqs.len() == n_vars` (otherwise the residual count differs from the torn count).
/// `tearable[v] == false` forbids `v` as a tearing variable unless nothing else works
/// (then it is still picked, with a logged warning). Deterministic.
pub fn tear(n_vars: usize, eqs: &[TearingEquation], tearable: Option<&[bool]>) -> Tearing {
    tear_with_priority(n_vars, eqs, tearable, None)
}

/// Like [`tear`], with `var_priority`: higher = prefer to keep as tearing variable (e.g. state
/// derivatives). Among tearable candidates the priority ranks first, then the number of
/// unassigned equations containing the variable, then how many equations tearing it would
/// make solvable, then the lowest index.
pub fn tear_with_priority(
    n_vars: usize,
    eqs: &[TearingEquation],
    tearable: Option<&[bool]>,
    var_priority: Option<&[f64]>,
) -> Tearing {
    if eqs.len() != n_vars {
        log::warn!(
            "tearing: block has {} equations but {n_vars} variables",
            eqs.len()
        );
    }
    let mut eq_vars: Vec<Vec<(usize, bool)>> = Vec::with_capacity(eqs.len());
    for eq in eqs {
        let mut vars: Vec<(usize, bool)> = eq
            .vars
            .iter()
            .copied()
            .filter(|&(v, _)| v < n_vars)
            .collect();
        vars.sort_unstable();
        // duplicated variable: solvable only if every occurrence says so
        vars.dedup_by(|later, kept| {
            let same = later.0 == kept.0;
            if same {
                kept.1 &= later.1;
            }
            same
        });
        eq_vars.push(vars);
    }
    let mut var_eqs: Vec<Vec<usize>> = vec![Vec::new(); n_vars];
    for (e, vars) in eq_vars.iter().enumerate() {
        for &(v, _) in vars {
            var_eqs[v].push(e);
        }
    }
    let count: Vec<usize> = eq_vars.iter().map(Vec::len).collect();
    let sum: Vec<usize> = eq_vars
        .iter()
        .map(|vs| vs.iter().map(|p| p.0).sum())
        .collect();
    let live: Vec<usize> = var_eqs.iter().map(Vec::len).collect();
    let n_eqs = eq_vars.len();
    let mut st = State {
        eq_vars,
        var_eqs,
        status: vec![VarState::Unknown; n_vars],
        eq_done: vec![false; n_eqs],
        count,
        sum,
        live,
        ready: BinaryHeap::new(),
        cands: BinaryHeap::new(),
        tearable,
        priority: var_priority,
        out: Tearing {
            torn_vars: Vec::new(),
            residual_eqs: Vec::new(),
            assignments: Vec::new(),
        },
    };
    for e in 0..n_eqs {
        if st.count[e] == 1 && st.solvable(e, st.sum[e]) {
            st.ready.push(Reverse(e));
        }
    }
    for v in 0..n_vars {
        let c = st.cand(v);
        st.cands.push(c);
    }
    loop {
        while let Some(Reverse(e)) = st.ready.pop() {
            if !st.eq_done[e] && st.count[e] == 1 {
                let v = st.sum[e];
                st.assign(e, v);
            }
        }
        match st.pick_tear() {
            Some(v) => st.tear_var(v),
            None => break,
        }
    }
    st.out.residual_eqs = (0..n_eqs).filter(|&e| !st.eq_done[e]).collect();
    st.out
}

#[cfg(test)]
#[path = "tearing_tests.rs"]
mod tests;
