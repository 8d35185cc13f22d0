//! The process-wide table of symbol names: every variable and parameter name is interned
//! once, as a number, and kept for the whole process as a `&'static str`.
//!
//! The table is split into shards by the hash of a name, each behind its own lock, so
//! that threads building different models rarely wait for each other. A symbol's number
//! holds its shard in its low bits.

use std::hash::BuildHasher;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard};

use hashbrown::HashTable;

/// Number of shards (a power of two).
const SHARDS: usize = 32;
/// Bits of a symbol number that give its shard.
const SHARD_BITS: u32 = SHARDS.trailing_zeros();

/// One shard: the names whose hash falls into it.
struct Shard {
    /// Where the names are kept.
    store: NameStore,
    /// Each name of the shard, by its index in the shard.
    names: Vec<&'static str>,
    /// Indices in the shard placed by the hash of their names, each with that hash
    /// (growing the table reads no name).
    table: HashTable<Entry>,
}

/// An entry of a shard's table: an index in the shard and the hash of its name.
#[derive(Clone, Copy)]
struct Entry {
    index: u32,
    hash: u64,
}

/// Storage for names that is never freed, so each name is a `&'static str`: a model's
/// variables carry their names as such (copying one touches no memory). Names are
/// written one after the other into large blocks (no allocation per name).
struct NameStore {
    /// The unused end of the current block.
    rest: &'static mut [u8],
}

impl NameStore {
    /// Bytes in a block (a longer name gets a block of its own length).
    const BLOCK: usize = 16 * 1024;

    /// A copy of `name` that lives as long as the process.
    fn keep(&mut self, name: &str) -> &'static str {
        let n = name.len();
        if self.rest.len() < n {
            self.rest = Box::leak(vec![0u8; n.max(Self::BLOCK)].into_boxed_slice());
        }
        let (head, tail) = std::mem::take(&mut self.rest).split_at_mut(n);
        self.rest = tail;
        head.copy_from_slice(name.as_bytes());
        let head: &'static [u8] = head;
        std::str::from_utf8(head).expect("a copy of a str")
    }
}

/// The hash of a symbol name.
fn name_hash(name: &str) -> u64 {
    crate::hash::FastBuild::default().hash_one(name)
}

/// The shard of a name's hash (from its high bits: the table uses the low ones).
fn shard_of_hash(hash: u64) -> usize {
    (hash >> (64 - SHARD_BITS)) as usize
}

static TABLE: [Mutex<Shard>; SHARDS] = [const {
    Mutex::new(Shard {
        store: NameStore { rest: &mut [] },
        names: Vec::new(),
        table: HashTable::new(),
    })
}; SHARDS];

/// Locks a shard (a poisoned lock is recovered: a shard only grows and stays
/// consistent).
fn lock(shard: usize) -> MutexGuard<'static, Shard> {
    TABLE[shard].lock().unwrap_or_else(|e| e.into_inner())
}

impl Shard {
    fn find(&self, name: &str, hash: u64) -> Option<u32> {
        self.table
            .find(hash, |e| {
                e.hash == hash && self.names[e.index as usize] == name
            })
            .map(|e| e.index)
    }
}

/// The symbol number of a shard index.
fn symbol_of(shard: usize, index: u32) -> u32 {
    let s = u64::from(index) << SHARD_BITS | shard as u64;
    u32::try_from(s).expect("fewer than 2^32 symbols")
}

/// Interns `name`: its symbol number, and the name as the table keeps it.
pub(crate) fn intern(name: &str) -> (u32, &'static str) {
    let hash = name_hash(name);
    let k = shard_of_hash(hash);
    let mut shard = lock(k);
    if let Some(i) = shard.find(name, hash) {
        return (symbol_of(k, i), shard.names[i as usize]);
    }
    let index = u32::try_from(shard.names.len()).expect("fewer than 2^32 symbols");
    let kept = shard.store.keep(name);
    shard.names.push(kept);
    shard
        .table
        .insert_unique(hash, Entry { index, hash }, |e| e.hash);
    let sym = symbol_of(k, index);
    BOUND.fetch_max(sym as usize + 1, Ordering::Relaxed);
    (sym, kept)
}

/// The symbol of `name`, if it was interned.
pub(crate) fn lookup(name: &str) -> Option<u32> {
    let hash = name_hash(name);
    let k = shard_of_hash(hash);
    lock(k).find(name, hash).map(|i| symbol_of(k, i))
}

/// The name of a symbol.
///
/// # Panics
/// If `sym` was never returned by [`intern`].
pub(crate) fn name(sym: u32) -> &'static str {
    let shard = lock(sym as usize & (SHARDS - 1));
    shard.names[(sym >> SHARD_BITS) as usize]
}

/// One more than the largest symbol number given out so far (a bound for tables
/// indexed by symbol).
pub(crate) fn bound() -> usize {
    BOUND.load(Ordering::Relaxed)
}

/// See [`bound`].
static BOUND: AtomicUsize = AtomicUsize::new(0);

/// The name of a symbol (a variable or parameter name interned by this process).
pub fn symbol_name(sym: u32) -> String {
    name(sym).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn symbols_are_interned_once_and_keep_their_names() {
        // Names that are prefixes of each other, the empty name, and enough names to
        // grow every shard several times (other tests intern names at the same time,
        // so only this test's names are checked).
        let names: Vec<String> = ["", "sym_test.a", "sym_test.a.b", "sym_test.a.bc"]
            .iter()
            .map(|s| s.to_string())
            .chain((0..5000).map(|k| format!("sym_test.chain.inertia{k}.flange_a.phi")))
            .collect();
        let ids: Vec<u32> = names.iter().map(|n| intern(n).0).collect();
        for (n, &id) in names.iter().zip(&ids) {
            assert_eq!(name(id), n);
            assert_eq!(intern(n).0, id, "interning again gives the same id");
            assert_eq!(lookup(n), Some(id));
            assert!((id as usize) < bound());
        }
        let mut sorted = ids.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), names.len(), "distinct names, distinct ids");
        assert_eq!(lookup("sym_test.a.b.d"), None);
    }

    #[test]
    fn threads_interning_the_same_names_agree() {
        let names: Vec<String> = (0..2000).map(|k| format!("sym_threads.n{k}")).collect();
        let a = std::thread::scope(|s| {
            let h: Vec<_> = (0..2)
                .map(|_| s.spawn(|| names.iter().map(|n| intern(n).0).collect::<Vec<_>>()))
                .collect();
            h.into_iter()
                .map(|h| h.join().expect("thread"))
                .collect::<Vec<_>>()
        });
        assert_eq!(a[0], a[1]);
    }
}
