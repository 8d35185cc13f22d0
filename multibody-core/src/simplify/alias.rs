//! Alias elimination: equations `a = ±b` and `a = constant` (an expression of parameters)
//! remove one unknown each, and `der(x) = v` makes `v` the derivative of `x`.
//!
//! Variables made equal by connections form alias sets; each set keeps one
//! representative (a fixed start value first, then the highest state priority, a start
//! value, an internal variable rather than a connector's, the earliest declared) and the
//! others become observed expressions `±representative`. A set that contains a constant
//! equation is replaced by that constant entirely. Equations that the substitution turns
//! into constants (`T_b = R_rel T_a` on a constant frame) are found by further passes.

use crate::hash::HashMap;

use crate::expr::{Arena, Id, Node, NodeMap};
use crate::model::{FlatSystem, VarKind};

/// What alias elimination found.
#[derive(Clone, Debug, Default)]
pub(crate) struct Aliases {
    /// Per flat variable: its replacement when eliminated (an expression of the kept
    /// variables and parameters).
    pub replaced: Vec<Option<Id>>,
    /// Per flat variable `x`: the variable `v` with `der(x) = v`, when `v` was made the
    /// derivative slot of `x`.
    pub derivative: Vec<Option<u32>>,
    /// Indices of the flat equations removed (alias and derivative-alias equations).
    pub removed: Vec<bool>,
    /// The substitution of eliminated variables applied to every expression (leaf ->
    /// replacement, dense by the leaf's id).
    pub map: NodeMap,
    /// `der(x) -> v` for the derivative aliases: applied after every time
    /// differentiation so derivatives land on existing variables.
    pub derivative_map: HashMap<Id, Id>,
    /// Per flat variable: whether a derivative rule (after the substitution) contains
    /// it (the angular velocities in the derivatives of orientation entries, and those
    /// entries themselves).
    pub in_rules: Vec<bool>,
}

enum Pattern {
    /// `a = sign * b`.
    Alias(u32, u32, f64),
    /// `a = value` (parameters and constants only).
    Constant(u32, Id),
}

/// Recognizes `k a + k' b = 0` with `|k| = |k'|`, and `k a + c = 0` with `c` free of
/// unknowns and time.
/// Parameters marked in `varying` (the model's inputs) change in time: they make no
/// constant.
fn pattern(arena: &mut Arena, r: Id, varying: &[bool]) -> Option<Pattern> {
    // Read the node in place (no clone): most equations match neither pattern.
    let (alias, single) = match arena.node(r) {
        Node::Var(i) => return Some(Pattern::Constant(*i, arena.zero())),
        Node::Sum(ts, c) => {
            let c = f64::from_bits(*c);
            let mut vars = arena
                .terms(*ts)
                .iter()
                .filter_map(|&(k, t)| match arena.node(t) {
                    Node::Var(i) => Some((f64::from_bits(k), *i)),
                    _ => None,
                });
            let first = vars.next();
            let second = vars.next();
            let more = vars.next().is_some();
            match (first, second, more) {
                (Some((k1, a)), Some((k2, b)), false)
                    if ts.len() == 2 && c == 0.0 && k1.abs() == k2.abs() && a != b =>
                {
                    (Some(Pattern::Alias(a, b, -k2 / k1)), None)
                }
                (Some((k, a)), None, false) => (None, Some((k, a))),
                _ => (None, None),
            }
        }
        _ => return None,
    };
    if alias.is_some() {
        return alias;
    }
    let (k, a) = single?;
    // `k a + rest = 0` with `rest` of parameters only.
    let x = arena.var(a);
    if let Node::Sum(ts, _) = arena.node(r)
        && !arena
            .terms(*ts)
            .iter()
            .filter(|&&(_, t)| t != x)
            .all(|&(_, t)| is_parameter_expression(arena, t))
    {
        return None;
    }
    if varying.iter().any(|&v| v) && varies(arena, r, varying) {
        return None;
    }
    let rest = arena.linear_combination(0.0, &[(1.0, r), (-k, x)]);
    let v = arena.scale(-1.0 / k, rest);
    Some(Pattern::Constant(a, v))
}

