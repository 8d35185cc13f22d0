//! Substitution, leaf sets and copying between arenas.

use crate::hash::{HashMap, HashSet};

use std::cell::RefCell;

use super::{Arena, Id, Node, NodeMap, NodeTable, is_leaf};

/// Work stacks of substitution: the rebuilt operands of the sums and products being
/// rebuilt, one above the other (kept in the arena to reuse their allocations).
#[derive(Debug, Default)]
pub(crate) struct SubstWork {
    terms: Vec<(f64, Id)>,
    factors: Vec<(Id, i32)>,
    powers: Vec<Id>,
}

thread_local! {
    /// The stack and scan list of [`Arena::walk`], reused from walk to walk.
    static WALK_BUFFERS: RefCell<(Vec<Id>, Vec<Id>)> =
        const { RefCell::new((Vec::new(), Vec::new())) };
}

impl Arena {
    /// Rebuilds `e` through the simplifying constructors after replacing every node found
    /// in `map` (usually leaves). A replaced `x` also replaces `der(x)` by the time
    /// derivative of its image, unless `der(x)` has an entry of its own.
    pub fn substitute(&mut self, e: Id, map: &HashMap<Id, Id>) -> Id {
        let mut memo = HashMap::default();
        self.subst_entry(e, map, &mut memo, false)
    }

    /// Like [`Arena::substitute`], but `der(x)` nodes are leaves of their own: they are
    /// replaced only by an entry of their own, never through `x` (as in an index-reduced
    /// system, where `x` and `der(x)` are distinct unknowns).
    pub fn substitute_leaves(&mut self, e: Id, map: &HashMap<Id, Id>) -> Id {
        let mut memo = HashMap::default();
        self.subst_entry(e, map, &mut memo, true)
    }

    /// [`Arena::substitute_leaves`] with a memo shared across calls. The map and the
    /// memo may be hash maps or dense [`NodeMap`]s (better when large).
    pub fn substitute_leaves_memo(
        &mut self,
        e: Id,
        map: &impl NodeTable,
        memo: &mut impl NodeTable,
    ) -> Id {
        self.subst_entry(e, map, memo, true)
    }

    /// [`Arena::substitute`] with a memo shared across calls (for many expressions
    /// under one map). The map and the memo may be hash maps or dense [`NodeMap`]s
    /// (better when large).
    pub fn substitute_memo(
        &mut self,
        e: Id,
        map: &impl NodeTable,
        memo: &mut impl NodeTable,
    ) -> Id {
        self.subst_entry(e, map, memo, false)
    }

    /// Runs the substitution with the arena's work space (taken for the call).
    fn subst_entry<M: NodeTable, T: NodeTable>(
        &mut self,
        e: Id,
        map: &M,
        memo: &mut T,
        opaque: bool,
    ) -> Id {
        let mut work = std::mem::take(&mut self.subst_work);
        let r = self.subst_rec(e, map, memo, opaque, &mut work);
        self.subst_work = work;
        r
    }

