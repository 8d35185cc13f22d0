//! Expressions to tape: iterative post-order compilation with common subexpressions
//! shared (per arena node and per instruction), statements, outputs and dead-code
//! elimination.

use crate::expr::{Arena, DenseU32, Id, Node, is_leaf};

use super::tape::{LsInfo, Op, SparsePattern, Tape};

use hashbrown::HashTable;

use super::{CodegenError, Stmt};

/// Hash of an instruction for value numbering, placing it by its newest operand
/// register (see [`crate::hash::anchored_hash`]).
#[inline]
fn hash_op(op: &Op) -> u64 {
    use std::hash::BuildHasher;
    let high = (crate::hash::FastBuild::default().hash_one(op) >> 32) as u32;
    // A linear solve's operands are in a side table; it is never numbered anyway.
    let mut anchor = None;
    if !matches!(op, Op::LinearSolve(_)) {
        op.for_each_operand(&[], |r| anchor = Some(anchor.map_or(r, |a: u32| a.max(r))));
    }
    crate::hash::anchored_hash(anchor, high)
}

/// Tags a value of `TapeBuilder::bound` as an input slot not emitted yet.
const PENDING: u32 = 1 << 31;

/// A map from arena ids to registers, stored densely by id (the arena is fixed while a
/// builder exists): no hashing on the builder's most frequent lookups. It remembers
/// which ids it holds, so clearing it costs what was inserted, not the arena's size.
#[derive(Clone, Debug)]
struct IdMap {
    values: DenseU32,
    /// Ids with a value, for `clear`.
    set: Vec<Id>,
}

impl IdMap {
    const NONE: u32 = u32::MAX;

    fn new(len: usize) -> Self {
        IdMap {
            values: DenseU32::with_len(len),
            set: Vec::new(),
        }
    }

    #[inline]
    fn get(&self, id: Id) -> Option<u32> {
        self.values.get(id)
    }

    fn insert(&mut self, id: Id, v: u32) {
        if self.values.get(id).is_none() {
            self.set.push(id);
        }
        self.values.insert(id, v);
    }

    fn clear(&mut self) {
        for &id in &self.set {
            self.values.remove(id);
        }
        self.set.clear();
    }
}

/// Compiles expressions of one [`Arena`] into a [`Tape`].
///
/// Bind leaves to input slots with [`input`](Self::input), add statements with
/// [`stmt`](Self::stmt) in execution order, then outputs with [`output`](Self::output)
/// or [`output_input_minus`](Self::output_input_minus), and finish with
/// [`build`](Self::build). Each arena node is compiled once while its leaves keep their
/// binding, and structurally identical instructions are emitted once (value numbering),
/// so shared subexpressions cost nothing extra.
pub struct TapeBuilder<'a> {
    arena: &'a Arena,
    names: Option<&'a dyn Fn(Id) -> String>,
    n_inputs: usize,
    ops: Vec<Op>,
    consts: Vec<f64>,
    const_index: crate::hash::HashMap<u64, u32>,
    /// Registers of the emitted instructions, placed by `hash_op` (value numbering);
    /// 4 bytes per entry, the instruction itself is read from `ops`. Inputs and
    /// constants are numbered densely instead (`input_regs`, `const_regs`).
    numbering: HashTable<u32>,
    /// The register of each input slot once emitted (`IdMap::NONE` before).
    input_regs: Vec<u32>,
    /// The register of each constant slot once emitted (`IdMap::NONE` before).
    const_regs: Vec<u32>,
    /// One bit per register: set when its instruction is a constant (so folding does
    /// not read the instructions of its operands).
    is_const: Vec<u64>,
    /// Registers bound to nodes, or `PENDING | slot` for a node bound to an input slot
    /// whose instruction is emitted at its first use: an input then sits next to the
    /// instructions that read it, and an unused one costs nothing.
    bound: IdMap,
    memo: IdMap,
    ls: Vec<LsInfo>,
    pub(super) outputs: Vec<u32>,
    stack: Vec<(Id, bool)>,
    invariant_inputs: (usize, usize),
}

