//! Maps from nodes to nodes: the substitutions and memos of rewriting passes.

use crate::hash::HashMap;

use super::Id;
use super::id_index::DenseU32;

/// A map from nodes to nodes, as substitution reads its map and memo: a hash map for
/// small ones, a [`NodeMap`] for those that cover much of a large arena.
pub trait NodeTable {
    /// The image of `e`, if it has one.
    fn get(&self, e: Id) -> Option<Id>;
    /// Records `r` as the image of `e`.
    fn insert(&mut self, e: Id, r: Id);
}

impl NodeTable for HashMap<Id, Id> {
    #[inline]
    fn get(&self, e: Id) -> Option<Id> {
        HashMap::get(self, &e).copied()
    }

    #[inline]
    fn insert(&mut self, e: Id, r: Id) {
        HashMap::insert(self, e, r);
    }
}

/// A map from nodes to nodes indexed densely by the key's id (a vector, not a hash
/// map): nodes made for one part of a model have nearby ids, so a pass that walks the
/// model part by part finds its entries in cache. One `u32` per id up to the largest
/// key. Used as the memo of [`Arena::import`](super::Arena::import) and of substitutions
/// over a whole model.
#[derive(Clone, Debug, Default)]
pub struct NodeMap(DenseU32);

impl NodeMap {
    /// An empty map.
    pub fn new() -> Self {
        NodeMap(DenseU32::default())
    }

    /// The image of `e`, if recorded.
    #[inline]
    pub fn get(&self, e: Id) -> Option<Id> {
        self.0.get(e).map(Id)
    }

    /// Records `r` as the image of `e`.
    #[inline]
    pub fn insert(&mut self, e: Id, r: Id) {
        self.0.insert(e, r.0);
    }

    /// Forgets every entry.
    pub fn clear(&mut self) {
        self.0.clear();
    }
}

impl NodeTable for NodeMap {
    #[inline]
    fn get(&self, e: Id) -> Option<Id> {
        NodeMap::get(self, e)
    }

    #[inline]
    fn insert(&mut self, e: Id, r: Id) {
        NodeMap::insert(self, e, r);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dense_and_hashed_maps_agree() {
        let mut dense = NodeMap::new();
        let mut hashed: HashMap<Id, Id> = HashMap::default();
        for (e, r) in [(5, 1), (0, 9), (300, 2), (5, 7)] {
            NodeTable::insert(&mut dense, Id(e), Id(r));
            NodeTable::insert(&mut hashed, Id(e), Id(r));
        }
        for e in [0, 1, 5, 299, 300, 301, 10_000] {
            assert_eq!(
                NodeTable::get(&dense, Id(e)),
                NodeTable::get(&hashed, Id(e))
            );
        }
        assert_eq!(dense.get(Id(5)), Some(Id(7)));
        dense.clear();
        assert_eq!(dense.get(Id(5)), None);
    }
}
