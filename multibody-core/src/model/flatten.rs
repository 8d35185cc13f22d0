//! Flattening: the system tree becomes scalar equations over numbered variables.

use std::sync::Arc;

use crate::hash::HashMap;

use crate::expr::handle::{Resolved, SymbolNames};
use crate::expr::store;
use crate::expr::{Arena, Expr, ExprStore, Id, NameResolver, Node, NodeMap};
use crate::names::closest;

use super::SharedText;
use super::error::ModelError;
use super::path_index::PathIndex;
use super::system::{Equation, System, join_path, join_path_into};
use super::variable::{Parameter, VarKind, Variable};

/// Where a flat equation came from (for messages).
#[derive(Clone, Debug)]
pub enum Origin {
    /// Declared in a component.
    Component {
        /// The component's path (empty for the root; a thin pointer, so that every flat
        /// equation stays small).
        path: Arc<String>,
        /// The equation as written.
        equation: Equation,
    },
    /// Equal potentials (or signals) of two connected connectors.
    Connect {
        /// The first of the two variables made equal (its index in
        /// [`FlatSystem::variables`]).
        a: u32,
        /// The second variable.
        b: u32,
    },
    /// Zero sum of the flows of a connection set.
    FlowSum {
        /// The flow variables of the set (indices in [`FlatSystem::variables`]), each
        /// with whether it enters the sum negated (a connector connected from outside
        /// its component).
        flows: Box<[(u32, bool)]>,
    },
    /// The flow of a connector that is connected nowhere is zero.
    UnconnectedFlow {
        /// The flow variable (its index in [`FlatSystem::variables`]).
        flow: u32,
    },
    /// Decided by the virtual connection graph (orientation propagation along a
    /// branch or connection, a loop closure residue, a root's equations). Boxed: rare,
    /// and it would make every equation's origin twice as large.
    Graph(Box<GraphOrigin>),
    /// A component's assertion on its parameters (see [`System::assert`]).
    Assertion {
        /// The component's path (empty for the root).
        path: Arc<String>,
        /// The condition as written.
        condition: Expr,
    },
    /// Added by dynamic state selection (the definition of a dynamic state).
    DynamicStates {
        /// The equation in words.
        text: String,
    },
    /// The crossing function of a relation that generates events.
    Crossing {
        /// The relation, as written in the model.
        relation: String,
    },
    /// A variable assigned in `when` clauses holds its value between events.
    Discrete {
        /// The variable's full name.
        variable: String,
    },
    /// An input of the model is the parameter of its name (see
    /// [`SimplifyOptions::inputs`](crate::simplify::SimplifyOptions::inputs)).
    Input {
        /// The input's full name.
        variable: String,
    },
    /// A start value declared `fixed` (initialization only).
    FixedStart {
        /// The variable.
        var: SharedText,
    },
}

/// An equation decided by the virtual connection graph (see [`Origin::Graph`]).
#[derive(Clone, Debug)]
pub struct GraphOrigin {
    /// The component (empty for connections).
    pub path: String,
    /// What it is, in words.
    pub text: String,
    /// The equation.
    pub equation: Equation,
}

/// One scalar equation `residual = 0` of a flat system.
#[derive(Clone, Debug)]
pub struct FlatEquation {
    /// The residual in the flat system's arena.
    pub residual: Id,
    /// Where it came from.
    pub origin: Origin,
    /// The variable on the left-hand side, when it is a lone variable as written
    /// (`frame_b.R.T[1,1] = ...`).
    pub lhs_var: Option<u32>,
}

/// A condition on parameters that must hold (see [`System::assert`]).
#[derive(Clone, Debug)]
pub struct FlatAssertion {
    /// The condition in the flat system's arena (parameters only), nonzero when it
    /// holds.
    pub condition: Id,
    /// What is wrong when it does not hold.
    pub message: SharedText,
    /// The path of the component that asserts it (empty for the model itself).
    pub component: Arc<String>,
    /// The component's type.
    pub type_name: SharedText,
}

