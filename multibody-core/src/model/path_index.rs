//! An index of paths (connectors by their full path) whose texts are copied into one
//! buffer: looking a path up compares it with that compact copy, not with the string
//! in the model, which in a large model lies in its own allocation far from anything
//! read recently.

use std::hash::BuildHasher;

use hashbrown::HashTable;

/// Paths by text, each with a value.
pub(crate) struct PathIndex {
    /// Every path's text, one after the other.
    text: String,
    /// Where each path ends in `text`; it starts where the previous one ends.
    ends: Vec<u32>,
    /// Entries placed by the hash of their path.
    table: HashTable<Entry>,
}

/// An entry of the table: which path (its position in `ends`), the hash of its text,
/// and the value recorded for it.
#[derive(Clone, Copy)]
struct Entry {
    path: u32,
    hash: u64,
    value: u32,
}

/// Path `i` of a text and its ends (a free function: `insert` reads it while the table
/// is borrowed mutably).
fn path_in<'t>(text: &'t str, ends: &[u32], i: u32) -> &'t str {
    let i = i as usize;
    let start = if i == 0 { 0 } else { ends[i - 1] as usize };
    &text[start..ends[i] as usize]
}

fn path_hash(path: &str) -> u64 {
    crate::hash::FastBuild::default().hash_one(path)
}

impl PathIndex {
    /// An empty index with room for `paths` paths of `bytes` bytes in all.
    pub(crate) fn with_capacity(paths: usize, bytes: usize) -> Self {
        PathIndex {
            text: String::with_capacity(bytes),
            ends: Vec::with_capacity(paths),
            table: HashTable::with_capacity(paths),
        }
    }

    /// The text of path `i` (in the order they were inserted).
    fn path(&self, i: u32) -> &str {
        path_in(&self.text, &self.ends, i)
    }

    /// Records `value` for `path` (a path inserted again gets the new value).
    pub(crate) fn insert(&mut self, path: &str, value: u32) {
        let hash = path_hash(path);
        let (text, ends) = (&self.text, &self.ends);
        let same = |e: &Entry| e.hash == hash && path_in(text, ends, e.path) == path;
        if let Some(e) = self.table.find_mut(hash, same) {
            e.value = value;
            return;
        }
        let i = u32::try_from(self.ends.len()).expect("fewer than 2^32 paths");
        self.text.push_str(path);
        self.ends
            .push(u32::try_from(self.text.len()).expect("paths under 4 GB"));
        let entry = Entry {
            path: i,
            hash,
            value,
        };
        self.table.insert_unique(hash, entry, |e| e.hash);
    }

    /// The value recorded for `path`.
    pub(crate) fn get(&self, path: &str) -> Option<u32> {
        let hash = path_hash(path);
        self.table
            .find(hash, |e| e.hash == hash && self.path(e.path) == path)
            .map(|e| e.value)
    }

    /// Every path, in the order first inserted.
    pub(crate) fn paths(&self) -> impl Iterator<Item = &str> {
        (0..self.ends.len() as u32).map(|i| self.path(i))
    }
}

#[cfg(test)]
mod tests {
    use super::PathIndex;

    #[test]
    fn paths_are_found_by_text_and_a_second_insert_updates_the_value() {
        let mut index = PathIndex::with_capacity(2, 8);
        // Prefixes of each other, the empty path, and enough paths to grow the table
        // and the text beyond what was reserved.
        let paths: Vec<String> = ["", "a", "a.b", "a.bc"]
            .iter()
            .map(|s| s.to_string())
            .chain((0..3000).map(|k| format!("chain.sd{k}.flange_a")))
            .collect();
        for (k, p) in paths.iter().enumerate() {
            index.insert(p, k as u32 * 2);
        }
        for (k, p) in paths.iter().enumerate() {
            assert_eq!(index.get(p), Some(k as u32 * 2), "{p}");
        }
        assert_eq!(index.get("a.b.c"), None);
        assert_eq!(index.get("chain.sd3000.flange_a"), None);
        index.insert("a.b", 7);
        assert_eq!(index.get("a.b"), Some(7));
        let listed: Vec<&str> = index.paths().collect();
        assert_eq!(
            listed.len(),
            paths.len(),
            "a path inserted twice is listed once"
        );
        assert_eq!(listed[..4], ["", "a", "a.b", "a.bc"]);
        assert_eq!(listed[4], "chain.sd0.flange_a");
    }
}
