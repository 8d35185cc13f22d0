//! Checks of a component declaration beyond its syntax.

use std::collections::HashMap;

use syn::Ident;

use crate::ast::{ComponentDef, ConnectorDef, Item, Modifier};

/// Attributes a variable declaration accepts.
pub const VARIABLE_MODIFIERS: &[&str] = &[
    "start",
    "fixed",
    "guess",
    "state_priority",
    "state_select",
    "unit",
    "discrete",
];

/// Attributes a parameter declaration accepts.
pub const PARAMETER_MODIFIERS: &[&str] = &["fixed", "unit", "evaluate", "min", "max"];

/// Names the generated code uses for itself.
const RESERVED: &[&str] = &["time", "self", "path"];

fn check_modifiers(mods: &[Modifier], allowed: &[&str], what: &str) -> syn::Result<()> {
    let mut seen: HashMap<String, &Ident> = HashMap::new();
    for m in mods {
        let k = m.key.to_string();
        if !allowed.contains(&k.as_str()) {
            return Err(syn::Error::new(
                m.key.span(),
                format!(
                    "unknown {what} attribute `{k}`: expected one of {}",
                    allowed.join(", ")
                ),
            ));
        }
        if seen.insert(k.clone(), &m.key).is_some() {
            return Err(syn::Error::new(
                m.key.span(),
                format!("`{k}` is given twice"),
            ));
        }
    }
    Ok(())
}

/// Checks names (no duplicates, no reserved ones) and declaration attributes.
pub fn check_component(def: &ComponentDef) -> syn::Result<()> {
    let mut names: HashMap<String, Ident> = HashMap::new();
    let mut declare = |id: &Ident| -> syn::Result<()> {
        let s = id.to_string();
        if RESERVED.contains(&s.as_str()) || s.starts_with("__") {
            return Err(syn::Error::new(
                id.span(),
                format!("`{s}` is a reserved name inside a component"),
            ));
        }
        if names.insert(s.clone(), id.clone()).is_some() {
            return Err(syn::Error::new(
                id.span(),
                format!("`{s}` is declared twice in `{}`", def.name),
            ));
        }
        Ok(())
    };
    for item in &def.items {
        if let Some(n) = item.name() {
            declare(n)?;
        }
        match item {
            Item::Variable { modifiers, .. } => {
                check_modifiers(modifiers, VARIABLE_MODIFIERS, "variable")?
            }
            Item::Parameter { modifiers, .. } => {
                check_modifiers(modifiers, PARAMETER_MODIFIERS, "parameter")?
            }
            Item::Extends { names: members, .. } => {
                for m in members {
                    declare(m)?;
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Checks a connector: unique variable names, at least one variable.
pub fn check_connector(def: &ConnectorDef) -> syn::Result<()> {
    if def.signal.is_none() && def.vars.is_empty() {
        return Err(syn::Error::new(
            def.name.span(),
            "a connector needs at least one variable",
        ));
    }
    let mut seen = HashMap::new();
    for v in &def.vars {
        if seen.insert(v.name.to_string(), ()).is_some() {
            return Err(syn::Error::new(
                v.name.span(),
                format!("`{}` is declared twice in `{}`", v.name, def.name),
            ));
        }
    }
    Ok(())
}
