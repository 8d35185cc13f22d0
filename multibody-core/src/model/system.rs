//! Systems: the tree of components a model is built from (the builder API).

use crate::expr::handle::{into_store, named_leaf};
use crate::expr::{Expr, ExprStore};

use super::SharedText;
use super::variable::{Parameter, VarKind, Variable};

/// A reusable model part: a component (Inertia, Resistor, ...) or a connector type
/// (Flange, Pin, ...). `build` declares its variables, parameters, sub-components,
/// connectors and equations into a [`System`] whose path is already set; structural
/// parameters are plain Rust values used while building.
pub trait Component {
    /// Type name for messages, e.g. `Rotational.Inertia`.
    fn type_name(&self) -> String;
    /// For connector types: the class that decides which connectors may be connected
    /// (equal classes connect). `None` for ordinary components.
    fn connector_class(&self) -> Option<String> {
        None
    }
    /// Declares the component's contents into `s`.
    fn build(&self, s: &mut System);
}

/// An equation `lhs = rhs`.
#[derive(Clone, Copy, Debug)]
pub struct Equation {
    /// Left-hand side.
    pub lhs: Expr,
    /// Right-hand side.
    pub rhs: Expr,
}

impl Equation {
    /// `lhs - rhs`, which the equation sets to zero.
    pub fn residual(&self) -> Expr {
        self.lhs - self.rhs
    }
}

/// A `connect(a, b)` statement: connector paths relative to the system holding it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Connection {
    /// First connector, e.g. `inertia.flange_b`.
    pub a: String,
    /// Second connector.
    pub b: String,
}

/// A node of the model tree: a component instance (or the whole model) with its
/// declarations. Names of everything declared are full paths (`motor.emf.phi`); the
/// root's path is empty so top-level names carry no prefix.
#[derive(Clone, Debug)]
pub struct System {
    /// Local name (`emf`); for the root, the model's name.
    pub name: String,
    /// Full path (`motor.emf`); empty for the root.
    pub path: String,
    /// Type name for messages.
    pub type_name: String,
    /// For connectors, the class that must match across a connection.
    pub connector_class: Option<String>,
    /// Unknowns declared here.
    pub variables: Vec<Variable>,
    /// Tunable parameters declared here.
    pub parameters: Vec<Parameter>,
    /// Equations.
    pub equations: Vec<Equation>,
    /// Initial equations (hold at the initial time only).
    pub initial_equations: Vec<Equation>,
    /// Sub-components and connectors.
    pub subsystems: Vec<System>,
    /// Connections among connectors of this system and its sub-components.
    pub connections: Vec<Connection>,
    /// Variables whose time derivative is an expression rather than an unknown
    /// (`der(R.T) = -skew(R.w) R.T`): `(variable, derivative)`.
    pub derivative_rules: Vec<(Expr, Expr)>,
    /// Overdetermined variable groups declared here (an orientation in a frame).
    pub overdetermined: Vec<super::overdetermined::OverdeterminedGroup>,
    /// Roots, potential roots and branches of the virtual connection graph.
    pub graph: Vec<super::overdetermined::GraphDecl>,
    /// The numeric structural parameters the component was built with (`n`, `r`,
    /// `radius`, ...; booleans as 0 or 1, an unset `Option` left out), by local name:
    /// what diagnoses of mechanisms and rendering read.
    pub structural: Vec<(String, Vec<f64>)>,
    /// The component's conditions on its parameters (see [`System::assert`]); most
    /// components have none.
    pub checks: Option<Box<Checks>>,
    /// `when` clauses (see [`System::when`]).
    pub whens: Vec<WhenClause>,
    /// `reinit` statements of the `when` clause being built.
    pub(crate) reinits: Vec<Equation>,
    /// `terminate` statements of the `when` clause being built.
    pub(crate) terminates: Vec<SharedText>,
    /// The conditions that [`System::sample`] made.
    pub samples: Vec<Expr>,
    /// The parameters that [`System::initial`] made.
    pub initials: Vec<Expr>,
    /// The parameters that [`System::terminal`] made.
    pub terminals: Vec<Expr>,
    /// Where the model's expressions live (shared by every system of one model).
    store: ExprStore,
}