    fn subst_rec<M: NodeTable, T: NodeTable>(
        &mut self,
        e: Id,
        map: &M,
        memo: &mut T,
        opaque: bool,
        work: &mut SubstWork,
    ) -> Id {
        if let Some(r) = map.get(e) {
            return r;
        }
        match self.node(e) {
            Node::Const(_) | Node::Var(_) | Node::Param(_) | Node::Time => return e,
            Node::Der(_) if opaque => return e,
            _ => {}
        }
        if let Some(r) = memo.get(e) {
            return r;
        }
        // Children are read by position: nothing is copied.
        let r = match *self.node(e) {
            Node::Const(_) | Node::Var(_) | Node::Param(_) | Node::Time => e,
            Node::Der(x) => {
                let nx = self.subst_rec(x, map, memo, opaque, work);
                if nx == x { e } else { self.der(nx) }
            }
            Node::Sum(ts, c) => {
                // New terms go on the work stack above those of the sums being
                // rebuilt around this one.
                let base = work.terms.len();
                let mut changed = false;
                for i in 0..ts.len() {
                    // The range stays valid while the pools grow.
                    let (k, t) = self.terms(ts)[i];
                    let nt = self.subst_rec(t, map, memo, opaque, work);
                    changed |= nt != t;
                    work.terms.push((f64::from_bits(k), nt));
                }
                let r = if changed {
                    self.linear_combination(f64::from_bits(c), &work.terms[base..])
                } else {
                    e
                };
                work.terms.truncate(base);
                r
            }
            Node::Prod(fs) => {
                let base = work.factors.len();
                let mut changed = false;
                for i in 0..fs.len() {
                    let (b, n) = self.factors(fs)[i];
                    let nb = self.subst_rec(b, map, memo, opaque, work);
                    changed |= nb != b;
                    work.factors.push((nb, n));
                }
                let r = if changed {
                    let powers = work.powers.len();
                    for j in base..work.factors.len() {
                        let (b, n) = work.factors[j];
                        let p = self.powi(b, n);
                        work.powers.push(p);
                    }
                    let r = self.product(&work.powers[powers..]);
                    work.powers.truncate(powers);
                    r
                } else {
                    e
                };
                work.factors.truncate(base);
                r
            }
            Node::Pow(a, b) => {
                let (na, nb) = (
                    self.subst_rec(a, map, memo, opaque, work),
                    self.subst_rec(b, map, memo, opaque, work),
                );
                self.pow(na, nb)
            }
            Node::F1(f, a) => {
                let na = self.subst_rec(a, map, memo, opaque, work);
                self.f1(f, na)
            }
            Node::F2(f, a, b) => {
                let (na, nb) = (
                    self.subst_rec(a, map, memo, opaque, work),
                    self.subst_rec(b, map, memo, opaque, work),
                );
                self.f2(f, na, nb)
            }
            Node::Cmp(op, a, b) => {
                let (na, nb) = (
                    self.subst_rec(a, map, memo, opaque, work),
                    self.subst_rec(b, map, memo, opaque, work),
                );
                self.cmp(op, na, nb)
            }
            Node::If(c, a, b) => {
                let nc = self.subst_rec(c, map, memo, opaque, work);
                let na = self.subst_rec(a, map, memo, opaque, work);
                let nb = self.subst_rec(b, map, memo, opaque, work);
                self.ite(nc, na, nb)
            }
        };
        memo.insert(e, r);
        r
    }

    /// The distinct leaves of `e` (variables, parameters, time, derivatives), sorted.
    /// `der(x)` is a leaf of its own; `x` is not listed for it.
    pub fn leaves(&self, e: Id) -> Vec<Id> {
        let mut out = Vec::new();
        self.leaves_into(e, &mut out);
        out
    }

    /// [`Arena::leaves`] into `out` (cleared first), for callers that reuse one buffer.
    pub fn leaves_into(&self, e: Id, out: &mut Vec<Id>) {
        out.clear();
        self.walk(e, &mut |x, n| {
            if is_leaf(n) {
                out.push(x);
                false
            } else {
                true
            }
        });
        out.sort_unstable();
        out.dedup();
    }

    /// Whether `leaf` occurs in `e`.
    pub fn contains(&self, e: Id, leaf: Id) -> bool {
        let mut found = false;
        self.walk(e, &mut |x, n| {
            found |= x == leaf;
            !found && !is_leaf(n)
        });
        found
    }

    /// Whether any of `leaves` occurs in `e`.
    pub fn contains_any(&self, e: Id, leaves: &HashSet<Id>) -> bool {
        let mut found = false;
        self.walk(e, &mut |x, n| {
            found |= leaves.contains(&x);
            !found && !is_leaf(n)
        });
        found
    }

    /// For every node of the arena (by id), whether it is one of `keys` or contains one:
    /// one pass in the order of the ids, since a node's operands are always older than
    /// the node. Cheaper than [`Arena::contains_any`] on each of many expressions when
    /// they cover much of the arena.
    pub fn containing(&self, keys: impl Iterator<Item = Id>) -> Vec<bool> {
        let n = self.len();
        let mut mark = vec![false; n];
        let mut first = n;
        for k in keys {
            mark[k.index()] = true;
            first = first.min(k.index());
        }
        let mut children = Vec::new();
        for i in first..n {
            if mark[i] {
                continue;
            }
            children.clear();
            self.push_children(Id(i as u32), &mut children);
            mark[i] = children.iter().any(|c| mark[c.index()]);
        }
        mark
    }