/// Whether `e` contains only constants and parameters.
pub(crate) fn is_parameter_expression(arena: &Arena, e: Id) -> bool {
    match arena.node(e) {
        Node::Param(_) | Node::Const(_) => true,
        Node::Var(_) | Node::Time | Node::Der(_) => false,
        _ => arena
            .leaves(e)
            .iter()
            .all(|&l| matches!(arena.node(l), Node::Param(_))),
    }
}

/// Whether `e` reads a parameter marked in `varying`.
fn varies(arena: &Arena, e: Id, varying: &[bool]) -> bool {
    arena.leaves(e).iter().any(
        |&l| matches!(arena.node(l), Node::Param(j) if varying.get(*j as usize) == Some(&true)),
    )
}

/// Union-find with the sign of each member relative to its parent.
struct SignedSets {
    parent: Vec<u32>,
    sign: Vec<f64>,
    /// The path of the last `find` (kept to reuse its allocation).
    path: Vec<u32>,
}

impl SignedSets {
    fn find(&mut self, x: u32) -> (u32, f64) {
        let mut path = std::mem::take(&mut self.path);
        path.clear();
        let mut cur = x;
        while self.parent[cur as usize] != cur {
            path.push(cur);
            cur = self.parent[cur as usize];
        }
        // Path compression, accumulating signs from the root down.
        let root = cur;
        for &p in path.iter().rev() {
            let par = self.parent[p as usize];
            if par != root {
                self.sign[p as usize] *= self.sign[par as usize];
            }
            self.parent[p as usize] = root;
        }
        self.path = path;
        (
            root,
            if x == root {
                1.0
            } else {
                self.sign[x as usize]
            },
        )
    }
}

/// The alias sets found so far: signed union-find and the constant of each set's root.
struct Found {
    sets: SignedSets,
    constant: Vec<Option<Id>>,
    /// Per parameter: whether it changes in time (an input of the model).
    varying: Vec<bool>,
}

impl Found {
    /// Takes the equations `eqs` of `flat` that read `a = ±b` (when `aliases`) or
    /// `a = constant` into the sets, marking them removed; the constants found, as
    /// `(a, value of a)`, and whether anything was found.
    fn scan(
        &mut self,
        flat: &mut FlatSystem,
        eqs: impl Iterator<Item = usize>,
        removed: &mut [bool],
        aliases: bool,
    ) -> (Vec<(u32, Id)>, bool) {
        let mut any = false;
        let mut constants = Vec::new();
        for e in eqs {
            let removed_e = &mut removed[e];
            if *removed_e {
                continue;
            }
            let r = flat.equations[e].residual;
            match pattern(&mut flat.arena, r, &self.varying) {
                Some(Pattern::Alias(a, b, s)) if aliases => {
                    let (ra, sa) = self.sets.find(a);
                    let (rb, sb) = self.sets.find(b);
                    if ra == rb {
                        continue; // a loop of aliases: keep as an equation (it is redundant)
                    }
                    if self.constant[ra as usize].is_some() && self.constant[rb as usize].is_some()
                    {
                        continue;
                    }
                    // a = s b, a = sa ra, b = sb rb  =>  ra = sa s sb rb
                    self.sets.parent[ra as usize] = rb;
                    self.sets.sign[ra as usize] = sa * s * sb;
                    if let Some(c) = self.constant[ra as usize].take() {
                        // ra = c  =>  rb = c / (sa s sb)
                        let k = sa * s * sb;
                        self.constant[rb as usize] = Some(flat.arena.scale(1.0 / k, c));
                    }
                    *removed_e = true;
                    any = true;
                }
                Some(Pattern::Constant(a, v)) => {
                    let (ra, sa) = self.sets.find(a);
                    if self.constant[ra as usize].is_some() {
                        continue;
                    }
                    // a = v, a = sa ra  =>  ra = sa v
                    self.constant[ra as usize] = Some(flat.arena.scale(sa, v));
                    *removed_e = true;
                    any = true;
                    constants.push((a, v));
                }
                _ => {}
            }
        }
        (constants, any)
    }

