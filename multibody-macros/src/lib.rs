//! Procedural macros of `multibody`: thin shims over `multibody-dsl`, where the parsing,
//! checking and expansion live. See the `multibody` crate for the documentation of
//! [`component!`], [`connector!`] and [`system!`].

use proc_macro::TokenStream;

/// The macro is parsed, checked and expanded by `multibody-dsl`.
#[proc_macro]
pub fn component(input: TokenStream) -> TokenStream {
    multibody_dsl::component(input.into()).into()
}

/// The macro is parsed, checked and expanded by `multibody-dsl`.
#[proc_macro]
pub fn connector(input: TokenStream) -> TokenStream {
    multibody_dsl::connector(input.into()).into()
}

/// The macro is parsed, checked and expanded by `multibody-dsl`.
#[proc_macro]
pub fn system(input: TokenStream) -> TokenStream {
    multibody_dsl::system(input.into()).into()
}
