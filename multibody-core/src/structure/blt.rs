//! Block lower triangular (BLT) ordering via an iterative Tarjan SCC.
//!
//! Equation `e` depends on equation `e'` when `e` contains a variable other
//! than its own matched one whose matched equation is `e'`. The strongly
//! connected components of that graph, in Tarjan's completion order, are the
//! blocks in evaluation order (dependencies first).

use super::matching::Matching;
use super::{BipartiteGraph, Rows};

/// One block: `vars[i]` is matched to `eqs[i]`; equations ascending.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// Equations of the block, ascending.
    pub eqs: Vec<usize>,
    /// The variable matched to each equation of `eqs`, position by position.
    pub vars: Vec<usize>,
}

/// All blocks in evaluation order, stored flat (two allocations in all instead of two
/// per block): block `k` is `eqs[k]` with `vars[k]`.
#[derive(Clone, Debug, Default)]
pub struct Blocks {
    /// Equations of each block, ascending.
    pub eqs: Rows,
    /// The variable matched to each equation of the block, position by position.
    pub vars: Rows,
}

/// One block of [`Blocks`], borrowed.
#[derive(Clone, Copy, Debug)]
pub struct BlockRef<'a> {
    /// Equations of the block, ascending.
    pub eqs: &'a [usize],
    /// The variable matched to each equation of `eqs`.
    pub vars: &'a [usize],
}

impl Blocks {
    /// Number of blocks.
    pub fn len(&self) -> usize {
        self.eqs.len()
    }

    /// Whether there is no block.
    pub fn is_empty(&self) -> bool {
        self.eqs.is_empty()
    }

    /// The blocks in evaluation order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = BlockRef<'_>> + '_ {
        self.eqs
            .iter()
            .zip(self.vars.iter())
            .map(|(eqs, vars)| BlockRef { eqs, vars })
    }
}

const UNVISITED: usize = usize::MAX;

/// Successor of equation `e` reached through its variable at position `pos`, if any.
fn successor(g: &BipartiteGraph, m: &Matching, e: usize, pos: usize) -> Option<usize> {
    let v = g.eq_vars[e][pos];
    let own = m.eq_to_var[e];
    if own == Some(v) {
        return None;
    }
    let target = m.var_to_eq.get(v).copied().flatten()?;
    (target != e).then_some(target)
}

/// Blocks in evaluation order: every block only uses variables solved in earlier blocks or
/// itself (or not allowed/known ones). Only matched equations take part. Deterministic.
pub fn blt(g: &BipartiteGraph, m: &Matching) -> Vec<Block> {
    blt_flat(g, m)
        .iter()
        .map(|b| Block {
            eqs: b.eqs.to_vec(),
            vars: b.vars.to_vec(),
        })
        .collect()
}