impl<'a> TapeBuilder<'a> {
    /// A builder for a tape with `n_inputs` input slots reading expressions of `arena`.
    pub fn new(arena: &'a Arena, n_inputs: usize) -> Self {
        TapeBuilder {
            arena,
            names: None,
            n_inputs,
            ops: Vec::new(),
            consts: Vec::new(),
            const_index: crate::hash::HashMap::default(),
            numbering: HashTable::new(),
            input_regs: vec![IdMap::NONE; n_inputs],
            const_regs: Vec::new(),
            is_const: Vec::new(),
            bound: IdMap::new(arena.len()),
            memo: IdMap::new(arena.len()),
            ls: Vec::new(),
            outputs: Vec::new(),
            stack: Vec::new(),
            invariant_inputs: (0, 0),
        }
    }

    /// Declares the input slots `slots` invariant: their values change rarely (the
    /// tunable parameters of a model). Instructions that depend only on them and on
    /// constants form the tape's prelude, evaluated first and skipped by later
    /// evaluations with the same workspace while these inputs keep their values.
    /// Default: no invariant input (the prelude then holds only constants).
    ///
    /// # Panics
    /// If `slots` is not within `0..n_inputs`.
    pub fn invariant_inputs(&mut self, slots: std::ops::Range<usize>) {
        assert!(
            slots.start <= slots.end && slots.end <= self.n_inputs,
            "TapeBuilder::invariant_inputs: {slots:?} out of range ({} inputs)",
            self.n_inputs
        );
        self.invariant_inputs = (slots.start, slots.end);
    }

    /// The leaf node `leaf` (a `Var`, `Param`, `Time` or `Der` node) reads input slot
    /// `slot`. Binding any other node substitutes the input for that whole expression.
    /// Rebinding a node affects only expressions compiled afterwards (and drops the
    /// per-node memo, so rebinding is meant to be rare).
    ///
    /// # Panics
    /// If `slot >= n_inputs`.
    pub fn input(&mut self, leaf: Id, slot: usize) {
        assert!(
            slot < self.n_inputs,
            "TapeBuilder::input: slot {slot} out of range ({} inputs)",
            self.n_inputs
        );
        self.bind(leaf, PENDING | slot as u32);
    }

    /// Adds a statement, executed after the earlier ones. Fails if an expression uses a
    /// leaf that is neither an input nor assigned earlier, if a target is not a leaf, or
    /// if the dimensions of a linear solve disagree.
    pub fn stmt(&mut self, s: &Stmt) -> Result<(), CodegenError> {
        match s {
            Stmt::Assign { target, expr, .. } => {
                self.check_leaf(*target)?;
                let r = self.compile(*expr)?;
                self.bind(*target, r);
            }
            Stmt::LinearSolve { targets, a, c } => {
                let k = targets.len();
                if k == 0 || a.len() != k * k || c.len() != k {
                    return Err(CodegenError::BadLinearSolve(format!(
                        "{k} targets need {} matrix entries and {k} constants, got {} and {}",
                        k * k,
                        a.len(),
                        c.len()
                    )));
                }
                self.linear_solve(targets, a, None, c)?;
            }
            Stmt::SparseLinearSolve {
                targets,
                entries,
                c,
            } => {
                let k = targets.len();
                if k == 0 || c.len() != k {
                    return Err(CodegenError::BadLinearSolve(format!(
                        "{k} targets need {k} constants, got {}",
                        c.len()
                    )));
                }
                let mut sorted: Vec<(usize, usize, Id)> = entries.clone();
                sorted.sort_by_key(|&(r, col, _)| (col, r));
                if let Some(&(r, col, _)) = sorted.iter().find(|&&(r, col, _)| r >= k || col >= k) {
                    return Err(CodegenError::BadLinearSolve(format!(
                        "entry ({r}, {col}) outside a {k} x {k} matrix"
                    )));
                }
                if sorted
                    .windows(2)
                    .any(|w| (w[0].0, w[0].1) == (w[1].0, w[1].1))
                {
                    return Err(CodegenError::BadLinearSolve(
                        "an entry of the sparse matrix is given twice".into(),
                    ));
                }
                let mut col_ptr = vec![0usize; k + 1];
                for &(_, col, _) in &sorted {
                    col_ptr[col + 1] += 1;
                }
                for j in 0..k {
                    col_ptr[j + 1] += col_ptr[j];
                }
                let row_idx: Vec<usize> = sorted.iter().map(|&(r, _, _)| r).collect();
                let exprs: Vec<Id> = sorted.iter().map(|&(_, _, e)| e).collect();
                let pattern = SparsePattern::new(k, col_ptr, row_idx);
                self.linear_solve(targets, &exprs, Some(std::sync::Arc::new(pattern)), c)?;
            }
        }
        Ok(())
    }

