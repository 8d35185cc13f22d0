//! Texts of equations for messages, rendered only when a message needs them.
//!
//! A model of a few hundred equations would otherwise spend most of its translation
//! time printing expressions nobody reads.

use std::fmt;
use std::sync::Arc;

use super::flatten::{FlatEquation, FlatSystem};
use super::variable::Variable;
use crate::expr::ExprStore;

/// A flat system's equations and the variables their origins refer to by index,
/// shared by the texts of all its equations (one allocation for the whole system
/// instead of one per equation).
#[derive(Debug)]
pub struct FlatOrigins {
    equations: Vec<FlatEquation>,
    variables: Arc<Vec<Variable>>,
    /// The stores of the expressions the origins print.
    _stores: Vec<ExprStore>,
}

impl FlatOrigins {
    /// The equations of a flat system whose variables are `variables` and whose
    /// expressions live in `stores`.
    pub fn new(
        equations: Vec<FlatEquation>,
        variables: Arc<Vec<Variable>>,
        stores: Vec<ExprStore>,
    ) -> Arc<Self> {
        Arc::new(FlatOrigins {
            equations,
            variables,
            _stores: stores,
        })
    }

    /// The equations.
    pub fn equations(&self) -> &[FlatEquation] {
        &self.equations
    }
}

#[derive(Debug)]
enum Kind {
    /// The time derivative of another equation.
    Derivative(EquationText),
    /// Written out already.
    Plain(String),
}

#[derive(Clone, Debug)]
enum Repr {
    /// Equation `k` of a flat system.
    Flat(Arc<FlatOrigins>, u32),
    Other(Arc<Kind>),
}

/// How an equation reads in messages (`j1: w = der(phi)`, `d/dt[...]`); cheap to clone
/// and rendered by `Display`.
#[derive(Clone, Debug)]
pub struct EquationText(Repr);

impl EquationText {
    /// The text of equation `k` of a flat system.
    ///
    /// # Panics
    /// If `k` is not an equation of `origins`.
    pub fn of(origins: &Arc<FlatOrigins>, k: usize) -> Self {
        assert!(
            k < origins.equations.len(),
            "EquationText::of: no equation {k}"
        );
        EquationText(Repr::Flat(origins.clone(), k as u32))
    }

    /// A text written out already.
    pub fn plain(text: String) -> Self {
        EquationText(Repr::Other(Arc::new(Kind::Plain(text))))
    }

    /// The text of this equation's time derivative.
    pub fn derivative(&self) -> Self {
        EquationText(Repr::Other(Arc::new(Kind::Derivative(self.clone()))))
    }
}

impl fmt::Display for EquationText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0 {
            Repr::Flat(o, k) => f.write_str(&FlatSystem::describe_origin(
                &o.variables,
                &o.equations[*k as usize].origin,
            )),
            Repr::Other(kind) => match &**kind {
                Kind::Derivative(inner) => write!(f, "d/dt[{inner}]"),
                Kind::Plain(text) => f.write_str(text),
            },
        }
    }
}
