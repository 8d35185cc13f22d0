//! The parsed forms of `component!`, `connector!` and `system!` inputs.

use syn::{Attribute, Expr, Ident, LitStr, Path, Stmt, Type, Visibility};

/// `key = value` in a declaration's parentheses: `(start = 0.0, fixed = true)`.
#[derive(Clone)]
pub struct Modifier {
    /// The attribute set.
    pub key: Ident,
    /// Its value (a Rust expression).
    pub value: Expr,
}

/// One declaration inside `component! { struct X { ... } }`.
#[derive(Clone)]
pub enum Item {
    /// `parameter J: f64 (modifiers) = 1.0;`: a tunable parameter and a struct field.
    Parameter {
        /// Doc comments.
        docs: Vec<Attribute>,
        /// Name.
        name: Ident,
        /// Rust type of the value (`f64`).
        ty: Type,
        /// Attributes (`fixed`, `unit`).
        modifiers: Vec<Modifier>,
        /// Default value.
        default: Expr,
    },
    /// `structural n: [f64; 3] = [0.0, 0.0, 1.0];`: a struct field folded in at build
    /// time.
    Structural {
        /// Doc comments.
        docs: Vec<Attribute>,
        /// Name.
        name: Ident,
        /// Rust type.
        ty: Type,
        /// Default value.
        default: Expr,
    },
    /// `connector flange_a: Flange;`, or `connector y(start = y_start): RealOutput;` for a
    /// signal connector whose value has a start.
    Connector {
        /// Doc comments.
        docs: Vec<Attribute>,
        /// Name.
        name: Ident,
        /// The connector type.
        ty: Path,
        /// Attributes of a signal connector's value (only `start`).
        modifiers: Vec<Modifier>,
    },
    /// `variable phi: Real (start = 0.0);`
    Variable {
        /// Doc comments (the description).
        docs: Vec<Attribute>,
        /// Name.
        name: Ident,
        /// The variable type (`Real`, `Vec3`).
        ty: Type,
        /// Attributes (`start`, `fixed`, `guess`, `state_priority`, `state_select`,
        /// `unit`).
        modifiers: Vec<Modifier>,
    },
    /// `component emf: EMF = EMF { k: 2.0 };` (the value defaults to `EMF::default()`).
    Component {
        /// Doc comments.
        docs: Vec<Attribute>,
        /// Name.
        name: Ident,
        /// The component type.
        ty: Path,
        /// Its value.
        value: Option<Expr>,
    },
    /// `extends PartialCompliant { flange_a, flange_b } = PartialCompliant::default();`
    Extends {
        /// The base component type.
        ty: Path,
        /// Members brought into scope by name.
        names: Vec<Ident>,
        /// The base's value (defaults to `Default::default()`).
        value: Option<Expr>,
    },
    /// `equation { ... }` or `initial_equation { ... }`.
    Equations {
        /// Whether these are initial equations.
        initial: bool,
        /// The statements.
        body: Vec<Stmt>,
        /// The section keyword (for spans).
        keyword: Ident,
    },
}

impl Item {
    /// The declared name, for declarations that have one.
    pub fn name(&self) -> Option<&Ident> {
        match self {
            Item::Parameter { name, .. }
            | Item::Structural { name, .. }
            | Item::Connector { name, .. }
            | Item::Variable { name, .. }
            | Item::Component { name, .. } => Some(name),
            Item::Extends { .. } | Item::Equations { .. } => None,
        }
    }
}

/// `component! { /// docs  pub struct Name { items } }`
#[derive(Clone)]
pub struct ComponentDef {
    /// Attributes of the struct (doc comments, derives are added).
    pub attrs: Vec<Attribute>,
    /// `#[type_name = "..."]`, the name in messages (defaults to the struct name).
    pub type_name: Option<LitStr>,
    /// Visibility.
    pub vis: Visibility,
    /// The struct name.
    pub name: Ident,
    /// Declarations and equations.
    pub items: Vec<Item>,
}

/// The role of a connector variable.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum ConnectorRole {
    /// Equal across a connection.
    Potential,
    /// Sums to zero across a connection.
    Flow,
    /// A causal input signal.
    Input,
    /// A causal output signal.
    Output,
    /// An overdetermined group (a frame's orientation): related through the virtual
    /// connection graph.
    Overdetermined,
}

/// A variable of a connector.
#[derive(Clone)]
pub struct ConnectorVar {
    /// Doc comments.
    pub docs: Vec<Attribute>,
    /// Its role.
    pub role: ConnectorRole,
    /// Name.
    pub name: Ident,
    /// Type (`Real`, `Vec3`).
    pub ty: Type,
}

/// `connector! { pub struct Flange { potential phi: Real; flow tau: Real; } }` or a
/// signal connector `connector! { pub struct RealInput = input Real; }`.
#[derive(Clone)]
pub struct ConnectorDef {
    /// Attributes (doc comments).
    pub attrs: Vec<Attribute>,
    /// Visibility.
    pub vis: Visibility,
    /// The struct name.
    pub name: Ident,
    /// The variables (for a signal connector: one, unnamed).
    pub vars: Vec<ConnectorVar>,
    /// For a signal connector: its role and the signal type's name (the connection
    /// class).
    pub signal: Option<(ConnectorRole, Ident)>,
}

/// One statement of `system! { ... }`.
#[derive(Clone)]
pub enum SystemItem {
    /// `j1 = Revolute { n: [1.0, 0.0, 0.0] };`
    Instance {
        /// Instance name.
        name: Ident,
        /// The component type, when written (`b: BodyShape = shape(0.5);`).
        ty: Option<syn::Type>,
        /// The component value.
        value: Expr,
    },
    /// `connect(a.x, b.y);`
    Connect {
        /// First connector.
        a: Expr,
        /// Second connector.
        b: Expr,
    },
    /// `equation lhs = rhs;` or `initial_equation lhs = rhs;`
    Equation {
        /// Initial equation?
        initial: bool,
        /// Left side.
        lhs: Expr,
        /// Right side.
        rhs: Expr,
    },
}

/// `system! { name: "m"; items }`, or a function that builds the model:
/// `system! { pub fn fourbar(d: f64) -> FourBar { items } }`.
#[derive(Clone)]
pub struct SystemDef {
    /// The function form's attributes, visibility and signature (its return type names
    /// the handles struct).
    pub function: Option<SystemFn>,
    /// The model name (default: the function's name, else `model`).
    pub name: Option<LitStr>,
    /// The statements.
    pub items: Vec<SystemItem>,
}

/// The function around a `system!` in its function form.
#[derive(Clone)]
pub struct SystemFn {
    /// Doc comments and other attributes.
    pub attrs: Vec<syn::Attribute>,
    /// Visibility of the function and of the handles struct.
    pub vis: syn::Visibility,
    /// The signature; its return type is the name of the handles struct.
    pub sig: syn::Signature,
    /// The handles struct's name.
    pub handles: Ident,
}
