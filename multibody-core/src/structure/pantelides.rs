//! Pantelides' index reduction on the integer equation-variable graph.
//!
//! Variables are numbered slots; `var_diff[v] = Some(w)` says slot `w` is the time
//! derivative of slot `v`. Only *highest-derivative* slots (those without a derivative
//! slot) take part in the matching. When an equation cannot be matched, the equations and
//! variables visited by the failed augmenting search are differentiated: new derivative
//! slots and new equations are appended, the derivative maps record which is which, and
//! the search continues with the derivative of the equation. The symbolic step that
//! rebuilds the differentiated equations lives elsewhere; here a differentiated equation
//! contains every variable of its antiderivative and each one's derivative, which is
//! exactly what matters for the matching (lower-order slots never take part in it).

use super::matching::{Matching, maximum_matching};
use super::{BipartiteGraph, Rows};

/// The result of index reduction.
#[derive(Clone, Debug, PartialEq)]
pub struct IndexReduction {
    /// The augmented graph: the original equations first, then the differentiated ones.
    pub graph: BipartiteGraph,
    /// For each slot, the slot of its time derivative (grown by the new slots).
    pub var_diff: Vec<Option<usize>>,
    /// For each equation, the equation that is its time derivative, if it was
    /// differentiated.
    pub eq_diff: Vec<Option<usize>>,
    /// A matching of every highest-order equation (one not differentiated) to a
    /// highest-derivative slot (one without a derivative slot); lower-order equations and
    /// slots are unmatched.
    pub matching: Matching,
}

impl IndexReduction {
    /// The equation of which `e` is the time derivative, if `e` was made by
    /// differentiation.
    pub fn antiderivative_eq(&self) -> Vec<Option<usize>> {
        invert(&self.eq_diff, self.eq_diff.len())
    }

    /// For each slot, the slot of which it is the time derivative.
    pub fn antiderivative_var(&self) -> Vec<Option<usize>> {
        invert(&self.var_diff, self.var_diff.len())
    }

    /// How many times each equation of the original system was differentiated.
    pub fn differentiation_counts(&self, n_original: usize) -> Vec<usize> {
        (0..n_original)
            .map(|e| {
                let mut k = 0;
                let mut cur = e;
                while let Some(d) = self.eq_diff[cur] {
                    k += 1;
                    cur = d;
                }
                k
            })
            .collect()
    }
}

/// Inverts a derivative map.
pub fn invert(map: &[Option<usize>], n: usize) -> Vec<Option<usize>> {
    let mut inv = vec![None; n];
    for (i, d) in map.iter().enumerate() {
        if let Some(d) = *d {
            inv[d] = Some(i);
        }
    }
    inv
}

/// Why index reduction failed.
#[derive(Clone, Debug, PartialEq)]
pub struct StructurallySingular {
    /// Equations (original numbering) of the over-determined part (or those taking part
    /// in a failed differentiation).
    pub equations: Vec<usize>,
    /// Slots determined more than once (the over-determined part).
    pub overdetermined: Vec<usize>,
    /// Slots no equation can determine.
    pub undetermined: Vec<usize>,
}

/// The graph with every slot replaced by the base slot of its derivative chain: a system
/// is solvable by differentiation exactly when this graph has a perfect matching
/// (differentiation never creates a new base variable).
pub fn chain_graph(
    graph: &BipartiteGraph,
    var_diff: &[Option<usize>],
) -> (BipartiteGraph, Vec<usize>) {
    let n = graph.n_vars;
    let anti = invert(var_diff, n.max(var_diff.len()));
    let mut base: Vec<usize> = (0..n).collect();
    for v in 0..n {
        let mut b = v;
        while let Some(a) = anti.get(b).copied().flatten() {
            b = a;
        }
        base[v] = b;
    }
    let mut g = BipartiteGraph::new(n);
    for vars in graph.eq_vars.iter() {
        g.add_equation(vars.iter().map(|&v| base[v]).collect());
    }
    (g, base)
}

struct Search<'a> {
    adj: &'a Rows,
    var_diff: &'a [Option<usize>],
    var_eq: &'a mut Vec<Option<usize>>,
    eq_var: &'a mut Vec<Option<usize>>,
    colored_eqs: Vec<usize>,
    colored_vars: Vec<usize>,
    /// Visit marks, all false between searches (only the colored entries are reset, so
    /// a search costs what it visits, not the size of the graph).
    eq_mark: &'a mut Vec<bool>,
    var_mark: &'a mut Vec<bool>,
    /// For each equation reached by the search: the equation it was reached from and
    /// the slot between them (valid for the marked equations only).
    via: &'a mut Vec<(usize, usize)>,
}

