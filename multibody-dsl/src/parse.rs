//! Parsing the macro inputs with `syn`.

use syn::parse::{Parse, ParseStream};
use syn::punctuated::Punctuated;
use syn::{
    Attribute, Block, Expr, Ident, LitStr, Path, Token, Type, Visibility, braced, parenthesized,
};

use crate::ast::*;

/// Modelica's `when CONDITION { ... }` and `elsewhen CONDITION { ... }`, wherever they
/// stand in an equation section (inside structural `if`s too), rewritten into the Rust
/// the section is parsed as: `if __when(CONDITION) { ... }` and
/// `if __elsewhen(CONDITION) { ... }`, which the translator turns into clauses.
fn rewrite_when(tokens: proc_macro2::TokenStream) -> proc_macro2::TokenStream {
    use proc_macro2::{Delimiter, Group, Ident as PmIdent, TokenTree};
    let tokens: Vec<TokenTree> = tokens.into_iter().collect();
    let mut out = Vec::with_capacity(tokens.len());
    let mut i = 0;
    while i < tokens.len() {
        match &tokens[i] {
            TokenTree::Ident(word) if word == "when" || word == "elsewhen" => {
                // A clause: the condition runs to the body in braces (a variable of that
                // name, `when = ...` or `when.x`, is left alone).
                let body = (i + 1..tokens.len()).find(|&j| {
                    matches!(&tokens[j], TokenTree::Group(g) if g.delimiter() == Delimiter::Brace)
                });
                let starts_condition = match tokens.get(i + 1) {
                    Some(TokenTree::Ident(_) | TokenTree::Group(_) | TokenTree::Literal(_)) => true,
                    Some(TokenTree::Punct(p)) => matches!(p.as_char(), '-' | '!'),
                    None => false,
                };
                let is_clause = starts_condition && body.is_some_and(|j| j > i + 1);
                let Some(j) = body.filter(|_| is_clause) else {
                    out.push(tokens[i].clone());
                    i += 1;
                    continue;
                };
                let marker = if word == "when" {
                    "__when"
                } else {
                    "__elsewhen"
                };
                let condition: proc_macro2::TokenStream =
                    tokens[i + 1..j].iter().cloned().map(rewrite_tree).collect();
                out.push(TokenTree::Ident(PmIdent::new("if", word.span())));
                out.push(TokenTree::Ident(PmIdent::new(marker, word.span())));
                let mut args = Group::new(Delimiter::Parenthesis, condition);
                args.set_span(word.span());
                out.push(TokenTree::Group(args));
                out.push(rewrite_tree(tokens[j].clone()));
                i = j + 1;
            }
            t => {
                out.push(rewrite_tree(t.clone()));
                i += 1;
            }
        }
    }
    out.into_iter().collect()
}

/// [`rewrite_when`] inside a token tree's groups.
fn rewrite_tree(t: proc_macro2::TokenTree) -> proc_macro2::TokenTree {
    match t {
        proc_macro2::TokenTree::Group(g) => {
            let mut inner = proc_macro2::Group::new(g.delimiter(), rewrite_when(g.stream()));
            inner.set_span(g.span());
            proc_macro2::TokenTree::Group(inner)
        }
        other => other,
    }
}

/// The statements of an equation section (see [`rewrite_when`]).
fn equation_statements(input: ParseStream<'_>) -> syn::Result<Vec<syn::Stmt>> {
    use syn::parse::Parser;
    let tokens: proc_macro2::TokenStream = input.parse()?;
    Block::parse_within.parse2(rewrite_when(tokens))
}

fn modifiers(input: ParseStream<'_>) -> syn::Result<Vec<Modifier>> {
    if !input.peek(syn::token::Paren) {
        return Ok(Vec::new());
    }
    let content;
    parenthesized!(content in input);
    let list: Punctuated<ModifierSyntax, Token![,]> =
        content.parse_terminated(ModifierSyntax::parse, Token![,])?;
    Ok(list.into_iter().map(|m| m.0).collect())
}

struct ModifierSyntax(Modifier);