/// The conditions a component puts on its parameters (see [`System::assert`]).
#[derive(Clone, Debug, Default)]
pub struct Checks {
    /// Conditions on tunable parameters, checked when a problem's parameter values are
    /// known (Modelica's `assert` on parameters).
    pub assertions: Vec<Assertion>,
    /// Conditions on structural parameters that failed while the component was built:
    /// each a message naming the parameter and its value.
    pub invalid: Vec<String>,
}

/// A `when` clause (Modelica's `when condition then ... end when`): at the event where
/// `condition` becomes true, each equation `v = expr` gives the discrete variable `v`
/// the value of `expr` (held until the next such event), and each reinit `x = expr`
/// sets the state `x`.
#[derive(Clone, Debug)]
pub struct WhenClause {
    /// Nonzero while the condition holds (relations on variables or time).
    pub condition: Expr,
    /// `v = expr`, `v` a variable that changes only here (a discrete variable).
    pub equations: Vec<Equation>,
    /// `x = expr` of `reinit(x, expr)`, `x` a state.
    pub reinits: Vec<Equation>,
    /// The message of its `terminate(..)`, which ends the simulation at its event.
    pub terminate: Option<SharedText>,
    /// Whether it is an `elsewhen` of the clause before it: skipped at an event where
    /// a clause before it in the chain fires.
    pub elsewhen: bool,
}

/// A condition on tunable parameters that must hold (see [`System::assert`]).
#[derive(Clone, Debug)]
pub struct Assertion {
    /// Nonzero when the condition holds (a comparison such as `m.ge(0.0)`).
    pub condition: Expr,
    /// What is wrong when it does not hold, e.g. "the mass m must not be negative".
    pub message: SharedText,
}

/// The condition of [`System::assert`]: known while the component is built (a Rust
/// `bool` on structural parameters), or an expression of tunable parameters, known when
/// a problem sets their values.
#[derive(Clone, Copy, Debug)]
pub enum Condition {
    /// Known now.
    Now(bool),
    /// An expression of parameters, nonzero when the condition holds.
    Parameters(Expr),
}

impl From<bool> for Condition {
    fn from(b: bool) -> Self {
        Condition::Now(b)
    }
}

impl From<Expr> for Condition {
    fn from(e: Expr) -> Self {
        Condition::Parameters(e)
    }
}

/// Joins a path and a local name with a dot (an empty side is left out).
pub fn join_path(path: &str, local: &str) -> String {
    let mut out = String::with_capacity(path.len() + 1 + local.len());
    join_path_into(path, local, &mut out);
    out
}

/// [`join_path`] written into `out` (cleared first), to reuse its allocation.
pub fn join_path_into(path: &str, local: &str, out: &mut String) {
    out.clear();
    out.push_str(path);
    // An element of the system itself (a vector signal connector's `[1]`) takes no dot.
    if !path.is_empty() && !local.is_empty() && !local.starts_with('[') {
        out.push('.');
    }
    out.push_str(local);
}

impl System {
    /// A new, empty model (the root of a tree).
    pub fn new(name: impl Into<String>) -> Self {
        Self::with_path(
            name.into(),
            String::new(),
            "Model".into(),
            None,
            ExprStore::for_new_model(),
        )
    }

    fn with_path(
        name: String,
        path: String,
        type_name: String,
        connector_class: Option<String>,
        store: ExprStore,
    ) -> Self {
        System {
            store,
            name,
            path,
            type_name,
            connector_class,
            variables: Vec::new(),
            parameters: Vec::new(),
            equations: Vec::new(),
            initial_equations: Vec::new(),
            subsystems: Vec::new(),
            connections: Vec::new(),
            derivative_rules: Vec::new(),
            checks: None,
            whens: Vec::new(),
            reinits: Vec::new(),
            terminates: Vec::new(),
            samples: Vec::new(),
            initials: Vec::new(),
            terminals: Vec::new(),
            overdetermined: Vec::new(),
            graph: Vec::new(),
            structural: Vec::new(),
        }
    }