    /// Compiles the matrix entries and constants of a linear solve and emits it.
    fn linear_solve(
        &mut self,
        targets: &[Id],
        a: &[Id],
        sparse: Option<std::sync::Arc<SparsePattern>>,
        c: &[Id],
    ) -> Result<(), CodegenError> {
        let k = targets.len();
        for &t in targets {
            self.check_leaf(t)?;
        }
        let mut ra = Vec::with_capacity(a.len());
        for &e in a {
            ra.push(self.compile(e)?);
        }
        let mut rc = Vec::with_capacity(k);
        for &e in c {
            rc.push(self.compile(e)?);
        }
        let names = targets
            .iter()
            .map(|&t| self.describe(t))
            .collect::<Vec<_>>()
            .join(", ");
        let base = self.push_linear_solve(ra, sparse, rc, names);
        for (i, &t) in targets.iter().enumerate() {
            self.bind(t, base + i as u32);
        }
        Ok(())
    }

    /// Appends the linear solve `A x + c = 0` over registers already emitted (`a`
    /// row-major k*k when dense, one per entry of `sparse` in CSC order; `c` one per
    /// row) with its parts; returns the register of its first unknown (the others
    /// follow). `names` names the unknowns for error messages.
    pub(super) fn push_linear_solve(
        &mut self,
        a: Vec<u32>,
        sparse: Option<std::sync::Arc<SparsePattern>>,
        c: Vec<u32>,
        names: String,
    ) -> u32 {
        let k = c.len();
        let base = self.ops.len() as u32;
        self.push_op(Op::LinearSolve(self.ls.len() as u32));
        for _ in 1..k {
            self.push_op(Op::LsPart);
        }
        self.ls.push(LsInfo {
            k,
            a,
            sparse,
            c,
            lu_off: 0,
            piv_off: 0,
            names,
        });
        base
    }

    /// Adds the output `e`; returns its index.
    pub fn output(&mut self, e: Id) -> Result<usize, CodegenError> {
        let r = self.compile(e)?;
        self.outputs.push(r);
        Ok(self.outputs.len() - 1)
    }

    /// Adds the output `inputs[slot] - e` (for rows `x' - f(x)` without building that
    /// expression in the arena); returns its index.
    pub fn output_input_minus(&mut self, slot: usize, e: Id) -> Result<usize, CodegenError> {
        if slot >= self.n_inputs {
            return Err(CodegenError::SlotOutOfRange {
                slot,
                n_inputs: self.n_inputs,
            });
        }
        let r = self.compile(e)?;
        let x = self.emit(Op::Input(slot as u32));
        let d = self.emit(Op::Sub(x, r));
        self.outputs.push(d);
        Ok(self.outputs.len() - 1)
    }

    /// Finishes the tape, keeping only the instructions the outputs depend on.
    pub fn build(self) -> Tape {
        self.build_outputs(0..self.outputs.len())
    }

