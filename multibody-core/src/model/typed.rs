//! The typed layer over [`System`]: components and connectors with *handles*.
//!
//! A handle names the connectors, variables and parameters of one instance as Rust
//! fields (`inertia.flange_a.phi`), so that a misspelt connector or a connection
//! between connectors of different types is a compile error at the offending tokens.
//! The `component!`, `connector!` and `system!` macros generate these impls; a program
//! can write them by hand as well.

use std::fmt;

use crate::expr::Expr;

use super::system::{Component, System, join_path};
use super::variable::{Parameter, VarKind, Variable};

/// A model built by `system!`: the system, and the typed handle of every instance as a
/// field (`model.j1.phi`, `model.b1.frame_a`), reached through `Deref`. Functions that
/// take a model take `&Model` as well as `&System` ([`AsRef<System>`]).
#[derive(Clone, Debug)]
pub struct Model<H> {
    system: System,
    handles: H,
}

impl<H> Model<H> {
    /// A model of `system` with the handles of its instances.
    pub fn new(system: System, handles: H) -> Self {
        Model { system, handles }
    }

    /// The system.
    pub fn system(&self) -> &System {
        &self.system
    }

    /// The system, to add to it (builder calls).
    pub fn system_mut(&mut self) -> &mut System {
        &mut self.system
    }

    /// The handles.
    pub fn handles(&self) -> &H {
        &self.handles
    }

    /// The system alone.
    pub fn into_system(self) -> System {
        self.system
    }

    /// The system and the handles.
    pub fn into_parts(self) -> (System, H) {
        (self.system, self.handles)
    }
}

impl<H> std::ops::Deref for Model<H> {
    type Target = H;
    fn deref(&self) -> &H {
        &self.handles
    }
}

impl<H> AsRef<System> for Model<H> {
    fn as_ref(&self) -> &System {
        &self.system
    }
}

impl AsRef<System> for System {
    fn as_ref(&self) -> &System {
        self
    }
}

impl<H> From<Model<H>> for System {
    fn from(m: Model<H>) -> System {
        m.system
    }
}

/// A component whose instances have a typed handle.
pub trait TypedComponent: Component {
    /// The handle type: connectors, variables and parameters as fields.
    type Handle: Clone;
    /// The handle of the instance at full path `path`.
    fn handle(path: &str) -> Self::Handle;
}

/// A connector type (`Flange`, `Pin`, `RealInput`, `Frame`).
pub trait Connector: Component {
    /// The handle of a connector instance.
    type Handle: ConnectorHandle;
    /// The handle of the connector at full path `path`.
    fn handle(path: &str) -> Self::Handle;
    /// Whether the connector is one value of its own (a scalar signal connector), which
    /// can be given a start value (`connector y(start = y_start): RealOutput;`).
    const HAS_VALUE: bool = false;
}

/// The handle of a connector instance: it knows its full path.
pub trait ConnectorHandle: Clone {
    /// The connector's full path (`motor.emf.flange`).
    fn path(&self) -> String;
}

/// A full path, interned (cheap to copy).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct PathId(Expr);

impl PathId {
    /// Interns a path.
    pub fn new(path: &str) -> PathId {
        PathId(Expr::var(path))
    }

    /// The path as text.
    pub fn as_string(&self) -> String {
        self.0.name().unwrap_or_default()
    }
}

impl fmt::Debug for PathId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.as_string())
    }
}

/// A causal signal connector's handle (`RealInput`, `RealOutput`): the connector is the
/// variable itself, so it is usable in equations as an expression.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct Signal(pub Expr);

impl ConnectorHandle for Signal {
    fn path(&self) -> String {
        self.0.name().unwrap_or_default()
    }
}

impl From<Signal> for Expr {
    fn from(s: Signal) -> Expr {
        s.0
    }
}

macro_rules! signal_ops {
    ($($tr:ident $m:ident),*) => {$(
        impl<T: Into<Expr>> std::ops::$tr<T> for Signal {
            type Output = Expr;
            fn $m(self, rhs: T) -> Expr {
                std::ops::$tr::$m(self.0, rhs.into())
            }
        }
        impl std::ops::$tr<Signal> for f64 {
            type Output = Expr;
            fn $m(self, rhs: Signal) -> Expr {
                std::ops::$tr::$m(Expr::from(self), rhs.0)
            }
        }
    )*};
}
signal_ops!(Add add, Sub sub, Mul mul, Div div);

impl std::ops::Neg for Signal {
    type Output = Expr;
    fn neg(self) -> Expr {
        -self.0
    }
}

/// A causal vector signal connector's handle (`RealInput3`): the connector is the
/// 3-vector itself (`force[1]`, `force[2]`, `force[3]`).
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct Signal3 {
    /// The three signals.
    pub value: crate::expr::Vec3,
    /// The connector's path.
    pub path: PathId,
}

impl ConnectorHandle for Signal3 {
    fn path(&self) -> String {
        self.path.as_string()
    }
}

impl std::ops::Deref for Signal3 {
    type Target = crate::expr::Vec3;
    fn deref(&self) -> &crate::expr::Vec3 {
        &self.value
    }
}

impl From<Signal3> for crate::expr::Vec3 {
    fn from(s: Signal3) -> crate::expr::Vec3 {
        s.value
    }
}

impl std::ops::Neg for Signal3 {
    type Output = crate::expr::Vec3;
    fn neg(self) -> crate::expr::Vec3 {
        -self.value
    }
}

impl<R: Into<crate::expr::Vec3>> Equate<R> for Signal3 {
    fn pairs(self, rhs: R) -> Vec<(Expr, Expr)> {
        self.value.pairs(rhs)
    }
}

