//! Dense maps keyed by node id: a vector indexed by id instead of a hash map.

use super::Id;

/// A `u32` per id (`u32::MAX` when absent), growing (doubling) on insertion: the
/// storage of [`IdIndex`] and [`NodeMap`](super::NodeMap).
#[derive(Clone, Debug, Default)]
pub(crate) struct DenseU32(Vec<u32>);

impl DenseU32 {
    const NONE: u32 = u32::MAX;

    /// An empty map sized for ids below `len`.
    pub(crate) fn with_len(len: usize) -> Self {
        DenseU32(vec![Self::NONE; len])
    }

    /// Forgets the value of `id`.
    #[inline]
    pub(crate) fn remove(&mut self, id: Id) {
        if let Some(v) = self.0.get_mut(id.index()) {
            *v = Self::NONE;
        }
    }

    /// The value of `id`, if set.
    #[inline]
    pub(crate) fn get(&self, id: Id) -> Option<u32> {
        match self.0.get(id.index()) {
            Some(&v) if v != Self::NONE => Some(v),
            _ => None,
        }
    }

    /// Sets the value of `id`.
    #[inline]
    pub(crate) fn insert(&mut self, id: Id, v: u32) {
        let i = id.index();
        if i >= self.0.len() {
            self.0.resize((i + 1).max(2 * self.0.len()), Self::NONE);
        }
        self.0[i] = v;
    }

    /// Forgets every value.
    pub(crate) fn clear(&mut self) {
        self.0.clear();
    }
}

/// The position of each id of a list, looked up by the id itself (a vector indexed by
/// id, not a hash map): ids made for one part of a model lie close together, so
/// lookups stay in cache where hashed ones would not. Memory is one `u32` per id up to
/// the largest listed.
#[derive(Clone, Debug, Default)]
pub struct IdIndex(DenseU32);

impl IdIndex {
    /// The index of `ids`; an id listed twice has its last position.
    pub fn new(ids: &[Id]) -> Self {
        let mut index = IdIndex::default();
        if let Some(last) = ids.iter().max() {
            index.insert(*last, 0); // sizes the vector once
        }
        for (k, &id) in ids.iter().enumerate() {
            index.insert(id, k);
        }
        index
    }

    /// Lists `id` at position `k` (growing the index when `id` is beyond it).
    pub fn insert(&mut self, id: Id, k: usize) {
        self.0.insert(id, k as u32);
    }

    /// The position of `id`, if listed.
    #[inline]
    pub fn get(&self, id: Id) -> Option<usize> {
        self.0.get(id).map(|k| k as usize)
    }

    /// Whether `id` is listed.
    #[inline]
    pub fn contains(&self, id: Id) -> bool {
        self.get(id).is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_are_found_by_id_and_the_last_of_a_repeated_id_wins() {
        let index = IdIndex::new(&[Id(7), Id(2), Id(40), Id(2)]);
        assert_eq!(index.get(Id(7)), Some(0));
        assert_eq!(index.get(Id(2)), Some(3));
        assert_eq!(index.get(Id(40)), Some(2));
        assert_eq!(index.get(Id(3)), None);
        assert_eq!(index.get(Id(41)), None);
        assert!(!IdIndex::new(&[]).contains(Id(0)));
        let mut grown = IdIndex::default();
        grown.insert(Id(9), 4);
        grown.insert(Id(1000), 5);
        assert_eq!((grown.get(Id(9)), grown.get(Id(1000))), (Some(4), Some(5)));
        assert_eq!(grown.get(Id(500)), None);
    }
}
