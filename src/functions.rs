//! Functions for equations: `der`, elementary functions, and conditionals.
//!
//! They accept anything that converts to an [`Expr`] (numbers, variables, signals), so
//! equations read as in Modelica: `der(phi) = w;`, `y = k * sin(2.0 * PI * f * time);`
//! (`PI` from the [`prelude`](crate::prelude)).

use multibody_core::expr::Expr;
use multibody_core::model::Signal;

/// Something with a time derivative.
pub trait Derivative {
    /// The type of the derivative.
    type Output;
    /// `d/dt self`.
    fn der(self) -> Self::Output;
}

impl Derivative for Expr {
    type Output = Expr;
    fn der(self) -> Expr {
        Expr::der(self)
    }
}

impl Derivative for multibody_core::expr::Vec3 {
    type Output = multibody_core::expr::Vec3;
    fn der(self) -> multibody_core::expr::Vec3 {
        multibody_core::expr::Vec3::der(self)
    }
}

impl Derivative for Signal {
    type Output = Expr;
    fn der(self) -> Expr {
        self.0.der()
    }
}

/// The time derivative `der(x)`.
pub fn der<T: Derivative>(x: T) -> T::Output {
    x.der()
}

macro_rules! unary {
    ($($(#[$doc:meta])* $name:ident => $method:ident;)*) => {$(
        $(#[$doc])*
        pub fn $name(x: impl Into<Expr>) -> Expr {
            x.into().$method()
        }
    )*};
}

unary! {
    /// Sine.
    sin => sin;
    /// Cosine.
    cos => cos;
    /// Tangent.
    tan => tan;
    /// Arc sine.
    asin => asin;
    /// Arc cosine.
    acos => acos;
    /// Arc tangent.
    atan => atan;
    /// Exponential.
    exp => exp;
    /// Natural logarithm.
    log => ln;
    /// Square root.
    sqrt => sqrt;
    /// Absolute value.
    abs => abs;
    /// Sign: -1, 0 or 1.
    sign => sign;
    /// Hyperbolic sine.
    sinh => sinh;
    /// Hyperbolic cosine.
    cosh => cosh;
    /// Hyperbolic tangent.
    tanh => tanh;
}

/// `atan2(y, x)`.
pub fn atan2(y: impl Into<Expr>, x: impl Into<Expr>) -> Expr {
    y.into().atan2(x)
}

/// The smaller of two values.
pub fn min(a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    a.into().min(b)
}

/// The larger of two values.
pub fn max(a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    a.into().max(b)
}

/// `a ^ b`.
pub fn pow(a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    a.into().pow(b)
}

/// `a < b` (1 when true, 0 otherwise). A relation on variables or time generates an
/// event where it changes (see [`no_event`]); `le`, `gt` and `ge` too.
pub fn lt(a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    a.into().lt(b)
}

/// `a <= b`.
pub fn le(a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    a.into().le(b)
}

/// `a > b`.
pub fn gt(a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    a.into().gt(b)
}

/// `a >= b`.
pub fn ge(a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    a.into().ge(b)
}

/// `a == b` (1 when true, 0 otherwise), for discrete values (a friction element's
/// `pre(mode) == STUCK`): never an event.
pub fn eq(a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    a.into().eq_to(b)
}

/// `a != b`, for discrete values: never an event.
pub fn ne(a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    a.into().ne_to(b)
}

/// Logical `a and b` of truth values (nonzero is true): 1 or 0.
pub fn and(a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    Expr::if_else(a.into(), Expr::if_else(b.into(), 1.0, 0.0), 0.0)
}

/// Logical `a or b` of truth values (nonzero is true): 1 or 0.
pub fn or(a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    Expr::if_else(a.into(), 1.0, Expr::if_else(b.into(), 1.0, 0.0))
}

/// Logical `not a` of a truth value (nonzero is true): 1 or 0.
pub fn not(a: impl Into<Expr>) -> Expr {
    Expr::if_else(a.into(), 0.0, 1.0)
}

/// Modelica's `noEvent(e)`: `e` itself, with its relations (`lt`, `ge`, ...) evaluated
/// as they are during integration. Without it, a relation on variables or time
/// generates an event where it changes (the integrator stops there and restarts), and
/// keeps its value between events. Use it where an expression is continuous across
/// the switch or only guards a singularity, as MSL does.
pub fn no_event(e: impl Into<Expr>) -> Expr {
    e.into().no_event()
}

/// Modelica's `pre(x)`: inside a `when` clause, the value of `x` just before the event
/// (`reinit(v, -e * pre(v))`); elsewhere `x` itself.
pub fn pre(x: impl Into<Expr>) -> Expr {
    x.into().pre()
}

/// Modelica's `edge(b)` in a `when` condition: true at the event where `b` (1 or 0)
/// becomes true, `b and not pre(b)`.
pub fn edge(b: impl Into<Expr>) -> Expr {
    let b = b.into();
    b * (1.0 - b.pre())
}

/// Modelica's `change(v)` in a `when` condition: true at the event where `v` changes,
/// `v <> pre(v)`.
pub fn change(v: impl Into<Expr>) -> Expr {
    let v = v.into();
    (v - v.pre()).abs().gt(0.0).no_event()
}

/// Modelica's `smooth(order, e)`: `e` is `order` times continuously differentiable
/// (`order` >= 0), so its relations need no events; here the same as [`no_event`].
pub fn smooth(order: u32, e: impl Into<Expr>) -> Expr {
    let _ = order;
    e.into().no_event()
}

/// `if cond then a else b` (`cond` nonzero is true).
pub fn if_else(cond: impl Into<Expr>, a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    Expr::if_else(cond.into(), a, b)
}
