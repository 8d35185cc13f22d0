//! The arena: node storage, hash-consing and simplification on construction.

use std::hash::BuildHasher;
use std::sync::Arc;

use hashbrown::HashTable;

use crate::hash::anchored_hash;

use super::{Cmp, Func1, Func2, Id, Node, Operands};

/// Hash-consed expression storage. Every constructor simplifies: constants fold,
/// neutral elements vanish, sums and products are flattened and ordered, and like terms
/// and like factors are collected.
///
/// An arena can extend a shared, frozen one ([`Arena::extending`]): the base's nodes
/// keep their ids and are read where they are, so a problem built on a compiled model
/// (its initialization) adds its own nodes without copying the model's.
#[derive(Debug)]
pub struct Arena {
    /// The frozen arena this one extends, whose nodes are the ids below `base_nodes`
    /// and whose pools are the operand indices below `base_terms` and `base_factors`.
    base: Option<Arc<Arena>>,
    /// Number of nodes of `base` (0 without one).
    base_nodes: usize,
    /// Entries of the term pool of `base`.
    base_terms: usize,
    /// Entries of the factor pool of `base`.
    base_factors: usize,
    /// The nodes of this arena: node `base_nodes + k` is `nodes[k]`.
    nodes: Vec<Node>,
    /// The terms of every sum node, each node's a contiguous range (offset by
    /// `base_terms`).
    term_pool: Vec<(u64, Id)>,
    /// The factors of every product node, each node's a contiguous range (offset by
    /// `base_factors`).
    factor_pool: Vec<(Id, i32)>,
    /// Node ids, placed by their newest operand ([`crate::hash::anchored_hash`]: work
    /// on one part of a large model finds its entries in cache; equal nodes have equal
    /// operands, so they still meet), each with its hash ([`TableEntry`]). Every node
    /// except the leaves with a direct index below is stored once, in `nodes`, and
    /// found here (or in the base's table, for the base's nodes).
    table: HashTable<TableEntry>,
    /// Direct index of the leaves `Var(i)` and `der(Var(i))` (`u32::MAX` when absent):
    /// their only index (they never enter the table).
    var_leaf: Vec<[u32; 2]>,
    /// Direct index of the leaves `Param(i)` (`u32::MAX` when absent), their only
    /// index.
    param_leaf: Vec<u32>,
    /// Work space of `linear_combination` (kept to reuse its allocations: small
    /// allocations freed by the million make the allocator slow on large models).
    combine_terms: Vec<(Id, f64)>,
    /// The merged terms of `linear_combination`.
    combine_merged: Vec<(u64, Id)>,
    /// Work stacks of substitution.
    pub(super) subst_work: super::subst::SubstWork,
}

/// Hash of a node of `arena` by content (the operands of sums and products, not their
/// ranges).
fn hash_node(n: &Node, arena: &Arena) -> u64 {
    let b = crate::hash::FastBuild::default();
    match *n {
        Node::Sum(ts, c) => b.hash_one((0u8, arena.terms(ts), c)),
        Node::Prod(fs) => b.hash_one((1u8, arena.factors(fs))),
        _ => b.hash_one(n),
    }
}

impl Clone for Arena {
    /// A copy (work spaces start empty); a base is shared, not copied.
    fn clone(&self) -> Self {
        Arena {
            base: self.base.clone(),
            base_nodes: self.base_nodes,
            base_terms: self.base_terms,
            base_factors: self.base_factors,
            nodes: self.nodes.clone(),
            term_pool: self.term_pool.clone(),
            factor_pool: self.factor_pool.clone(),
            table: self.table.clone(),
            var_leaf: self.var_leaf.clone(),
            param_leaf: self.param_leaf.clone(),
            combine_terms: Vec::new(),
            combine_merged: Vec::new(),
            subst_work: Default::default(),
        }
    }
}