/// A flattened model: numbered variables and parameters, and scalar equations in a local
/// arena where `Var(i)` is `variables[i]` and `Param(j)` is `parameters[j]`.
#[derive(Clone, Debug)]
pub struct FlatSystem {
    /// Model name.
    pub name: String,
    /// All unknowns, in declaration order.
    pub variables: Vec<Variable>,
    /// All tunable parameters.
    pub parameters: Vec<Parameter>,
    /// Expression storage for the equations below.
    pub arena: Arena,
    /// Equations.
    pub equations: Vec<FlatEquation>,
    /// Initial equations.
    pub initial_equations: Vec<FlatEquation>,
    /// Start values in the local arena (parameters may occur).
    pub starts: Vec<Option<Id>>,
    /// Parameter bindings in the local arena.
    pub parameter_values: Vec<Option<Id>>,
    /// `(variable, derivative)`: variables whose time derivative is an expression.
    pub derivative_rules: Vec<(u32, Id)>,
    /// Connections that close loops of overdetermined connectors (cut), by node.
    pub cuts: Vec<(String, String)>,
    /// The stores of the model's expressions, which the equations' origins print (kept
    /// for messages).
    pub stores: Vec<ExprStore>,
    /// Conditions on parameters, checked when a problem sets their values.
    pub assertions: Vec<FlatAssertion>,
    /// Full names of the numeric structural parameters (fixed when the model was
    /// built), for messages.
    pub structural: Vec<String>,
    /// `when` clauses.
    pub whens: Vec<FlatWhen>,
    /// The conditions of `sample(..)` (relations `time >= next`).
    pub samples: Vec<Id>,
    /// The parameters of `initial()`.
    pub initials: Vec<usize>,
    /// The parameters of `terminal()`.
    pub terminals: Vec<usize>,
}

/// A `when` clause of a flat system (see [`WhenClause`](super::WhenClause)).
#[derive(Clone, Debug)]
pub struct FlatWhen {
    /// The path of the component that declared it.
    pub path: Arc<String>,
    /// The condition.
    pub condition: Id,
    /// `(variable, value)`: the discrete variables it assigns.
    pub assignments: Vec<(u32, Id)>,
    /// `(state, value)` of its `reinit`s.
    pub reinits: Vec<(u32, Id)>,
    /// The message of its `terminate(..)`.
    pub terminate: Option<String>,
    /// Whether it is an `elsewhen` of the clause before it.
    pub elsewhen: bool,
}

/// Names of a flat system's leaves.
pub struct FlatNames<'a> {
    /// Variables.
    pub variables: &'a [Variable],
    /// Parameters.
    pub parameters: &'a [Parameter],
}

impl NameResolver for FlatNames<'_> {
    fn var(&self, i: u32) -> String {
        self.variables[i as usize].name.to_string()
    }
    fn param(&self, i: u32) -> String {
        self.parameters[i as usize].name.to_string()
    }
}

impl FlatSystem {
    /// Leaf names for display.
    pub fn names(&self) -> FlatNames<'_> {
        FlatNames {
            variables: &self.variables,
            parameters: &self.parameters,
        }
    }

    /// Text of an expression of this system.
    pub fn show(&self, e: Id) -> String {
        self.arena.display(e, &self.names())
    }

    /// A readable description of an equation for messages.
    pub fn describe(&self, eq: &FlatEquation) -> String {
        Self::describe_origin(&self.variables, &eq.origin)
    }

    /// A readable description of an equation of the given origin; `variables` are the
    /// flat system's, which connection origins refer to by index.
    pub fn describe_origin(variables: &[Variable], origin: &Origin) -> String {
        let name = |v: u32| &*variables[v as usize].name;
        match origin {
            Origin::Component { path, equation } => {
                let at = if path.is_empty() { "model" } else { path };
                format!("{at}: {} = {}", equation.lhs, equation.rhs)
            }
            Origin::Connect { a, b } => format!("connection: {} = {}", name(*a), name(*b)),
            Origin::FlowSum { flows } => {
                let terms: Vec<String> = flows
                    .iter()
                    .map(|&(v, negated)| {
                        if negated {
                            format!("-{}", name(v))
                        } else {
                            name(v).to_string()
                        }
                    })
                    .collect();
                format!("connection: {} = 0", terms.join(" + "))
            }
            Origin::UnconnectedFlow { flow } => {
                format!("unconnected flow: {} = 0", name(*flow))
            }
            Origin::FixedStart { var } => format!("fixed start value of {var}"),
            Origin::DynamicStates { text } => format!("dynamic state selection: {text}"),
            Origin::Crossing { relation } => format!("crossing function of {relation}"),
            Origin::Input { variable } => format!("{variable} is an input of the model"),
            Origin::Discrete { variable } => {
                format!("{variable} holds the value it took at the last event")
            }
            Origin::Assertion { path, condition } => {
                let at = if path.is_empty() { "model" } else { path };
                format!("{at}: assert({condition})")
            }
            Origin::Graph(g) => {
                format!("{}: {} = {}", g.text, g.equation.lhs, g.equation.rhs)
            }
        }
    }
}