impl Search<'_> {
    /// Breadth-first augmenting-path search from equation `root` over
    /// highest-derivative slots: the shortest path is taken (depth first, the searches
    /// of a chain of N bodies walked along the chain and grew with N). On failure the
    /// visited equations and slots, everything reachable, are left colored.
    fn augment(&mut self, root: usize) -> bool {
        self.mark_eq(root);
        let mut head = 0;
        while head < self.colored_eqs.len() {
            let e = self.colored_eqs[head];
            head += 1;
            let vars = &self.adj[e];
            let free = vars
                .iter()
                .copied()
                .find(|&v| self.var_diff[v].is_none() && self.var_eq[v].is_none());
            if let Some(v) = free {
                // Flip the alternating path root -> ... -> e -> v.
                let (mut e, mut v) = (e, v);
                loop {
                    let previous = self.eq_var[e];
                    self.var_eq[v] = Some(e);
                    self.eq_var[e] = Some(v);
                    if e == root {
                        break;
                    }
                    let (parent, through) = self.via[e];
                    debug_assert_eq!(previous, Some(through));
                    (e, v) = (parent, through);
                }
                return true;
            }
            for i in 0..self.adj[e].len() {
                let v = self.adj[e][i];
                if self.var_diff[v].is_some() || self.var_mark[v] {
                    continue;
                }
                self.var_mark[v] = true;
                self.colored_vars.push(v);
                if let Some(e2) = self.var_eq[v]
                    && !self.eq_mark[e2]
                {
                    self.via[e2] = (e, v);
                    self.mark_eq(e2);
                }
            }
        }
        false
    }

    fn mark_eq(&mut self, e: usize) {
        if !self.eq_mark[e] {
            self.eq_mark[e] = true;
            self.colored_eqs.push(e);
        }
    }
}

/// Runs Pantelides' algorithm. `var_diff` must have one entry per slot of `graph`
/// (`graph.n_vars`). Fails with the singular part when the system is structurally
/// singular (no number of differentiations makes it solvable).
pub fn pantelides(
    graph: &BipartiteGraph,
    var_diff: &[Option<usize>],
) -> Result<IndexReduction, StructurallySingular> {
    pantelides_with_implicit(graph, var_diff, &[], &[])
}