    /// A model holding a single component as `name` (for simulating a component alone).
    pub fn from_component(name: &str, c: &dyn Component) -> Self {
        let mut s = System::new(name);
        s.type_name = c.type_name();
        s.build_from(c);
        s
    }

    /// Full path of a name local to this system.
    pub fn full(&self, local: &str) -> String {
        join_path(&self.path, local)
    }

    /// Declares an unknown with default attributes and returns it.
    pub fn var(&mut self, local: &str) -> Expr {
        self.variable_at(local, Variable::new(""))
    }

    /// Declares an unknown (its `name` is local to this system) and returns it.
    pub fn variable(&mut self, v: Variable) -> Expr {
        let local = v.name.clone();
        self.variable_at(&local, v)
    }

    /// Declares `v` under the local name `local` and returns it (`v`'s own name is
    /// replaced by the full path, as the symbol table keeps it: the variable holds no
    /// allocation for its name). For variables declared from one template
    /// (`frame.r_0[1]`, ...).
    pub fn variable_at(&mut self, local: &str, v: Variable) -> Expr {
        let (e, name, symbol) = self.declared(local, false);
        let start = v.start.map(|x| self.own(x));
        self.variables.push(Variable {
            name,
            symbol,
            start,
            ..v
        });
        e
    }

    /// The leaf (a parameter's with `param`), name and symbol of a declaration under
    /// the local name `local`.
    fn declared(&self, local: &str, param: bool) -> (Expr, SharedText, Option<u32>) {
        let (e, symbol, name) = named_leaf(&self.full(local), param);
        (e, SharedText::from(name), Some(symbol))
    }

    /// Declares a connector variable of the given kind (a local name of `""` makes the
    /// variable the connector itself, as Modelica's `RealInput`).
    pub fn connector_var(&mut self, local: &str, kind: VarKind) -> Expr {
        self.variable_at(local, Variable::new("").kind(kind))
    }

    /// Declares a tunable parameter with a default value and returns it.
    pub fn param(&mut self, local: &str, default: impl Into<Expr>) -> Expr {
        self.parameter_at(local, Parameter::new("", default))
    }

    /// Declares a tunable parameter (its `name` is local) and returns it.
    pub fn parameter(&mut self, p: Parameter) -> Expr {
        let local = p.name.clone();
        self.parameter_at(&local, p)
    }

    /// Declares `p` under the local name `local` and returns it (see
    /// [`System::variable_at`]).
    pub fn parameter_at(&mut self, local: &str, p: Parameter) -> Expr {
        let (e, name, symbol) = self.declared(local, true);
        let value = p.value.map(|x| self.own(x));
        self.parameters.push(Parameter {
            name,
            symbol,
            value,
            ..p
        });
        e
    }

    /// The unknown at a path relative to this system (`flange_a.phi`). Whether it exists
    /// is checked when the model is flattened.
    pub fn v(&self, local_path: &str) -> Expr {
        Expr::var(&self.full(local_path))
    }

    /// The parameter at a path relative to this system.
    pub fn p(&self, local_path: &str) -> Expr {
        Expr::param(&self.full(local_path))
    }

