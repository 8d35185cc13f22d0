//! Errors of initialization, integration and solution access.

/// Consistent initial values could not be found.
#[derive(Debug, Clone, thiserror::Error, PartialEq)]
pub enum InitError {
    /// More conditions than unknowns at the initial time.
    #[error(
        "model `{model}`: the initialization is over-determined: these equations leave \
         nothing to determine:\n    {}",
        .equations.join("\n    ")
    )]
    OverDetermined {
        /// Model name.
        model: String,
        /// The conflicting equations (fixed start values appear as `fixed start value of x`).
        equations: Vec<String>,
    },
    /// Too few conditions even after fixing the start values of all states.
    #[error(
        "model `{model}`: the initialization is under-determined: nothing determines {}",
        crate::names::list(.variables, 16)
    )]
    UnderDetermined {
        /// Model name.
        model: String,
        /// Unknowns left undetermined.
        variables: Vec<String>,
    },
    /// Newton's method did not converge.
    #[error("{}", newton_message(.model, .iterations, .reason, .residuals, .variables, .conditions))]
    NotConverged {
        /// Model name.
        model: String,
        /// Iterations made.
        iterations: usize,
        /// Why Newton stopped (a singular Jacobian, the iteration limit).
        reason: String,
        /// The equations with the largest residuals, with their residual values.
        residuals: Vec<(String, f64)>,
        /// The iteration variables with their last values.
        variables: Vec<(String, f64)>,
        /// The initial conditions in force: fixed start values and assumed ones.
        conditions: Vec<(String, f64)>,
    },
    /// A fixed start value contradicts a value the model determines alone.
    #[error(
        "model `{model}`: the fixed start value {start} of `{variable}` contradicts its \
         value {value} in the model"
    )]
    Inconsistent {
        /// Model name.
        model: String,
        /// The variable.
        variable: String,
        /// Its fixed start value.
        start: f64,
        /// The value the model gives it.
        value: f64,
    },
    /// A name given to the problem is neither a variable nor a parameter.
    #[error("model `{model}` has no variable or parameter `{name}`{}", suggest(.suggestions))]
    UnknownName {
        /// Model name.
        model: String,
        /// The name given.
        name: String,
        /// Names close to it.
        suggestions: Vec<String>,
    },
    /// A name given to the problem is a structural parameter, fixed when the model was
    /// built.
    #[error(
        "model `{model}`: `{name}` is a structural parameter, fixed when the model was \
         built: give it in the component's value and simplify the model again"
    )]
    StructuralParameter {
        /// Model name.
        model: String,
        /// The name given.
        name: String,
    },
    /// A component's condition on its parameters does not hold for the problem's
    /// values.
    #[error("model `{model}`: {type_name} `{component}`: {message} ({values})")]
    AssertionFailed {
        /// Model name.
        model: String,
        /// The component's path.
        component: String,
        /// Its type.
        type_name: String,
        /// What is wrong.
        message: String,
        /// The parameters of the condition with their values (`m = -1`).
        values: String,
    },
    /// A parameter value or start value could not be evaluated.
    #[error("model `{model}`: {message}")]
    BadValue {
        /// Model name.
        model: String,
        /// What is wrong.
        message: String,
    },
}

fn newton_message(
    model: &str,
    iterations: &usize,
    reason: &str,
    residuals: &[(String, f64)],
    variables: &[(String, f64)],
    conditions: &[(String, f64)],
) -> String {
    let mut m = format!(
        "model `{model}`: initialization did not converge after {iterations} Newton iterations ({reason})"
    );
    if !conditions.is_empty() {
        m.push_str(&format!(
            "\n  initial conditions in force: {}",
            conditions
                .iter()
                .take(12)
                .map(|(n, v)| format!("{n} = {v}"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    if !residuals.is_empty() {
        m.push_str("\n  largest residuals:");
        for (e, r) in residuals {
            m.push_str(&format!("\n    {r:.3e} in {e}"));
        }
    }
    if !variables.is_empty() {
        m.push_str(&format!(
            "\n  iteration variables (last values): {}",
            variables
                .iter()
                .map(|(n, v)| format!("{n} = {v:.6}"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
        let mut components: Vec<&str> = variables
            .iter()
            .map(|(n, _)| n.rsplit_once('.').map_or(n.as_str(), |(path, _)| path))
            .collect();
        components.dedup();
        m.push_str(&format!(
            "\n  the coordinates of {} did not converge: give start values closer to a \
             consistent configuration for them as guesses \
             (DaeProblem::new_with_guesses(&ssys, values, &[(\"{}\", ...)], tspan)), or check \
             that the fixed values leave the mechanism a configuration at all",
            components
                .iter()
                .map(|c| format!("`{c}`"))
                .collect::<Vec<_>>()
                .join(", "),
            variables[0].0
        ));
    }
    m
}

pub(crate) fn suggest(s: &[String]) -> String {
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

/// The integrator failed.
#[derive(Debug, Clone, thiserror::Error, PartialEq)]
#[error("model `{model}`: the solver failed at t = {}: {message}", crate::names::number(*.t))]
pub struct SolveError {
    /// Model name.
    pub model: String,
    /// The time reached.
    pub t: f64,
    /// IDA's return flag (`IDA_CONV_FAIL`, ...), `MAX_POINTS` (more reported points
    /// than allowed), `BAD_OPTION` (an option that cannot be used), `EVENT_ITERATION`
    /// (the relations do not settle at an event), `EVENT_ACCUMULATION` (events
    /// accumulate: Zeno behaviour) or `WHEN` (a `when` clause's expression cannot be
    /// evaluated).
    pub flag: String,
    /// What went wrong, in words.
    pub message: String,
}

/// A solution was asked for something it does not have.
#[derive(Debug, Clone, thiserror::Error, PartialEq)]
pub enum SolutionError {
    /// No parameter of that name.
    #[error("the solution has no parameter `{name}`{}", suggest(.suggestions))]
    UnknownParameter {
        /// The name asked for.
        name: String,
        /// Names close to it.
        suggestions: Vec<String>,
    },
    /// No variable of that name.
    #[error("the solution has no variable `{name}`{}", suggest(.suggestions))]
    UnknownVariable {
        /// The name asked for.
        name: String,
        /// Names close to it.
        suggestions: Vec<String>,
    },
    /// A time outside the solved interval.
    #[error("t = {t} is outside the solved interval [{t0}, {t1}]")]
    OutOfRange {
        /// The time asked for.
        t: f64,
        /// Start of the interval.
        t0: f64,
        /// End of the interval.
        t1: f64,
    },
    /// A variable's value is not a number (NaN) or infinite at a time: the model
    /// computes nothing there (a square root of a negative number, a division by zero).
    #[error("`{name}` is {value} at t = {}{}", crate::names::number(*.t), reason.as_deref().map(|r| format!(" ({r})")).unwrap_or_default())]
    NotFinite {
        /// The variable.
        name: String,
        /// The time.
        t: f64,
        /// The value (NaN or infinite).
        value: f64,
        /// What failed in the computation, when known.
        reason: Option<String>,
    },
    /// Writing a file failed.
    #[error("cannot write `{path}`: {message}")]
    Io {
        /// The file.
        path: String,
        /// The I/O error.
        message: String,
    },
}
