//! Coarse Dulmage–Mendelsohn decomposition, used to explain structural errors.
//!
//! Given a maximum matching, the underdetermined part is everything reachable
//! from an unmatched variable by alternating paths, and the overdetermined
//! part everything reachable from an unmatched equation.

use super::BipartiteGraph;
use super::matching::Matching;

/// Under- and overdetermined parts of a system (all lists sorted ascending).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct DmDecomposition {
    /// Equations in the underdetermined part.
    pub under_eqs: Vec<usize>,
    /// Variables in the underdetermined part (including the unmatched ones).
    pub under_vars: Vec<usize>,
    /// Equations in the overdetermined part (including the unmatched ones).
    pub over_eqs: Vec<usize>,
    /// Variables in the overdetermined part.
    pub over_vars: Vec<usize>,
    /// Equations without a matched variable.
    pub unmatched_eqs: Vec<usize>,
    /// Allowed (unknown) variables without a matched equation.
    pub unmatched_vars: Vec<usize>,
}

fn marked(flags: &[bool]) -> Vec<usize> {
    flags
        .iter()
        .enumerate()
        .filter_map(|(i, &f)| f.then_some(i))
        .collect()
}

/// Computes the coarse Dulmage–Mendelsohn decomposition of `g` with respect to the
/// maximum matching `m`. Variables with `var_allowed[v] == false` are knowns and take no part.
///
/// Under = unmatched variables plus everything reachable from them by alternating paths
/// (variable -> equation containing it -> that equation's matched variable -> ...).
/// Over = unmatched equations plus everything reachable by alternating paths
/// (equation -> variable in it -> that variable's matched equation -> ...).
pub fn dulmage_mendelsohn(
    g: &BipartiteGraph,
    m: &Matching,
    var_allowed: Option<&[bool]>,
) -> DmDecomposition {
    let allowed = |v: usize| var_allowed.is_none_or(|a| a.get(v).copied().unwrap_or(false));
    let n_eqs = g.n_eqs();
    let n_vars = g.n_vars;
    let var_to_eq = |v: usize| m.var_to_eq.get(v).copied().flatten();
    let eq_to_var = |e: usize| m.eq_to_var.get(e).copied().flatten();

    let unmatched_eqs: Vec<usize> = (0..n_eqs).filter(|&e| eq_to_var(e).is_none()).collect();
    let unmatched_vars: Vec<usize> = (0..n_vars)
        .filter(|&v| allowed(v) && var_to_eq(v).is_none())
        .collect();

    // Underdetermined: BFS over variables.
    let var_eqs = g.var_eqs();
    let mut under_eq = vec![false; n_eqs];
    let mut under_var = vec![false; n_vars];
    let mut stack: Vec<usize> = unmatched_vars.clone();
    for &v in &stack {
        under_var[v] = true;
    }
    while let Some(v) = stack.pop() {
        for &e in &var_eqs[v] {
            if under_eq[e] {
                continue;
            }
            under_eq[e] = true;
            if let Some(w) = eq_to_var(e).filter(|&w| !under_var[w]) {
                under_var[w] = true;
                stack.push(w);
            }
        }
    }

    // Overdetermined: BFS over equations.
    let mut over_eq = vec![false; n_eqs];
    let mut over_var = vec![false; n_vars];
    let mut stack: Vec<usize> = unmatched_eqs.clone();
    for &e in &stack {
        over_eq[e] = true;
    }
    while let Some(e) = stack.pop() {
        for &v in &g.eq_vars[e] {
            if !allowed(v) || over_var[v] {
                continue;
            }
            over_var[v] = true;
            if let Some(f) = var_to_eq(v).filter(|&f| !over_eq[f]) {
                over_eq[f] = true;
                stack.push(f);
            }
        }
    }

    DmDecomposition {
        under_eqs: marked(&under_eq),
        under_vars: marked(&under_var),
        over_eqs: marked(&over_eq),
        over_vars: marked(&over_var),
        unmatched_eqs,
        unmatched_vars,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::structure::matching::maximum_matching;

    #[test]
    fn overdetermined_pair() {
        let mut g = BipartiteGraph::new(2);
        g.add_equation(vec![0]);
        g.add_equation(vec![0]);
        g.add_equation(vec![0, 1]);
        let m = maximum_matching(&g, None, None);
        assert_eq!(m.size(), 2);
        let dm = dulmage_mendelsohn(&g, &m, None);
        assert_eq!(dm.over_eqs, vec![0, 1]);
        assert_eq!(dm.over_vars, vec![0]);
        assert_eq!(dm.unmatched_eqs, vec![1]);
        assert!(dm.under_eqs.is_empty() && dm.under_vars.is_empty());
        assert!(dm.unmatched_vars.is_empty());
    }

    #[test]
    fn two_equations_one_variable() {
        let mut g = BipartiteGraph::new(1);
        g.add_equation(vec![0]);
        g.add_equation(vec![0]);
        let m = maximum_matching(&g, None, None);
        assert_eq!(m.size(), 1);
        let dm = dulmage_mendelsohn(&g, &m, None);
        assert_eq!(
            dm,
            DmDecomposition {
                under_eqs: vec![],
                under_vars: vec![],
                over_eqs: vec![0, 1],
                over_vars: vec![0],
                unmatched_eqs: vec![1],
                unmatched_vars: vec![],
            }
        );
    }

    #[test]
    fn underdetermined_chain() {
        // eq0: x0 + x1, eq1: x1 + x2, eq2: x3 (well determined)
        let mut g = BipartiteGraph::new(4);
        g.add_equation(vec![0, 1]);
        g.add_equation(vec![1, 2]);
        g.add_equation(vec![3]);
        let m = maximum_matching(&g, None, None);
        let dm = dulmage_mendelsohn(&g, &m, None);
        assert_eq!(dm.unmatched_vars, vec![1]);
        assert_eq!(dm.under_vars, vec![0, 1, 2]);
        assert_eq!(dm.under_eqs, vec![0, 1]);
        assert!(dm.over_eqs.is_empty() && dm.over_vars.is_empty());
        assert!(dm.unmatched_eqs.is_empty());
    }

    #[test]
    fn known_variables_are_ignored() {
        // x1 is known: eq0 determines x0, eq1 contains only knowns.
        let mut g = BipartiteGraph::new(2);
        g.add_equation(vec![0, 1]);
        g.add_equation(vec![1]);
        let allowed = [true, false];
        let m = maximum_matching(&g, Some(&allowed), None);
        let dm = dulmage_mendelsohn(&g, &m, Some(&allowed));
        assert_eq!(dm.unmatched_eqs, vec![1]);
        assert_eq!(dm.over_eqs, vec![1]);
        assert!(dm.over_vars.is_empty());
        assert!(dm.unmatched_vars.is_empty() && dm.under_vars.is_empty());
    }
}