    /// Sets the start value (a guess unless the variable is `fixed`) of the unknown at
    /// `local_path`, declared here or in a sub-component or connector (a signal
    /// connector's value is at the connector's own path, `y`). Returns whether that
    /// unknown exists.
    pub fn set_start(&mut self, local_path: &str, value: impl Into<Expr>) -> bool {
        fn find<'s>(s: &'s mut System, full: &str) -> Option<&'s mut Variable> {
            if let Some(i) = s.variables.iter().position(|v| &*v.name == full) {
                return Some(&mut s.variables[i]);
            }
            s.subsystems
                .iter_mut()
                .filter(|c| {
                    full.strip_prefix(c.path.as_str())
                        .is_some_and(|rest| rest.is_empty() || rest.starts_with(['.', '[']))
                })
                .find_map(|c| find(c, full))
        }
        let full = self.full(local_path);
        let value = self.own(value.into());
        match find(self, &full) {
            Some(v) => {
                v.start = Some(value);
                true
            }
            None => false,
        }
    }

    /// Adds the equation `lhs = rhs`.
    pub fn equation(&mut self, lhs: impl Into<Expr>, rhs: impl Into<Expr>) {
        let (lhs, rhs) = (self.own(lhs.into()), self.own(rhs.into()));
        self.equations.push(Equation { lhs, rhs });
    }

    /// Adds an initial equation `lhs = rhs`.
    pub fn initial_equation(&mut self, lhs: impl Into<Expr>, rhs: impl Into<Expr>) {
        let (lhs, rhs) = (self.own(lhs.into()), self.own(rhs.into()));
        self.initial_equations.push(Equation { lhs, rhs });
    }

    /// A `when` clause: the equations that `body` adds (`v = expr`, each `v` a variable
    /// that then changes only at these events) and its [`reinit`](Self::reinit)s take
    /// effect at the event where `condition` becomes true, with `pre(x)` the value of
    /// `x` just before it. Between events the discrete variables keep their values.
    pub fn when(&mut self, condition: impl Into<Expr>, body: impl FnOnce(&mut System)) {
        let condition = self.own(condition.into());
        let (n_equations, n_reinits) = (self.equations.len(), self.reinits.len());
        let n_terminates = self.terminates.len();
        body(self);
        let equations = self.equations.split_off(n_equations);
        let reinits = self.reinits.split_off(n_reinits);
        let terminate = self.terminates.split_off(n_terminates).into_iter().next();
        self.whens.push(WhenClause {
            condition,
            equations,
            reinits,
            terminate,
            elsewhen: false,
        });
    }

    /// An `elsewhen` branch of the last [`when`](Self::when) clause of this component:
    /// like a clause of its own, but skipped at an event where a branch before it
    /// fires.
    pub fn elsewhen(&mut self, condition: impl Into<Expr>, body: impl FnOnce(&mut System)) {
        if self.whens.is_empty() {
            self.invalid("elsewhen needs a when clause before it".to_string());
        }
        self.when(condition, body);
        if let Some(w) = self.whens.last_mut() {
            w.elsewhen = true;
        }
    }

    /// `terminate(message)` inside a [`when`](Self::when) clause: the simulation ends
    /// successfully at its event, with `message` as the reason (Modelica's
    /// `terminate`; [`Solution::terminated`](crate::solve::Solution::terminated)).
    pub fn terminate(&mut self, message: impl Into<SharedText>) {
        self.terminates.push(message.into());
    }

    /// Modelica's `sample(start, interval)`, the condition of a [`when`](Self::when)
    /// clause that holds at the instants `start + k interval` (k = 0, 1, ...): each a
    /// time event, the first at the initial time when `start` is not later. It is
    /// `time >= start + sampleN.count * interval`, with a hidden counter that a clause
    /// of its own advances (so that the instants are exact multiples, not sums).
    pub fn sample(&mut self, start: impl Into<Expr>, interval: impl Into<Expr>) -> Expr {
        let k = self.samples.len() + 1;
        let count = self.variable(
            Variable::new(format!("sample{k}.count"))
                .start(0.0)
                .description("instants of sample(start, interval) so far"),
        );
        let (start, interval) = (self.own(start.into()), self.own(interval.into()));
        let condition = self.own(Expr::time().ge(start + count * interval));
        self.samples.push(condition);
        self.when(condition, |s| s.equation(count, count.pre() + 1.0));
        condition
    }

    /// Modelica's `initial()` for the condition of a [`when`](Self::when) clause: true
    /// at the initial event only, so that the clause acts once, at the start (after the
    /// initialization). A hidden parameter `initialN`, 1 only there.
    pub fn initial(&mut self) -> Expr {
        let k = self.initials.len() + 1;
        let p = self.parameter(Parameter::new(format!("initial{k}"), 0.0));
        self.initials.push(p);
        p
    }

    /// Modelica's `terminal()` for the condition of a [`when`](Self::when) clause: true
    /// at the end of a successful simulation only (its stop time, or a `terminate`),
    /// where the clause acts once more; the solution's last point is then its right
    /// limit. A hidden parameter `terminalN`, 1 only there.
    pub fn terminal(&mut self) -> Expr {
        let k = self.terminals.len() + 1;
        let p = self.parameter(Parameter::new(format!("terminal{k}"), 0.0));
        self.terminals.push(p);
        p
    }

    /// `reinit(state, value)` inside a [`when`](Self::when) clause: at its event, the
    /// state takes `value` (evaluated there, `pre(x)` the values just before).
    pub fn reinit(&mut self, state: impl Into<Expr>, value: impl Into<Expr>) {
        let (lhs, rhs) = (self.own(state.into()), self.own(value.into()));
        self.reinits.push(Equation { lhs, rhs });
    }

    /// Requires `condition` (Modelica's `assert(condition, message)` on parameters): a
    /// `bool` on structural parameters is checked now, and compiling the model fails
    /// with `message` and this component's path when it is false; an expression of
    /// tunable parameters is checked when a problem sets their values.
    pub fn assert(&mut self, condition: impl Into<Condition>, message: impl Into<SharedText>) {
        match condition.into() {
            Condition::Now(true) => {}
            Condition::Now(false) => self.invalid(message.into().to_string()),
            Condition::Parameters(e) => {
                let condition = self.own(e);
                let message = message.into();
                self.checks_mut()
                    .assertions
                    .push(Assertion { condition, message });
            }
        }
    }

    /// Records that a structural parameter has a value the component rejects
    /// (`message` names it and its value).
    pub fn invalid(&mut self, message: String) {
        self.checks_mut().invalid.push(message);
    }

    fn checks_mut(&mut self) -> &mut Checks {
        self.checks.get_or_insert_with(Box::default)
    }

    /// The messages of the structural parameters the component rejected.
    pub fn invalid_parameters(&self) -> &[String] {
        self.checks.as_ref().map_or(&[], |c| &c.invalid)
    }

    /// The component's conditions on its tunable parameters.
    pub fn assertions(&self) -> &[Assertion] {
        self.checks.as_ref().map_or(&[], |c| &c.assertions)
    }

    /// Adds a sub-component (or connector) instance named `local` and returns it.
    pub fn add(&mut self, local: &str, c: &dyn Component) -> &mut System {
        let mut sub = System::with_path(
            local.to_string(),
            self.full(local),
            c.type_name(),
            c.connector_class(),
            self.store.clone(),
        );
        sub.build_from(c);
        self.subsystems.push(sub);
        self.subsystems.last_mut().expect("just pushed")
    }

    /// Replaces the sub-component named `local` by a fresh instance of `c` (same name
    /// and path). Returns false when there is no such sub-component.
    pub fn replace(&mut self, local: &str, c: &dyn Component) -> bool {
        let Some(k) = self.subsystems.iter().position(|s| s.name == local) else {
            return false;
        };
        let mut sub = System::with_path(
            local.to_string(),
            self.full(local),
            c.type_name(),
            c.connector_class(),
            self.store.clone(),
        );
        sub.build_from(c);
        self.subsystems[k] = sub;
        true
    }

    /// The sub-system at a relative path, mutably.
    pub fn subsystem_mut(&mut self, local_path: &str) -> Option<&mut System> {
        let mut cur = self;
        for part in local_path.split('.') {
            cur = cur.subsystems.iter_mut().find(|s| s.name == part)?;
        }
        Some(cur)
    }

    /// Declares `extends`: builds a partial component's declarations into this same
    /// system (no new name level), as Modelica's `extends PartialCompliant`.
    pub fn extend(&mut self, c: &dyn Component) {
        self.build_from(c);
    }

    /// Builds `c` into this system, with this system's store current (the expressions
    /// the component builds live there).
    fn build_from(&mut self, c: &dyn Component) {
        let _current = self.store.enter();
        c.build(self);
    }

    /// The store of this model's expressions.
    pub fn store(&self) -> &ExprStore {
        &self.store
    }

    /// `e` as an expression of this model's store (copied there if it was built for
    /// another model).
    pub fn own(&self, e: Expr) -> Expr {
        into_store(e, &self.store.0)
    }

    /// Connects two connectors given by paths relative to this system.
    pub fn connect(&mut self, a: &str, b: &str) {
        self.connections.push(Connection {
            a: a.to_string(),
            b: b.to_string(),
        });
    }

    /// The sub-system at a relative path (`motor.emf`), if any.
    pub fn subsystem(&self, local_path: &str) -> Option<&System> {
        let mut cur = self;
        for part in local_path.split('.') {
            cur = cur.subsystems.iter().find(|s| s.name == part)?;
        }
        Some(cur)
    }

    /// Records a structural parameter's value (see [`System::structural`]); `None`
    /// records nothing.
    /// A value that is not finite (NaN or infinite) makes the component invalid: the
    /// model does not compile, and the error names the parameter.
    pub fn record_structural(&mut self, name: &str, value: Option<Vec<f64>>) {
        if let Some(v) = value {
            if v.iter().any(|x| !x.is_finite()) {
                self.invalid(format!(
                    "structural parameter `{name}` = {} is not finite",
                    show_values(&v)
                ));
            }
            self.structural.push((name.to_string(), v));
        }
    }

    /// The recorded value of the structural parameter `name` of this system.
    pub fn structural_value(&self, name: &str) -> Option<&[f64]> {
        self.structural
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_slice())
    }

    /// Whether this system is a connector.
    pub fn is_connector(&self) -> bool {
        self.connector_class.is_some()
    }
}

