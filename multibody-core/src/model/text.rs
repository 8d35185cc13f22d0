//! Texts of equations for messages, rendered only when a message needs them.
//!
//! A model of a few hundred equations would otherwise spend most of its translation
//! time printing expressions nobody reads.

use std::fmt;
use std::sync::Arc;

use super::flatten::{FlatSystem, Origin};

#[derive(Debug)]
enum Kind {
    /// A flat equation, by where it came from.
    Origin(Origin),
    /// The time derivative of another equation.
    Derivative(EquationText),
    /// Written out already.
    Plain(String),
}

/// How an equation reads in messages (`j1: w = der(phi)`, `d/dt[...]`); cheap to clone
/// and rendered by `Display`.
#[derive(Clone, Debug)]
pub struct EquationText(Arc<Kind>);

impl EquationText {
    /// The text of a flat equation.
    pub fn of(origin: &Origin) -> Self {
        EquationText(Arc::new(Kind::Origin(origin.clone())))
    }

    /// A text written out already.
    pub fn plain(text: String) -> Self {
        EquationText(Arc::new(Kind::Plain(text)))
    }

    /// The text of this equation's time derivative.
    pub fn derivative(&self) -> Self {
        EquationText(Arc::new(Kind::Derivative(self.clone())))
    }
}

impl fmt::Display for EquationText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &*self.0 {
            Kind::Origin(origin) => f.write_str(&FlatSystem::describe_origin(origin)),
            Kind::Derivative(inner) => write!(f, "d/dt[{inner}]"),
            Kind::Plain(text) => f.write_str(text),
        }
    }
}