/// Declares the three variables of a vector signal connector.
pub fn declare_signal3(
    s: &mut System,
    kind: VarKind,
    description: impl Into<super::SharedText>,
) -> Signal3 {
    let value =
        crate::expr::Vec3::declare(s, Variable::new("").kind(kind).description(description));
    Signal3 {
        value,
        path: PathId::new(&s.path),
    }
}

/// The handle of a vector signal connector at `path`.
pub fn signal3_at(path: &str) -> Signal3 {
    Signal3 {
        value: crate::expr::Vec3::at(path),
        path: PathId::new(path),
    }
}

/// A type a component may declare as a variable (`Real` for a scalar).
pub trait VariableType: Copy {
    /// Declares the variable described by `template` (its name local to `s`) and
    /// returns it.
    fn declare(s: &mut System, template: Variable) -> Self;
    /// The variable at full path `path` (what [`declare`](Self::declare) returned).
    fn at(path: &str) -> Self;
}

/// A scalar real variable (Modelica's `Real`).
pub type Real = Expr;

impl VariableType for Expr {
    fn declare(s: &mut System, template: Variable) -> Self {
        s.variable(template)
    }
    fn at(path: &str) -> Self {
        Expr::var(path)
    }
}

/// A type a component may declare as a tunable parameter (`f64`).
pub trait ParameterType: Clone {
    /// The symbolic form used in equations.
    type Symbolic: Copy;
    /// Declares the parameter `template` with this value as its default.
    fn declare(&self, s: &mut System, template: Parameter) -> Self::Symbolic;
    /// The parameter at full path `path`.
    fn at(path: &str) -> Self::Symbolic;
}

impl ParameterType for f64 {
    type Symbolic = Expr;
    fn declare(&self, s: &mut System, mut template: Parameter) -> Expr {
        template.value = Some(Expr::constant(*self));
        s.parameter(template)
    }
    fn at(path: &str) -> Expr {
        Expr::param(path)
    }
}

/// Sides of an equation that can be equated: scalars (and, for 3-D mechanics, vectors
/// and matrices element by element).
pub trait Equate<Rhs> {
    /// The scalar equations `lhs_i = rhs_i`.
    fn pairs(self, rhs: Rhs) -> Vec<(Expr, Expr)>;
}

macro_rules! scalar_equate {
    ($($l:ty),*) => {
        scalar_equate!(@each [$($l),*] [$($l),*]);
    };
    (@each [$($l:ty),*] $r:tt) => {
        $( scalar_equate!(@row $l $r); )*
    };
    (@row $l:ty [$($r:ty),*]) => {
        $(
            impl Equate<$r> for $l {
                fn pairs(self, rhs: $r) -> Vec<(Expr, Expr)> {
                    vec![(Expr::from(self), Expr::from(rhs))]
                }
            }
        )*
    };
}
scalar_equate!(Expr, f64, i32, Signal);

impl System {
    /// Declares a typed sub-component (or connector) and returns its handle.
    pub fn add_typed<C: TypedComponent>(&mut self, local: &str, c: &C) -> C::Handle {
        let h = C::handle(&self.full(local));
        self.add(local, c);
        h
    }

    /// Declares a connector instance and returns its handle.
    pub fn add_connector<C: Connector>(&mut self, local: &str, c: &C) -> C::Handle {
        let h = C::handle(&self.full(local));
        self.add(local, c);
        h
    }

    /// Includes a base component's declarations here (Modelica's `extends`) and
    /// returns its handle (at this system's own path).
    pub fn extend_typed<C: TypedComponent>(&mut self, c: &C) -> C::Handle {
        let h = C::handle(&self.path);
        self.extend(c);
        h
    }

    /// Connects two connectors of the same type, given by their handles.
    pub fn connect_handles<H: ConnectorHandle>(&mut self, a: &H, b: &H) {
        let (pa, pb) = (a.path(), b.path());
        let rel = |p: &str| -> String {
            if self.path.is_empty() {
                p.to_string()
            } else {
                p.strip_prefix(&format!("{}.", self.path))
                    .unwrap_or(p)
                    .to_string()
            }
        };
        let (ra, rb) = (rel(&pa), rel(&pb));
        self.connect(&ra, &rb);
    }

    /// Declares a variable of any [`VariableType`].
    pub fn declare<T: VariableType>(&mut self, template: Variable) -> T {
        T::declare(self, template)
    }

    /// Declares a connector variable of a connector type (potential, flow or signal).
    pub fn declare_connector_variable<T: VariableType>(&mut self, template: Variable) -> T {
        T::declare(self, template)
    }

    /// Adds the equations `lhs = rhs` (one per element for vectors).
    pub fn equate<L: Equate<R>, R>(&mut self, lhs: L, rhs: R) {
        for (l, r) in lhs.pairs(rhs) {
            self.equation(l, r);
        }
    }

    /// Adds the initial equations `lhs = rhs`.
    pub fn initial_equate<L: Equate<R>, R>(&mut self, lhs: L, rhs: R) {
        for (l, r) in lhs.pairs(rhs) {
            self.initial_equation(l, r);
        }
    }
}

/// Declares the single variable of a signal connector (the connector itself).
pub fn declare_signal(
    s: &mut System,
    kind: VarKind,
    description: impl Into<super::SharedText>,
) -> Signal {
    let v = Variable::new("").kind(kind).description(description);
    Signal(s.variable(v))
}

/// The handle of a signal connector at `path`.
pub fn signal_at(path: &str) -> Signal {
    Signal(Expr::var(path))
}

/// Joins a handle path and a local name.
pub fn member(path: &str, local: &str) -> String {
    join_path(path, local)
}