/// Numbers as written in messages: one alone, several in brackets.
pub fn show_values(v: &[f64]) -> String {
    match v {
        [x] => x.to_string(),
        _ => format!(
            "[{}]",
            v.iter().map(f64::to_string).collect::<Vec<_>>().join(", ")
        ),
    }
}

/// A structural parameter value that can be recorded as numbers (see
/// [`System::structural`]).
pub trait StructuralValue {
    /// The value as numbers, `None` when there is nothing to record.
    fn structural_values(&self) -> Option<Vec<f64>>;
}

impl StructuralValue for f64 {
    fn structural_values(&self) -> Option<Vec<f64>> {
        Some(vec![*self])
    }
}

impl StructuralValue for bool {
    fn structural_values(&self) -> Option<Vec<f64>> {
        Some(vec![if *self { 1.0 } else { 0.0 }])
    }
}

impl StructuralValue for usize {
    fn structural_values(&self) -> Option<Vec<f64>> {
        Some(vec![*self as f64])
    }
}

impl<const N: usize> StructuralValue for [f64; N] {
    fn structural_values(&self) -> Option<Vec<f64>> {
        Some(self.to_vec())
    }
}

impl<const N: usize> StructuralValue for Vec<[f64; N]> {
    fn structural_values(&self) -> Option<Vec<f64>> {
        Some(self.iter().flatten().copied().collect())
    }
}

impl<T: StructuralValue> StructuralValue for Option<T> {
    fn structural_values(&self) -> Option<Vec<f64>> {
        self.as_ref().and_then(StructuralValue::structural_values)
    }
}