impl Parse for ModifierSyntax {
    fn parse(input: ParseStream<'_>) -> syn::Result<Self> {
        let key: Ident = input.parse()?;
        input.parse::<Token![=]>()?;
        let value: Expr = input.parse()?;
        Ok(ModifierSyntax(Modifier { key, value }))
    }
}

fn docs_only(attrs: Vec<Attribute>) -> syn::Result<Vec<Attribute>> {
    for a in &attrs {
        if !a.path().is_ident("doc") {
            return Err(syn::Error::new_spanned(
                a,
                "only doc comments may precede a declaration inside a component",
            ));
        }
    }
    Ok(attrs)
}

const KEYWORDS: &str = "parameter, structural, connector, variable, component, extends, \
                        equation or initial_equation";

impl Parse for Item {
    fn parse(input: ParseStream<'_>) -> syn::Result<Self> {
        let docs = docs_only(input.call(Attribute::parse_outer)?)?;
        let kw: Ident = input.parse().map_err(|e| {
            syn::Error::new(e.span(), format!("expected a declaration: {KEYWORDS}"))
        })?;
        let item = match kw.to_string().as_str() {
            "parameter" => {
                let name: Ident = input.parse()?;
                let modifiers = modifiers(input)?;
                input.parse::<Token![:]>()?;
                let ty: Type = input.parse()?;
                input.parse::<Token![=]>().map_err(|e| {
                    syn::Error::new(e.span(), "a parameter needs a default value: `= value`")
                })?;
                let default: Expr = input.parse()?;
                input.parse::<Token![;]>()?;
                Item::Parameter {
                    docs,
                    name,
                    ty,
                    modifiers,
                    default,
                }
            }
            "structural" => {
                let name: Ident = input.parse()?;
                input.parse::<Token![:]>()?;
                let ty: Type = input.parse()?;
                input.parse::<Token![=]>().map_err(|e| {
                    syn::Error::new(
                        e.span(),
                        "a structural parameter needs a default value: `= value`",
                    )
                })?;
                let default: Expr = input.parse()?;
                input.parse::<Token![;]>()?;
                Item::Structural {
                    docs,
                    name,
                    ty,
                    default,
                }
            }
            "connector" => {
                let name: Ident = input.parse()?;
                let modifiers = modifiers(input)?;
                if let Some(m) = modifiers.iter().find(|m| m.key != "start") {
                    return Err(syn::Error::new(
                        m.key.span(),
                        format!(
                            "a connector takes only `start` (of a signal connector's value), \
                             not `{}`",
                            m.key
                        ),
                    ));
                }
                input.parse::<Token![:]>()?;
                let ty: Path = input.parse()?;
                input.parse::<Token![;]>()?;
                Item::Connector {
                    docs,
                    name,
                    ty,
                    modifiers,
                }
            }
            "variable" => {
                let name: Ident = input.parse()?;
                let modifiers = modifiers(input)?;
                input.parse::<Token![:]>()?;
                let ty: Type = input.parse()?;
                input.parse::<Token![;]>()?;
                Item::Variable {
                    docs,
                    name,
                    ty,
                    modifiers,
                }
            }
            "component" => {
                let name: Ident = input.parse()?;
                input.parse::<Token![:]>()?;
                let ty: Path = input.parse()?;
                let value = if input.peek(Token![=]) {
                    input.parse::<Token![=]>()?;
                    Some(input.parse::<Expr>()?)
                } else {
                    None
                };
                input.parse::<Token![;]>()?;
                Item::Component {
                    docs,
                    name,
                    ty,
                    value,
                }
            }
            "extends" => {
                let ty: Path = input.parse()?;
                let content;
                braced!(content in input);
                let names: Punctuated<Ident, Token![,]> =
                    content.parse_terminated(Ident::parse, Token![,])?;
                let value = if input.peek(Token![=]) {
                    input.parse::<Token![=]>()?;
                    Some(input.parse::<Expr>()?)
                } else {
                    None
                };
                input.parse::<Token![;]>()?;
                Item::Extends {
                    ty,
                    names: names.into_iter().collect(),
                    value,
                }
            }
            "equation" | "initial_equation" => {
                let content;
                braced!(content in input);
                let body = content.call(equation_statements)?;
                Item::Equations {
                    initial: kw == "initial_equation",
                    body,
                    keyword: kw,
                }
            }
            other => {
                return Err(syn::Error::new(
                    kw.span(),
                    format!("unknown declaration `{other}`: expected {KEYWORDS}"),
                ));
            }
        };
        Ok(item)
    }
}

