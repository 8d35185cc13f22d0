//! Expression stores: where the nodes of [`Expr`](super::Expr) values live.
//!
//! A store is an [`Arena`] that belongs to a model: every [`System`](crate::model::System)
//! holds its store, the systems built inside it share it, and the compiled forms that
//! print the model's equations keep it too. Dropping them returns the store's memory.
//! Each store has its own lock, so threads building or compiling different models never
//! wait for each other.
//!
//! Expressions built outside any component (`phi.sin() * 2.0` in user code) go to the
//! thread's *current* store: the store of the model being built on this thread (set by
//! [`System::new`](crate::model::System::new) and while a component builds itself), or,
//! before any model exists, a new store that the next model on this thread adopts.
//! An expression used in a system of another store is copied into that system's store.

use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::sync::{Arc, LazyLock, Mutex, MutexGuard, RwLock, Weak};

use super::{Arena, Id, NodeMap};
use crate::hash::HashMap;

/// The first store number (smaller numbers tag the leaves of [`Expr`](super::Expr)).
pub(crate) const FIRST_STORE: u32 = 3;

/// A store: its number and its arena.
pub(crate) struct StoreCell {
    id: u32,
    arena: Mutex<Arena>,
    /// Whether a system holds it (a store made for expressions built before any model
    /// is adopted by the next model).
    owned: AtomicBool,
}

impl StoreCell {
    /// The store's number.
    pub(crate) fn id(&self) -> u32 {
        self.id
    }

    /// Locks the store's arena (a poisoned lock is recovered: the arena only grows and
    /// stays consistent).
    pub(crate) fn lock(&self) -> MutexGuard<'_, Arena> {
        self.arena.lock().unwrap_or_else(|e| e.into_inner())
    }
}

impl Drop for StoreCell {
    fn drop(&mut self) {
        registry().remove(&self.id);
    }
}

impl std::fmt::Debug for StoreCell {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "ExprStore#{}", self.id)
    }
}

/// Every live store by number (only for expressions met outside their own thread's
/// current store).
static REGISTRY: LazyLock<RwLock<HashMap<u32, Weak<StoreCell>>>> =
    LazyLock::new(|| RwLock::new(HashMap::default()));

fn registry() -> std::sync::RwLockWriteGuard<'static, HashMap<u32, Weak<StoreCell>>> {
    REGISTRY.write().unwrap_or_else(|e| e.into_inner())
}

static NEXT_ID: AtomicU32 = AtomicU32::new(FIRST_STORE);

fn new_cell(owned: bool) -> Arc<StoreCell> {
    let id = NEXT_ID.fetch_add(1, Ordering::Relaxed);
    assert!(id >= FIRST_STORE, "fewer than 2^32 expression stores");
    let cell = Arc::new(StoreCell {
        id,
        arena: Mutex::new(Arena::new()),
        owned: AtomicBool::new(owned),
    });
    registry().insert(id, Arc::downgrade(&cell));
    cell
}

/// A model's expression store, shared by the systems built in it (cheap to clone).
#[derive(Clone, Debug)]
pub struct ExprStore(pub(crate) Arc<StoreCell>);

/// This thread's current store and recently used ones.
struct Current {
    /// The current store.
    current: Weak<StoreCell>,
    /// The current store while no system holds it (kept alive here until a model
    /// adopts it).
    unowned: Option<Arc<StoreCell>>,
    /// Stores met lately, by number.
    recent: Vec<(u32, Weak<StoreCell>)>,
}

thread_local! {
    static CURRENT: RefCell<Current> = const {
        RefCell::new(Current { current: Weak::new(), unowned: None, recent: Vec::new() })
    };
}

/// How many stores a thread remembers besides its current one.
const RECENT: usize = 4;

impl ExprStore {
    /// The store of a new model built on this thread: the current store if no system
    /// holds it yet (it has the expressions built before the model), otherwise a new
    /// one. It becomes the thread's current store.
    pub fn for_new_model() -> ExprStore {
        CURRENT.with_borrow_mut(|c| {
            let cell = match c.unowned.take() {
                Some(cell) => cell,
                None => new_cell(true),
            };
            cell.owned.store(true, Ordering::Relaxed);
            c.current = Arc::downgrade(&cell);
            ExprStore(cell)
        })
    }

    /// Makes this the thread's current store until the guard is dropped.
    pub fn enter(&self) -> StoreGuard {
        let previous =
            CURRENT.with_borrow_mut(|c| std::mem::replace(&mut c.current, Arc::downgrade(&self.0)));
        StoreGuard { previous }
    }

    /// The store's number (the tag of the expressions that live in it).
    pub fn id(&self) -> u32 {
        self.0.id
    }

    /// How many stores exist in this process (each model, with what was compiled from
    /// it, holds one; a thread may hold one more for expressions built before its next
    /// model).
    pub fn live() -> usize {
        REGISTRY.read().unwrap_or_else(|e| e.into_inner()).len()
    }

    /// Whether two handles are the same store.
    pub fn same(&self, other: &ExprStore) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// Restores the previous current store when dropped (see [`ExprStore::enter`]).
pub struct StoreGuard {
    previous: Weak<StoreCell>,
}

impl Drop for StoreGuard {
    fn drop(&mut self) {
        let previous = std::mem::take(&mut self.previous);
        CURRENT.with_borrow_mut(|c| c.current = previous);
    }
}

/// The thread's current store (a new one, kept by the thread until a model adopts it,
/// when there is none).
pub(crate) fn current() -> Arc<StoreCell> {
    CURRENT.with_borrow_mut(|c| {
        if let Some(cell) = c.current.upgrade() {
            return cell;
        }
        let cell = new_cell(false);
        c.current = Arc::downgrade(&cell);
        c.unowned = Some(cell.clone());
        cell
    })
}

/// The store numbered `id`.
///
/// # Panics
/// If that store was dropped: the expression belonged to a model (and its compiled
/// forms) that no longer exists.
pub(crate) fn get(id: u32) -> Arc<StoreCell> {
    find(id).unwrap_or_else(|| {
        panic!(
            "an expression was used after the model it was built for (and everything \
             compiled from it) was dropped"
        )
    })
}

/// The store numbered `id`, if it still exists.
pub(crate) fn find(id: u32) -> Option<Arc<StoreCell>> {
    CURRENT.with_borrow_mut(|c| {
        if let Some(cell) = c.current.upgrade()
            && cell.id == id
        {
            return Some(cell);
        }
        if let Some(k) = c.recent.iter().position(|(i, _)| *i == id) {
            if let Some(cell) = c.recent[k].1.upgrade() {
                return Some(cell);
            }
            c.recent.swap_remove(k);
        }
        let cell = REGISTRY
            .read()
            .unwrap_or_else(|e| e.into_inner())
            .get(&id)
            .and_then(Weak::upgrade)?;
        if c.recent.len() >= RECENT {
            c.recent.remove(0);
        }
        c.recent.push((id, Arc::downgrade(&cell)));
        Some(cell)
    })
}

/// A copy of node `e` of store `from` (and everything below it) in a new arena,
/// made while holding no other store's lock.
pub(crate) fn export(from: &StoreCell, e: Id) -> (Arena, Id) {
    let src = from.lock();
    let mut out = Arena::new();
    let mut memo = NodeMap::new();
    let id = out.import(&src, e, &mut super::handle::same_leaf, &mut memo);
    (out, id)
}
