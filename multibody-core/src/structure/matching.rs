//! Maximum bipartite matching between equations and variables.
//!
//! A greedy pass (equations with the fewest candidates first) matches most of
//! a typical model in O(E); Hopcroft–Karp with an iterative, pointer-based DFS
//! then completes it in O(E sqrt V) worst case.

use super::{BipartiteGraph, Rows};
use std::collections::VecDeque;

/// A matching between equations and variables.
#[derive(Clone, Debug, PartialEq)]
pub struct Matching {
    /// For each equation, the variable it is matched to.
    pub eq_to_var: Vec<Option<usize>>,
    /// For each variable, the equation it is matched to.
    pub var_to_eq: Vec<Option<usize>>,
}

impl Matching {
    /// Number of matched pairs.
    pub fn size(&self) -> usize {
        self.eq_to_var.iter().filter(|m| m.is_some()).count()
    }

    /// True when every equation and every variable is matched.
    pub fn is_perfect(&self) -> bool {
        self.eq_to_var.iter().all(Option::is_some) && self.var_to_eq.iter().all(Option::is_some)
    }
}

const INF: usize = usize::MAX;

/// Per-equation candidate variables, in the order they are tried: higher
/// preference first, then fewer equations, then lower index.
fn candidate_lists(
    g: &BipartiteGraph,
    var_allowed: Option<&[bool]>,
    var_preference: Option<&[f64]>,
) -> Rows {
    let allowed = |v: usize| var_allowed.is_none_or(|a| a.get(v).copied().unwrap_or(false));
    let mut var_deg = vec![0usize; g.n_vars];
    for vars in g.eq_vars.iter() {
        for &v in vars {
            if allowed(v) {
                var_deg[v] += 1;
            }
        }
    }
    let pref = |v: usize| {
        var_preference
            .and_then(|p| p.get(v).copied())
            .unwrap_or(0.0)
    };
    let mut out = Rows::with_capacity(g.eq_vars.len(), g.eq_vars.n_items());
    let mut c: Vec<usize> = Vec::new();
    for vars in g.eq_vars.iter() {
        c.clear();
        c.extend(vars.iter().copied().filter(|&v| allowed(v)));
        c.sort_by(|&a, &b| {
            pref(b)
                .total_cmp(&pref(a))
                .then(var_deg[a].cmp(&var_deg[b]))
                .then(a.cmp(&b))
        });
        out.push(&c);
    }
    out
}

/// Greedy initial matching: equations in order of increasing candidate count
/// (ties by index), each takes its first free candidate.
fn greedy(adj: &Rows, m: &mut Matching) {
    let max_deg = adj.iter().map(<[usize]>::len).max().unwrap_or(0);
    let mut buckets: Vec<Vec<usize>> = vec![Vec::new(); max_deg + 1];
    for (e, c) in adj.iter().enumerate() {
        buckets[c.len()].push(e);
    }
    for e in buckets.into_iter().flatten() {
        if let Some(&v) = adj[e].iter().find(|&&v| m.var_to_eq[v].is_none()) {
            m.eq_to_var[e] = Some(v);
            m.var_to_eq[v] = Some(e);
        }
    }
}

/// BFS layering from the free equations. Returns true if some free variable is reachable.
fn bfs_layers(adj: &Rows, m: &Matching, dist: &mut [usize]) -> bool {
    let mut queue = VecDeque::new();
    for (e, d) in dist.iter_mut().enumerate() {
        if m.eq_to_var[e].is_none() && !adj[e].is_empty() {
            *d = 0;
            queue.push_back(e);
        } else {
            *d = INF;
        }
    }
    let mut found = false;
    while let Some(e) = queue.pop_front() {
        for &v in adj[e].iter() {
            match m.var_to_eq[v] {
                None => found = true,
                Some(w) if dist[w] == INF => {
                    dist[w] = dist[e] + 1;
                    queue.push_back(w);
                }
                Some(_) => {}
            }
        }
    }
    found
}

/// Iterative layered DFS from free equation `root`; augments on success.
fn dfs_augment(
    adj: &Rows,
    m: &mut Matching,
    dist: &mut [usize],
    next: &mut [usize],
    stack: &mut Vec<usize>,
    root: usize,
) -> bool {
    stack.clear();
    stack.push(root);
    while let Some(&e) = stack.last() {
        if next[e] >= adj[e].len() {
            dist[e] = INF;
            stack.pop();
            if let Some(&parent) = stack.last() {
                next[parent] += 1;
            }
            continue;
        }
        let v = adj[e][next[e]];
        match m.var_to_eq[v] {
            None => {
                for &u in stack.iter() {
                    let var = adj[u][next[u]];
                    m.eq_to_var[u] = Some(var);
                    m.var_to_eq[var] = Some(u);
                }
                return true;
            }
            Some(w) if dist[w] != INF && dist[w] == dist[e] + 1 => stack.push(w),
            Some(_) => next[e] += 1,
        }
    }
    false
}

/// Maximum matching. `var_allowed[v] == false` excludes a variable (it is known, not an unknown).
/// `var_preference`: optional per-variable weight; when several augmenting choices exist
/// prefer higher weight (the greedy phase honours it, and Hopcroft–Karp tries candidates in
/// the same order). Deterministic: same input -> same output.
pub fn maximum_matching(
    g: &BipartiteGraph,
    var_allowed: Option<&[bool]>,
    var_preference: Option<&[f64]>,
) -> Matching {
    let n_eqs = g.n_eqs();
    let adj = candidate_lists(g, var_allowed, var_preference);
    let mut m = Matching {
        eq_to_var: vec![None; n_eqs],
        var_to_eq: vec![None; g.n_vars],
    };
    greedy(&adj, &mut m);
    let mut dist = vec![INF; n_eqs];
    let mut next = vec![0usize; n_eqs];
    let mut stack = Vec::new();
    while bfs_layers(&adj, &m, &mut dist) {
        next.iter_mut().for_each(|n| *n = 0);
        let mut augmented = false;
        for e in 0..n_eqs {
            if m.eq_to_var[e].is_none() && dist[e] == 0 {
                augmented |= dfs_augment(&adj, &mut m, &mut dist, &mut next, &mut stack, e);
            }
        }
        if !augmented {
            break;
        }
    }
    m
}

#[cfg(test)]
#[path = "matching_tests.rs"]
mod tests;