impl Arena {
    /// An empty arena on top of `base`: every node of `base` is a node of the new
    /// arena with the same id, read in `base` (not copied), and new nodes are added
    /// after them. Building it costs only the direct indexes of the leaves. Bases are
    /// never chained: when `base` extends an arena itself, a standalone copy of it
    /// (the same nodes under the same ids) becomes the base.
    pub fn extending(base: Arc<Arena>) -> Arena {
        let base = match &base.base {
            None => base,
            Some(_) => Arc::new(base.as_ref().clone().into_standalone()),
        };
        Arena {
            base_nodes: base.len(),
            base_terms: base.term_pool.len(),
            base_factors: base.factor_pool.len(),
            nodes: Vec::new(),
            term_pool: Vec::new(),
            factor_pool: Vec::new(),
            table: HashTable::new(),
            var_leaf: base.var_leaf.clone(),
            param_leaf: base.param_leaf.clone(),
            combine_terms: Vec::new(),
            combine_merged: Vec::new(),
            subst_work: Default::default(),
            base: Some(base),
        }
    }

    /// This arena with its base's storage copied in: the same nodes under the same
    /// ids, and no base.
    fn into_standalone(self) -> Arena {
        let Some(base) = &self.base else {
            return self;
        };
        // A base extends no other arena, so its copy has none either.
        let mut out = base.as_ref().clone();
        out.nodes.extend_from_slice(&self.nodes);
        out.term_pool.extend_from_slice(&self.term_pool);
        out.factor_pool.extend_from_slice(&self.factor_pool);
        for e in &self.table {
            out.table.insert_unique(e.hash(), *e, TableEntry::hash);
        }
        out.var_leaf = self.var_leaf;
        out.param_leaf = self.param_leaf;
        out
    }
}

impl Default for Arena {
    fn default() -> Self {
        Self::new()
    }
}

/// An entry of the arena's table: a node id with its whole hash, so that growing the
/// table re-reads no node (a large model's nodes and pools are read in random order
/// otherwise).
#[derive(Clone, Copy, Debug)]
struct TableEntry {
    id: u32,
    /// High half of the node's content hash (also the high half of the table hash).
    high: u32,
    /// Low half of the table hash ([`crate::hash::anchored_hash`]).
    low: u32,
}

impl TableEntry {
    fn hash(&self) -> u64 {
        (u64::from(self.high) << 32) | u64::from(self.low)
    }
}

/// The operand with the largest id (the newest), for a node of `arena` that has
/// operands.
fn newest_operand(n: &Node, arena: &Arena) -> Option<u32> {
    let id = match *n {
        Node::Const(_) | Node::Var(_) | Node::Param(_) | Node::Time => return None,
        Node::Der(a) | Node::F1(_, a) => a,
        Node::Pow(a, b) | Node::F2(_, a, b) | Node::Cmp(_, a, b) => a.max(b),
        Node::If(c, a, b) => c.max(a).max(b),
        Node::Sum(ts, _) => arena.terms(ts).iter().map(|&(_, t)| t).max()?,
        Node::Prod(fs) => arena.factors(fs).iter().map(|&(b, _)| b).max()?,
    };
    Some(id.0)
}

/// Entry `i` of a direct index, growing it (doubling, filled with `empty`) when short.
fn grow_to<T: Copy>(v: &mut Vec<T>, i: u32, empty: T) -> &mut T {
    let i = i as usize;
    if v.len() <= i {
        v.resize((i + 1).max(2 * v.len()), empty);
    }
    &mut v[i]
}

/// Appends `items` to `pool`, whose first entry is operand `offset`: the operands of a
/// new sum or product.
fn append<T: Copy>(pool: &mut Vec<T>, offset: usize, items: &[T]) -> Operands {
    let start = offset + pool.len();
    pool.extend_from_slice(items);
    Operands::new(start, items.len())
}