    /// The replacement of every eliminated variable (its set's constant, or `±` the
    /// set's representative), and per representative the state priority and start value
    /// it takes over from its set.
    fn replacements(&mut self, flat: &mut FlatSystem) -> (Vec<Option<Id>>, Vec<Merge>) {
        let nv = flat.variables.len();
        let sets = &mut self.sets;
        // Members of each set, grouped by root (a counting sort: members of a root in
        // increasing order, roots in increasing order).
        let root_of: Vec<u32> = (0..nv as u32).map(|x| sets.find(x).0).collect();
        let mut start = vec![0u32; nv + 1];
        for &r in &root_of {
            start[r as usize + 1] += 1;
        }
        for i in 0..nv {
            start[i + 1] += start[i];
        }
        let mut grouped = vec![0u32; nv];
        let mut fill = start.clone();
        for (x, &r) in root_of.iter().enumerate() {
            grouped[fill[r as usize] as usize] = x as u32;
            fill[r as usize] += 1;
        }
        let mut replaced: Vec<Option<Id>> = vec![None; nv];
        let mut merges = Vec::new();
        for root in 0..nv as u32 {
            let ms = &grouped[start[root as usize] as usize..start[root as usize + 1] as usize];
            if ms.is_empty() {
                continue;
            }
            let sign_of = |sets: &mut SignedSets, x: u32| sets.find(x).1;
            if let Some(c) = self.constant[root as usize] {
                for &x in ms {
                    let s = sign_of(sets, x);
                    let v = flat.arena.scale(s, c);
                    replaced[x as usize] = Some(v);
                }
                continue;
            }
            if ms.len() == 1 {
                continue;
            }
            let rep = *ms
                .iter()
                .max_by(|&&a, &&b| {
                    let key = |x: u32| {
                        let v = &flat.variables[x as usize];
                        (
                            v.fixed,
                            v.kind != VarKind::Overdetermined,
                            v.state_priority,
                            v.start.is_some(),
                            v.kind == VarKind::Internal,
                        )
                    };
                    let (ka, kb) = (key(a), key(b));
                    ka.0.cmp(&kb.0)
                        .then(ka.1.cmp(&kb.1))
                        .then(ka.2.total_cmp(&kb.2))
                        .then(ka.3.cmp(&kb.3))
                        .then(ka.4.cmp(&kb.4))
                        .then(b.cmp(&a))
                })
                .expect("non-empty set");
            let s_rep = sign_of(sets, rep);
            let rep_leaf = flat.arena.var(rep);
            let mut best_priority = flat.variables[rep as usize].state_priority;
            let mut start = flat.starts[rep as usize];
            for &x in ms {
                if x == rep {
                    continue;
                }
                // x = sx root, rep = srep root  =>  x = sx srep rep
                let s = sign_of(sets, x) * s_rep;
                replaced[x as usize] = Some(flat.arena.scale(s, rep_leaf));
                best_priority = best_priority.max(flat.variables[x as usize].state_priority);
                if start.is_none()
                    && let Some(sx) = flat.starts[x as usize]
                {
                    start = Some(flat.arena.scale(s, sx));
                }
            }
            merges.push(Merge {
                rep,
                priority: best_priority,
                start,
            });
        }
        (replaced, merges)
    }
}

/// What the representative of an alias set takes over from its members.
struct Merge {
    rep: u32,
    priority: f64,
    start: Option<Id>,
}

/// The substitution of `replaced` as a map from leaves (dense by the leaf's id: the pass
/// over the whole model reads it in model order).
fn node_map(flat: &mut FlatSystem, replaced: &[Option<Id>]) -> NodeMap {
    let mut map = NodeMap::new();
    for (x, r) in replaced.iter().enumerate() {
        if let Some(r) = *r {
            let leaf = flat.arena.var(x as u32);
            map.insert(leaf, r);
        }
    }
    map
}

/// Per variable: the equations (not removed) whose residual contains it.
fn occurrences(flat: &FlatSystem, removed: &[bool]) -> Vec<Vec<u32>> {
    let mut occ: Vec<Vec<u32>> = vec![Vec::new(); flat.variables.len()];
    let mut leaves = Vec::new();
    for (e, eq) in flat.equations.iter().enumerate() {
        if removed[e] {
            continue;
        }
        flat.arena.leaves_into(eq.residual, &mut leaves);
        for &l in &leaves {
            // `der(x)` counts as an occurrence of x (a constant x has derivative 0).
            let mut l = l;
            while let Node::Der(x) = flat.arena.node(l) {
                l = *x;
            }
            if let Node::Var(v) = flat.arena.node(l) {
                occ[*v as usize].push(e as u32);
            }
        }
    }
    occ
}

