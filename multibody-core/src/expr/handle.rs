//! [`Expr`]: the user-facing expression handle, with named symbols as leaves.

use crate::hash::HashMap;
use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};
use std::sync::Arc;

use super::store::{self, FIRST_STORE, StoreCell};
use super::{Arena, Cmp, Func1, Func2, Id, NameResolver, Node, NodeMap, symbols};

/// A symbolic expression: cheap to copy, comparable by identity (within a model,
/// structurally equal expressions are the same `Expr`), and built with the usual
/// operators:
///
/// ```
/// use multibody_core::expr::Expr;
/// let phi = Expr::var("pendulum.phi");
/// let e = phi.sin() * 2.0 + Expr::var("pendulum.w");
/// assert_eq!(e.to_string(), "2*sin(pendulum.phi) + pendulum.w");
/// ```
///
/// Variables, parameters and time are names and belong to no model. Every other
/// expression lives in the store of the model it was built for (see
/// [`ExprStore`](super::ExprStore)): it stays valid while that model, or something
/// compiled from it, exists, and using it afterwards panics.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Expr {
    /// [`VAR`], [`PARAM`] or [`TIME`] for a leaf, otherwise the number of the store.
    space: u32,
    /// The symbol of a variable or parameter, or the node in the store.
    index: u32,
}

/// `Expr::space` of a variable leaf.
const VAR: u32 = 0;
/// `Expr::space` of a parameter leaf.
const PARAM: u32 = 1;
/// `Expr::space` of time.
const TIME: u32 = 2;

/// What an [`Expr`] is, for the compiler: a leaf by symbol, or a node of a store.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Resolved {
    /// The unknown with this symbol.
    Var(u32),
    /// The parameter with this symbol.
    Param(u32),
    /// Time.
    Time,
    /// Node `Id` of the store with this number.
    Node(u32, Id),
}

/// The leaf of `arena` for a leaf node of another arena with the same symbols.
pub(crate) fn same_leaf(a: &mut Arena, n: &Node) -> Id {
    match *n {
        Node::Var(s) => a.var(s),
        Node::Param(s) => a.param(s),
        _ => a.time(),
    }
}

/// An operand made ready for a store: a leaf or node of the store itself, or a copy of
/// a node of another store.
enum Operand {
    Here(Expr),
    Copied(Box<Arena>, Id),
}

impl Expr {
    /// What this expression is.
    pub(crate) fn resolve(self) -> Resolved {
        match self.space {
            VAR => Resolved::Var(self.index),
            PARAM => Resolved::Param(self.index),
            TIME => Resolved::Time,
            s => Resolved::Node(s, Id(self.index)),
        }
    }

    /// Whether this expression is a node of a store (not a leaf).
    fn in_store(self) -> bool {
        self.space >= FIRST_STORE
    }

    /// The expression for node `id` of `arena` (the arena of store `store`): leaves by
    /// their symbols, anything else as that node.
    pub(crate) fn of_node(store: u32, arena: &Arena, id: Id) -> Expr {
        match *arena.node(id) {
            Node::Var(s) => Expr {
                space: VAR,
                index: s,
            },
            Node::Param(s) => Expr {
                space: PARAM,
                index: s,
            },
            Node::Time => Expr {
                space: TIME,
                index: 0,
            },
            _ => Expr {
                space: store,
                index: id.0,
            },
        }
    }

    /// This expression as a node of `arena` (the arena of store `store`); a node of
    /// another store must have been copied (see [`Operand`]).
    fn id_in(self, store: u32, arena: &mut Arena) -> Id {
        match self.space {
            VAR => arena.var(self.index),
            PARAM => arena.param(self.index),
            TIME => arena.time(),
            s => {
                debug_assert_eq!(s, store, "an operand of another store");
                Id(self.index)
            }
        }
    }

    /// The store the result of an operation on `operands` goes to: that of the first
    /// operand that lives in a store, or the thread's current one.
    fn target(operands: &[Expr]) -> Arc<StoreCell> {
        match operands.iter().find(|e| e.in_store()) {
            Some(e) => store::get(e.space),
            None => store::current(),
        }
    }

    /// Applies `f` to the operands' nodes in one store and returns the result.
    fn build<const N: usize>(
        operands: [Expr; N],
        f: impl FnOnce(&mut Arena, [Id; N]) -> Id,
    ) -> Expr {
        let cell = Self::target(&operands);
        let sid = cell.id();
        // Nodes of other stores are copied out before this store is locked (no thread
        // ever holds two stores' locks here).
        let prepared = operands.map(|e| prepare(e, sid));
        let mut arena = cell.lock();
        let mut memo = NodeMap::new();
        let ids = prepared.map(|p| p.id_in(sid, &mut arena, &mut memo));
        let r = f(&mut arena, ids);
        Expr::of_node(sid, &arena, r)
    }