    /// A tape of the outputs numbered `outputs` (as [`output`](Self::output) returned
    /// them), keeping only the instructions they depend on. One builder can so give
    /// several tapes over the same inputs that share their statements, compiled once
    /// (a residual and the observed variables).
    ///
    /// # Panics
    /// If `outputs` is not within the outputs added so far.
    pub fn build_outputs(&self, outputs: std::ops::Range<usize>) -> Tape {
        let outputs = &self.outputs[outputs];
        let n = self.ops.len();
        assert!(n < u32::MAX as usize, "tape too long");
        let ops = &self.ops;
        let ls = &self.ls;
        let mut live = vec![false; n];
        for &o in outputs {
            live[o as usize] = true;
        }
        for i in (0..n).rev() {
            match ops[i] {
                Op::LsPart => {}
                op @ Op::LinearSolve(s) => {
                    let k = ls[s as usize].k;
                    if live[i..i + k].iter().any(|&l| l) {
                        live[i..i + k].fill(true);
                        op.for_each_operand(ls, |r| live[r as usize] = true);
                    }
                }
                op => {
                    if live[i] {
                        op.for_each_operand(ls, |r| live[r as usize] = true);
                    }
                }
            }
        }
        let mut new_index = vec![u32::MAX; n];
        let mut new_ops = Vec::with_capacity(live.iter().filter(|&&l| l).count());
        let mut new_ls = Vec::new();
        let (mut lu_len, mut piv_len, mut max_k) = (0, 0, 0);
        // Instructions that depend on nothing but constants and invariant inputs.
        let (lo, hi) = self.invariant_inputs;
        let mut invariant = vec![false; n];
        for i in 0..n {
            invariant[i] = match ops[i] {
                Op::Const(_) => true,
                Op::Input(s) => (lo..hi).contains(&(s as usize)),
                Op::LinearSolve(_) | Op::LsPart => false,
                op => {
                    let mut all = true;
                    op.for_each_operand(ls, |r| all &= invariant[r as usize]);
                    all
                }
            };
        }
        let order = super::schedule::grouped_order(ops, ls, &live, &invariant);
        let prelude_len = order.iter().take_while(|&&i| invariant[i]).count();
        let mut units = Vec::with_capacity(n);
        for i in order {
            units.push(i);
            if let Op::LinearSolve(s) = ops[i] {
                units.extend(i + 1..i + ls[s as usize].k);
            }
        }
        for i in units {
            let op = ops[i];
            new_index[i] = new_ops.len() as u32;
            let map = |r: u32| new_index[r as usize];
            let op = match op {
                Op::LinearSolve(s) => {
                    let old = &ls[s as usize];
                    let info = LsInfo {
                        k: old.k,
                        a: old.a.iter().map(|&r| map(r)).collect(),
                        sparse: old.sparse.clone(),
                        c: old.c.iter().map(|&r| map(r)).collect(),
                        lu_off: lu_len,
                        piv_off: piv_len,
                        names: old.names.clone(),
                    };
                    if old.sparse.is_none() {
                        lu_len += old.k * old.k;
                        piv_len += old.k;
                    }
                    max_k = max_k.max(old.k);
                    new_ls.push(info);
                    Op::LinearSolve(new_ls.len() as u32 - 1)
                }
                op => op.remap(map),
            };
            new_ops.push(op);
        }
        let outputs = outputs.iter().map(|&r| new_index[r as usize]).collect();
        let runs = super::tape::runs_of(&new_ops, prelude_len);
        let prelude_runs = runs
            .iter()
            .take_while(|r| (r.end as usize) <= prelude_len)
            .count();
        static NEXT_ID: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
        Tape {
            id: NEXT_ID.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
            runs,
            prelude_runs,
            prelude_len,
            invariant_inputs: self.invariant_inputs,
            ops: new_ops,
            consts: self.consts.clone(),
            ls: new_ls,
            outputs,
            n_inputs: self.n_inputs,
            lu_len,
            piv_len,
            max_k,
        }
    }

    /// The debug form of a node, for messages.
    fn describe(&self, id: Id) -> String {
        match self.names {
            Some(f) => f(id),
            None => format!("{:?} = {:?}", id, self.arena.node(id)),
        }
    }

    /// Names leaves in messages (linear systems that fail name their unknowns).
    pub fn with_names(mut self, names: &'a dyn Fn(Id) -> String) -> Self {
        self.names = Some(names);
        self
    }

    fn check_leaf(&self, id: Id) -> Result<(), CodegenError> {
        if is_leaf(self.arena.node(id)) {
            Ok(())
        } else {
            Err(CodegenError::NotALeaf(self.describe(id)))
        }
    }

    /// Binds `id` to register `r`, or to an input not emitted yet when `r` is
    /// `PENDING | slot` (see `bound`); compiled expressions that might have used an
    /// older binding are forgotten.
    fn bind(&mut self, id: Id, r: u32) {
        if self.bound.get(id) == Some(r) {
            return;
        }
        if self.bound.get(id).is_some() || self.memo.get(id).is_some() {
            self.memo.clear();
        }
        self.bound.insert(id, r);
    }

    /// The register of `id` if it is compiled (a node bound to an input that is not
    /// emitted yet is not).
    #[inline]
    fn lookup(&self, id: Id) -> Option<u32> {
        match self.bound.get(id) {
            Some(r) if r & PENDING == 0 => Some(r),
            Some(_) => None,
            None => self.memo.get(id),
        }
    }