    /// Visits each distinct node of `e` once (depth first); `visit` returns whether to
    /// descend into the node's operands. Small expressions are deduplicated by a linear
    /// scan, larger ones by a hash set. The stack and the scan list are buffers kept per
    /// thread, so the common case allocates nothing (a walk started from inside `visit`
    /// gets buffers of its own).
    pub(crate) fn walk(&self, e: Id, visit: &mut dyn FnMut(Id, &Node) -> bool) {
        WALK_BUFFERS.with(|cell| match cell.try_borrow_mut() {
            Ok(mut buffers) => {
                let (stack, seen) = &mut *buffers;
                self.walk_with(e, visit, stack, seen);
            }
            Err(_) => self.walk_with(e, visit, &mut Vec::new(), &mut Vec::new()),
        });
    }

    fn walk_with(
        &self,
        e: Id,
        visit: &mut dyn FnMut(Id, &Node) -> bool,
        stack: &mut Vec<Id>,
        seen_small: &mut Vec<Id>,
    ) {
        const SMALL: usize = 48;
        stack.clear();
        seen_small.clear();
        stack.push(e);
        let mut seen_large: Option<HashSet<Id>> = None;
        while let Some(x) = stack.pop() {
            let new = match &mut seen_large {
                Some(set) => set.insert(x),
                None => {
                    if seen_small.contains(&x) {
                        false
                    } else if seen_small.len() < SMALL {
                        seen_small.push(x);
                        true
                    } else {
                        let mut set: HashSet<Id> = seen_small.drain(..).collect();
                        set.insert(x);
                        seen_large = Some(set);
                        true
                    }
                }
            };
            if !new {
                continue;
            }
            if visit(x, self.node(x)) {
                self.push_children(x, stack);
            }
        }
    }

    /// Copies `e` from `src` into this arena; `leaf` maps each leaf node of `src`
    /// (variables, parameters, time; never `der`, which is rebuilt from its argument) to a
    /// node of this arena. `memo` is shared across calls so common subexpressions are
    /// copied once.
    pub fn import(
        &mut self,
        src: &Arena,
        e: Id,
        leaf: &mut dyn FnMut(&mut Arena, &Node) -> Id,
        memo: &mut NodeMap,
    ) -> Id {
        if let Some(r) = memo.get(e) {
            return r;
        }
        let r = match src.node(e) {
            Node::Const(b) => self.constant(f64::from_bits(*b)),
            n @ (Node::Var(_) | Node::Param(_) | Node::Time) => leaf(self, n),
            Node::Der(x) => {
                let nx = self.import(src, *x, leaf, memo);
                self.der(nx)
            }
            Node::Sum(ts, c) => {
                let terms: Vec<(f64, Id)> = src
                    .terms(*ts)
                    .iter()
                    .map(|&(k, t)| (f64::from_bits(k), self.import(src, t, leaf, memo)))
                    .collect();
                self.linear_combination(f64::from_bits(*c), &terms)
            }
            Node::Prod(fs) => {
                let ps: Vec<Id> = src
                    .factors(*fs)
                    .iter()
                    .map(|&(b, n)| {
                        let nb = self.import(src, b, leaf, memo);
                        self.powi(nb, n)
                    })
                    .collect();
                self.product(&ps)
            }
            Node::Pow(a, b) => {
                let na = self.import(src, *a, leaf, memo);
                let nb = self.import(src, *b, leaf, memo);
                self.pow(na, nb)
            }
            Node::F1(f, a) => {
                let na = self.import(src, *a, leaf, memo);
                self.f1(*f, na)
            }
            Node::F2(f, a, b) => {
                let na = self.import(src, *a, leaf, memo);
                let nb = self.import(src, *b, leaf, memo);
                self.f2(*f, na, nb)
            }
            Node::Cmp(op, a, b) => {
                let na = self.import(src, *a, leaf, memo);
                let nb = self.import(src, *b, leaf, memo);
                self.cmp(*op, na, nb)
            }
            Node::If(c, a, b) => {
                let nc = self.import(src, *c, leaf, memo);
                let na = self.import(src, *a, leaf, memo);
                let nb = self.import(src, *b, leaf, memo);
                self.ite(nc, na, nb)
            }
        };
        memo.insert(e, r);
        r
    }
}
