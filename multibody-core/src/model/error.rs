//! Errors found while flattening a model.

/// A problem with the model's declarations or connections, naming everything by its full
/// path.
#[derive(Debug, Clone, thiserror::Error, PartialEq)]
pub enum ModelError {
    /// An equation refers to a variable or parameter that is not declared.
    #[error("unknown {what} `{name}` in {place}{}", suggest(.suggestions))]
    UnknownName {
        /// "variable" or "parameter".
        what: &'static str,
        /// The full name used.
        name: String,
        /// Where it was used (an equation's text).
        place: String,
        /// Declared names close to it.
        suggestions: Vec<String>,
    },
    /// Two declarations share a full name.
    #[error("`{0}` is declared twice")]
    DuplicateName(String),
    /// `connect()` names something that is not a connector.
    #[error("in `{connection}`: `{name}` is not a connector{}", suggest(.suggestions))]
    UnknownConnector {
        /// The connect statement as written, with the system's path.
        connection: String,
        /// The full name that was not found.
        name: String,
        /// Connectors close to it.
        suggestions: Vec<String>,
    },
    /// `connect()` joins connectors of different classes.
    #[error("in `{connection}`: cannot connect `{a}` ({class_a}) with `{b}` ({class_b})")]
    IncompatibleConnectors {
        /// The connect statement.
        connection: String,
        /// First connector.
        a: String,
        /// Its class.
        class_a: String,
        /// Second connector.
        b: String,
        /// Its class.
        class_b: String,
    },
    /// `connect()` joins two outputs: both would determine the same signal.
    #[error(
        "in `{connection}`: `{a}` and `{b}` are both outputs, and an output is the only \
         thing that determines its signal: connect an output to inputs"
    )]
    TwoOutputs {
        /// The connect statement.
        connection: String,
        /// First output.
        a: String,
        /// Second output.
        b: String,
    },
    /// The virtual connection graph of overdetermined connectors (orientations) is
    /// wrong: two roots in one mechanism, a part with no root, a loop of rigid branches.
    #[error("{message}")]
    Graph {
        /// What is wrong, naming the frames and components.
        message: String,
    },
    /// A component was built with structural parameters it does not accept (a zero
    /// axis, a NaN length, an axis sequence with a repeated axis).
    #[error("{type_name} `{component}`: {message}")]
    InvalidComponent {
        /// The component's path.
        component: String,
        /// Its type.
        type_name: String,
        /// What is wrong, naming the parameter and its value.
        message: String,
    },
    /// Components refer to an instance by a name that the model does not declare at its
    /// top (Modelica's `inner`: bodies and joints read gravity from `world`).
    #[error(
        "model `{model}` has no instance `{name}` ({type_name}), which its components \
         refer to by that name{}",
        found_inner(.name, .found)
    )]
    MissingInner {
        /// The model.
        model: String,
        /// The name the components use.
        name: String,
        /// The type it must have.
        type_name: String,
        /// Instances of that type under other names.
        found: Vec<String>,
    },
    /// An assertion of a component refers to variables: only conditions on parameters
    /// are supported.
    #[error(
        "{component}: the assertion `{condition}` refers to variables; only conditions on parameters are checked"
    )]
    AssertionOnVariables {
        /// The component's path.
        component: String,
        /// The condition as written.
        condition: String,
    },
    /// A `when` clause or `reinit` that cannot be what it says.
    #[error("{component}: {message}")]
    InvalidWhen {
        /// The component's path.
        component: String,
        /// What is wrong.
        message: String,
    },
    /// An expression of the model was built for another model that no longer exists.
    #[error("{place}: uses an expression of a model that was dropped")]
    DroppedExpression {
        /// Where it is used (an equation's text).
        place: String,
    },
    /// A variable named as an input of the model that cannot be one.
    #[error("input `{name}` {message}")]
    InvalidInput {
        /// The variable's full path.
        name: String,
        /// Why it cannot be an input.
        message: String,
    },
    /// A parameter has no value and is not computed at initialization.
    #[error("parameter `{0}` has no value")]
    ParameterWithoutValue(String),
    /// As many equations as unknowns are needed.
    #[error("{}", unbalanced_message(.model, .equations, .unknowns, .undetermined, .overdetermined, .unconnected_inputs))]
    Unbalanced {
        /// Model name.
        model: String,
        /// Number of equations.
        equations: usize,
        /// Number of unknowns.
        unknowns: usize,
        /// Unknowns that no equation can determine (full paths).
        undetermined: Vec<String>,
        /// Equations with nothing left to determine (as text).
        overdetermined: Vec<String>,
        /// Input signals connected to nothing (when equations are missing).
        unconnected_inputs: Vec<String>,
    },
}

fn suggest(s: &[String]) -> String {
    if s.is_empty() {
        String::new()
    } else {
        format!(
            " (did you mean {}?)",
            s.iter()
                .map(|x| format!("`{x}`"))
                .collect::<Vec<_>>()
                .join(", ")
        )
    }
}

fn unbalanced_message(
    model: &str,
    equations: &usize,
    unknowns: &usize,
    under: &[String],
    over: &[String],
    inputs: &[String],
) -> String {
    let mut m =
        format!("model `{model}` is not balanced: {equations} equations for {unknowns} unknowns");
    if !inputs.is_empty() {
        m.push_str(&format!(
            "\n  inputs connected to nothing: {} (connect an output to each, give it an \
             equation, or make it an input of the model: SimplifyOptions::inputs or \
             open_inputs)",
            crate::names::list(inputs, 12)
        ));
    }
    if !under.is_empty() {
        m.push_str(&format!(
            "\n  under-determined: no equation is left for {}",
            crate::names::list(under, 12)
        ));
    }
    if !over.is_empty() {
        m.push_str(&format!(
            "\n  over-determined: nothing is left to determine in {}",
            crate::names::list(over, 12)
        ));
    }
    m
}

/// `: add one` or `; rename `w` to `world``, for [`ModelError::MissingInner`].
fn found_inner(name: &str, found: &[String]) -> String {
    match found {
        [] => format!(": add one named `{name}`"),
        [one] => format!("; the model has one named `{one}`: name it `{name}`"),
        many => format!(
            "; the model has {} named {}: name one `{name}`",
            many.len(),
            many.iter()
                .map(|f| format!("`{f}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}