    /// [`Self::lookup`], emitting the input of a node bound to one but not yet used.
    #[inline]
    fn lookup_or_emit_input(&mut self, id: Id) -> Option<u32> {
        match self.bound.get(id) {
            Some(p) if p & PENDING != 0 => {
                let r = self.emit(Op::Input(p & !PENDING));
                self.bound.insert(id, r);
                Some(r)
            }
            Some(r) => Some(r),
            None => self.memo.get(id),
        }
    }

    /// Appends `op` without numbering it; returns its register.
    #[inline]
    fn push_op(&mut self, op: Op) -> u32 {
        let r = self.ops.len() as u32;
        assert!(r < PENDING, "tape too long");
        if let Op::Const(_) = op {
            let w = r as usize / 64;
            if w >= self.is_const.len() {
                self.is_const.resize(w + 1, 0);
            }
            self.is_const[w] |= 1 << (r % 64);
        }
        self.ops.push(op);
        r
    }

    #[inline]
    fn reg(&self, id: Id) -> u32 {
        self.lookup(id).expect("operand compiled before its parent")
    }

    /// The value of register `r` if it is a constant.
    #[inline]
    pub(super) fn const_value(&self, r: u32) -> Option<f64> {
        let bit = self
            .is_const
            .get(r as usize / 64)
            .is_some_and(|w| w & (1 << (r % 64)) != 0);
        if !bit {
            return None;
        }
        match self.ops[r as usize] {
            Op::Const(k) => Some(self.consts[k as usize]),
            _ => None,
        }
    }

    /// Folds `op` when its operands make it trivial: every operand constant (evaluated
    /// now), or a neutral or absorbing constant (`x * 0`, `x + 0`, `x * 1`, ...), or a
    /// condition known at compile time. Assigned variables that turn out constant (a
    /// rotation entry that is 0 for a structural axis) thereby vanish from everything
    /// computed from them. As in the symbolic simplifier, `0 * x` is 0 even for
    /// non-finite `x`.
    fn fold(&mut self, op: Op) -> Option<u32> {
        let c = |r: u32| self.const_value(r);
        let mut all_const = true;
        op.for_each_operand(&self.ls, |r| all_const &= c(r).is_some());
        match op {
            Op::Const(_) | Op::Input(_) | Op::LinearSolve(_) | Op::LsPart => return None,
            _ if all_const => {
                // Evaluate on a local register file holding the operands' values.
                let mut operands: Vec<u32> = Vec::with_capacity(3);
                op.for_each_operand(&self.ls, |r| operands.push(r));
                let local: Vec<f64> = operands.iter().map(|&r| c(r).unwrap_or(f64::NAN)).collect();
                let local_op =
                    op.remap(|r| operands.iter().position(|&x| x == r).unwrap_or(0) as u32);
                let v = super::tape::value(local_op, &self.consts, &[], &local);
                return Some(self.constant(v));
            }
            _ => {}
        }
        match op {
            Op::Add(a, b) => match (c(a), c(b)) {
                (Some(0.0), _) => Some(b),
                (_, Some(0.0)) => Some(a),
                _ => None,
            },
            Op::Sub(a, b) => match (c(a), c(b)) {
                (_, Some(0.0)) => Some(a),
                (Some(0.0), _) => Some(self.emit(Op::Neg(b))),
                _ => None,
            },
            Op::Mul(a, b) => match (c(a), c(b)) {
                (Some(0.0), _) | (_, Some(0.0)) => Some(self.constant(0.0)),
                (Some(1.0), _) => Some(b),
                (_, Some(1.0)) => Some(a),
                (Some(-1.0), _) => Some(self.emit(Op::Neg(b))),
                (_, Some(-1.0)) => Some(self.emit(Op::Neg(a))),
                (Some(k), _) => {
                    let k = self.const_slot(k);
                    Some(self.emit(Op::Scale(k, b)))
                }
                (_, Some(k)) => {
                    let k = self.const_slot(k);
                    Some(self.emit(Op::Scale(k, a)))
                }
                _ => None,
            },
            Op::Div(a, b) => match (c(a), c(b)) {
                (Some(0.0), _) => Some(self.constant(0.0)),
                (_, Some(1.0)) => Some(a),
                (_, Some(k)) if k != 0.0 => {
                    let k = self.const_slot(1.0 / k);
                    Some(self.emit(Op::Scale(k, a)))
                }
                _ => None,
            },
            Op::Neg(a) => match self.ops[a as usize] {
                Op::Neg(x) => Some(x),
                _ => None,
            },
            Op::Scale(k, a) => {
                let k = self.consts[k as usize];
                if k == 0.0 {
                    Some(self.constant(0.0))
                } else if k == 1.0 {
                    Some(a)
                } else if k == -1.0 {
                    Some(self.emit(Op::Neg(a)))
                } else {
                    None
                }
            }
            Op::AddScaled(a, k, b) => {
                let kv = self.consts[k as usize];
                match (c(a), c(b)) {
                    (_, Some(0.0)) => Some(a),
                    _ if kv == 0.0 => Some(a),
                    (Some(0.0), _) => Some(self.emit(Op::Scale(k, b))),
                    _ if kv == 1.0 => Some(self.emit(Op::Add(a, b))),
                    _ if kv == -1.0 => Some(self.emit(Op::Sub(a, b))),
                    _ => None,
                }
            }
            Op::PowI(a, e) => match e {
                0 => Some(self.constant(1.0)),
                1 => Some(a),
                _ => None,
            },
            Op::Select(cond, a, b) => match c(cond) {
                Some(v) => Some(if v != 0.0 { a } else { b }),
                None if a == b => Some(a),
                None => None,
            },
            _ => None,
        }
    }