    /// [`Expr::build`] for any number of operands.
    fn build_n(operands: &[Expr], f: impl FnOnce(&mut Arena, &[Id]) -> Id) -> Expr {
        let cell = Self::target(operands);
        let sid = cell.id();
        let prepared: Vec<Operand> = operands.iter().map(|&e| prepare(e, sid)).collect();
        let mut arena = cell.lock();
        let mut memo = NodeMap::new();
        let ids: Vec<Id> = prepared
            .into_iter()
            .map(|p| p.id_in(sid, &mut arena, &mut memo))
            .collect();
        let r = f(&mut arena, &ids);
        Expr::of_node(sid, &arena, r)
    }

    /// Reads this expression's node in its store (a leaf in a scratch arena).
    fn read<R>(self, f: impl FnOnce(&Arena, Id) -> R) -> R {
        if self.in_store() {
            let cell = store::get(self.space);
            let arena = cell.lock();
            f(&arena, Id(self.index))
        } else {
            let mut arena = Arena::new();
            let id = self.id_in(0, &mut arena);
            f(&arena, id)
        }
    }

    /// A numeric constant.
    pub fn constant(c: f64) -> Expr {
        Self::build([], |a, []| a.constant(c))
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
        Expr {
            space: TIME,
            index: 0,
        }
    }

    /// The value when this is a constant.
    pub fn as_f64(self) -> Option<f64> {
        if !self.in_store() {
            return None;
        }
        self.read(|a, id| a.as_const(id))
    }

    /// The name when this is a variable or parameter leaf.
    pub fn name(self) -> Option<String> {
        match self.space {
            VAR | PARAM => Some(symbols::name(self.index).to_string()),
            _ => None,
        }
    }

    /// Whether this is a variable leaf.
    pub fn is_var(self) -> bool {
        self.space == VAR
    }

    /// Time derivative `der(self)`.
    pub fn der(self) -> Expr {
        Self::build([self], |a, [x]| a.der(x))
    }

