//! Procedural macros of `multibody`: thin shims over `multibody-dsl`, where the parsing,
//! checking and expansion live. See the `multibody` crate for the documentation of
//! [`component!`], [`connector!`] and [`system!`].

use proc_macro::TokenStream;

/// Declares a component type: parameters, connectors, variables, sub-components and
/// equations. See `multibody::component!`.
#[proc_macro]
pub fn component(input: TokenStream) -> TokenStream {
    multibody_dsl::component(input.into()).into()
}

/// Declares a connector type. See `multibody::connector!`.
#[proc_macro]
pub fn connector(input: TokenStream) -> TokenStream {
    multibody_dsl::connector(input.into()).into()
}

/// Builds a model of named instances and connections. See `multibody::system!`.
#[proc_macro]
pub fn system(input: TokenStream) -> TokenStream {
    multibody_dsl::system(input.into()).into()
}