    /// The entry of an input or a constant in its dense numbering (`IdMap::NONE` until
    /// emitted); `None` for other instructions.
    fn dense_register(&mut self, op: Op) -> Option<&mut u32> {
        match op {
            Op::Input(s) => Some(&mut self.input_regs[s as usize]),
            Op::Const(k) => Some(&mut self.const_regs[k as usize]),
            _ => None,
        }
    }

    /// Emits `op` unless an identical instruction exists or it folds; returns its
    /// register.
    pub(super) fn emit(&mut self, op: Op) -> u32 {
        if let Some(r) = self.dense_register(op).map(|r| *r) {
            if r != IdMap::NONE {
                return r;
            }
            let r = self.push_op(op);
            *self.dense_register(op).expect("an input or a constant") = r;
            return r;
        }
        if let Some(r) = self.fold(op) {
            return r;
        }
        let op = match op {
            Op::Add(a, b) if b < a => Op::Add(b, a),
            Op::Mul(a, b) if b < a => Op::Mul(b, a),
            op => op,
        };
        let h = hash_op(&op);
        let ops = &self.ops;
        if let Some(&r) = self.numbering.find(h, |&i| ops[i as usize] == op) {
            return r;
        }
        let r = self.push_op(op);
        let ops = &self.ops;
        self.numbering
            .insert_unique(h, r, |&i| hash_op(&ops[i as usize]));
        r
    }

    pub(super) fn const_slot(&mut self, c: f64) -> u32 {
        let next = self.consts.len() as u32;
        let k = *self.const_index.entry(c.to_bits()).or_insert(next);
        if k == next {
            self.consts.push(c);
            self.const_regs.push(IdMap::NONE);
        }
        k
    }

    pub(super) fn constant(&mut self, c: f64) -> u32 {
        let k = self.const_slot(c);
        self.emit(Op::Const(k))
    }

    /// Compiles `root` (post-order with an explicit stack); returns its register.
    fn compile(&mut self, root: Id) -> Result<u32, CodegenError> {
        if let Some(r) = self.lookup_or_emit_input(root) {
            return Ok(r);
        }
        let arena = self.arena;
        let mut stack = std::mem::take(&mut self.stack);
        stack.clear();
        stack.push((root, false));
        let mut result = Ok(());
        while let Some((id, expanded)) = stack.pop() {
            if self.lookup_or_emit_input(id).is_some() {
                continue;
            }
            let node = arena.node(id);
            if expanded {
                let r = self.emit_node(node);
                self.memo.insert(id, r);
                continue;
            }
            match node {
                Node::Const(b) => {
                    let r = self.constant(f64::from_bits(*b));
                    self.memo.insert(id, r);
                    continue;
                }
                n if is_leaf(n) => {
                    result = Err(CodegenError::UndefinedLeaf(self.describe(id)));
                    break;
                }
                _ => {}
            }
            stack.push((id, true));
            let mut push = |c: Id| {
                if self.lookup(c).is_none() {
                    stack.push((c, false));
                }
            };
            match node {
                Node::Sum(ts, _) => arena.terms(*ts).iter().rev().for_each(|&(_, t)| push(t)),
                Node::Prod(fs) => arena.factors(*fs).iter().rev().for_each(|&(b, _)| push(b)),
                Node::Pow(a, b) | Node::F2(_, a, b) | Node::Cmp(_, a, b) => {
                    push(*b);
                    push(*a);
                }
                Node::F1(_, a) => push(*a),
                Node::If(c, a, b) => {
                    push(*b);
                    push(*a);
                    push(*c);
                }
                Node::Const(_) | Node::Var(_) | Node::Param(_) | Node::Time | Node::Der(_) => {}
            }
        }
        stack.clear();
        self.stack = stack;
        result?;
        Ok(self.reg(root))
    }

