//! Instruction order of a tape: a topological order that groups instructions of the same
//! kind into runs. An interpreter pays a mispredicted branch whenever the next
//! instruction's kind differs from what the predictor expects; in runs of one kind the
//! dispatch branch is predicted, which makes evaluation and forward mode several times
//! faster on large tapes than the order in which expressions were compiled.

use super::tape::{LsInfo, Op};

/// A key per dispatch target: instructions with equal keys run the same code.
fn kind(op: &Op) -> usize {
    match op {
        Op::Const(_) => 0,
        Op::Input(_) => 1,
        Op::Add(..) => 2,
        Op::Sub(..) => 3,
        Op::Mul(..) => 4,
        Op::Div(..) => 5,
        Op::Neg(_) => 6,
        Op::Scale(..) => 7,
        Op::AddScaled(..) => 8,
        Op::PowI(..) => 9,
        Op::Pow(..) => 10,
        Op::Cmp(..) => 11,
        Op::Select(..) => 12,
        Op::LinearSolve(_) | Op::LsPart => 13,
        Op::F1(f, _) => 14 + *f as usize,
        Op::F2(f, ..) => 40 + *f as usize,
    }
}

/// Number of distinct kinds [`kind`] returns (an upper bound).
const KINDS: usize = 48;

/// The live instructions of `ops` (`live[i]`) in an order that respects dependencies
/// and groups kinds: repeatedly, every ready instruction of the kind with the most ready
/// instructions is emitted, in original order. The instructions marked `first` (closed
/// under dependencies: their operands are marked too) all come before the others. A
/// linear solve and the parts that follow it stay together. Returns old indices (heads
/// of linear solves stand for the solve and its parts, which the caller appends).
pub(crate) fn grouped_order(
    ops: &[Op],
    ls: &[LsInfo],
    live: &[bool],
    first: &[bool],
) -> Vec<usize> {
    let n = ops.len();
    // Head of the unit each register belongs to (a part belongs to its solve).
    let mut head = vec![0u32; n];
    let mut last_head = 0u32;
    for (i, op) in ops.iter().enumerate() {
        if !matches!(op, Op::LsPart) {
            last_head = i as u32;
        }
        head[i] = last_head;
    }
    let mut indegree = vec![0u32; n];
    let mut succ_ptr = vec![0u32; n + 1];
    // Most instructions have one or two operands.
    let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(2 * n);
    let mut preds: Vec<u32> = Vec::new();
    for (i, op) in ops.iter().enumerate() {
        if !live[i] || matches!(op, Op::LsPart) {
            continue;
        }
        preds.clear();
        op.for_each_operand(ls, |r| preds.push(head[r as usize]));
        preds.sort_unstable();
        preds.dedup();
        indegree[i] = preds.len() as u32;
        for &p in &preds {
            pairs.push((p, i as u32));
            succ_ptr[p as usize + 1] += 1;
        }
    }
    for i in 0..n {
        succ_ptr[i + 1] += succ_ptr[i];
    }
    let mut fill: Vec<u32> = succ_ptr.clone();
    let mut succ = vec![0u32; pairs.len()];
    for &(p, s) in &pairs {
        succ[fill[p as usize] as usize] = s;
        fill[p as usize] += 1;
    }
    // Ready instructions by kind, the `first` ones at `KINDS + kind`.
    let slot = |i: usize| kind(&ops[i]) + if first[i] { KINDS } else { 0 };
    let mut ready: Vec<Vec<u32>> = vec![Vec::new(); 2 * KINDS];
    for (i, op) in ops.iter().enumerate() {
        if live[i] && !matches!(op, Op::LsPart) && indegree[i] == 0 {
            ready[slot(i)].push(i as u32);
        }
    }
    let mut order = Vec::with_capacity(n);
    let mut batch: Vec<u32> = Vec::new();
    for phase in [KINDS..2 * KINDS, 0..KINDS] {
        while let Some(k) = phase
            .clone()
            .filter(|&k| !ready[k].is_empty())
            .max_by_key(|&k| (ready[k].len(), std::cmp::Reverse(k)))
        {
            std::mem::swap(&mut batch, &mut ready[k]);
            batch.sort_unstable();
            for &i in &batch {
                order.push(i as usize);
                let iu = i as usize;
                for &s in &succ[succ_ptr[iu] as usize..succ_ptr[iu + 1] as usize] {
                    let su = s as usize;
                    indegree[su] -= 1;
                    if indegree[su] == 0 {
                        ready[slot(su)].push(s);
                    }
                }
            }
            batch.clear();
        }
    }
    order
}
