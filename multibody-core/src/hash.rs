//! Hashing for the compiler's maps: keys are small integers, expression nodes and
//! names, never chosen by an adversary, so rustc's Fx hash (`rustc-hash`) is safe and
//! several times faster than SipHash; and the placement of interned items by locality
//! ([`anchored_hash`]).

/// The [`BuildHasher`](std::hash::BuildHasher) of the maps below.
pub type FastBuild = rustc_hash::FxBuildHasher;

/// A hash map with the Fx hash (build with `HashMap::default()`).
pub type HashMap<K, V> = std::collections::HashMap<K, V, FastBuild>;

/// A hash set with the Fx hash (build with `HashSet::default()`).
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