/// Finds alias and derivative-alias equations of `flat` (after constant folding) and
/// the substitution that removes them.
///
/// Substituting the aliases and constants found can turn further equations into
/// aliases or constants: the orientation of a frame rotated by a constant rotation from
/// a constant frame (`T_b = R_rel T_a` with `T_a` the world's identity) is a linear
/// combination of constants, and so is its angular velocity. The search is repeated on
/// the substituted equations until it finds nothing more, so such a frame is a constant
/// (as a frame merely translated from a constant one is after one pass), and no
/// equation is left that defines a constant orientation entry.
pub(crate) fn eliminate_aliases(flat: &mut FlatSystem, inputs: &[usize]) -> Aliases {
    let nv = flat.variables.len();
    let ne = flat.equations.len();
    let mut varying = vec![false; flat.parameters.len()];
    for &j in inputs {
        varying[j] = true;
    }
    let mut found = Found {
        varying,
        sets: SignedSets {
            parent: (0..nv as u32).collect(),
            sign: vec![1.0; nv],
            path: Vec::new(),
        },
        constant: vec![None; nv],
    };
    let mut removed = vec![false; ne];
    found.scan(flat, 0..ne, &mut removed, true);
    let (mut replaced, mut merges) = found.replacements(flat);
    let mut map = node_map(flat, &replaced);
    // Apply the substitution to the remaining equations.
    let mut memo = NodeMap::new();
    let mut changed: Vec<usize> = Vec::new();
    for (e, eq) in flat.equations.iter_mut().enumerate() {
        if !removed[e] {
            let r = flat.arena.substitute_memo(eq.residual, &map, &mut memo);
            if r != eq.residual {
                changed.push(e);
            }
            eq.residual = r;
        }
    }
    // Later passes take constants only (an alias found there could tie an orientation
    // entry to an ordinary variable, which would inherit its derivative rule), and
    // substitute each new constant only into the equations that contain it.
    let (mut new_constants, _) = found.scan(flat, changed.iter().copied(), &mut removed, false);
    if !new_constants.is_empty() {
        let occurrences = occurrences(flat, &removed);
        let mut passes = 1usize;
        while !new_constants.is_empty() {
            passes += 1;
            let mut step: HashMap<Id, Id> = HashMap::default();
            let mut affected: Vec<usize> = Vec::new();
            for &(a, v) in &new_constants {
                let leaf = flat.arena.var(a);
                step.insert(leaf, v);
                affected.extend(occurrences[a as usize].iter().map(|&e| e as usize));
            }
            affected.sort_unstable();
            affected.dedup();
            let mut step_memo: HashMap<Id, Id> = HashMap::default();
            changed.clear();
            for e in affected {
                if removed[e] {
                    continue;
                }
                let old = flat.equations[e].residual;
                let r = flat.arena.substitute_memo(old, &step, &mut step_memo);
                if r != old {
                    flat.equations[e].residual = r;
                    changed.push(e);
                }
            }
            new_constants = found
                .scan(flat, changed.iter().copied(), &mut removed, false)
                .0;
        }
        log::debug!("alias elimination: {passes} passes");
        (replaced, merges) = found.replacements(flat);
        map = node_map(flat, &replaced);
        memo = NodeMap::new();
    }
    for m in merges {
        flat.variables[m.rep as usize].state_priority = m.priority;
        flat.starts[m.rep as usize] = m.start;
    }
    // Which remaining equations read `der(x) = v` (which ones are taken is decided
    // below, once the derivative rules are known).
    let mut derivative_candidates: Vec<(usize, u32, u32)> = Vec::new();
    for (e, eq) in flat.equations.iter().enumerate() {
        if !removed[e]
            && let Some((x, v)) = derivative_pattern(&flat.arena, eq.residual)
        {
            derivative_candidates.push((e, x, v));
        }
    }
    // Derivative rules (der(x) is an expression, as for an orientation matrix): moved
    // onto the representative of an eliminated variable, dropped for constants.
    let mut dmap: HashMap<Id, Id> = HashMap::default();
    let mut has_rule = vec![false; nv];
    let rules = flat.derivative_rules.clone();
    let mut in_rules = vec![false; nv];
    let mut leaves = Vec::new();
    for (x, expr) in rules {
        // The memo of the equations' pass: the same substitution, and the rules share
        // their angular velocities with the equations and with each other.
        let e = flat.arena.substitute_memo(expr, &map, &mut memo);
        flat.arena.leaves_into(e, &mut leaves);
        for &leaf in &leaves {
            if let Node::Var(v) = flat.arena.node(leaf) {
                in_rules[*v as usize] = true;
            }
        }
        let (target, sign) = match replaced[x as usize] {
            None => (x, 1.0),
            Some(r) => match *flat.arena.node(r) {
                Node::Var(rep) => (rep, 1.0),
                Node::Sum(ts, c) if ts.len() == 1 && f64::from_bits(c) == 0.0 => {
                    let (k, t) = flat.arena.terms(ts)[0];
                    match flat.arena.node(t) {
                        Node::Var(rep) => (*rep, 1.0 / f64::from_bits(k)),
                        _ => continue,
                    }
                }
                _ => continue,
            },
        };
        if has_rule[target as usize] {
            continue;
        }
        has_rule[target as usize] = true;
        let xl = flat.arena.var(target);
        let dx = flat.arena.der(xl);
        let value = flat.arena.scale(sign, e);
        dmap.insert(dx, value);
    }
    // Derivative aliases: der(x) = v.
    let mut derivative: Vec<Option<u32>> = vec![None; nv];
    let mut is_derivative = vec![false; nv];
    for (e, x, v) in derivative_candidates {
        if derivative[x as usize].is_some()
            || is_derivative[v as usize]
            || x == v
            || has_rule[x as usize]
        {
            continue;
        }
        // No cycle: following derivatives from v must not reach x.
        let mut cur = v;
        let mut cycle = false;
        while let Some(d) = derivative[cur as usize] {
            if d == x {
                cycle = true;
                break;
            }
            cur = d;
        }
        if cycle {
            continue;
        }
        derivative[x as usize] = Some(v);
        is_derivative[v as usize] = true;
        removed[e] = true;
    }
    for (x, d) in derivative.iter().enumerate() {
        if let Some(v) = *d {
            let xl = flat.arena.var(x as u32);
            let dx = flat.arena.der(xl);
            let vl = flat.arena.var(v);
            dmap.insert(dx, vl);
        }
    }
    if !dmap.is_empty() {
        // Only equations that contain a replaced derivative change: found in one pass
        // over the arena in order, not by walking every equation.
        let affected = flat.arena.containing(dmap.keys().copied());
        let mut memo = NodeMap::new();
        for (e, eq) in flat.equations.iter_mut().enumerate() {
            if !removed[e] && affected[eq.residual.index()] {
                eq.residual = flat.arena.substitute_memo(eq.residual, &dmap, &mut memo);
            }
        }
    }
    Aliases {
        replaced,
        derivative,
        removed,
        map,
        derivative_map: dmap,
        in_rules,
    }
}

/// Recognizes `k der(x) - k v = 0`.
fn derivative_pattern(arena: &Arena, r: Id) -> Option<(u32, u32)> {
    let Node::Sum(ts, c) = arena.node(r) else {
        return None;
    };
    if ts.len() != 2 || f64::from_bits(*c) != 0.0 {
        return None;
    }
    let mut der = None;
    let mut var = None;
    for &(k, t) in arena.terms(*ts) {
        let k = f64::from_bits(k);
        match arena.node(t) {
            Node::Der(inner) => match arena.node(*inner) {
                Node::Var(x) => der = Some((k, *x)),
                _ => return None,
            },
            Node::Var(v) => var = Some((k, *v)),
            _ => return None,
        }
    }
    let ((kd, x), (kv, v)) = (der?, var?);
    (kd == -kv).then_some((x, v))
}