    /// Emits the instructions of a non-leaf node whose children are compiled.
    fn emit_node(&mut self, node: &Node) -> u32 {
        match node {
            Node::Sum(ts, c) => {
                let c = f64::from_bits(*c);
                let mut acc = if c != 0.0 {
                    Some(self.constant(c))
                } else {
                    None
                };
                for &(kb, t) in self.arena.terms(*ts) {
                    let k = f64::from_bits(kb);
                    let rt = self.reg(t);
                    let op = match acc {
                        None if k == 1.0 => {
                            acc = Some(rt);
                            continue;
                        }
                        None if k == -1.0 => Op::Neg(rt),
                        None => Op::Scale(self.const_slot(k), rt),
                        Some(a) if k == 1.0 => Op::Add(a, rt),
                        Some(a) if k == -1.0 => Op::Sub(a, rt),
                        Some(a) => Op::AddScaled(a, self.const_slot(k), rt),
                    };
                    acc = Some(self.emit(op));
                }
                match acc {
                    Some(r) => r,
                    None => self.constant(c),
                }
            }
            Node::Prod(fs) => {
                let mut num: Option<u32> = None;
                let mut den: Option<u32> = None;
                let mut single_den: Option<(u32, i32)> = None;
                for &(b, e) in self.arena.factors(*fs) {
                    let rb = self.reg(b);
                    let mag = e.unsigned_abs() as i32;
                    let p = if mag == 1 {
                        rb
                    } else {
                        self.emit(Op::PowI(rb, mag))
                    };
                    let slot = if e > 0 { &mut num } else { &mut den };
                    let prev = *slot;
                    if e < 0 {
                        single_den = if prev.is_none() { Some((rb, e)) } else { None };
                    }
                    let v = match prev {
                        None => p,
                        Some(a) => self.emit(Op::Mul(a, p)),
                    };
                    if e > 0 {
                        num = Some(v);
                    } else {
                        den = Some(v);
                    }
                }
                match (num, den) {
                    (Some(n), None) => n,
                    (Some(n), Some(d)) => self.emit(Op::Div(n, d)),
                    (None, Some(d)) => match single_den {
                        Some((rb, e)) => self.emit(Op::PowI(rb, e)),
                        None => {
                            let one = self.constant(1.0);
                            self.emit(Op::Div(one, d))
                        }
                    },
                    (None, None) => self.constant(1.0),
                }
            }
            Node::Pow(a, b) => {
                let (a, b) = (self.reg(*a), self.reg(*b));
                self.emit(Op::Pow(a, b))
            }
            Node::F1(f, a) => {
                let a = self.reg(*a);
                self.emit(Op::F1(*f, a))
            }
            Node::F2(f, a, b) => {
                let (a, b) = (self.reg(*a), self.reg(*b));
                self.emit(Op::F2(*f, a, b))
            }
            Node::Cmp(op, a, b) => {
                let (a, b) = (self.reg(*a), self.reg(*b));
                self.emit(Op::Cmp(*op, a, b))
            }
            Node::If(c, a, b) => {
                let (c, a, b) = (self.reg(*c), self.reg(*a), self.reg(*b));
                self.emit(Op::Select(c, a, b))
            }
            Node::Const(_) | Node::Var(_) | Node::Param(_) | Node::Time | Node::Der(_) => {
                unreachable!("leaves are bound, not emitted")
            }
        }
    }
}