    fn f1(self, f: Func1) -> Expr {
        Self::build([self], |a, [x]| a.f1(f, x))
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
    /// Modelica's `noEvent(self)`: the same value, with its relations (`<`, `>=`, ...)
    /// evaluated as they are during integration instead of generating events.
    pub fn no_event(self) -> Expr {
        self.f1(Func1::NoEvent)
    }
    /// Modelica's `pre(self)`: in a `when` clause, the value just before the event.
    pub fn pre(self) -> Expr {
        self.f1(Func1::Pre)
    }

    fn f2(self, f: Func2, b: impl Into<Expr>) -> Expr {
        Self::build([self, b.into()], |a, [x, y]| a.f2(f, x, y))
    }
    /// `atan2(self, x)`
    pub fn atan2(self, x: impl Into<Expr>) -> Expr {
        self.f2(Func2::Atan2, x)
    }
    /// minimum
    pub fn min(self, b: impl Into<Expr>) -> Expr {
        self.f2(Func2::Min, b)
    }
    /// maximum
    pub fn max(self, b: impl Into<Expr>) -> Expr {
        self.f2(Func2::Max, b)
    }
    /// `self ^ e`
    pub fn pow(self, e: impl Into<Expr>) -> Expr {
        Self::build([self, e.into()], |a, [x, y]| a.pow(x, y))
    }
    /// `self ^ n`
    pub fn powi(self, n: i32) -> Expr {
        Self::build([self], |a, [x]| a.powi(x, n))
    }

    fn cmp(self, op: Cmp, b: impl Into<Expr>) -> Expr {
        Self::build([self, b.into()], |a, [x, y]| a.cmp(op, x, y))
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
    /// `self == b` (never an event: for discrete values)
    pub fn eq_to(self, b: impl Into<Expr>) -> Expr {
        self.cmp(Cmp::Eq, b)
    }
    /// `self != b` (never an event: for discrete values)
    pub fn ne_to(self, b: impl Into<Expr>) -> Expr {
        self.cmp(Cmp::Ne, b)
    }

    /// `if cond then a else b` (cond nonzero means true).
    pub fn if_else(cond: Expr, a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
        Self::build([cond, a.into(), b.into()], |ar, [c, x, y]| ar.ite(c, x, y))
    }

    /// Partial derivative with respect to a leaf (variable, parameter, time or `der(x)`).
    pub fn diff(self, wrt: Expr) -> Expr {
        Self::build([self, wrt], |a, [e, x]| a.diff(e, x))
    }

    /// Total time derivative.
    pub fn time_derivative(self) -> Expr {
        Self::build([self], |a, [e]| a.time_derivative(e))
    }

    /// Replaces leaves (or any subexpressions) and re-simplifies.
    pub fn substitute(self, pairs: &[(Expr, Expr)]) -> Expr {
        let mut operands = Vec::with_capacity(1 + 2 * pairs.len());
        operands.push(self);
        for &(k, v) in pairs {
            operands.push(k);
            operands.push(v);
        }
        Self::build_n(&operands, |a, ids| {
            let map: HashMap<Id, Id> = ids[1..].chunks(2).map(|p| (p[0], p[1])).collect();
            a.substitute(ids[0], &map)
        })
    }

    /// Solves `self = 0` for the leaf `x` when linear in it: `(solution, coefficient)`.
    pub fn solve_for(self, x: Expr) -> Option<(Expr, Expr)> {
        let cell = Self::target(&[self, x]);
        let sid = cell.id();
        let [pe, px] = [self, x].map(|e| prepare(e, sid));
        let mut arena = cell.lock();
        let mut memo = NodeMap::new();
        let e = pe.id_in(sid, &mut arena, &mut memo);
        let v = px.id_in(sid, &mut arena, &mut memo);
        let s = arena.solve_linear(e, v)?;
        Some((
            Expr::of_node(sid, &arena, s.solution),
            Expr::of_node(sid, &arena, s.coefficient),
        ))
    }

    /// Whether the leaf `x` occurs in this expression.
    pub fn contains(self, x: Expr) -> bool {
        if !self.in_store() {
            return self == x;
        }
        let cell = store::get(self.space);
        let mut arena = cell.lock();
        let xi = match x.resolve() {
            Resolved::Node(s, id) if s == self.space => id,
            Resolved::Node(..) => return false,
            _ => x.id_in(self.space, &mut arena),
        };
        arena.contains(Id(self.index), xi)
    }

    /// Evaluates with leaf values by name (`"time"` for time); `None` when a leaf has no
    /// value.
    pub fn eval(self, values: &dyn Fn(&str) -> Option<f64>) -> Option<f64> {
        self.read(|a, id| {
            a.eval(id, &|n| match n {
                Node::Var(s) | Node::Param(s) => values(symbols::name(*s)),
                Node::Time => values("time"),
                _ => None,
            })
        })
    }
}

impl Operand {
    fn id_in(self, store: u32, arena: &mut Arena, memo: &mut NodeMap) -> Id {
        match self {
            Operand::Here(e) => e.id_in(store, arena),
            Operand::Copied(src, id) => {
                memo.clear();
                arena.import(&src, id, &mut same_leaf, memo)
            }
        }
    }
}

/// `e` ready to be used in store `store`.
fn prepare(e: Expr, store: u32) -> Operand {
    if e.in_store() && e.space != store {
        let (arena, id) = store::export(&store::get(e.space), Id(e.index));
        Operand::Copied(Box::new(arena), id)
    } else {
        Operand::Here(e)
    }
}

/// `e` as an expression of store `to` (copied there when it lives in another store).
pub(crate) fn into_store(e: Expr, to: &StoreCell) -> Expr {
    if !e.in_store() || e.space == to.id() {
        return e;
    }
    let Operand::Copied(src, id) = prepare(e, to.id()) else {
        unreachable!("a node of another store is copied")
    };
    let mut arena = to.lock();
    let mut memo = NodeMap::new();
    let r = arena.import(&src, id, &mut same_leaf, &mut memo);
    Expr::of_node(to.id(), &arena, r)
}

/// The unknown (or, with `param`, the parameter) named `name`, its symbol, and its
/// name as the symbol table keeps it (for the whole process: copying it is free).
pub(crate) fn named_leaf(name: &str, param: bool) -> (Expr, u32, &'static str) {
    let (sym, kept) = symbols::intern(name);
    let e = Expr {
        space: if param { PARAM } else { VAR },
        index: sym,
    };
    (e, sym, kept)
}

/// Names of the leaves of a store's arena: symbol names.
pub(crate) struct SymbolNames;

impl NameResolver for SymbolNames {
    fn var(&self, i: u32) -> String {
        symbols::name(i).to_string()
    }
    fn param(&self, i: u32) -> String {
        symbols::name(i).to_string()
    }
}

impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = match self.space {
            VAR | PARAM => symbols::name(self.index).to_string(),
            TIME => "time".to_string(),
            sid => match store::find(sid) {
                Some(cell) => cell.lock().display(Id(self.index), &SymbolNames),
                None => "<an expression of a dropped model>".to_string(),
            },
        };
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
                Expr::build([self, rhs.into()], |a, [x, y]| a.$f(x, y))
            }
        }
        impl $tr<Expr> for f64 {
            type Output = Expr;
            fn $m(self, rhs: Expr) -> Expr {
                Expr::build([rhs], |a, [y]| {
                    let x = a.constant(self);
                    a.$f(x, y)
                })
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
        Expr::build([self], |a, [x]| a.neg(x))
    }
}

impl std::iter::Sum for Expr {
    fn sum<I: Iterator<Item = Expr>>(iter: I) -> Expr {
        let operands: Vec<Expr> = iter.collect();
        Expr::build_n(&operands, |a, ids| a.sum(ids))
    }
}