impl Parse for ComponentDef {
    fn parse(input: ParseStream<'_>) -> syn::Result<Self> {
        let all = input.call(Attribute::parse_outer)?;
        let mut attrs = Vec::new();
        let mut type_name = None;
        for a in all {
            if a.path().is_ident("type_name") {
                let nv = a.meta.require_name_value()?;
                match &nv.value {
                    Expr::Lit(syn::ExprLit {
                        lit: syn::Lit::Str(s),
                        ..
                    }) => type_name = Some(s.clone()),
                    other => {
                        return Err(syn::Error::new_spanned(
                            other,
                            "`type_name` takes a string: #[type_name = \"Rotational.Inertia\"]",
                        ));
                    }
                }
            } else {
                attrs.push(a);
            }
        }
        let vis: Visibility = input.parse()?;
        input.parse::<Token![struct]>()?;
        let name: Ident = input.parse()?;
        let content;
        braced!(content in input);
        let mut items = Vec::new();
        while !content.is_empty() {
            items.push(content.parse::<Item>()?);
        }
        if !input.is_empty() {
            return Err(input.error("unexpected tokens after the component"));
        }
        Ok(ComponentDef {
            attrs,
            type_name,
            vis,
            name,
            items,
        })
    }
}

fn role(kw: &Ident) -> syn::Result<ConnectorRole> {
    match kw.to_string().as_str() {
        "potential" => Ok(ConnectorRole::Potential),
        "flow" => Ok(ConnectorRole::Flow),
        "input" => Ok(ConnectorRole::Input),
        "output" => Ok(ConnectorRole::Output),
        "overdetermined" => Ok(ConnectorRole::Overdetermined),
        other => Err(syn::Error::new(
            kw.span(),
            format!(
                "unknown connector variable kind `{other}`: expected potential, flow, input, \
                 output or overdetermined"
            ),
        )),
    }
}

impl Parse for ConnectorDef {
    fn parse(input: ParseStream<'_>) -> syn::Result<Self> {
        let attrs = input.call(Attribute::parse_outer)?;
        let vis: Visibility = input.parse()?;
        input.parse::<Token![struct]>()?;
        let name: Ident = input.parse()?;
        if input.peek(Token![=]) {
            input.parse::<Token![=]>()?;
            let kw: Ident = input.parse()?;
            let r = role(&kw)?;
            if !matches!(r, ConnectorRole::Input | ConnectorRole::Output) {
                return Err(syn::Error::new(
                    kw.span(),
                    "a signal connector is `input Type` or `output Type`",
                ));
            }
            let ty: Ident = input.parse()?;
            input.parse::<Token![;]>()?;
            return Ok(ConnectorDef {
                attrs,
                vis,
                name,
                vars: Vec::new(),
                signal: Some((r, ty)),
            });
        }
        let content;
        braced!(content in input);
        let mut vars = Vec::new();
        while !content.is_empty() {
            let docs = docs_only(content.call(Attribute::parse_outer)?)?;
            let kw: Ident = content.parse()?;
            let role = role(&kw)?;
            let vname: Ident = content.parse()?;
            content.parse::<Token![:]>()?;
            let ty: Type = content.parse()?;
            content.parse::<Token![;]>()?;
            vars.push(ConnectorVar {
                docs,
                role,
                name: vname,
                ty,
            });
        }
        Ok(ConnectorDef {
            attrs,
            vis,
            name,
            vars,
            signal: None,
        })
    }
}

impl Parse for SystemDef {
    fn parse(input: ParseStream<'_>) -> syn::Result<Self> {
        let fork = input.fork();
        let _ = fork.call(syn::Attribute::parse_outer);
        let _ = fork.parse::<syn::Visibility>();
        if fork.peek(Token![fn]) {
            return parse_system_fn(input);
        }
        parse_system_items(input, None)
    }
}

