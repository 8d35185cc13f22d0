//! Hash-consed symbolic expressions.
//!
//! An [`Arena`] stores expression nodes once each (hash-consing), simplifies on
//! construction (constant folding, neutral elements, flattened and ordered sums and
//! products with numeric coefficients) and offers differentiation with respect to a leaf
//! or to time, substitution, linear solving and infix display.
//!
//! Two kinds of arena exist: the stores behind the user-facing [`Expr`] handle, one per
//! model (leaves are named symbols, interned once per process, so Rust code can write
//! `phi * 2.0 + w`), and local arenas that the compiler builds for one model (leaves are
//! dense variable indices). All algorithms are written once, on [`Arena`].

mod arena;
mod diff;
mod display;
mod eval;
pub(crate) mod handle;
mod id_index;
mod linear_form;
mod node_map;
mod solve;
pub(crate) mod store;
mod subst;
pub(crate) mod symbols;
mod vector;

pub use arena::Arena;
pub use display::NameResolver;
pub use handle::Expr;
pub(crate) use id_index::DenseU32;
pub use id_index::IdIndex;
pub use linear_form::LinearForm;
pub use node_map::{NodeMap, NodeTable};
pub use solve::LinearSolve;
pub use store::{ExprStore, StoreGuard};
pub use symbols::symbol_name;
pub use vector::{Mat3, Vec3};

/// Index of a node in an [`Arena`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Id(pub u32);

impl Id {
    /// The index as `usize`.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Unary functions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Func1 {
    /// sine
    Sin,
    /// cosine
    Cos,
    /// tangent
    Tan,
    /// arc sine
    Asin,
    /// arc cosine
    Acos,
    /// arc tangent
    Atan,
    /// natural exponential
    Exp,
    /// natural logarithm
    Log,
    /// square root
    Sqrt,
    /// absolute value
    Abs,
    /// sign: -1, 0 or 1
    Sign,
    /// hyperbolic sine
    Sinh,
    /// hyperbolic cosine
    Cosh,
    /// hyperbolic tangent
    Tanh,
    /// Modelica's `noEvent(x)`: `x` itself, whose relations are evaluated as they are
    /// (no crossing functions, no events).
    NoEvent,
    /// Modelica's `pre(x)`: in a `when` clause, the value of `x` just before the
    /// event; elsewhere `x` itself.
    Pre,
}

impl Func1 {
    /// The function's name as displayed.
    pub fn name(self) -> &'static str {
        match self {
            Func1::Sin => "sin",
            Func1::Cos => "cos",
            Func1::Tan => "tan",
            Func1::Asin => "asin",
            Func1::Acos => "acos",
            Func1::Atan => "atan",
            Func1::Exp => "exp",
            Func1::Log => "log",
            Func1::Sqrt => "sqrt",
            Func1::Abs => "abs",
            Func1::Sign => "sign",
            Func1::Sinh => "sinh",
            Func1::Cosh => "cosh",
            Func1::Tanh => "tanh",
            Func1::NoEvent => "noEvent",
            Func1::Pre => "pre",
        }
    }

    /// Numeric value.
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Func1::Sin => x.sin(),
            Func1::Cos => x.cos(),
            Func1::Tan => x.tan(),
            Func1::Asin => x.asin(),
            Func1::Acos => x.acos(),
            Func1::Atan => x.atan(),
            Func1::Exp => x.exp(),
            Func1::Log => x.ln(),
            Func1::Sqrt => x.sqrt(),
            Func1::Abs => x.abs(),
            Func1::Sign => {
                if x > 0.0 {
                    1.0
                } else if x < 0.0 {
                    -1.0
                } else {
                    0.0
                }
            }
            Func1::Sinh => x.sinh(),
            Func1::Cosh => x.cosh(),
            Func1::Tanh => x.tanh(),
            Func1::NoEvent | Func1::Pre => x,
        }
    }
}

/// Binary functions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Func2 {
    /// `atan2(y, x)`
    Atan2,
    /// minimum
    Min,
    /// maximum
    Max,
}

