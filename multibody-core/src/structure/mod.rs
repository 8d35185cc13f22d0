//! Structural algorithms on integer bipartite graphs.
//!
//! Equations and variables are plain indices here; turning results back into
//! symbolic equations is done elsewhere. Every algorithm is iterative (no
//! recursion) and near-linear, so models with hundreds of thousands of
//! equations are handled without stack overflow.
//!
//! * [`matching`]: maximum bipartite matching (greedy + Hopcroft–Karp).
//! * [`dm`]: coarse Dulmage–Mendelsohn decomposition for diagnostics.
//! * [`blt`]: block lower triangular ordering (iterative Tarjan SCC).
//! * [`tearing`]: greedy tearing of one algebraic block.
//! * [`pantelides`]: index reduction (which equations to differentiate how often).
//! * [`dummy_derivatives`]: static state selection honouring state priorities.

pub mod blt;
pub mod dm;
pub mod dummy_derivatives;
pub mod matching;
pub mod pantelides;
mod rows;
pub mod tearing;

pub use rows::Rows;

/// Bipartite incidence: equations (rows) x variables (columns).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BipartiteGraph {
    /// Number of variables (columns); every variable index is `< n_vars`.
    pub n_vars: usize,
    /// For each equation, the sorted, deduplicated variables it contains.
    pub eq_vars: Rows,
}

impl BipartiteGraph {
    /// An empty graph with `n_vars` variables and no equations.
    pub fn new(n_vars: usize) -> Self {
        Self::with_capacity(n_vars, 0, 0)
    }

    /// An empty graph with `n_vars` variables and room for `n_eqs` equations of
    /// `n_items` incidences in all (a large model's graph is then not copied as it
    /// grows).
    pub fn with_capacity(n_vars: usize, n_eqs: usize, n_items: usize) -> Self {
        Self {
            n_vars,
            eq_vars: Rows::with_capacity(n_eqs, n_items),
        }
    }

    /// Adds an equation containing `vars` (sorted and deduplicated here) and
    /// returns its index. Variables `>= n_vars` grow `n_vars` accordingly.
    pub fn add_equation(&mut self, mut vars: Vec<usize>) -> usize {
        self.add_equation_from(&mut vars)
    }

    /// [`Self::add_equation`] from a buffer the caller reuses (sorted and deduplicated
    /// in place).
    pub fn add_equation_from(&mut self, vars: &mut Vec<usize>) -> usize {
        vars.sort_unstable();
        vars.dedup();
        let needed = vars.last().map_or(0, |&last| last + 1);
        self.n_vars = self.n_vars.max(needed);
        self.eq_vars.push(vars);
        self.eq_vars.len() - 1
    }

    /// Number of equations (rows).
    pub fn n_eqs(&self) -> usize {
        self.eq_vars.len()
    }

    /// The transpose: for each variable, the ascending list of equations containing it.
    pub fn var_eqs(&self) -> Vec<Vec<usize>> {
        let mut deg = vec![0usize; self.n_vars];
        for vars in self.eq_vars.iter() {
            for &v in vars {
                deg[v] += 1;
            }
        }
        let mut out: Vec<Vec<usize>> = deg.into_iter().map(Vec::with_capacity).collect();
        for (e, vars) in self.eq_vars.iter().enumerate() {
            for &v in vars {
                out[v].push(e);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn add_equation_sorts_dedups_and_transposes() {
        let mut g = BipartiteGraph::new(3);
        assert_eq!(g.add_equation(vec![2, 0, 2]), 0);
        assert_eq!(g.add_equation(vec![1]), 1);
        assert_eq!(g.add_equation(vec![]), 2);
        assert_eq!(g.eq_vars.to_vecs(), vec![vec![0, 2], vec![1], vec![]]);
        assert_eq!(g.n_eqs(), 3);
        assert_eq!(g.var_eqs(), vec![vec![0], vec![1], vec![0]]);
    }

    #[test]
    fn add_equation_grows_n_vars() {
        let mut g = BipartiteGraph::new(1);
        g.add_equation(vec![4]);
        assert_eq!(g.n_vars, 5);
        assert_eq!(g.var_eqs().len(), 5);
    }
}
