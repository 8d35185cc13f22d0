//! Models: variables, parameters, systems, connectors, `connect`, flattening and the
//! balance check.

mod balance;
mod connection_graph;
mod error;
mod flatten;
mod named;
mod overdetermined;
mod path_index;
mod shared_text;
mod system;
mod text;
mod typed;
mod variable;
mod vector;

pub(crate) use balance::unconnected_input_variables;
pub use balance::{check_balance, evaluate_bindings};
pub use error::ModelError;
pub use flatten::{
    FlatAssertion, FlatEquation, FlatNames, FlatSystem, FlatWhen, GraphOrigin, Origin, flatten,
};
pub use named::{Named, names};
pub use overdetermined::{GraphDecl, GraphNode, OverdeterminedGroup, OverdeterminedType};
pub use shared_text::SharedText;
pub use system::{
    Assertion, Checks, Component, Condition, Connection, Equation, StructuralValue, System,
    WhenClause, join_path, show_values,
};
pub use text::{EquationText, FlatOrigins};
pub use typed::{
    Connector, ConnectorHandle, Equate, Model, ParameterType, PathId, Real, Signal, Signal3,
    TypedComponent, VariableType, declare_signal, declare_signal3, member, signal_at, signal3_at,
};
pub use variable::{Parameter, StateSelect, VarKind, Variable};

#[cfg(test)]
mod tests;
