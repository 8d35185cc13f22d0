//! The priority queue of the extended Jacobian's vertex elimination
//! ([`ExtendedJacobian`](super::extended::ExtendedJacobian)): vertices by cost, then by
//! index, cheapest first.

use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap};

/// Vertices by `(cost, vertex)`, lowest first, with repeats allowed (entries go stale
/// and are checked when popped); costs above a limit are never queued. Costs are few
/// distinct small integers: one bucket per cost, holding the vertices first queued in
/// ascending order as a plain list (most vertices are queued once, so most pops read
/// memory in order) and those queued again in a heap.
pub(crate) struct EliminationQueue {
    max_cost: i64,
    buckets: BTreeMap<i64, CostBucket>,
}

#[derive(Default)]
struct CostBucket {
    ascending: Vec<u32>,
    next: usize,
    again: BinaryHeap<Reverse<u32>>,
}

impl EliminationQueue {
    /// An empty queue that ignores costs above `max_cost`.
    pub(crate) fn up_to(max_cost: i64) -> Self {
        EliminationQueue {
            max_cost,
            buckets: BTreeMap::new(),
        }
    }

    /// Queues `v` at cost `c`; within a cost, calls give ascending vertices.
    pub(crate) fn push_ascending(&mut self, c: i64, v: u32) {
        if c > self.max_cost {
            return;
        }
        let b = self.buckets.entry(c).or_default();
        debug_assert!(b.ascending.last().is_none_or(|&l| l < v));
        b.ascending.push(v);
    }

    /// Queues `v` at cost `c`, in any order.
    pub(crate) fn push(&mut self, c: i64, v: u32) {
        if c > self.max_cost {
            return;
        }
        self.buckets.entry(c).or_default().again.push(Reverse(v));
    }

    /// The lowest `(cost, vertex)` queued, removed.
    pub(crate) fn pop(&mut self) -> Option<(i64, u32)> {
        loop {
            let mut entry = self.buckets.first_entry()?;
            let c = *entry.key();
            let b = entry.get_mut();
            let first = b.ascending.get(b.next).copied();
            let again = b.again.peek().map(|r| r.0);
            let v = match (first, again) {
                (Some(f), Some(a)) if a < f => b.again.pop().map(|r| r.0),
                (Some(f), _) => {
                    b.next += 1;
                    Some(f)
                }
                (None, Some(_)) => b.again.pop().map(|r| r.0),
                (None, None) => None,
            };
            match v {
                Some(v) => return Some((c, v)),
                None => {
                    entry.remove();
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The queue pops exactly what a binary heap of `(cost, vertex)` pops, repeats
    /// included, for interleaved ascending first pushes, later pushes and pops.
    #[test]
    fn elimination_queue_pops_in_cost_then_vertex_order() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = |m: u64| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 33) % m
        };
        let mut queue = EliminationQueue::up_to(i64::MAX);
        let mut heap: BinaryHeap<Reverse<(i64, u32)>> = BinaryHeap::new();
        for v in 0..500u32 {
            let c = next(7) as i64 - 3;
            queue.push_ascending(c, v);
            heap.push(Reverse((c, v)));
        }
        let mut popped = 0;
        while let Some(Reverse(expected)) = heap.pop() {
            assert_eq!(queue.pop(), Some(expected));
            popped += 1;
            // Push some vertices again, at costs around the current one.
            for _ in 0..next(3) {
                if popped < 1500 {
                    let (c, v) = (expected.0 + next(5) as i64 - 2, next(500) as u32);
                    queue.push(c, v);
                    heap.push(Reverse((c, v)));
                }
            }
        }
        assert_eq!(queue.pop(), None);
        assert!(popped > 500);
    }

    /// Costs above the limit never enter (the elimination would stop before them).
    #[test]
    fn costs_above_the_limit_are_not_queued() {
        let mut queue = EliminationQueue::up_to(2);
        queue.push_ascending(3, 0);
        queue.push_ascending(2, 1);
        queue.push(5, 2);
        queue.push(-1, 3);
        assert_eq!(queue.pop(), Some((-1, 3)));
        assert_eq!(queue.pop(), Some((2, 1)));
        assert_eq!(queue.pop(), None);
    }
}
