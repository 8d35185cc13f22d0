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

/// Augmenting paths from one unmatched equation at a time, for a matching completed
/// incrementally (the initialization adds equations one by one). The work space is
/// kept across searches: dense marks, reset where the last search went, so a search
/// costs what it visits, with no hashing and no allocation.
pub struct Augmenter {
    /// Per variable: the equation the search reached it from (`usize::MAX`: not reached).
    parent: Vec<usize>,
    /// Per equation: reached by the search.
    seen_eq: Vec<bool>,
    touched_vars: Vec<usize>,
    touched_eqs: Vec<usize>,
    queue: VecDeque<usize>,
}

impl Augmenter {
    /// A work space for a graph of `n_vars` variables and `n_eqs` equations (both may
    /// grow between searches).
    pub fn new(n_vars: usize, n_eqs: usize) -> Self {
        Augmenter {
            parent: vec![usize::MAX; n_vars],
            seen_eq: vec![false; n_eqs],
            touched_vars: Vec::new(),
            touched_eqs: Vec::new(),
            queue: VecDeque::new(),
        }
    }

    /// Augments the matching along an alternating path from the unmatched equation
    /// `root` (breadth first); false when there is none.
    pub fn augment(
        &mut self,
        adj: &Rows,
        root: usize,
        var_to_eq: &mut [Option<usize>],
        eq_to_var: &mut [Option<usize>],
    ) -> bool {
        for &v in &self.touched_vars {
            self.parent[v] = usize::MAX;
        }
        for &e in &self.touched_eqs {
            self.seen_eq[e] = false;
        }
        self.touched_vars.clear();
        self.touched_eqs.clear();
        self.queue.clear();
        if self.seen_eq.len() < adj.len() {
            self.seen_eq.resize(adj.len(), false);
        }
        if self.parent.len() < var_to_eq.len() {
            self.parent.resize(var_to_eq.len(), usize::MAX);
        }
        self.queue.push_back(root);
        self.seen_eq[root] = true;
        self.touched_eqs.push(root);
        while let Some(e) = self.queue.pop_front() {
            for &v in &adj[e] {
                if self.parent[v] != usize::MAX {
                    continue;
                }
                self.parent[v] = e;
                self.touched_vars.push(v);
                match var_to_eq[v] {
                    None => {
                        // Flip back to the root.
                        let mut v = v;
                        loop {
                            let e = self.parent[v];
                            let prev = eq_to_var[e];
                            eq_to_var[e] = Some(v);
                            var_to_eq[v] = Some(e);
                            match prev {
                                Some(pv) if e != root => v = pv,
                                _ => return true,
                            }
                        }
                    }
                    Some(e2) => {
                        if !self.seen_eq[e2] {
                            self.seen_eq[e2] = true;
                            self.touched_eqs.push(e2);
                            self.queue.push_back(e2);
                        }
                    }
                }
            }
        }
        false
    }
}

#[cfg(test)]
#[path = "matching_tests.rs"]
mod tests;
