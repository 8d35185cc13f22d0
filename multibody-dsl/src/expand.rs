//! Code generation: the builder calls and impls that the macros expand to.

use proc_macro2::TokenStream;
use quote::{format_ident, quote, quote_spanned};
use syn::spanned::Spanned;
use syn::{Attribute, Expr, Ident};

use crate::ast::*;
use crate::equations;

/// Where the generated code finds the library.
fn lib() -> TokenStream {
    quote!(::multibody::__private)
}

/// The unit a doc comment declares: its last bracketed token outside code spans, as
/// rustdoc docs write it (`Rotation angle \[rad\]`, `Torque \[N.m\]`); `None`
/// when there is none.
pub fn doc_unit(text: &str) -> Option<String> {
    let mut plain = String::with_capacity(text.len());
    let mut in_code = false;
    for c in text.chars() {
        match c {
            '`' => in_code = !in_code,
            '\\' => {}
            c if !in_code => plain.push(c),
            _ => {}
        }
    }
    let close = plain.rfind(']')?;
    let open = plain[..close].rfind('[')?;
    let unit = plain[open + 1..close].trim();
    let valid = !unit.is_empty()
        && unit.len() <= 24
        && unit
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "./-^%".contains(c));
    valid.then(|| unit.to_string())
}

/// `.unit("rad")` when the doc text declares a unit (see [`doc_unit`]).
fn unit_call(text: &str) -> TokenStream {
    match doc_unit(text) {
        Some(u) => quote!(.unit(#u)),
        None => TokenStream::new(),
    }
}

/// The text of doc comments, joined into one line.
pub fn doc_text(docs: &[Attribute]) -> String {
    let mut parts = Vec::new();
    for a in docs {
        if let syn::Meta::NameValue(nv) = &a.meta
            && let Expr::Lit(syn::ExprLit {
                lit: syn::Lit::Str(s),
                ..
            }) = &nv.value
        {
            let t = s.value();
            let t = t.trim();
            if !t.is_empty() {
                parts.push(t.to_string());
            }
        }
    }
    parts.join(" ")
}

/// Escapes unit brackets (`[kg.m2]`) so rustdoc does not read them as links; brackets
/// holding code (`` [`Flange`] ``) stay links.
pub fn escape_units(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let chars: Vec<char> = text.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        if chars[i] == '['
            && (i == 0 || (chars[i - 1] != '\\' && chars[i - 1] != ']'))
            && let Some(len) = chars[i + 1..].iter().position(|&c| c == ']')
        {
            {
                let inner: String = chars[i + 1..i + 1 + len].iter().collect();
                let followed_by_link = chars
                    .get(i + 2 + len)
                    .is_some_and(|&c| c == '(' || c == '[');
                if !inner.contains('`') && !followed_by_link && !inner.is_empty() {
                    out.push_str("\\[");
                    out.push_str(&inner);
                    out.push_str("\\]");
                    i += len + 2;
                    continue;
                }
            }
        }
        out.push(chars[i]);
        i += 1;
    }
    out
}

/// Doc attributes with unit brackets escaped.
fn docs_escaped(docs: &[Attribute]) -> TokenStream {
    let mut out = TokenStream::new();
    for a in docs {
        if let syn::Meta::NameValue(nv) = &a.meta
            && let Expr::Lit(syn::ExprLit {
                lit: syn::Lit::Str(s),
                ..
            }) = &nv.value
        {
            let t = escape_units(&s.value());
            out.extend(quote!(#[doc = #t]));
        } else {
            out.extend(quote!(#a));
        }
    }
    out
}

fn default_doc(default: &Expr) -> TokenStream {
    let text = format!(
        "Default: `{}`.",
        quote!(#default).to_string().replace(" . ", ".")
    );
    quote!(#[doc = ""] #[doc = #text])
}

/// Whether a variable's type is a 3-vector (`Vec3`), whose start is set per element.
fn is_vector_type(ty: &syn::Type) -> bool {
    matches!(ty, syn::Type::Path(p) if p.path.segments.last().is_some_and(|s| s.ident == "Vec3"))
}

fn variable_modifiers(mods: &[Modifier]) -> TokenStream {
    let mut out = TokenStream::new();
    for m in mods {
        let v = &m.value;
        let key = &m.key;
        // The builder method has the attribute's name.
        out.extend(quote_spanned!(key.span()=> .#key(#v)));
    }
    out
}

/// Expands `component!`.
pub fn component(def: &ComponentDef) -> syn::Result<TokenStream> {
    let p = lib();
    let name = &def.name;
    let vis = &def.vis;
    let attrs = &def.attrs;
    let handle = format_ident!("{}Handle", name);
    let type_name = match &def.type_name {
        Some(s) => s.value(),
        None => name.to_string(),
    };

    let mut fields = TokenStream::new();
    let mut defaults = TokenStream::new();
    let mut handle_fields = TokenStream::new();
    let mut handle_init = TokenStream::new();
    let mut build = TokenStream::new();
    let mut structural = TokenStream::new();
    let mut parameters = TokenStream::new();
    let mut bases = TokenStream::new();
    let mut connectors = TokenStream::new();
    let mut components = TokenStream::new();
    let mut variables = TokenStream::new();
    let mut equations = TokenStream::new();
    let mut deref = TokenStream::new();
    let mut n_bases = 0usize;
    let mut translator = equations::Translator::default();

    for item in &def.items {
        match item {
            Item::Parameter {
                docs,
                name: n,
                ty,
                modifiers,
                default,
            } => {
                let dd = default_doc(default);
                let desc = doc_text(docs);
                let docs = docs_escaped(docs);
                fields.extend(quote!(#docs #dd pub #n: #ty,));
                defaults.extend(quote!(#n: #default,));
                handle_fields.extend(quote!(#docs pub #n: <#ty as #p::ParameterType>::Symbolic,));
                let s = n.to_string();
                handle_init
                    .extend(quote!(#n: <#ty as #p::ParameterType>::at(&#p::member(path, #s)),));
                let mods = variable_modifiers(modifiers);
                let unit = unit_call(&desc);
                parameters.extend(quote!(
                    let #n = #p::ParameterType::declare(
                        &self.#n,
                        __s,
                        #p::Parameter::new(#s, 0.0).description(#desc) #unit #mods,
                    );
                ));
            }
            Item::Structural {
                docs,
                name: n,
                ty,
                default,
            } => {
                let dd = default_doc(default);
                let docs = docs_escaped(docs);
                fields.extend(quote!(#docs #dd pub #n: #ty,));
                defaults.extend(quote!(#n: #default,));
                structural.extend(quote!(let #n: #ty = ::core::clone::Clone::clone(&self.#n);));
                // Recorded as numbers when the type is a `StructuralValue` (autoref
                // specialization: other types record nothing).
                let s = n.to_string();
                structural.extend(quote!({
                    use #p::{RecordsNothing as _, RecordsNumbers as _};
                    __s.record_structural(#s, (&#p::Recorded(&#n)).numbers());
                }));
            }
            Item::Connector {
                docs,
                name: n,
                ty,
                modifiers,
            } => {
                let s = n.to_string();
                let docs = docs_escaped(docs);
                handle_fields.extend(quote!(#docs pub #n: <#ty as #p::Connector>::Handle,));
                handle_init
                    .extend(quote!(#n: <#ty as #p::Connector>::handle(&#p::member(path, #s)),));
                connectors.extend(quote!(
                    let #n = __s.add_connector(#s, &<#ty as ::core::default::Default>::default());
                ));
                for m in modifiers {
                    let v = &m.value;
                    connectors.extend(quote_spanned!(m.key.span()=>
                        const _: () = ::core::assert!(
                            <#ty as #p::Connector>::HAS_VALUE,
                            "`start` is only for a scalar signal connector (RealInput, RealOutput)"
                        );
                        __s.set_start(#s, #v);
                    ));
                }
            }
            Item::Variable {
                docs,
                name: n,
                ty,
                modifiers,
            } => {
                let s = n.to_string();
                let desc = doc_text(docs);
                // A vector's start may differ per element: set after the declaration
                // (`start = [a, b, c]`, or one value for all).
                let vector = is_vector_type(ty);
                let (element_starts, others): (Vec<Modifier>, Vec<Modifier>) = modifiers
                    .iter()
                    .cloned()
                    .partition(|m| vector && m.key == "start");
                let mods = variable_modifiers(&others);
                let docs = docs_escaped(docs);
                handle_fields.extend(quote!(#docs pub #n: #ty,));
                handle_init
                    .extend(quote!(#n: <#ty as #p::VariableType>::at(&#p::member(path, #s)),));
                let unit = unit_call(&desc);
                variables.extend(quote!(
                    let #n: #ty = __s.declare::<#ty>(
                        #p::Variable::new(#s).description(#desc) #unit #mods
                    );
                ));
                for m in element_starts {
                    let v = &m.value;
                    variables.extend(quote_spanned!(m.key.span()=>
                        if let Some(__v) = #p::VectorStart::elements(#v) {
                            for (__i, __v) in __v.into_iter().enumerate() {
                                __s.set_start(&::std::format!("{}[{}]", #s, __i + 1), __v);
                            }
                        }
                    ));
                }
            }
            Item::Component {
                docs,
                name: n,
                ty,
                value,
            } => {
                let s = n.to_string();
                let docs = docs_escaped(docs);
                handle_fields.extend(quote!(#docs pub #n: <#ty as #p::TypedComponent>::Handle,));
                handle_init.extend(
                    quote!(#n: <#ty as #p::TypedComponent>::handle(&#p::member(path, #s)),),
                );
                let v = match value {
                    Some(v) => quote!(#v),
                    None => quote!(<#ty as ::core::default::Default>::default()),
                };
                components.extend(quote!(
                    let #n: <#ty as #p::TypedComponent>::Handle = __s.add_typed(#s, &(#v));
                ));
            }
            Item::Extends { ty, names, value } => {
                let field = if n_bases == 0 {
                    format_ident!("base")
                } else {
                    format_ident!("base_{}", n_bases)
                };
                let local = format_ident!("__base{}", n_bases);
                let doc = format!(
                    "The `{}` part (extends).",
                    quote!(#ty).to_string().replace(' ', "")
                );
                handle_fields
                    .extend(quote!(#[doc = #doc] pub #field: <#ty as #p::TypedComponent>::Handle,));
                handle_init.extend(quote!(#field: <#ty as #p::TypedComponent>::handle(path),));
                let v = match value {
                    Some(v) => quote!(#v),
                    None => quote!(<#ty as ::core::default::Default>::default()),
                };
                bases.extend(quote!(let #local = __s.extend_typed(&(#v));));
                for m in names {
                    bases.extend(quote_spanned!(m.span()=>
                        let #m = ::core::clone::Clone::clone(&#local.#m);
                    ));
                }
                if n_bases == 0 {
                    deref = quote!(
                        impl ::core::ops::Deref for #handle {
                            type Target = <#ty as #p::TypedComponent>::Handle;
                            fn deref(&self) -> &Self::Target {
                                &self.base
                            }
                        }
                    );
                }
                n_bases += 1;
            }
            Item::Equations { initial, body, .. } => {
                equations.extend(translator.translate(body, *initial)?);
            }
        }
    }
    equations.extend(translator.finish());
    build.extend(structural);
    build.extend(parameters);
    build.extend(bases);
    build.extend(connectors);
    build.extend(components);
    build.extend(variables);
    let handle_doc = format!(
        "Handle of a [`{name}`] instance: its connectors, variables and parameters by name."
    );
    let attrs = docs_escaped(attrs);
    Ok(quote! {
        #attrs
        #[derive(Clone, Debug)]
        #[allow(non_snake_case)]
        #vis struct #name { #fields }

        impl ::core::default::Default for #name {
            fn default() -> Self {
                #name { #defaults }
            }
        }

        #[doc = #handle_doc]
        #[derive(Clone, Copy, Debug)]
        #[allow(non_snake_case)]
        #vis struct #handle {
            /// The instance's full path.
            pub path: #p::PathId,
            #handle_fields
        }

        #deref

        impl #p::TypedComponent for #name {
            type Handle = #handle;
            fn handle(path: &str) -> #handle {
                #handle { path: #p::PathId::new(path), #handle_init }
            }
        }

        impl #p::Component for #name {
            fn type_name(&self) -> ::std::string::String {
                ::std::string::String::from(#type_name)
            }
            #[allow(non_snake_case, unused_variables, unused_mut, clippy::all)]
            fn build(&self, __s: &mut #p::System) {
                #build
                let time = #p::Expr::time();
                {
                    #[allow(unused_imports)]
                    use #p::dsl::*;
                    #equations
                }
            }
        }
    })
}

fn role_tokens(role: ConnectorRole) -> TokenStream {
    let p = lib();
    match role {
        ConnectorRole::Potential => quote!(#p::VarKind::Potential),
        ConnectorRole::Flow => quote!(#p::VarKind::Flow),
        ConnectorRole::Input => quote!(#p::VarKind::Input),
        ConnectorRole::Output => quote!(#p::VarKind::Output),
        ConnectorRole::Overdetermined => quote!(#p::VarKind::Overdetermined),
    }
}

/// Expands `connector!`.
pub fn connector(def: &ConnectorDef) -> syn::Result<TokenStream> {
    let p = lib();
    let name = &def.name;
    let vis = &def.vis;
    let attrs = &def.attrs;
    let name_str = name.to_string();
    let desc = doc_text(attrs);
    if let Some((role, ty)) = &def.signal {
        let kind = role_tokens(*role);
        let class = format!("signal:{ty}");
        let has_value = ty != "Vec3";
        let (handle_ty, declare, at) = if ty == "Vec3" {
            (
                quote!(#p::Signal3),
                quote!(#p::declare_signal3),
                quote!(#p::signal3_at),
            )
        } else {
            (
                quote!(#p::Signal),
                quote!(#p::declare_signal),
                quote!(#p::signal_at),
            )
        };
        let attrs = docs_escaped(attrs);
        return Ok(quote! {
            #attrs
            #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
            #vis struct #name;

            impl #p::Component for #name {
                fn type_name(&self) -> ::std::string::String {
                    ::std::string::String::from(#name_str)
                }
                fn connector_class(&self) -> ::core::option::Option<::std::string::String> {
                    ::core::option::Option::Some(::std::string::String::from(#class))
                }
                fn build(&self, __s: &mut #p::System) {
                    #declare(__s, #kind, #desc);
                }
            }

            impl #p::Connector for #name {
                type Handle = #handle_ty;
                fn handle(path: &str) -> #handle_ty {
                    #at(path)
                }
                const HAS_VALUE: bool = #has_value;
            }
        });
    }
    let handle = format_ident!("{}Handle", name);
    let mut fields = TokenStream::new();
    let mut init = TokenStream::new();
    let mut build = TokenStream::new();
    for v in &def.vars {
        let (docs, n, ty) = (&v.docs, &v.name, &v.ty);
        let s = n.to_string();
        let vd = doc_text(docs);
        let unit = unit_call(&vd);
        let kind = role_tokens(v.role);
        let docs = docs_escaped(docs);
        fields.extend(quote!(#docs pub #n: #ty,));
        init.extend(quote!(#n: <#ty as #p::VariableType>::at(&#p::member(path, #s)),));
        if v.role == ConnectorRole::Overdetermined {
            build.extend(quote!(
                __s.declare_overdetermined::<#ty>(#p::Variable::new(#s).description(#vd) #unit);
            ));
        } else {
            build.extend(quote!(
                __s.declare::<#ty>(#p::Variable::new(#s).kind(#kind).description(#vd) #unit);
            ));
        }
    }
    let handle_doc = format!("Handle of a [`{name}`] connector instance: its variables by name.");
    let attrs = docs_escaped(attrs);
    Ok(quote! {
        #attrs
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        #vis struct #name;

        #[doc = #handle_doc]
        #[derive(Clone, Copy, Debug)]
        #[allow(non_snake_case)]
        #vis struct #handle {
            /// The connector's full path.
            pub path: #p::PathId,
            #fields
        }

        impl #p::ConnectorHandle for #handle {
            fn path(&self) -> ::std::string::String {
                self.path.as_string()
            }
        }

        impl #p::Component for #name {
            fn type_name(&self) -> ::std::string::String {
                ::std::string::String::from(#name_str)
            }
            fn connector_class(&self) -> ::core::option::Option<::std::string::String> {
                ::core::option::Option::Some(::std::string::String::from(#name_str))
            }
            fn build(&self, __s: &mut #p::System) {
                #build
            }
        }

        impl #p::Connector for #name {
            type Handle = #handle;
            fn handle(path: &str) -> #handle {
                #handle { path: #p::PathId::new(path), #init }
            }
        }
    })
}

/// Adds `..Default::default()` to a struct literal that lists only some fields.
fn with_defaults(value: &Expr) -> Expr {
    match value {
        Expr::Struct(s) if s.rest.is_none() => {
            let mut s = s.clone();
            if !s.fields.empty_or_trailing() {
                s.fields.push_punct(Default::default());
            }
            s.dot2_token = Some(Default::default());
            s.rest = Some(Box::new(syn::parse_quote!(
                ::core::default::Default::default()
            )));
            Expr::Struct(s)
        }
        other => other.clone(),
    }
}

/// Expands `system!`: a block that builds the model and returns it with its handles
/// (`Model<Handles>`), or, in the function form, the handles struct and the function.
pub fn system(def: &SystemDef) -> syn::Result<TokenStream> {
    let p = lib();
    let name = match (&def.name, &def.function) {
        (Some(s), _) => s.value(),
        (None, Some(f)) => f.sig.ident.to_string(),
        (None, None) => "model".to_string(),
    };
    let instances = system_instances(def)?;
    let body = system_body(def);
    let fields: Vec<&Ident> = instances.iter().map(|(n, _)| *n).collect();
    let Some(function) = &def.function else {
        let params: Vec<Ident> = (0..fields.len())
            .map(|i| quote::format_ident!("H{}", i))
            .collect();
        let generics = if params.is_empty() {
            quote!()
        } else {
            quote!(<#(#params),*>)
        };
        return Ok(quote!({
            /// The typed handle of every instance of the model, a field each.
            #[derive(Clone, Copy, Debug)]
            #[allow(non_camel_case_types, dead_code)]
            pub struct Handles #generics {
                #(
                    #[allow(missing_docs)]
                    pub #fields: #params,
                )*
            }
            let mut __s = #p::System::new(#name);
            #body
            #p::Model::new(__s, Handles { #(#fields),* })
        }));
    };
    let mut types = Vec::new();
    for (n, ty) in &instances {
        match ty {
            Some(t) => types.push(quote!(<#t as #p::TypedComponent>::Handle)),
            None => {
                return Err(syn::Error::new(
                    n.span(),
                    format!(
                        "the type of `{n}` is not written: in a model function each instance \
                         is `{n} = Type {{ .. }}`, `{n} = Type::constructor(..)` or \
                         `{n}: Type = value`, so that its handle has a type"
                    ),
                ));
            }
        }
    }
    let SystemFn {
        attrs,
        vis,
        sig,
        handles,
    } = function;
    let mut sig = sig.clone();
    sig.output = syn::parse_quote!(-> #p::Model<#handles>);
    let struct_doc = format!(
        "The typed handles of the instances of the model built by [`{}`], a field each.",
        sig.ident
    );
    let field_docs: Vec<String> = fields.iter().map(|f| format!("`{f}`")).collect();
    Ok(quote!(
        #[doc = #struct_doc]
        #[derive(Clone, Copy, Debug)]
        #vis struct #handles {
            #(
                #[doc = #field_docs]
                pub #fields: #types,
            )*
        }

        #(#attrs)*
        #vis #sig {
            let mut __s = #p::System::new(#name);
            #body
            #p::Model::new(__s, #handles { #(#fields),* })
        }
    ))
}

/// The instances in order, with their component types where known: written
/// (`b: BodyShape = ..`), a struct literal (`Revolute { .. }`) or a constructor call
/// (`World::default()`). Rejects a name declared twice.
fn system_instances(def: &SystemDef) -> syn::Result<Vec<(&Ident, Option<syn::Type>)>> {
    let mut seen: std::collections::HashSet<String> = Default::default();
    let mut out = Vec::new();
    for item in &def.items {
        if let SystemItem::Instance { name, ty, value } = item {
            if !seen.insert(name.to_string()) {
                return Err(syn::Error::new(
                    name.span(),
                    format!("`{name}` is declared twice"),
                ));
            }
            out.push((name, ty.clone().or_else(|| component_type(value))));
        }
    }
    Ok(out)
}

/// The component type an instance's value names: `Type { .. }` or `Type::f(..)`.
fn component_type(value: &Expr) -> Option<syn::Type> {
    let path = match value {
        Expr::Struct(s) => s.path.clone(),
        Expr::Call(c) => match &*c.func {
            Expr::Path(p) if p.qself.is_none() && p.path.segments.len() >= 2 => {
                let mut path = p.path.clone();
                path.segments.pop();
                let last = path.segments.pop().expect("two segments").into_value();
                path.segments.push(last);
                path
            }
            _ => return None,
        },
        _ => return None,
    };
    Some(syn::Type::Path(syn::TypePath { qself: None, path }))
}

/// The statements that add instances, connections and equations to `__s`.
fn system_body(def: &SystemDef) -> TokenStream {
    let p = lib();
    let mut body = TokenStream::new();
    for item in &def.items {
        match item {
            SystemItem::Instance { name: n, ty, value } => {
                let s = n.to_string();
                let v = with_defaults(value);
                let add = match ty {
                    Some(t) => quote_spanned!(value.span()=> __s.add_typed::<#t>(#s, &(#v))),
                    None => quote_spanned!(value.span()=> __s.add_typed(#s, &(#v))),
                };
                body.extend(quote_spanned!(value.span()=>
                    #[allow(unused_variables, clippy::needless_update)]
                    let #n = #add;
                ));
            }
            SystemItem::Connect { a, b } => {
                // Spanned at the second connector, where a type mismatch is reported.
                let a = quote_spanned!(a.span()=> &#a);
                let b = quote_spanned!(b.span()=> &#b);
                body.extend(quote!(__s.connect_handles(#a, #b);));
            }
            SystemItem::Equation { initial, lhs, rhs } => {
                let call = if *initial {
                    quote!(__s.initial_equate(#lhs, #rhs);)
                } else {
                    quote!(__s.equate(#lhs, #rhs);)
                };
                body.extend(quote!({
                    #[allow(unused_imports)]
                    use #p::dsl::*;
                    let time = #p::Expr::time();
                    #call
                }));
            }
        }
    }
    body
}