/// [`pantelides`] for systems where some slots have an *implicit* derivative: an
/// expression of other slots rather than a slot of its own (the entries of an
/// orientation matrix, whose derivative is `-skew(w) T`). `implicit[v]` lists the slots
/// that derivative contains (empty for ordinary slots; the slice may be shorter than the
/// number of slots), and `definitions[e]` marks the equations that define implicit slots
/// (`T_b = T_rel T_a`).
///
/// Implicit slots and their defining equations stay out of the matching: the definitions
/// are solved for the implicit slots explicitly and never differentiated (their
/// derivatives are the angular-velocity equations, already in the system). In any other
/// equation an implicit slot counts as known at its own level, and differentiating the
/// equation brings in the slots of its implicit derivative.
pub fn pantelides_with_implicit(
    graph: &BipartiteGraph,
    var_diff: &[Option<usize>],
    implicit: &[Vec<usize>],
    definitions: &[bool],
) -> Result<IndexReduction, StructurallySingular> {
    let is_implicit = |v: usize| implicit.get(v).is_some_and(|d| !d.is_empty());
    let is_definition = |e: usize| definitions.get(e).copied().unwrap_or(false);
    assert_eq!(
        var_diff.len(),
        graph.n_vars,
        "pantelides: one var_diff entry per slot"
    );
    // Solvability: a perfect matching of all equations (definitions included) to the
    // derivative chains (an implicit slot is a chain of its own).
    let (chains, base) = chain_graph(graph, var_diff);
    let allowed: Vec<bool> = (0..graph.n_vars).map(|v| base[v] == v).collect();
    let cm = maximum_matching(&chains, Some(&allowed), None);
    if cm.size() < graph.n_eqs() {
        let dm = super::dm::dulmage_mendelsohn(&chains, &cm, Some(&allowed));
        let equations = if dm.over_eqs.is_empty() {
            dm.unmatched_eqs.clone()
        } else {
            dm.over_eqs.clone()
        };
        return Err(StructurallySingular {
            equations,
            overdetermined: dm.over_vars.clone(),
            undetermined: dm.under_vars.clone(),
        });
    }

    // Matching graph: implicit slots removed (they are known inside the matching). Rows
    // in one vector each (a vector per equation scatters a large model's graph).
    let mut adj = Rows::with_capacity(graph.n_eqs(), graph.eq_vars.n_items());
    // The implicit slots of each equation, for its derivative.
    let mut hidden = Rows::with_capacity(graph.n_eqs(), 0);
    let mut row: Vec<usize> = Vec::new();
    for vars in graph.eq_vars.iter() {
        row.clear();
        row.extend(vars.iter().copied().filter(|&v| !is_implicit(v)));
        adj.push(&row);
        row.clear();
        row.extend(vars.iter().copied().filter(|&v| is_implicit(v)));
        hidden.push(&row);
    }
    let mut var_diff: Vec<Option<usize>> = var_diff.to_vec();
    let mut eq_diff: Vec<Option<usize>> = vec![None; adj.len()];
    let mut var_eq: Vec<Option<usize>> = vec![None; var_diff.len()];
    let mut eq_var: Vec<Option<usize>> = vec![None; adj.len()];
    let n_original = adj.len();
    // A differentiation bound that a solvable system never reaches.
    let limit = 4 * (graph.n_vars + n_original) + 16;
    let mut rounds = 0usize;
    let mut eq_mark: Vec<bool> = Vec::new();
    let mut var_mark: Vec<bool> = Vec::new();
    let mut via: Vec<(usize, usize)> = Vec::new();

    for k in 0..n_original {
        if is_definition(k) {
            continue;
        }
        let mut i = k;
        loop {
            eq_mark.resize(adj.len(), false);
            var_mark.resize(var_diff.len(), false);
            via.resize(adj.len(), (0, 0));
            let mut s = Search {
                adj: &adj,
                var_diff: &var_diff,
                var_eq: &mut var_eq,
                eq_var: &mut eq_var,
                colored_eqs: Vec::new(),
                colored_vars: Vec::new(),
                eq_mark: &mut eq_mark,
                var_mark: &mut var_mark,
                via: &mut via,
            };
            let augmented = s.augment(i);
            let (colored_eqs, colored_vars) = (s.colored_eqs, s.colored_vars);
            for &e in &colored_eqs {
                eq_mark[e] = false;
            }
            for &v in &colored_vars {
                var_mark[v] = false;
            }
            if augmented {
                break;
            }
            rounds += 1;
            if rounds > limit {
                // Slots made by differentiation here are reported as the slots they are
                // derivatives of (the caller knows only the slots it gave).
                let mut anti: Vec<Option<usize>> = vec![None; var_diff.len()];
                for (v, d) in var_diff.iter().enumerate() {
                    if let Some(d) = *d {
                        anti[d] = Some(v);
                    }
                }
                let mut overdetermined: Vec<usize> = colored_vars
                    .into_iter()
                    .map(|mut v| {
                        while v >= graph.n_vars {
                            match anti[v] {
                                Some(a) => v = a,
                                None => break,
                            }
                        }
                        v
                    })
                    .filter(|&v| v < graph.n_vars)
                    .collect();
                overdetermined.sort_unstable();
                overdetermined.dedup();
                return Err(StructurallySingular {
                    equations: colored_eqs
                        .into_iter()
                        .filter(|&e| e < n_original)
                        .collect(),
                    overdetermined,
                    undetermined: Vec::new(),
                });
            }
            for &v in &colored_vars {
                if var_diff[v].is_none() {
                    let w = var_diff.len();
                    var_diff.push(None);
                    var_eq.push(None);
                    var_diff[v] = Some(w);
                }
            }
            for &e in &colored_eqs {
                if eq_diff[e].is_none() {
                    let mut vars: Vec<usize> = Vec::with_capacity(adj[e].len() * 2);
                    let mut hid: Vec<usize> = hidden[e].to_vec();
                    for &v in &adj[e] {
                        vars.push(v);
                        if let Some(d) = var_diff[v] {
                            vars.push(d);
                        }
                    }
                    for &h in &hidden[e] {
                        for &d in &implicit[h] {
                            if is_implicit(d) {
                                hid.push(d);
                            } else {
                                vars.push(d);
                            }
                        }
                    }
                    vars.sort_unstable();
                    vars.dedup();
                    hid.sort_unstable();
                    hid.dedup();
                    let ne = adj.len();
                    adj.push(&vars);
                    hidden.push(&hid);
                    eq_diff.push(None);
                    eq_var.push(None);
                    eq_diff[e] = Some(ne);
                }
            }
            // The derivatives of the colored slots inherit the derivatives of their
            // equations; the old pairs are dropped (lower-order slots leave the matching).
            for &v in &colored_vars {
                if let Some(e) = var_eq[v] {
                    let dv = var_diff[v].expect("created above");
                    let de = eq_diff[e].expect("colored equation was differentiated");
                    var_eq[dv] = Some(de);
                    eq_var[de] = Some(dv);
                    var_eq[v] = None;
                    if eq_var[e] == Some(v) {
                        eq_var[e] = None;
                    }
                }
            }
            i = eq_diff[i].expect("the failed equation is colored");
        }
    }
    // The final graph has the full incidence (implicit slots included).
    let mut g =
        BipartiteGraph::with_capacity(var_diff.len(), adj.len(), adj.n_items() + hidden.n_items());
    for (vars, h) in adj.iter().zip(hidden.iter()) {
        row.clear();
        row.extend_from_slice(vars);
        row.extend_from_slice(h);
        g.add_equation_from(&mut row);
    }
    Ok(IndexReduction {
        graph: g,
        var_diff,
        eq_diff,
        matching: Matching {
            eq_to_var: eq_var,
            var_to_eq: var_eq,
        },
    })
}

#[cfg(test)]
#[path = "pantelides_tests.rs"]
pub(crate) mod tests;