impl Func2 {
    /// The function's name as displayed.
    pub fn name(self) -> &'static str {
        match self {
            Func2::Atan2 => "atan2",
            Func2::Min => "min",
            Func2::Max => "max",
        }
    }

    /// Numeric value.
    pub fn apply(self, a: f64, b: f64) -> f64 {
        match self {
            Func2::Atan2 => a.atan2(b),
            Func2::Min => a.min(b),
            Func2::Max => a.max(b),
        }
    }
}

/// Comparison operators; a comparison node is 1.0 when true and 0.0 when false.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Cmp {
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `==`
    Eq,
    /// `!=`
    Ne,
}

impl Cmp {
    /// The operator as displayed.
    pub fn symbol(self) -> &'static str {
        match self {
            Cmp::Lt => "<",
            Cmp::Le => "<=",
            Cmp::Gt => ">",
            Cmp::Ge => ">=",
            Cmp::Eq => "==",
            Cmp::Ne => "!=",
        }
    }

    /// Numeric value (1.0 or 0.0).
    pub fn apply(self, a: f64, b: f64) -> f64 {
        let r = match self {
            Cmp::Lt => a < b,
            Cmp::Le => a <= b,
            Cmp::Gt => a > b,
            Cmp::Ge => a >= b,
            Cmp::Eq => a == b,
            Cmp::Ne => a != b,
        };
        if r { 1.0 } else { 0.0 }
    }
}

/// The operands of a sum or product node: a range of its arena's operand pool (read
/// them with [`Arena::terms`] or [`Arena::factors`]). Nodes keep no heap memory of their
/// own, so an arena is a few flat vectors (on top of a shared base, if it extends one):
/// cloned by copying, hash-consed without chasing pointers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Operands {
    start: u32,
    len: u32,
}

impl Operands {
    /// Number of operands.
    pub fn len(self) -> usize {
        self.len as usize
    }

    /// Whether there is no operand (never, for a node of an arena).
    pub fn is_empty(self) -> bool {
        self.len == 0
    }

    fn new(start: usize, len: usize) -> Operands {
        Operands {
            start: start as u32,
            len: len as u32,
        }
    }

    fn start(self) -> usize {
        self.start as usize
    }
}

/// One expression node. Constants are stored by their bit pattern so nodes hash exactly.
/// Nodes are plain values (`Copy`); the operands of sums and products live in the arena.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A number (`f64::to_bits`).
    Const(u64),
    /// An unknown: a symbol in a store, a variable index in a local arena.
    Var(u32),
    /// A parameter: a symbol in a store, a parameter index in a local arena.
    Param(u32),
    /// Time.
    Time,
    /// Time derivative of a leaf (a `Var`, or a `Der` for higher derivatives).
    Der(Id),
    /// `constant + sum(coefficient * term)`: terms `(coefficient bits, term)` (see
    /// [`Arena::terms`]) sorted by id, none a constant or a sum, no zero coefficient, and
    /// never a single term with coefficient 1 and constant 0.
    Sum(Operands, u64),
    /// `product(factor ^ exponent)` with integer exponents: factors `(base, exponent)`
    /// (see [`Arena::factors`]) sorted by id, none a constant, sum with a single term, or
    /// product; at least two factors or one with an exponent other than 1.
    Prod(Operands),
    /// `base ^ exponent` for a non-integer or symbolic exponent.
    Pow(Id, Id),
    /// A unary function.
    F1(Func1, Id),
    /// A binary function.
    F2(Func2, Id, Id),
    /// A comparison, 1.0 when true.
    Cmp(Cmp, Id, Id),
    /// `if cond != 0 then a else b`.
    If(Id, Id, Id),
}

/// Whether a node is a leaf (variable, parameter, time or derivative of a leaf).
pub fn is_leaf(node: &Node) -> bool {
    matches!(
        node,
        Node::Var(_) | Node::Param(_) | Node::Time | Node::Der(_)
    )
}

#[cfg(test)]
mod diff_tests;
#[cfg(test)]
mod linear_form_tests;
#[cfg(test)]
mod tests;
