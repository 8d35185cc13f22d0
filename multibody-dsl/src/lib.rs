//! The logic behind multibody's procedural macros: parse, check, expand.
//!
//! Each entry point takes the macro's input tokens and returns the expansion, or a
//! `compile_error!` pointing at the offending tokens. `multibody-macros` is a thin shim
//! over these functions; the unit tests here call them directly.
//!
//! * [`component`]: a component type: parameters (struct fields with defaults and
//!   docs), structural parameters, connectors, variables, sub-components, `extends`, and
//!   equations written like `der(phi) = w;` and `connect(a.x, b.y);`.
//! * [`connector`]: a connector type with potential, flow or signal variables.
//! * [`system`]: a model of named instances and `connect(...)` lines.

pub mod ast;
pub mod check;
pub mod equations;
pub mod expand;
pub mod parse;

use proc_macro2::TokenStream;

/// Expands `component! { ... }`.
pub fn component(input: TokenStream) -> TokenStream {
    syn::parse2::<ast::ComponentDef>(input)
        .and_then(|d| {
            check::check_component(&d)?;
            expand::component(&d)
        })
        .unwrap_or_else(|e| e.to_compile_error())
}

/// Expands `connector! { ... }`.
pub fn connector(input: TokenStream) -> TokenStream {
    syn::parse2::<ast::ConnectorDef>(input)
        .and_then(|d| {
            check::check_connector(&d)?;
            expand::connector(&d)
        })
        .unwrap_or_else(|e| e.to_compile_error())
}

/// Expands `system! { ... }`.
pub fn system(input: TokenStream) -> TokenStream {
    syn::parse2::<ast::SystemDef>(input)
        .and_then(|d| expand::system(&d))
        .unwrap_or_else(|e| e.to_compile_error())
}

#[cfg(test)]
mod tests;