/// Integer value of `x` if it is one that fits an exponent.
fn as_exponent(x: f64) -> Option<i32> {
    if x.fract() == 0.0 && x.abs() <= 1024.0 {
        Some(x as i32)
    } else {
        None
    }
}

impl Arena {
    /// An empty arena.
    pub fn new() -> Self {
        let mut a = Arena {
            base: None,
            base_nodes: 0,
            base_terms: 0,
            base_factors: 0,
            nodes: Vec::new(),
            term_pool: Vec::new(),
            factor_pool: Vec::new(),
            table: HashTable::new(),
            var_leaf: Vec::new(),
            param_leaf: Vec::new(),
            combine_terms: Vec::new(),
            combine_merged: Vec::new(),
            subst_work: Default::default(),
        };
        a.constant(0.0);
        a.constant(1.0);
        a
    }

    /// Room for parameter leaves up to `parameters` and for `expressions` more nodes,
    /// so that adding many does not copy and rehash the growing storage again and
    /// again (an estimate: more are added as needed; an unused vector capacity costs
    /// address space only).
    pub fn reserve(&mut self, parameters: usize, expressions: usize) {
        self.nodes.reserve(expressions);
        self.term_pool.reserve(expressions);
        self.factor_pool.reserve(expressions / 2);
        self.table.reserve(expressions, TableEntry::hash);
        if self.param_leaf.len() < parameters {
            self.param_leaf.resize(parameters, u32::MAX);
        }
    }

    /// The node behind `id`.
    #[inline]
    pub fn node(&self, id: Id) -> &Node {
        let i = id.index();
        if i >= self.base_nodes {
            return &self.nodes[i - self.base_nodes];
        }
        &self.base().nodes[i]
    }

    /// The terms `(coefficient bits, term)` of a sum node.
    #[inline]
    pub fn terms(&self, ts: Operands) -> &[(u64, Id)] {
        self.operands(ts, &self.term_pool, self.base_terms, |b| &b.term_pool)
    }

    /// The factors `(base, exponent)` of a product node.
    #[inline]
    pub fn factors(&self, fs: Operands) -> &[(Id, i32)] {
        self.operands(fs, &self.factor_pool, self.base_factors, |b| &b.factor_pool)
    }