/// [`blt`], stored flat.
pub fn blt_flat(g: &BipartiteGraph, m: &Matching) -> Blocks {
    let n = g.n_eqs();
    let mut index = vec![UNVISITED; n];
    let mut low = vec![0usize; n];
    let mut on_stack = vec![false; n];
    let mut scc_stack: Vec<usize> = Vec::new();
    // call stack frames: (equation, next variable position)
    let mut call: Vec<(usize, usize)> = Vec::new();
    let mut counter = 0usize;
    let mut blocks = Blocks::default();
    let (mut eqs, mut vars) = (Vec::new(), Vec::new());

    for root in 0..n {
        if index[root] != UNVISITED || m.eq_to_var[root].is_none() {
            continue;
        }
        index[root] = counter;
        low[root] = counter;
        counter += 1;
        scc_stack.push(root);
        on_stack[root] = true;
        call.push((root, 0));

        while let Some(frame) = call.last_mut() {
            let e = frame.0;
            if frame.1 < g.eq_vars[e].len() {
                let pos = frame.1;
                frame.1 += 1;
                let Some(w) = successor(g, m, e, pos) else {
                    continue;
                };
                if index[w] == UNVISITED {
                    index[w] = counter;
                    low[w] = counter;
                    counter += 1;
                    scc_stack.push(w);
                    on_stack[w] = true;
                    call.push((w, 0));
                } else if on_stack[w] {
                    low[e] = low[e].min(index[w]);
                }
                continue;
            }
            // all successors of e done
            call.pop();
            if let Some(&(parent, _)) = call.last() {
                low[parent] = low[parent].min(low[e]);
            }
            if low[e] == index[e] {
                eqs.clear();
                loop {
                    let x = scc_stack.pop().expect("Tarjan stack holds the component");
                    on_stack[x] = false;
                    eqs.push(x);
                    if x == e {
                        break;
                    }
                }
                eqs.sort_unstable();
                vars.clear();
                vars.extend(
                    eqs.iter()
                        .map(|&x| m.eq_to_var[x].expect("only matched equations are visited")),
                );
                blocks.eqs.push(&eqs);
                blocks.vars.push(&vars);
            }
        }
    }
    blocks
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::structure::matching::maximum_matching;

    fn block(eqs: &[usize], vars: &[usize]) -> Block {
        Block {
            eqs: eqs.to_vec(),
            vars: vars.to_vec(),
        }
    }

    /// Every variable used by a block is solved in an earlier block or in itself.
    fn check_order(g: &BipartiteGraph, m: &Matching, blocks: &[Block]) {
        let mut solved = vec![false; g.n_vars];
        for b in blocks {
            for &v in &b.vars {
                solved[v] = true;
            }
            for &e in &b.eqs {
                for &v in &g.eq_vars[e] {
                    assert!(solved[v] || m.var_to_eq[v].is_none(), "eq {e} uses var {v}");
                }
            }
        }
    }

    #[test]
    fn five_equations_with_one_loop() {
        // e0: x0 = f()          -> var 0
        // e1: x1 = f(x0, x2)    -> loop with e2
        // e2: x2 = f(x1)
        // e3: x3 = f(x4)        -> after e4
        // e4: x4 = f(x1)
        let mut g = BipartiteGraph::new(5);
        g.add_equation(vec![0]);
        g.add_equation(vec![0, 1, 2]);
        g.add_equation(vec![1, 2]);
        g.add_equation(vec![3, 4]);
        g.add_equation(vec![1, 4]);
        let m = Matching {
            eq_to_var: vec![Some(0), Some(1), Some(2), Some(3), Some(4)],
            var_to_eq: vec![Some(0), Some(1), Some(2), Some(3), Some(4)],
        };
        let blocks = blt(&g, &m);
        assert_eq!(
            blocks,
            vec![
                block(&[0], &[0]),
                block(&[1, 2], &[1, 2]),
                block(&[4], &[4]),
                block(&[3], &[3]),
            ]
        );
        check_order(&g, &m, &blocks);
    }

    #[test]
    fn pairs_stay_together_when_sorted() {
        // e0 solves x2, e1 solves x0, loop between them; e2 solves x1 from x0.
        let mut g = BipartiteGraph::new(3);
        g.add_equation(vec![0, 2]);
        g.add_equation(vec![0, 2]);
        g.add_equation(vec![0, 1]);
        let m = Matching {
            eq_to_var: vec![Some(2), Some(0), Some(1)],
            var_to_eq: vec![Some(1), Some(2), Some(0)],
        };
        let blocks = blt(&g, &m);
        assert_eq!(blocks, vec![block(&[0, 1], &[2, 0]), block(&[2], &[1])]);
    }

    #[test]
    fn unmatched_equations_and_known_vars_are_skipped() {
        let mut g = BipartiteGraph::new(3);
        g.add_equation(vec![0, 2]); // x2 known (unmatched)
        g.add_equation(vec![0]); // redundant, unmatched
        g.add_equation(vec![0, 1]);
        let m = maximum_matching(&g, Some(&[true, true, false]), None);
        assert_eq!(m.eq_to_var, vec![Some(0), None, Some(1)]);
        let blocks = blt(&g, &m);
        assert_eq!(blocks, vec![block(&[0], &[0]), block(&[2], &[1])]);
    }

    #[test]
    fn long_chain_does_not_overflow() {
        // e_i: x_i = f(x_{i+1}), e_{n-1}: x_{n-1} = c. The DFS from e0 goes n deep.
        let n = 200_000;
        let mut g = BipartiteGraph::new(n);
        for i in 0..n - 1 {
            g.add_equation(vec![i, i + 1]);
        }
        g.add_equation(vec![n - 1]);
        let m = maximum_matching(&g, None, None);
        assert!(m.is_perfect());
        let blocks = blt(&g, &m);
        assert_eq!(blocks.len(), n);
        assert!(
            blocks
                .iter()
                .enumerate()
                .all(|(k, b)| b.eqs == [n - 1 - k] && b.vars == [n - 1 - k])
        );
        check_order(&g, &m, &blocks);

        // One big cycle: e_i contains x_i and x_{i+1 mod n}; matched e_i <-> x_i.
        let mut g = BipartiteGraph::new(n);
        for i in 0..n {
            g.add_equation(vec![i, (i + 1) % n]);
        }
        let m = Matching {
            eq_to_var: (0..n).map(Some).collect(),
            var_to_eq: (0..n).map(Some).collect(),
        };
        let blocks = blt(&g, &m);
        assert_eq!(blocks.len(), 1);
        assert_eq!(blocks[0].eqs.len(), n);
        check_order(&g, &m, &blocks);
    }
}