/// `#[attrs] vis fn name(args) -> Handles { items }`
fn parse_system_fn(input: ParseStream<'_>) -> syn::Result<SystemDef> {
    let attrs = input.call(syn::Attribute::parse_outer)?;
    let vis: syn::Visibility = input.parse()?;
    let sig: syn::Signature = input.parse()?;
    let handles = match &sig.output {
        syn::ReturnType::Type(_, ty) => match &**ty {
            syn::Type::Path(p) if p.qself.is_none() && p.path.get_ident().is_some() => {
                p.path.get_ident().cloned().expect("checked")
            }
            other => {
                return Err(syn::Error::new_spanned(
                    other,
                    "the return type names the struct of handles that `system!` declares: \
                     one identifier, like `-> FourBar`",
                ));
            }
        },
        syn::ReturnType::Default => {
            return Err(syn::Error::new_spanned(
                &sig,
                "a model function names the struct of its handles as its return type: \
                 `fn fourbar() -> FourBar { ... }` (it returns `Model<FourBar>`)",
            ));
        }
    };
    if !sig.generics.params.is_empty() {
        return Err(syn::Error::new_spanned(
            &sig.generics,
            "a model function takes no generic parameters",
        ));
    }
    let content;
    syn::braced!(content in input);
    let function = SystemFn {
        attrs,
        vis,
        sig,
        handles,
    };
    let def = parse_system_items(&content, Some(function))?;
    if !input.is_empty() {
        return Err(input.error("one model function per `system!`"));
    }
    Ok(def)
}

/// The statements of a `system!`.
fn parse_system_items(
    input: ParseStream<'_>,
    function: Option<SystemFn>,
) -> syn::Result<SystemDef> {
    {
        let mut name = None;
        let mut items = Vec::new();
        while !input.is_empty() {
            let ident: Ident = input.parse()?;
            let kw = ident.to_string();
            if kw == "name" && input.peek(Token![:]) && input.peek2(LitStr) {
                input.parse::<Token![:]>()?;
                name = Some(input.parse::<LitStr>()?);
            } else if kw == "connect" && input.peek(syn::token::Paren) {
                let content;
                parenthesized!(content in input);
                let args: Punctuated<Expr, Token![,]> =
                    content.parse_terminated(Expr::parse, Token![,])?;
                if args.len() != 2 {
                    return Err(syn::Error::new(
                        ident.span(),
                        format!(
                            "connect takes two connectors, `connect(a.x, b.y)`; found {}",
                            args.len()
                        ),
                    ));
                }
                let mut it = args.into_iter();
                let a = it.next().expect("two");
                let b = it.next().expect("two");
                items.push(SystemItem::Connect { a, b });
            } else if kw == "equation" || kw == "initial_equation" {
                let e: Expr = input.parse()?;
                match e {
                    Expr::Assign(a) => items.push(SystemItem::Equation {
                        initial: kw == "initial_equation",
                        lhs: *a.left,
                        rhs: *a.right,
                    }),
                    other => {
                        return Err(syn::Error::new_spanned(
                            other,
                            "an equation is written `equation lhs = rhs;`",
                        ));
                    }
                }
            } else {
                let ty = if input.peek(Token![:]) {
                    input.parse::<Token![:]>()?;
                    Some(input.parse::<syn::Type>()?)
                } else {
                    None
                };
                input.parse::<Token![=]>().map_err(|e| {
                    syn::Error::new(
                        e.span(),
                        "expected `name = Component { ... };`, `name: Type = value;`, \
                         `connect(a, b);` or `equation lhs = rhs;`",
                    )
                })?;
                let value: Expr = input.parse()?;
                items.push(SystemItem::Instance {
                    name: ident,
                    ty,
                    value,
                });
            }
            if !input.is_empty() {
                input.parse::<Token![;]>()?;
            }
        }
        Ok(SystemDef {
            function,
            name,
            items,
        })
    }
}
