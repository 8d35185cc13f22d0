//! The process-wide arena behind [`Expr`], with named symbols as leaves.

use crate::hash::HashMap;
use hashbrown::HashTable;
use std::fmt;
use std::hash::BuildHasher;
use std::ops::{Add, Div, Mul, Neg, Sub};
use std::sync::{LazyLock, Mutex, MutexGuard};

use super::{Arena, Cmp, Func1, Func2, Id, NameResolver, Node};

/// The global arena and its symbol table.
pub(crate) struct Global {
    pub(crate) arena: Arena,
    /// Where the names are kept.
    store: NameStore,
    /// Each symbol's name, by id.
    names: Vec<&'static str>,
    /// Symbol ids placed by the hash of their names, each with that hash (growing the
    /// table reads no name).
    table: HashTable<SymbolEntry>,
}

/// An entry of the symbol table: a symbol id and the hash of its name.
#[derive(Clone, Copy)]
struct SymbolEntry {
    id: u32,
    hash: u64,
}

/// Storage for symbol names that is never freed, so each name is a `&'static str`:
/// a model's variables carry their names as such (copying one touches no memory).
/// Names are written one after the other into large blocks (no allocation per name,
/// and the names of one model lie in the order they were made). Symbols live as long
/// as the process anyway: the global arena is append-only.
struct NameStore {
    /// The unused end of the current block.
    rest: &'static mut [u8],
}

impl NameStore {
    /// Bytes in a block (a longer name gets a block of its own length).
    const BLOCK: usize = 64 * 1024;

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

impl Global {
    /// An empty arena and symbol table.
    fn new() -> Self {
        Global {
            arena: Arena::new(),
            store: NameStore { rest: &mut [] },
            names: Vec::new(),
            table: HashTable::new(),
        }
    }

    /// Interns a symbol name.
    pub(crate) fn symbol(&mut self, name: &str) -> u32 {
        let hash = name_hash(name);
        if let Some(i) = self.find(name, hash) {
            return i;
        }
        let i = u32::try_from(self.names.len()).expect("fewer than 2^32 symbols");
        let kept = self.store.keep(name);
        self.names.push(kept);
        self.table
            .insert_unique(hash, SymbolEntry { id: i, hash }, |e| e.hash);
        i
    }

    /// The symbol named `name`, whose name hashes to `hash`.
    fn find(&self, name: &str, hash: u64) -> Option<u32> {
        self.table
            .find(hash, |e| e.hash == hash && self.name(e.id) == name)
            .map(|e| e.id)
    }

    /// The id of an interned symbol name.
    pub(crate) fn lookup(&self, name: &str) -> Option<u32> {
        self.find(name, name_hash(name))
    }

    /// The name of a symbol.
    pub(crate) fn name(&self, sym: u32) -> &'static str {
        self.names[sym as usize]
    }

    /// Number of interned symbols.
    pub(crate) fn n_symbols(&self) -> usize {
        self.names.len()
    }
}

impl NameResolver for Global {
    fn var(&self, i: u32) -> String {
        self.name(i).to_string()
    }
    fn param(&self, i: u32) -> String {
        self.name(i).to_string()
    }
}

static GLOBAL: LazyLock<Mutex<Global>> = LazyLock::new(|| Mutex::new(Global::new()));

/// Locks the global arena (a poisoned lock is recovered: the arena is append-only and
/// stays consistent).
pub(crate) fn global() -> MutexGuard<'static, Global> {
    GLOBAL.lock().unwrap_or_else(|e| e.into_inner())
}

/// The unknown (or, with `param`, the parameter) named `name`, its symbol, and its
/// name as the symbol table keeps it (for the whole process: copying it is free).
pub(crate) fn named_leaf(name: &str, param: bool) -> (Expr, u32, &'static str) {
    let mut g = global();
    let s = g.symbol(name);
    let id = if param {
        g.arena.param(s)
    } else {
        g.arena.var(s)
    };
    (Expr(id), s, g.name(s))
}

/// The name of a global symbol.
pub fn symbol_name(sym: u32) -> String {
    global().name(sym).to_string()
}

/// A symbolic expression in the process-wide arena: cheap to copy, comparable by
/// identity (structurally equal expressions are the same `Expr`), and built with the
/// usual operators:
///
/// ```
/// use multibody_core::expr::Expr;
/// let phi = Expr::var("pendulum.phi");
/// let e = phi.sin() * 2.0 + Expr::var("pendulum.w");
/// assert_eq!(e.to_string(), "2*sin(pendulum.phi) + pendulum.w");
/// ```
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Expr(pub(crate) Id);

fn with<R>(f: impl FnOnce(&mut Arena) -> R) -> R {
    f(&mut global().arena)
}

