//! Declarations of unknowns and parameters.

use crate::expr::Expr;

use super::SharedText;

/// What a variable is to connections.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VarKind {
    /// An ordinary unknown of a component.
    Internal,
    /// A potential (across) variable of a connector: equal in a connection set.
    Potential,
    /// A flow (through) variable of a connector: sums to zero in a connection set.
    Flow,
    /// A causal input signal of a connector: equal to the output it is connected to.
    Input,
    /// A causal output signal of a connector.
    Output,
    /// A variable of an overdetermined group (an orientation in a frame): connections
    /// relate it through the virtual connection graph, not by plain equality.
    Overdetermined,
}

/// Modelica's `StateSelect`, mapped onto [`Variable::state_priority`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StateSelect {
    /// Never a state (priority -100).
    Never,
    /// Avoid as a state (priority -1).
    Avoid,
    /// No preference (priority 0).
    Default,
    /// Prefer as a state (priority 10).
    Prefer,
    /// Must be a state (priority 1000, a hard requirement).
    Always,
}

impl StateSelect {
    /// The state priority this choice stands for.
    pub fn priority(self) -> f64 {
        match self {
            StateSelect::Never => -100.0,
            StateSelect::Avoid => -1.0,
            StateSelect::Default => 0.0,
            StateSelect::Prefer => 10.0,
            StateSelect::Always => 1000.0,
        }
    }
}

/// An unknown of the model.
#[derive(Clone, Debug)]
pub struct Variable {
    /// Full path, e.g. `motor.inertia.phi` (local until declared in a system, which
    /// replaces it by the full path as the symbol table keeps it: a `&'static str`).
    pub name: SharedText,
    /// Start value (a constant or an expression of parameters); default: none (0).
    pub start: Option<Expr>,
    /// Whether the start value must hold at the initial time (default: false, so the
    /// start value is only a guess).
    pub fixed: bool,
    /// Initial guess for iterations, when different from the start value (default: none).
    pub guess: Option<f64>,
    /// Description for documentation and messages (default: empty).
    pub description: SharedText,
    /// Unit, e.g. `rad` (default: empty).
    pub unit: SharedText,
    /// Preference for being chosen as a state: higher stays a state (default 0).
    pub state_priority: f64,
    /// Role in connections (default: [`VarKind::Internal`]).
    pub kind: VarKind,
    /// Whether it is a discrete variable (Modelica's `discrete`, `Boolean`, `Integer`;
    /// default: false): constant between events. One that no `when` clause assigns is
    /// defined by an equation `v = expr`, evaluated at every event (see
    /// [`System::when`](crate::model::System::when)).
    pub discrete: bool,
    /// The interned symbol of `name`, recorded when declared in a system.
    pub(crate) symbol: Option<u32>,
}

impl Variable {
    /// An internal unknown with no start value.
    pub fn new(name: impl Into<SharedText>) -> Self {
        Variable {
            name: name.into(),
            start: None,
            fixed: false,
            guess: None,
            description: SharedText::default(),
            unit: SharedText::default(),
            state_priority: 0.0,
            kind: VarKind::Internal,
            discrete: false,
            symbol: None,
        }
    }

    /// Sets the start value.
    pub fn start(mut self, value: impl Into<Expr>) -> Self {
        self.start = Some(value.into());
        self
    }

    /// Sets whether the start value is fixed.
    pub fn fixed(mut self, fixed: bool) -> Self {
        self.fixed = fixed;
        self
    }

    /// Sets the iteration guess.
    pub fn guess(mut self, value: f64) -> Self {
        self.guess = Some(value);
        self
    }

    /// Sets the description.
    pub fn description(mut self, text: impl Into<SharedText>) -> Self {
        self.description = text.into();
        self
    }

    /// Sets the unit.
    pub fn unit(mut self, unit: impl Into<SharedText>) -> Self {
        self.unit = unit.into();
        self
    }

    /// Sets the state priority.
    pub fn state_priority(mut self, p: f64) -> Self {
        self.state_priority = p;
        self
    }

    /// Sets the state priority from a Modelica `StateSelect`.
    pub fn state_select(mut self, s: StateSelect) -> Self {
        self.state_priority = s.priority();
        self
    }

    /// Declares it discrete (see [`Variable::discrete`]).
    pub fn discrete(mut self, discrete: bool) -> Self {
        self.discrete = discrete;
        self
    }

    /// Sets the connection role.
    pub fn kind(mut self, kind: VarKind) -> Self {
        self.kind = kind;
        self
    }
}

/// A tunable parameter: a value of the compiled problem, changeable without
/// recompiling. (Structural parameters are plain Rust values folded in when the
/// component is built.)
#[derive(Clone, Debug)]
pub struct Parameter {
    /// Full path, e.g. `motor.R` (local until declared, as [`Variable::name`]).
    pub name: SharedText,
    /// Default value or binding expression of other parameters (default: none, which is
    /// an error unless the parameter is computed at initialization).
    pub value: Option<Expr>,
    /// `false` means the parameter is computed during initialization (MSL
    /// `fixed=false`), its value only a guess (default: true).
    pub fixed: bool,
    /// Description (default: empty).
    pub description: SharedText,
    /// Unit (default: empty).
    pub unit: SharedText,
    /// `true` folds the value into the equations at `structural_simplify` (MSL
    /// `Evaluate=true`): zero offsets and switches then vanish from the compiled code,
    /// and the parameter can no longer be changed without simplifying again
    /// (default: false).
    pub evaluate: bool,
    /// Smallest value the parameter accepts (Modelica's `min`; default: -infinity). A
    /// problem with a smaller value is rejected, naming the parameter.
    pub min: f64,
    /// Largest value the parameter accepts (Modelica's `max`; default: infinity).
    pub max: f64,
    /// The interned symbol of `name`, recorded when declared in a system.
    pub(crate) symbol: Option<u32>,
}

impl Parameter {
    /// A parameter with a default value.
    pub fn new(name: impl Into<SharedText>, value: impl Into<Expr>) -> Self {
        Parameter {
            name: name.into(),
            value: Some(value.into()),
            fixed: true,
            description: SharedText::default(),
            unit: SharedText::default(),
            evaluate: false,
            min: f64::NEG_INFINITY,
            max: f64::INFINITY,
            symbol: None,
        }
    }

    /// Sets the smallest accepted value.
    pub fn min(mut self, min: f64) -> Self {
        self.min = min;
        self
    }

    /// Sets the largest accepted value.
    pub fn max(mut self, max: f64) -> Self {
        self.max = max;
        self
    }

    /// Sets whether the value is folded in at `structural_simplify` (see
    /// [`Parameter::evaluate`](struct@Parameter)).
    pub fn evaluate(mut self, evaluate: bool) -> Self {
        self.evaluate = evaluate;
        self
    }

    /// Sets whether the parameter is fixed (false: computed at initialization).
    pub fn fixed(mut self, fixed: bool) -> Self {
        self.fixed = fixed;
        self
    }

    /// Sets the description.
    pub fn description(mut self, text: impl Into<SharedText>) -> Self {
        self.description = text.into();
        self
    }

    /// Sets the unit.
    pub fn unit(mut self, unit: impl Into<SharedText>) -> Self {
        self.unit = unit.into();
        self
    }
}