struct ConnectorInfo {
    /// The connector class, by its position in `Flattener::classes`.
    class: u32,
    vars: Vec<(usize, VarKind)>,
    connected_inside: bool,
}

/// The stores of a model's systems, locked while it is flattened (in the order of their
/// numbers, so that two threads flattening models that share stores cannot deadlock),
/// each with the memo of its nodes already translated.
struct LockedStores<'g> {
    ids: Vec<u32>,
    arenas: Vec<std::sync::MutexGuard<'g, Arena>>,
    memos: Vec<NodeMap>,
}

impl<'g> LockedStores<'g> {
    fn lock(cells: &'g [ExprStore]) -> Self {
        LockedStores {
            ids: cells.iter().map(ExprStore::id).collect(),
            arenas: cells.iter().map(|c| c.0.lock()).collect(),
            memos: cells.iter().map(|_| NodeMap::new()).collect(),
        }
    }

    /// The text of `e` (an expression of a locked store is read through its lock).
    fn show(&self, e: Expr) -> String {
        match e.resolve() {
            Resolved::Node(sid, id) => match self.ids.iter().position(|&i| i == sid) {
                Some(k) => self.arenas[k].display(id, &SymbolNames),
                None => e.to_string(),
            },
            _ => e.to_string(),
        }
    }
}

struct Flattener<'g, 's> {
    stores: LockedStores<'g>,
    flat: FlatSystem,
    /// Flat index of each declared variable and parameter, by global symbol.
    var_of_sym: Vec<u32>,
    param_of_sym: Vec<u32>,
    connectors: Vec<ConnectorInfo>,
    /// Connectors by path (a compact copy of the paths: a lookup compares with it, not
    /// with the model's strings).
    connector_of_path: PathIndex,
    /// Connector classes by name, numbered in the order met.
    class_of_name: HashMap<&'s str, u32>,
    /// Connector class names by number.
    classes: Vec<&'s str>,
    /// Declarations whose names were never interned (pushed by hand): for duplicates.
    unnamed: HashMap<SharedText, u32>,
    errors: Vec<ModelError>,
    /// Work space for the paths of connectors looked up.
    path_buffer: String,
}

/// Records `idx` for symbol `sym`; false if the symbol is declared already.
fn claim(table: &mut Vec<u32>, sym: u32, idx: u32) -> bool {
    let s = sym as usize;
    if s >= table.len() {
        table.resize(s + 1, u32::MAX);
    }
    if table[s] != u32::MAX {
        return false;
    }
    table[s] = idx;
    true
}

/// Where an expression being translated comes from, in words.
/// Characters of an equation that a message about it shows.
const PLACE_CHARS: usize = 160;

fn describe_place(origin: &Origin, stores: &LockedStores<'_>) -> String {
    match origin {
        Origin::Component { path, equation } => format!(
            "{}: {}",
            if path.is_empty() { "model" } else { path },
            crate::names::elide(
                &format!(
                    "{} = {}",
                    stores.show(equation.lhs),
                    stores.show(equation.rhs)
                ),
                PLACE_CHARS
            )
        ),
        Origin::FixedStart { var } => format!("the start value or binding of {var}"),
        Origin::Assertion { path, condition } => format!(
            "{}: assert({})",
            if path.is_empty() { "model" } else { path },
            crate::names::elide(&stores.show(*condition), PLACE_CHARS)
        ),
        _ => "a connection".into(),
    }
}