impl Expr {
    /// The node id in the global arena.
    pub fn id(self) -> Id {
        self.0
    }

    /// A numeric constant.
    pub fn constant(c: f64) -> Expr {
        Expr(with(|a| a.constant(c)))
    }

    /// The unknown named `name` (a full path such as `motor.inertia.phi`).
    pub fn var(name: &str) -> Expr {
        named_leaf(name, false).0
    }

    /// The parameter named `name`.
    pub fn param(name: &str) -> Expr {
        named_leaf(name, true).0
    }

    /// Time.
    pub fn time() -> Expr {
        Expr(with(|a| a.time()))
    }

    /// The value when this is a constant.
    pub fn as_f64(self) -> Option<f64> {
        with(|a| a.as_const(self.0))
    }

    /// The name when this is a variable or parameter leaf.
    pub fn name(self) -> Option<String> {
        let g = global();
        match g.arena.node(self.0) {
            Node::Var(s) | Node::Param(s) => Some(g.name(*s).to_string()),
            _ => None,
        }
    }

    /// Whether this is a variable leaf.
    pub fn is_var(self) -> bool {
        matches!(with(|a| *a.node(self.0)), Node::Var(_))
    }

    /// Time derivative `der(self)`.
    pub fn der(self) -> Expr {
        Expr(with(|a| a.der(self.0)))
    }

    fn f1(self, f: Func1) -> Expr {
        Expr(with(|a| a.f1(f, self.0)))
    }

    /// sine
    pub fn sin(self) -> Expr {
        self.f1(Func1::Sin)
    }
    /// cosine
    pub fn cos(self) -> Expr {
        self.f1(Func1::Cos)
    }
    /// tangent
    pub fn tan(self) -> Expr {
        self.f1(Func1::Tan)
    }
    /// arc sine
    pub fn asin(self) -> Expr {
        self.f1(Func1::Asin)
    }
    /// arc cosine
    pub fn acos(self) -> Expr {
        self.f1(Func1::Acos)
    }
    /// arc tangent
    pub fn atan(self) -> Expr {
        self.f1(Func1::Atan)
    }
    /// exponential
    pub fn exp(self) -> Expr {
        self.f1(Func1::Exp)
    }
    /// natural logarithm
    pub fn ln(self) -> Expr {
        self.f1(Func1::Log)
    }
    /// square root
    pub fn sqrt(self) -> Expr {
        self.f1(Func1::Sqrt)
    }
    /// absolute value
    pub fn abs(self) -> Expr {
        self.f1(Func1::Abs)
    }
    /// sign (-1, 0, 1)
    pub fn sign(self) -> Expr {
        self.f1(Func1::Sign)
    }
    /// hyperbolic sine
    pub fn sinh(self) -> Expr {
        self.f1(Func1::Sinh)
    }
    /// hyperbolic cosine
    pub fn cosh(self) -> Expr {
        self.f1(Func1::Cosh)
    }
    /// hyperbolic tangent
    pub fn tanh(self) -> Expr {
        self.f1(Func1::Tanh)
    }
    /// `atan2(self, x)`
    pub fn atan2(self, x: impl Into<Expr>) -> Expr {
        let x = x.into();
        Expr(with(|a| a.f2(Func2::Atan2, self.0, x.0)))
    }
    /// minimum
    pub fn min(self, b: impl Into<Expr>) -> Expr {
        let b = b.into();
        Expr(with(|a| a.f2(Func2::Min, self.0, b.0)))
    }
    /// maximum
    pub fn max(self, b: impl Into<Expr>) -> Expr {
        let b = b.into();
        Expr(with(|a| a.f2(Func2::Max, self.0, b.0)))
    }
    /// `self ^ e`
    pub fn pow(self, e: impl Into<Expr>) -> Expr {
        let e = e.into();
        Expr(with(|a| a.pow(self.0, e.0)))
    }
    /// `self ^ n`
    pub fn powi(self, n: i32) -> Expr {
        Expr(with(|a| a.powi(self.0, n)))
    }

    fn cmp(self, op: Cmp, b: impl Into<Expr>) -> Expr {
        let b = b.into();
        Expr(with(|a| a.cmp(op, self.0, b.0)))
    }
    /// `self < b` (1 when true, 0 when false)
    pub fn lt(self, b: impl Into<Expr>) -> Expr {
        self.cmp(Cmp::Lt, b)
    }
    /// `self <= b`
    pub fn le(self, b: impl Into<Expr>) -> Expr {
        self.cmp(Cmp::Le, b)
    }
    /// `self > b`
    pub fn gt(self, b: impl Into<Expr>) -> Expr {
        self.cmp(Cmp::Gt, b)
    }
    /// `self >= b`
    pub fn ge(self, b: impl Into<Expr>) -> Expr {
        self.cmp(Cmp::Ge, b)
    }