    /// The range `ops` of a pool whose entries below `offset` are the base's
    /// (`base_pool`) and the others `own[k - offset]`.
    #[inline]
    fn operands<'a, T>(
        &'a self,
        ops: Operands,
        own: &'a [T],
        offset: usize,
        base_pool: impl FnOnce(&'a Arena) -> &'a [T],
    ) -> &'a [T] {
        let start = ops.start();
        match start.checked_sub(offset) {
            Some(k) => &own[k..k + ops.len()],
            None => &base_pool(self.base())[start..start + ops.len()],
        }
    }

    /// The arena this one extends (only asked for ids and operands below its sizes,
    /// which exist only when there is one; it extends no other).
    #[inline]
    fn base(&self) -> &Arena {
        match &self.base {
            Some(base) => base,
            None => unreachable!("only an extending arena has ids below its own"),
        }
    }

    /// Entries of the term and factor pools (tests check that equal nodes share them).
    #[cfg(test)]
    pub(crate) fn pool_lens(&self) -> (usize, usize) {
        (self.term_pool.len(), self.factor_pool.len())
    }

    /// Number of distinct nodes (a base's included).
    pub fn len(&self) -> usize {
        self.base_nodes + self.nodes.len()
    }

    /// Whether any node of the arena is a comparison (one scan of the nodes).
    pub(crate) fn has_comparison(&self) -> bool {
        (0..self.len()).any(|i| matches!(self.node(Id(i as u32)), Node::Cmp(..)))
    }

    /// Whether any node of the arena is `pre(x)` (one scan of the nodes).
    pub(crate) fn has_pre(&self) -> bool {
        (0..self.len()).any(|i| matches!(self.node(Id(i as u32)), Node::F1(super::Func1::Pre, _)))
    }

    /// Whether the arena holds no node (never true: 0 and 1 always exist).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn intern(&mut self, n: Node) -> Id {
        match n {
            Node::Var(i) => return self.var(i),
            Node::Param(i) => return self.param(i),
            Node::Der(x) => {
                if let Node::Var(i) = *self.node(x) {
                    return self.der_var(i, x);
                }
            }
            _ => {}
        }
        self.intern_hashed(n)
    }

    /// `der(x)` for `x = Var(i)`, through the direct index.
    fn der_var(&mut self, i: u32, x: Id) -> Id {
        let slot = self.var_leaf.get(i as usize).map_or(u32::MAX, |s| s[1]);
        if slot != u32::MAX {
            return Id(slot);
        }
        let id = self.push_node(Node::Der(x));
        self.leaf_slot(i)[1] = id.0;
        id
    }

    fn leaf_slot(&mut self, i: u32) -> &mut [u32; 2] {
        grow_to(&mut self.var_leaf, i, [u32::MAX; 2])
    }

    /// A sum node with these terms (already sorted and merged).
    fn intern_sum(&mut self, terms: &[(u64, Id)], c: u64) -> Id {
        let ts = append(&mut self.term_pool, self.base_terms, terms);
        self.intern_hashed(Node::Sum(ts, c))
    }

    /// A product node with these factors (already sorted and merged).
    fn intern_product(&mut self, factors: &[(Id, i32)]) -> Id {
        let fs = append(&mut self.factor_pool, self.base_factors, factors);
        self.intern_hashed(Node::Prod(fs))
    }

    /// The node `n`, stored unless an equal one exists. A sum or product candidate has
    /// its operands appended at the end of its pool; they are given back when an equal
    /// node already holds them. Never called for `Var`, `Param` or `der(Var)`: those
    /// are found through their direct indexes only.
    fn intern_hashed(&mut self, n: Node) -> Id {
        debug_assert!(
            !matches!(n, Node::Var(_) | Node::Param(_))
                && !matches!(n, Node::Der(x) if matches!(self.node(x), Node::Var(_))),
            "leaves with a direct index never enter the table"
        );
        let high = (hash_node(&n, self) >> 32) as u32;
        let newest = newest_operand(&n, self);
        let h = anchored_hash(newest, high);
        // Equal by content: the operands of a stored sum or product are compared, not
        // its range in the pool.
        let same = |e: &TableEntry| {
            e.high == high
                && match (*self.node(Id(e.id)), n) {
                    (Node::Sum(a, ca), Node::Sum(b, cb)) => {
                        ca == cb && self.terms(a) == self.terms(b)
                    }
                    (Node::Prod(a), Node::Prod(b)) => self.factors(a) == self.factors(b),
                    (stored, n) => stored == n,
                }
        };
        // A node with an operand newer than the base cannot be in the base.
        let maybe_in_base = newest.is_none_or(|k| (k as usize) < self.base_nodes);
        if let Some(id) = self.find(h, maybe_in_base, same) {
            match n {
                Node::Sum(ts, _) => self.term_pool.truncate(ts.start() - self.base_terms),
                Node::Prod(fs) => self.factor_pool.truncate(fs.start() - self.base_factors),
                _ => {}
            }
            return Id(id);
        }
        let id = self.push_node(n);
        let entry = TableEntry {
            id: id.0,
            high,
            low: h as u32,
        };
        self.table.insert_unique(h, entry, TableEntry::hash);
        id
    }

    /// The id of the node in this arena's table (or its base's, when `in_base` says it
    /// may be there) with hash `h` that `same` accepts.
    fn find(&self, h: u64, in_base: bool, same: impl Fn(&TableEntry) -> bool) -> Option<u32> {
        // A base extends no other arena: its own table holds all its nodes.
        if in_base
            && let Some(base) = &self.base
            && let Some(e) = base.table.find(h, &same)
        {
            return Some(e.id);
        }
        self.table.find(h, same).map(|e| e.id)
    }

    /// Stores `n` as a new node, without entering it in the table (the caller does
    /// that, or records a leaf in its direct index).
    fn push_node(&mut self, n: Node) -> Id {
        let id = self.len() as u32;
        self.nodes.push(n);
        Id(id)
    }

    /// The constant 0.
    pub fn zero(&self) -> Id {
        Id(0)
    }

    /// The constant 1.
    pub fn one(&self) -> Id {
        Id(1)
    }

    /// A numeric constant (`-0.0` is stored as `0.0`).
    pub fn constant(&mut self, c: f64) -> Id {
        let c = if c == 0.0 { 0.0 } else { c };
        self.intern(Node::Const(c.to_bits()))
    }

    /// The value of a constant node.
    pub fn as_const(&self, id: Id) -> Option<f64> {
        match self.node(id) {
            Node::Const(b) => Some(f64::from_bits(*b)),
            _ => None,
        }
    }

    /// A variable leaf.
    pub fn var(&mut self, i: u32) -> Id {
        let slot = self.var_leaf.get(i as usize).map_or(u32::MAX, |s| s[0]);
        if slot != u32::MAX {
            return Id(slot);
        }
        let id = self.push_node(Node::Var(i));
        self.leaf_slot(i)[0] = id.0;
        id
    }

    /// A parameter leaf.
    pub fn param(&mut self, i: u32) -> Id {
        let k = i as usize;
        if let Some(&slot) = self.param_leaf.get(k)
            && slot != u32::MAX
        {
            return Id(slot);
        }
        let id = self.push_node(Node::Param(i));
        *grow_to(&mut self.param_leaf, i, u32::MAX) = id.0;
        id
    }

    /// Time.
    pub fn time(&mut self) -> Id {
        self.intern(Node::Time)
    }

    /// Time derivative. For a variable (or a derivative of one) this is the leaf
    /// `der(x)`; for any other expression it is computed symbolically.
    pub fn der(&mut self, x: Id) -> Id {
        match self.node(x) {
            Node::Var(_) | Node::Der(_) => self.intern(Node::Der(x)),
            _ => self.time_derivative(x),
        }
    }

    /// `sum(coefficient * term) + constant`, simplified.
    pub fn linear_combination(&mut self, constant: f64, terms: &[(f64, Id)]) -> Id {
        let mut acc = std::mem::take(&mut self.combine_terms);
        let mut merged = std::mem::take(&mut self.combine_merged);
        acc.clear();
        merged.clear();
        let mut c0 = constant;
        for &(k, t) in terms {
            if k == 0.0 {
                continue;
            }
            match self.node(t) {
                Node::Const(b) => c0 += k * f64::from_bits(*b),
                Node::Sum(ts, c) => {
                    c0 += k * f64::from_bits(*c);
                    for &(kk, tt) in self.terms(*ts) {
                        acc.push((tt, k * f64::from_bits(kk)));
                    }
                }
                _ => acc.push((t, k)),
            }
        }
        acc.sort_by_key(|&(id, _)| id);
        let mut i = 0;
        while i < acc.len() {
            let id = acc[i].0;
            let mut k = 0.0;
            while i < acc.len() && acc[i].0 == id {
                k += acc[i].1;
                i += 1;
            }
            if k != 0.0 {
                merged.push((k.to_bits(), id));
            }
        }
        let result = if merged.is_empty() {
            self.constant(c0)
        } else if merged.len() == 1 && c0 == 0.0 && f64::from_bits(merged[0].0) == 1.0 {
            merged[0].1
        } else {
            let c0 = if c0 == 0.0 { 0.0 } else { c0 };
            self.intern_sum(&merged, c0.to_bits())
        };
        self.combine_terms = acc;
        self.combine_merged = merged;
        result
    }

    /// `a + b`.
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        self.linear_combination(0.0, &[(1.0, a), (1.0, b)])
    }

    /// Sum of several expressions.
    pub fn sum(&mut self, terms: &[Id]) -> Id {
        let t: Vec<(f64, Id)> = terms.iter().map(|&x| (1.0, x)).collect();
        self.linear_combination(0.0, &t)
    }

    /// `a - b`.
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        self.linear_combination(0.0, &[(1.0, a), (-1.0, b)])
    }

    /// `-a`.
    pub fn neg(&mut self, a: Id) -> Id {
        self.linear_combination(0.0, &[(-1.0, a)])
    }

    /// `k * a`.
    pub fn scale(&mut self, k: f64, a: Id) -> Id {
        self.linear_combination(0.0, &[(k, a)])
    }

    /// Splits a factor into a numeric coefficient and `(base, exponent)` pairs.
    fn factor_parts(&self, x: Id, out: &mut Vec<(Id, i32)>) -> f64 {
        match self.node(x) {
            Node::Const(b) => f64::from_bits(*b),
            Node::Sum(ts, c) if ts.len() == 1 && f64::from_bits(*c) == 0.0 => {
                let (k, t) = self.terms(*ts)[0];
                let k = f64::from_bits(k);
                match self.node(t) {
                    Node::Prod(fs) => out.extend_from_slice(self.factors(*fs)),
                    _ => out.push((t, 1)),
                }
                k
            }
            Node::Prod(fs) => {
                out.extend_from_slice(self.factors(*fs));
                1.0
            }
            _ => {
                out.push((x, 1));
                1.0
            }
        }
    }

    /// Builds `coefficient * product(base ^ exponent)` from unsorted factors.
    fn build_product(&mut self, coef: f64, mut fs: Vec<(Id, i32)>) -> Id {
        if coef == 0.0 {
            return self.zero();
        }
        fs.sort_by_key(|&(id, _)| id);
        let mut merged: Vec<(Id, i32)> = Vec::with_capacity(fs.len());
        for (b, e) in fs {
            match merged.last_mut() {
                Some((lb, le)) if *lb == b => *le += e,
                _ => merged.push((b, e)),
            }
        }
        merged.retain(|&(_, e)| e != 0);
        let core = match merged.len() {
            0 => return self.constant(coef),
            1 if merged[0].1 == 1 => merged[0].0,
            _ => self.intern_product(&merged),
        };
        if coef == 1.0 {
            core
        } else {
            self.linear_combination(0.0, &[(coef, core)])
        }
    }

    /// Product of several expressions.
    pub fn product(&mut self, factors: &[Id]) -> Id {
        let mut fs = Vec::with_capacity(factors.len() + 2);
        let mut coef = 1.0;
        for &f in factors {
            coef *= self.factor_parts(f, &mut fs);
        }
        self.build_product(coef, fs)
    }

    /// `a * b`.
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        if let Some(k) = self.as_const(a) {
            return self.scale(k, b);
        }
        if let Some(k) = self.as_const(b) {
            return self.scale(k, a);
        }
        self.product(&[a, b])
    }

    /// `a / b`.
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        if let Some(k) = self.as_const(b) {
            return self.scale(1.0 / k, a);
        }
        let inv = self.powi(b, -1);
        self.mul(a, inv)
    }

    /// `a ^ n` for an integer `n`.
    pub fn powi(&mut self, a: Id, n: i32) -> Id {
        if n == 0 {
            return self.one();
        }
        if n == 1 {
            return a;
        }
        if let Some(c) = self.as_const(a) {
            return self.constant(c.powi(n));
        }
        let mut fs = Vec::new();
        let coef = match self.node(a) {
            Node::Sum(ts, c) if ts.len() == 1 && f64::from_bits(*c) == 0.0 => {
                self.factor_parts(a, &mut fs)
            }
            Node::Prod(_) => self.factor_parts(a, &mut fs),
            _ => {
                fs.push((a, 1));
                1.0
            }
        };
        for f in fs.iter_mut() {
            f.1 *= n;
        }
        self.build_product(coef.powi(n), fs)
    }

    /// `a ^ b`.
    pub fn pow(&mut self, a: Id, b: Id) -> Id {
        if let Some(e) = self.as_const(b) {
            if let Some(n) = as_exponent(e) {
                return self.powi(a, n);
            }
            if let Some(c) = self.as_const(a) {
                return self.constant(c.powf(e));
            }
        }
        if let Some(1.0) = self.as_const(a) {
            return self.one();
        }
        self.intern(Node::Pow(a, b))
    }

    /// A unary function, folded when its argument is constant.
    pub fn f1(&mut self, f: Func1, a: Id) -> Id {
        if let Some(c) = self.as_const(a) {
            return self.constant(f.apply(c));
        }
        if let (Func1::Sqrt, Node::Prod(fs)) = (f, *self.node(a))
            && let [(base, 2)] = *self.factors(fs)
        {
            return self.f1(Func1::Abs, base);
        }
        if f == Func1::NoEvent
            && matches!(
                self.node(a),
                Node::Var(_)
                    | Node::Param(_)
                    | Node::Time
                    | Node::Der(_)
                    | Node::F1(Func1::NoEvent, _)
            )
        {
            // Nothing below that could have an event.
            return a;
        }
        self.intern(Node::F1(f, a))
    }

    /// A binary function, folded when both arguments are constant.
    pub fn f2(&mut self, f: Func2, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(f.apply(x, y));
        }
        if a == b && f != Func2::Atan2 {
            return a;
        }
        self.intern(Node::F2(f, a, b))
    }

    /// A comparison (1.0 when true), folded when both sides are constant.
    pub fn cmp(&mut self, op: Cmp, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(op.apply(x, y));
        }
        self.intern(Node::Cmp(op, a, b))
    }

    /// `if cond != 0 then a else b`, folded when the condition is constant or both
    /// branches are equal.
    pub fn ite(&mut self, cond: Id, a: Id, b: Id) -> Id {
        if let Some(c) = self.as_const(cond) {
            return if c != 0.0 { a } else { b };
        }
        if a == b {
            return a;
        }
        self.intern(Node::If(cond, a, b))
    }

    /// Logical and of two conditions (values 0 or 1).
    pub fn and(&mut self, a: Id, b: Id) -> Id {
        let zero = self.zero();
        self.ite(a, b, zero)
    }

    /// Logical or of two conditions (values 0 or 1).
    pub fn or(&mut self, a: Id, b: Id) -> Id {
        let one = self.one();
        self.ite(a, one, b)
    }

    /// Logical not of a condition (value 0 or 1).
    pub fn not(&mut self, a: Id) -> Id {
        let zero = self.zero();
        let one = self.one();
        self.ite(a, zero, one)
    }

    /// The children of a node, in order.
    pub fn children(&self, id: Id) -> Vec<Id> {
        let mut out = Vec::new();
        self.push_children(id, &mut out);
        out
    }

    /// Appends the direct operands of `id` to `out` (no allocation of its own).
    pub fn push_children(&self, id: Id, out: &mut Vec<Id>) {
        match self.node(id) {
            Node::Const(_) | Node::Var(_) | Node::Param(_) | Node::Time => {}
            Node::Der(x) | Node::F1(_, x) => out.push(*x),
            Node::Sum(ts, _) => out.extend(self.terms(*ts).iter().map(|&(_, t)| t)),
            Node::Prod(fs) => out.extend(self.factors(*fs).iter().map(|&(b, _)| b)),
            Node::Pow(a, b) | Node::F2(_, a, b) | Node::Cmp(_, a, b) => {
                out.push(*a);
                out.push(*b);
            }
            Node::If(c, a, b) => {
                out.push(*c);
                out.push(*a);
                out.push(*b);
            }
        }
    }
}
