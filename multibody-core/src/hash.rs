//! Fast hashing for the compiler's maps: keys are small integers, expression nodes and
//! names, never chosen by an adversary, so a multiplicative hash (FxHash-like) is safe
//! and several times faster than SipHash.

use std::hash::{BuildHasherDefault, Hasher};

/// A fast multiplicative hasher.
#[derive(Default, Clone, Copy)]
pub struct FastHasher(u64);

const SEED: u64 = 0x51_7c_c1_b7_27_22_0a_95;

impl FastHasher {
    #[inline]
    fn add(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(SEED);
    }
}

impl Hasher for FastHasher {
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        let mut chunks = bytes.chunks_exact(8);
        for c in &mut chunks {
            self.add(u64::from_le_bytes(c.try_into().expect("8 bytes")));
        }
        let rest = chunks.remainder();
        if !rest.is_empty() {
            let mut buf = [0u8; 8];
            buf[..rest.len()].copy_from_slice(rest);
            self.add(u64::from_le_bytes(buf) ^ ((rest.len() as u64) << 56));
        }
    }
    #[inline]
    fn write_u8(&mut self, i: u8) {
        self.add(u64::from(i));
    }
    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.add(u64::from(i));
    }
    #[inline]
    fn write_i32(&mut self, i: i32) {
        self.add(u64::from(i as u32));
    }
    #[inline]
    fn write_u64(&mut self, i: u64) {
        self.add(i);
    }
    #[inline]
    fn write_usize(&mut self, i: usize) {
        self.add(i as u64);
    }
    #[inline]
    fn write_isize(&mut self, i: isize) {
        self.add(i as u64);
    }
    #[inline]
    fn finish(&self) -> u64 {
        self.0
    }
}

/// The [`BuildHasher`](std::hash::BuildHasher) of [`FastHasher`].
pub type FastBuild = BuildHasherDefault<FastHasher>;

/// A hash map with [`FastHasher`] (build with `HashMap::default()`).
pub type HashMap<K, V> = std::collections::HashMap<K, V, FastBuild>;

/// A hash set with [`FastHasher`] (build with `HashSet::default()`).
pub type HashSet<K> = std::collections::HashSet<K, FastBuild>;

/// A hash for a `hashbrown` table of items built from other items (expression nodes
/// from their operands, instructions from their registers), placing each by its
/// `anchor` (the newest operand's index) rather than by content: items built from
/// nearby items sit in nearby buckets, so a pass over one part of a large model finds
/// its entries in cache, where a content-only bucket would miss it every time. The
/// content hash's high half `high` gives hashbrown's tag (the top seven bits, on
/// 64-bit targets) and the offset of the bucket within a window of 64 that starts at
/// four buckets per anchor: items sharing an anchor (`x^2`, `x^3`, `2 x + 1`, ...)
/// spread over the window instead of piling onto one bucket, while the window stays
/// a few cache lines. Items without an anchor are placed by `high`. Equal items must
/// have equal anchors.
#[inline]
pub fn anchored_hash(anchor: Option<u32>, high: u32) -> u64 {
    let bucket = match anchor {
        Some(a) => a.wrapping_mul(4).wrapping_add(high & 63),
        None => high,
    };
    (u64::from(high) << 32) | u64::from(bucket)
}