    /// `if cond then a else b` (cond nonzero means true).
    pub fn if_else(cond: Expr, a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
        let (a, b) = (a.into(), b.into());
        Expr(with(|ar| ar.ite(cond.0, a.0, b.0)))
    }

    /// Partial derivative with respect to a leaf (variable, parameter, time or `der(x)`).
    pub fn diff(self, wrt: Expr) -> Expr {
        Expr(with(|a| a.diff(self.0, wrt.0)))
    }

    /// Total time derivative.
    pub fn time_derivative(self) -> Expr {
        Expr(with(|a| a.time_derivative(self.0)))
    }

    /// Replaces leaves (or any subexpressions) and re-simplifies.
    pub fn substitute(self, pairs: &[(Expr, Expr)]) -> Expr {
        let map: HashMap<Id, Id> = pairs.iter().map(|(k, v)| (k.0, v.0)).collect();
        Expr(with(|a| a.substitute(self.0, &map)))
    }

    /// Solves `self = 0` for the leaf `x` when linear in it: `(solution, coefficient)`.
    pub fn solve_for(self, x: Expr) -> Option<(Expr, Expr)> {
        with(|a| a.solve_linear(self.0, x.0)).map(|s| (Expr(s.solution), Expr(s.coefficient)))
    }

    /// Whether the leaf `x` occurs in this expression.
    pub fn contains(self, x: Expr) -> bool {
        with(|a| a.contains(self.0, x.0))
    }

    /// Evaluates with leaf values by name (`"time"` for time); `None` when a leaf has no
    /// value.
    pub fn eval(self, values: &dyn Fn(&str) -> Option<f64>) -> Option<f64> {
        let g = global();
        g.arena.eval(self.0, &|n| match n {
            Node::Var(s) | Node::Param(s) => values(g.name(*s)),
            Node::Time => values("time"),
            Node::Der(_) => None,
            _ => None,
        })
    }
}

impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let g = global();
        let s = g.arena.display(self.0, &*g);
        f.write_str(&s)
    }
}

impl fmt::Debug for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Expr({self})")
    }
}

impl From<f64> for Expr {
    fn from(c: f64) -> Expr {
        Expr::constant(c)
    }
}

impl From<i32> for Expr {
    fn from(c: i32) -> Expr {
        Expr::constant(c as f64)
    }
}

macro_rules! binop {
    ($tr:ident, $m:ident, $f:ident) => {
        impl<T: Into<Expr>> $tr<T> for Expr {
            type Output = Expr;
            fn $m(self, rhs: T) -> Expr {
                let rhs = rhs.into();
                Expr(with(|a| a.$f(self.0, rhs.0)))
            }
        }
        impl $tr<Expr> for f64 {
            type Output = Expr;
            fn $m(self, rhs: Expr) -> Expr {
                Expr::constant(self).$m(rhs)
            }
        }
    };
}

binop!(Add, add, add);
binop!(Sub, sub, sub);
binop!(Mul, mul, mul);
binop!(Div, div, div);

impl Neg for Expr {
    type Output = Expr;
    fn neg(self) -> Expr {
        Expr(with(|a| a.neg(self.0)))
    }
}

impl std::iter::Sum for Expr {
    fn sum<I: Iterator<Item = Expr>>(iter: I) -> Expr {
        let ids: Vec<Id> = iter.map(|e| e.0).collect();
        Expr(with(|a| a.sum(&ids)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn symbols_are_interned_once_and_keep_their_names() {
        let mut g = Global::new();
        // Names that are prefixes of each other, the empty name, and enough names to
        // grow the table several times.
        let names: Vec<String> = ["", "a", "a.b", "a.bc", "a.b.c", "der(a.b)"]
            .iter()
            .map(|s| s.to_string())
            .chain((0..5000).map(|k| format!("chain.inertia{k}.flange_a.phi")))
            .collect();
        let ids: Vec<u32> = names.iter().map(|n| g.symbol(n)).collect();
        assert_eq!(g.n_symbols(), names.len());
        for (k, (n, &id)) in names.iter().zip(&ids).enumerate() {
            assert_eq!(id as usize, k, "ids in the order of first use");
            assert_eq!(g.name(id), n);
            assert_eq!(g.symbol(n), id, "interning again gives the same id");
            assert_eq!(g.lookup(n), Some(id));
        }
        assert_eq!(g.n_symbols(), names.len(), "nothing interned twice");
        assert_eq!(g.lookup("a.b.d"), None);
        assert_eq!(g.lookup("chain.inertia5000.flange_a.phi"), None);
    }
}