fn union_find_root(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// Flattens a model: collects every variable, parameter and equation under full names,
/// adds the connection equations (potentials equal, flows summing to zero, unconnected
/// flows zero), and checks names and connector classes. The balance check is separate
/// ([`super::balance::check_balance`]).
pub fn flatten(sys: &System) -> Result<FlatSystem, ModelError> {
    // The tree in the order its declarations are numbered, and the sizes of the flat
    // vectors (growing them by doubling copies a large model's declarations several
    // times over); on the way, the first component built with structural parameters
    // it rejects (its equations may make no sense, so it is reported before anything
    // else) and the stores of the model's expressions.
    let (mut n_variables, mut n_parameters, mut n_equations) = (0, 0, 0);
    // Connections add at most one equation per connector variable.
    let (mut n_connectors, mut n_connector_variables, mut n_connector_path_bytes) = (0, 0, 0);
    let mut stack = vec![sys];
    let mut order = Vec::new();
    let mut stores: Vec<ExprStore> = Vec::new();
    while let Some(s) = stack.pop() {
        if !s.invalid_parameters().is_empty() {
            return Err(ModelError::InvalidComponent {
                component: if s.path.is_empty() {
                    s.name.clone()
                } else {
                    s.path.clone()
                },
                type_name: s.type_name.clone(),
                message: s.invalid_parameters().join("; "),
            });
        }
        // Nearly always one store (every system of a model shares it).
        if stores.last().is_none_or(|l| !l.same(s.store()))
            && !stores.iter().any(|o| o.same(s.store()))
        {
            stores.push(s.store().clone());
        }
        order.push(s);
        n_variables += s.variables.len();
        n_parameters += s.parameters.len();
        n_equations += s.equations.len();
        if s.connector_class.is_some() {
            n_connectors += 1;
            n_connector_variables += s.variables.len();
            n_connector_path_bytes += s.path.len();
        }
        for sub in s.subsystems.iter().rev() {
            stack.push(sub);
        }
    }
    stores.sort_by_key(ExprStore::id);
    // The graph builds expressions (residues), in the model's store: before the stores
    // are locked.
    let graph = {
        let _current = sys.store().enter();
        super::connection_graph::resolve(sys)?
    };
    let n_symbols = crate::expr::symbols::bound();
    let mut f = Flattener {
        stores: LockedStores::lock(&stores),
        flat: FlatSystem {
            name: sys.name.clone(),
            variables: Vec::new(),
            parameters: Vec::new(),
            arena: Arena::new(),
            equations: Vec::new(),
            initial_equations: Vec::new(),
            starts: Vec::new(),
            parameter_values: Vec::new(),
            derivative_rules: Vec::new(),
            cuts: graph.cuts.clone(),
            stores: stores.clone(),
            assertions: Vec::new(),
            structural: Vec::new(),
            whens: Vec::new(),
            samples: Vec::new(),
            initials: Vec::new(),
            terminals: Vec::new(),
        },
        var_of_sym: vec![u32::MAX; n_symbols],
        param_of_sym: vec![u32::MAX; n_symbols],
        connectors: Vec::new(),
        connector_of_path: PathIndex::with_capacity(0, 0),
        class_of_name: HashMap::default(),
        classes: Vec::new(),
        unnamed: HashMap::default(),
        errors: Vec::new(),
        path_buffer: String::new(),
    };
    // Pass 1: declarations.
    f.flat.variables.reserve_exact(n_variables);
    f.flat.starts.reserve_exact(n_variables);
    f.flat.parameters.reserve_exact(n_parameters);
    f.flat.parameter_values.reserve_exact(n_parameters);
    f.flat
        .equations
        .reserve(n_equations + n_connector_variables + graph.equations.len());
    // Growing the index of connectors by path would hash every path again at each
    // doubling, reading the model's strings once more.
    f.connectors.reserve_exact(n_connectors);
    f.connector_of_path = PathIndex::with_capacity(n_connectors, n_connector_path_bytes);
    for &s in &order {
        f.declare(s);
    }
    if let Some(e) = f.errors.first() {
        return Err(e.clone());
    }
    // Pass 2: equations, starts and parameter values.
    for s in order.iter() {
        // One shared copy of the path for all of this component's equations.
        let path: Arc<String> = Arc::new(s.path.clone());
        for eq in &s.equations {
            let origin = Origin::Component {
                path: path.clone(),
                equation: *eq,
            };
            if let Some((r, lhs_var)) = f.translate_equation(eq, &origin) {
                f.flat.equations.push(FlatEquation {
                    residual: r,
                    origin,
                    lhs_var,
                });
            }
        }
        for eq in &s.initial_equations {
            let origin = Origin::Component {
                path: path.clone(),
                equation: *eq,
            };
            if let Some((r, lhs_var)) = f.translate_equation(eq, &origin) {
                f.flat.initial_equations.push(FlatEquation {
                    residual: r,
                    origin,
                    lhs_var,
                });
            }
        }
        f.flatten_whens(s, &path);
        for a in s.assertions() {
            let origin = Origin::Assertion {
                path: path.clone(),
                condition: a.condition,
            };
            let Some(condition) = f.translate(a.condition, &origin) else {
                continue;
            };
            let arena = &f.flat.arena;
            if arena
                .leaves(condition)
                .iter()
                .any(|&l| !matches!(arena.node(l), Node::Param(_)))
            {
                f.errors.push(ModelError::AssertionOnVariables {
                    component: if s.path.is_empty() {
                        "model".into()
                    } else {
                        s.path.clone()
                    },
                    condition: f.stores.show(a.condition),
                });
                continue;
            }
            f.flat.assertions.push(FlatAssertion {
                condition,
                message: a.message.clone(),
                component: path.clone(),
                // Type names are few: kept once for the process, like symbols.
                type_name: SharedText::from(crate::expr::symbols::intern(&s.type_name).1),
            });
        }
        for (var, der) in &s.derivative_rules {
            let origin = Origin::Component {
                path: path.clone(),
                equation: Equation {
                    lhs: *var,
                    rhs: *der,
                },
            };
            if let (Some(v), Some(d)) = (f.translate(*var, &origin), f.translate(*der, &origin))
                && let Node::Var(i) = f.flat.arena.node(v)
            {
                let i = *i;
                f.flat.derivative_rules.push((i, d));
            }
        }
    }
    for ge in graph.equations {
        let origin = Origin::Graph(Box::new(GraphOrigin {
            path: ge.path,
            text: ge.text,
            equation: ge.equation,
        }));
        if let Some((r, lhs_var)) = f.translate_equation(&ge.equation, &origin) {
            f.flat.equations.push(FlatEquation {
                residual: r,
                origin,
                lhs_var,
            });
        }
    }
    for i in 0..f.flat.variables.len() {
        let start = f.translate_binding(f.flat.variables[i].start, |flat| {
            flat.variables[i].name.clone()
        });
        f.flat.starts.push(start);
    }
    for i in 0..f.flat.parameters.len() {
        let val = f.translate_binding(f.flat.parameters[i].value, |flat| {
            flat.parameters[i].name.clone()
        });
        let fixed = f.flat.parameters[i].fixed;
        if val.is_none() && fixed {
            let name = f.flat.parameters[i].name.to_string();
            f.errors.push(ModelError::ParameterWithoutValue(name));
        }
        f.flat.parameter_values.push(val);
    }
    // Pass 3: connections.
    f.connections(&order);
    if let Some(e) = f.errors.into_iter().next() {
        return Err(e);
    }
    Ok(f.flat)
}

impl<'s> Flattener<'_, 's> {
    fn declare(&mut self, s: &'s System) {
        self.flat.structural.extend(
            s.structural
                .iter()
                .map(|(name, _)| join_path(&s.path, name)),
        );
        let mut conn_vars = Vec::new();
        for v in &s.variables {
            let idx = self.flat.variables.len() as u32;
            let sym = v.symbol.or_else(|| crate::expr::symbols::lookup(&v.name));
            let duplicate = match sym {
                Some(sym) => !claim(&mut self.var_of_sym, sym, idx),
                None => self.unnamed.insert(v.name.clone(), idx).is_some(),
            };
            if duplicate {
                self.errors
                    .push(ModelError::DuplicateName(v.name.to_string()));
            }
            self.flat.variables.push(v.clone());
            if v.kind != VarKind::Internal {
                conn_vars.push((idx as usize, v.kind));
            }
        }
        for p in &s.parameters {
            let idx = self.flat.parameters.len() as u32;
            let sym = p.symbol.or_else(|| crate::expr::symbols::lookup(&p.name));
            let duplicate = match sym {
                Some(sym) => !claim(&mut self.param_of_sym, sym, idx),
                None => self.unnamed.insert(p.name.clone(), idx).is_some(),
            };
            if duplicate {
                self.errors
                    .push(ModelError::DuplicateName(p.name.to_string()));
            }
            self.flat.parameters.push(p.clone());
        }
        if let Some(class_name) = &s.connector_class {
            let n_classes = self.classes.len() as u32;
            let class = *self
                .class_of_name
                .entry(class_name.as_str())
                .or_insert(n_classes);
            if class == n_classes {
                self.classes.push(class_name.as_str());
            }
            self.connector_of_path
                .insert(&s.path, self.connectors.len() as u32);
            self.connectors.push(ConnectorInfo {
                class,
                vars: conn_vars,
                connected_inside: false,
            });
        }
    }

    /// A start value or parameter binding in the local arena; `name` gives the name of
    /// its variable or parameter for messages (read only when there is a value, so
    /// declarations without one touch no name).
    fn translate_binding(
        &mut self,
        value: Option<Expr>,
        name: impl FnOnce(&FlatSystem) -> SharedText,
    ) -> Option<Id> {
        let e = value?;
        let origin = Origin::FixedStart {
            var: name(&self.flat),
        };
        self.translate(e, &origin)
    }

    /// `lhs - rhs` of an equation in the local arena (built there, so the global lock
    /// held by the flattener is never taken twice).
    /// The `when` clauses of `s` into the flat system.
    fn flatten_whens(&mut self, s: &System, path: &Arc<String>) {
        let component = || {
            if s.path.is_empty() {
                "model".to_string()
            } else {
                s.path.clone()
            }
        };
        if !s.reinits.is_empty() || !s.terminates.is_empty() {
            self.errors.push(ModelError::InvalidWhen {
                component: component(),
                message: "reinit(..) and terminate(..) belong inside a when clause".into(),
            });
        }
        for (&p, terminal) in
            (s.initials.iter().map(|p| (p, false))).chain(s.terminals.iter().map(|p| (p, true)))
        {
            let o = Origin::Component {
                path: path.clone(),
                equation: Equation { lhs: p, rhs: p },
            };
            if let Some(p) = self.translate(p, &o)
                && let Node::Param(j) = *self.flat.arena.node(p)
            {
                if terminal {
                    self.flat.terminals.push(j as usize);
                } else {
                    self.flat.initials.push(j as usize);
                }
            }
        }
        for &c in &s.samples {
            let o = Origin::Component {
                path: path.clone(),
                equation: Equation { lhs: c, rhs: c },
            };
            if let Some(c) = self.translate(c, &o) {
                self.flat.samples.push(c);
            }
        }
        for w in &s.whens {
            let origin = |equation: Equation| Origin::Component {
                path: path.clone(),
                equation,
            };
            let whole = origin(Equation {
                lhs: w.condition,
                rhs: w.condition,
            });
            let Some(condition) = self.translate(w.condition, &whole) else {
                continue;
            };
            let mut pairs = |list: &[Equation], what: &str| -> Vec<(u32, Id)> {
                let mut out = Vec::with_capacity(list.len());
                for eq in list {
                    let o = origin(*eq);
                    let (Some(l), Some(r)) =
                        (self.translate(eq.lhs, &o), self.translate(eq.rhs, &o))
                    else {
                        continue;
                    };
                    match *self.flat.arena.node(l) {
                        Node::Var(v) => out.push((v, r)),
                        _ => self.errors.push(ModelError::InvalidWhen {
                            component: component(),
                            message: format!(
                                "in a when clause, {what} `{}` must be a variable",
                                self.flat.show(l)
                            ),
                        }),
                    }
                }
                out
            };
            let assignments = pairs(&w.equations, "the left-hand side");
            let reinits = pairs(&w.reinits, "the first argument of reinit");
            let terminate = w.terminate.as_ref().map(|m| {
                let at = if s.path.is_empty() { "model" } else { &s.path };
                format!("{at}: {m}")
            });
            self.flat.whens.push(FlatWhen {
                path: path.clone(),
                condition,
                assignments,
                reinits,
                terminate,
                elsewhen: w.elsewhen,
            });
        }
    }

    fn translate_equation(&mut self, eq: &Equation, origin: &Origin) -> Option<(Id, Option<u32>)> {
        let l = self.translate(eq.lhs, origin)?;
        let r = self.translate(eq.rhs, origin)?;
        let lhs_var = match self.flat.arena.node(l) {
            Node::Var(i) => Some(*i),
            _ => None,
        };
        Some((self.flat.arena.sub(l, r), lhs_var))
    }

    fn translate(&mut self, e: Expr, origin: &Origin) -> Option<Id> {
        let var_of_sym = &self.var_of_sym;
        let param_of_sym = &self.param_of_sym;
        let mut missing: Option<(&'static str, u32)> = None;
        let mut leaf = |a: &mut Arena, n: &Node| match n {
            Node::Var(s) => match var_of_sym.get(*s as usize).filter(|&&i| i != u32::MAX) {
                Some(&i) => a.var(i),
                None => {
                    missing.get_or_insert(("variable", *s));
                    a.zero()
                }
            },
            Node::Param(s) => match param_of_sym.get(*s as usize).filter(|&&i| i != u32::MAX) {
                Some(&i) => a.param(i),
                None => {
                    missing.get_or_insert(("parameter", *s));
                    a.zero()
                }
            },
            _ => a.time(),
        };
        let arena = &mut self.flat.arena;
        let r = match e.resolve() {
            Resolved::Var(s) => leaf(arena, &Node::Var(s)),
            Resolved::Param(s) => leaf(arena, &Node::Param(s)),
            Resolved::Time => arena.time(),
            Resolved::Node(sid, id) => match self.stores.ids.iter().position(|&i| i == sid) {
                Some(k) => arena.import(
                    &self.stores.arenas[k],
                    id,
                    &mut leaf,
                    &mut self.stores.memos[k],
                ),
                // An expression of a store no system of the model holds (put into a
                // system's fields by hand): copied out of it first.
                None => match store::find(sid) {
                    Some(cell) => {
                        let (src, id) = store::export(&cell, id);
                        arena.import(&src, id, &mut leaf, &mut NodeMap::new())
                    }
                    None => {
                        let place = describe_place(origin, &self.stores);
                        self.errors.push(ModelError::DroppedExpression { place });
                        return None;
                    }
                },
            },
        };
        if let Some((what, s)) = missing {
            // A failed import may have cached partial results; drop the memos.
            self.stores.memos.iter_mut().for_each(NodeMap::clear);
            let name = crate::expr::symbols::name(s).to_string();
            let place = describe_place(origin, &self.stores);
            let candidates: Vec<&str> = if what == "variable" {
                self.flat.variables.iter().map(|v| &*v.name).collect()
            } else {
                self.flat.parameters.iter().map(|p| &*p.name).collect()
            };
            let suggestions = closest(&name, candidates, 3);
            self.errors.push(ModelError::UnknownName {
                what,
                name,
                place,
                suggestions,
            });
            return None;
        }
        Some(r)
    }

    fn connections(&mut self, order: &[&'s System]) {
        let nv = self.flat.variables.len();
        let mut pot_parent: Vec<usize> = (0..nv).collect();
        // Flow connection sets over elements (connector, inside?).
        let mut elem_index: HashMap<(usize, bool), usize> = HashMap::default();
        let mut elems: Vec<(usize, bool)> = Vec::new();
        let mut elem_parent: Vec<usize> = Vec::new();
        for s in order {
            for c in &s.connections {
                // Written out only for messages.
                let text = || {
                    format!(
                        "{}connect({}, {})",
                        if s.path.is_empty() {
                            String::new()
                        } else {
                            format!("{}: ", s.path)
                        },
                        c.a,
                        c.b
                    )
                };
                let Some(ia) = self.resolve_connector(s, &c.a, &text) else {
                    continue;
                };
                let Some(ib) = self.resolve_connector(s, &c.b, &text) else {
                    continue;
                };
                let (ca, cb) = (&self.connectors[ia], &self.connectors[ib]);
                if ca.class != cb.class || ca.vars.len() != cb.vars.len() {
                    self.errors.push(ModelError::IncompatibleConnectors {
                        connection: text(),
                        a: join_path(&s.path, &c.a),
                        class_a: self.classes[ca.class as usize].to_string(),
                        b: join_path(&s.path, &c.b),
                        class_b: self.classes[cb.class as usize].to_string(),
                    });
                    continue;
                }
                // A connector of a sub-component (`sd.flange_a`), not of this system
                // itself: its path goes past this system's by more than one name.
                let inside_a = c.a.contains('.');
                let inside_b = c.b.contains('.');
                // Two outputs of sub-components would both determine the signal.
                let output =
                    |c: &ConnectorInfo| c.vars.first().is_some_and(|v| v.1 == VarKind::Output);
                if inside_a && inside_b && output(ca) && output(cb) {
                    self.errors.push(ModelError::TwoOutputs {
                        connection: text(),
                        a: join_path(&s.path, &c.a),
                        b: join_path(&s.path, &c.b),
                    });
                    continue;
                }
                let pairs: Vec<((usize, VarKind), (usize, VarKind))> = ca
                    .vars
                    .iter()
                    .copied()
                    .zip(cb.vars.iter().copied())
                    .collect();
                for ((va, ka), (vb, _)) in pairs {
                    if ka == VarKind::Flow || ka == VarKind::Overdetermined {
                        continue;
                    }
                    let (ra, rb) = (
                        union_find_root(&mut pot_parent, va),
                        union_find_root(&mut pot_parent, vb),
                    );
                    if ra != rb {
                        pot_parent[ra] = rb;
                        let (xa, xb) = (
                            self.flat.arena.var(va as u32),
                            self.flat.arena.var(vb as u32),
                        );
                        let r = self.flat.arena.sub(xa, xb);
                        self.flat.equations.push(FlatEquation {
                            residual: r,
                            origin: Origin::Connect {
                                a: va as u32,
                                b: vb as u32,
                            },
                            lhs_var: None,
                        });
                    }
                }
                let mut elem = |key: (usize, bool)| -> usize {
                    *elem_index.entry(key).or_insert_with(|| {
                        elems.push(key);
                        elem_parent.push(elem_parent.len());
                        elem_parent.len() - 1
                    })
                };
                let (ea, eb) = (elem((ia, inside_a)), elem((ib, inside_b)));
                let (ra, rb) = (
                    union_find_root(&mut elem_parent, ea),
                    union_find_root(&mut elem_parent, eb),
                );
                if ra != rb {
                    elem_parent[ra] = rb;
                }
                if inside_a {
                    self.connectors[ia].connected_inside = true;
                }
                if inside_b {
                    self.connectors[ib].connected_inside = true;
                }
            }
        }
        // Flow sums, one per set and flow position.
        let mut sets: HashMap<usize, Vec<usize>> = HashMap::default();
        let mut set_order = Vec::new();
        for i in 0..elems.len() {
            let r = union_find_root(&mut elem_parent, i);
            let e = sets.entry(r).or_default();
            if e.is_empty() {
                set_order.push(r);
            }
            e.push(i);
        }
        let mut terms = Vec::new();
        for r in set_order {
            let members = &sets[&r];
            let (c0, _) = elems[members[0]];
            let nflows = self.connectors[c0].vars.len();
            for k in 0..nflows {
                if self.connectors[c0].vars[k].1 != VarKind::Flow {
                    continue;
                }
                terms.clear();
                let mut flows = Vec::with_capacity(members.len());
                for &m in members {
                    let (c, inside) = elems[m];
                    let v = self.connectors[c].vars[k].0;
                    let x = self.flat.arena.var(v as u32);
                    terms.push((if inside { 1.0 } else { -1.0 }, x));
                    flows.push((v as u32, !inside));
                }
                let r = self.flat.arena.linear_combination(0.0, &terms);
                self.flat.equations.push(FlatEquation {
                    residual: r,
                    origin: Origin::FlowSum {
                        flows: flows.into_boxed_slice(),
                    },
                    lhs_var: None,
                });
            }
        }
        // Flows of connectors never connected from outside are zero.
        for c in 0..self.connectors.len() {
            if self.connectors[c].connected_inside {
                continue;
            }
            for k in 0..self.connectors[c].vars.len() {
                let (v, kind) = self.connectors[c].vars[k];
                if kind == VarKind::Flow {
                    let x = self.flat.arena.var(v as u32);
                    self.flat.equations.push(FlatEquation {
                        residual: x,
                        origin: Origin::UnconnectedFlow { flow: v as u32 },
                        lhs_var: None,
                    });
                }
            }
        }
    }

    fn resolve_connector(
        &mut self,
        s: &System,
        local: &str,
        text: &dyn Fn() -> String,
    ) -> Option<usize> {
        join_path_into(&s.path, local, &mut self.path_buffer);
        if let Some(i) = self.connector_of_path.get(&self.path_buffer) {
            return Some(i as usize);
        }
        let full = join_path(&s.path, local);
        let prefix = if s.path.is_empty() {
            String::new()
        } else {
            format!("{}.", s.path)
        };
        let candidates: Vec<&str> = self
            .connector_of_path
            .paths()
            .filter(|k| k.starts_with(&prefix))
            .collect();
        let mut candidates = candidates;
        candidates.sort();
        let suggestions = closest(&full, candidates, 3);
        self.errors.push(ModelError::UnknownConnector {
            connection: text(),
            name: full,
            suggestions,
        });
        None
    }
}
