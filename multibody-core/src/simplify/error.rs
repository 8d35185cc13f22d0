//! Errors of structural simplification.

/// What structural simplification found wrong with a model. Equations are quoted as
/// written (with the component's path), variables by their full paths.
#[derive(Debug, Clone, thiserror::Error, PartialEq)]
pub enum SimplifyError {
    /// No assignment of equations to unknowns exists, even after differentiation.
    #[error("{}", singular_message(.model, .equations, .overdetermined, .undetermined, .hint))]
    StructurallySingular {
        /// Model name.
        model: String,
        /// Equations of the over-determined part (more equations than they determine).
        equations: Vec<String>,
        /// Unknowns these equations determine more than once.
        overdetermined: Vec<String>,
        /// Unknowns no equation determines.
        undetermined: Vec<String>,
        /// What this means for the model, when known.
        hint: Option<String>,
    },
    /// A closed kinematic loop whose revolute joints all have parallel axes: the
    /// constraint forces along the axes (and the torques across them) cannot be
    /// determined, so the loop's equations are structurally singular.
    #[error(
        "model `{model}`: the kinematic loop through {} is planar (the axes of its revolute \
         joints are parallel): the cut forces along the axes cannot be computed. Replace one \
         revolute joint of the loop by RevolutePlanarLoopConstraint, or simplify with \
         `SimplifyOptions {{ planar_loops: PlanarLoops::RemoveRedundant, .. }}` to remove the \
         redundant constraints automatically",
        .joints.iter().map(|j| format!("`{j}`")).collect::<Vec<_>>().join(", ")
    )]
    PlanarLoop {
        /// Model name.
        model: String,
        /// The loop's joints, by full path, in loop order.
        joints: Vec<String>,
    },
    /// State selection could not honour a hard requirement.
    #[error("model `{model}`: {message}")]
    StateSelection {
        /// Model name.
        model: String,
        /// What went wrong.
        message: String,
    },
    /// Index reduction has to differentiate an equation that reads an input of the
    /// model, whose derivative is not known (an input given as a function of time).
    #[error(
        "model `{model}`: index reduction has to differentiate `{equation}`, which reads the \
         input `{input}`, but an input's derivative is not known. Let the input drive a force \
         or a torque rather than a position or a speed, or pass it through a filter whose \
         states give its derivatives (blocks::CriticalDamping) and make the filter's input \
         the model's input"
    )]
    DifferentiatedInput {
        /// Model name.
        model: String,
        /// The input, by full path.
        input: String,
        /// The equation index reduction differentiates.
        equation: String,
    },
    /// Code generation failed (an internal error: please report it).
    #[error("model `{model}`: code generation failed: {message}")]
    Codegen {
        /// Model name.
        model: String,
        /// The code generator's message.
        message: String,
    },
}

impl SimplifyError {
    /// A structural singularity without a hint.
    pub fn singular(
        model: &str,
        equations: Vec<String>,
        overdetermined: Vec<String>,
        undetermined: Vec<String>,
    ) -> Self {
        SimplifyError::StructurallySingular {
            model: model.to_string(),
            equations,
            overdetermined,
            undetermined,
            hint: None,
        }
    }
}

fn singular_message(
    model: &str,
    equations: &[String],
    overdetermined: &[String],
    undetermined: &[String],
    hint: &Option<String>,
) -> String {
    let mut m = format!("model `{model}` is structurally singular");
    if !undetermined.is_empty() {
        m.push_str(&format!(
            "\n  no equation determines {}",
            crate::names::list(undetermined, 16)
        ));
    }
    if !overdetermined.is_empty() {
        m.push_str(&format!(
            "\n  determined more than once: {}",
            crate::names::list(overdetermined, 16)
        ));
    }
    if !equations.is_empty() {
        m.push_str("\n  by the equations:");
        for e in equations.iter().take(16) {
            m.push_str(&format!("\n    {e}"));
        }
        if equations.len() > 16 {
            m.push_str(&format!("\n    ... ({} more)", equations.len() - 16));
        }
    }
    if let Some(h) = hint {
        m.push_str(&format!("\n  {h}"));
    }
    m
}
