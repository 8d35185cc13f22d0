//! Translation of equation sections into builder calls.
//!
//! `lhs = rhs;` becomes `__s.equate(lhs, rhs)`, `connect(a, b);` becomes
//! `__s.connect_handles(&a, &b)`, `assert(condition, message);` becomes
//! `__s.assert(condition, message)` (a `bool` of structural parameters, or an expression
//! of tunable parameters); `let`, `if`, `match` and `for` stay Rust (structural
//! choices made while building); anything else is an error pointing at the statement.
//!
//! The virtual connection graph of overdetermined connectors (Modelica's `Connections`
//! operators) is written as in Modelica:
//! - `root(frame_b.R);` declares a definite root;
//! - `branch(frame_a.R, frame_b.R);` declares a branch, and a following
//!   `if rooted(frame_a.R) { ... } else { ... }` gives its equations for either side
//!   being nearer the root (decided when the model is flattened);
//! - `potential_root(frame_a.R);` (optionally with a priority) and
//!   `if is_root(frame_a.R) { ... } else { ... }` do the same for potential roots.

use proc_macro2::TokenStream;
use quote::{quote, quote_spanned};
use syn::spanned::Spanned;
use syn::{Expr, Stmt};

/// A branch or potential root waiting for its conditional equations.
struct Pending {
    nodes: Vec<Expr>,
    keys: Vec<String>,
    priority: Option<Expr>,
    used: bool,
}

/// Translates the equation sections of one component, keeping track of the graph
/// declarations across them.
#[derive(Default)]
pub struct Translator {
    branches: Vec<Pending>,
    potential_roots: Vec<Pending>,
    /// Inside the body of a `when` clause.
    in_when: bool,
}

fn key(e: &Expr) -> String {
    quote!(#e).to_string()
}

fn call_name(e: &Expr) -> Option<(String, &syn::ExprCall)> {
    match e {
        Expr::Call(c) => match &*c.func {
            Expr::Path(p) => p.path.get_ident().map(|i| (i.to_string(), c)),
            _ => None,
        },
        _ => None,
    }
}

/// `sample(start, interval)` and `initial()` in a `when` condition made the builder's
/// `__s.sample(start, interval)` and `__s.initial()` (they declare what they need in
/// the component).
fn with_samples(e: &mut Expr) {
    match e {
        Expr::Call(c) => {
            if call_name(&Expr::Call(c.clone())).is_some_and(|(n, _)| n == "sample") {
                let args = &c.args;
                *e = syn::parse_quote_spanned!(c.span()=> __s.sample(#args));
                return;
            }
            if call_name(&Expr::Call(c.clone())).is_some_and(|(n, _)| n == "initial")
                && c.args.is_empty()
            {
                *e = syn::parse_quote_spanned!(c.span()=> __s.initial());
                return;
            }
            if call_name(&Expr::Call(c.clone())).is_some_and(|(n, _)| n == "terminal")
                && c.args.is_empty()
            {
                *e = syn::parse_quote_spanned!(c.span()=> __s.terminal());
                return;
            }
            c.args.iter_mut().for_each(with_samples);
        }
        Expr::MethodCall(m) => {
            with_samples(&mut m.receiver);
            m.args.iter_mut().for_each(with_samples);
        }
        Expr::Binary(b) => {
            with_samples(&mut b.left);
            with_samples(&mut b.right);
        }
        Expr::Unary(u) => with_samples(&mut u.expr),
        Expr::Paren(p) => with_samples(&mut p.expr),
        _ => {}
    }
}

impl Translator {
    /// Translates a list of statements.
    pub fn translate(&mut self, stmts: &[Stmt], initial: bool) -> syn::Result<TokenStream> {
        let mut out = TokenStream::new();
        for s in stmts {
            out.extend(self.statement(s, initial)?);
        }
        Ok(out)
    }

    /// Registers the branches and potential roots that no conditional followed (their
    /// equations are written unconditionally).
    pub fn finish(self) -> TokenStream {
        registrations(self.branches, self.potential_roots)
    }

    fn statement(&mut self, s: &Stmt, initial: bool) -> syn::Result<TokenStream> {
        match s {
            Stmt::Local(l) => Ok(quote!(#l)),
            Stmt::Item(i) => Ok(quote!(#i)),
            Stmt::Macro(m) => Ok(quote!(#m)),
            Stmt::Expr(e, semi) => {
                let needs_semi = matches!(e, Expr::Assign(_) | Expr::Call(_));
                if needs_semi && semi.is_none() {
                    return Err(syn::Error::new(e.span(), "an equation ends with `;`"));
                }
                self.expression(e, initial)
            }
        }
    }

    fn block(&mut self, b: &syn::Block, initial: bool) -> syn::Result<TokenStream> {
        let (nb, np) = (self.branches.len(), self.potential_roots.len());
        let mut inner = self.translate(&b.stmts, initial)?;
        // Declarations of this block that no conditional followed belong to it (a
        // branch inside `else` of `if iscut` exists only when the joint is no cut).
        let branches = self.branches.split_off(nb);
        let potential_roots = self.potential_roots.split_off(np);
        inner.extend(registrations(branches, potential_roots));
        Ok(quote!({ #inner }))
    }

    fn else_block(&mut self, e: &Expr, initial: bool) -> syn::Result<TokenStream> {
        match e {
            Expr::Block(b) => self.block(&b.block, initial),
            other @ Expr::If(_) => {
                let t = self.expression(other, initial)?;
                Ok(quote!({ #t }))
            }
            other => Err(syn::Error::new(other.span(), "expected a block")),
        }
    }

    fn graph_call(
        &mut self,
        name: &str,
        c: &syn::ExprCall,
        initial: bool,
    ) -> syn::Result<TokenStream> {
        if initial {
            return Err(syn::Error::new(
                c.span(),
                format!("`{name}` belongs in `equation`, not `initial_equation`"),
            ));
        }
        let args: Vec<Expr> = c.args.iter().cloned().collect();
        match name {
            "root" => {
                if args.len() != 1 {
                    return Err(syn::Error::new(
                        c.span(),
                        "root takes one orientation: `root(frame_b.R)`",
                    ));
                }
                let n = &args[0];
                Ok(quote!(__s.root(&#n);))
            }
            "branch" => {
                if args.len() != 2 {
                    return Err(syn::Error::new(
                        c.span(),
                        "branch takes two orientations: `branch(frame_a.R, frame_b.R)`",
                    ));
                }
                self.branches.push(Pending {
                    keys: args.iter().map(key).collect(),
                    nodes: args,
                    priority: None,
                    used: false,
                });
                Ok(TokenStream::new())
            }
            _ => {
                if args.is_empty() || args.len() > 2 {
                    return Err(syn::Error::new(
                        c.span(),
                        "potential_root takes an orientation and an optional priority",
                    ));
                }
                let priority = args.get(1).cloned();
                self.potential_roots.push(Pending {
                    keys: vec![key(&args[0])],
                    nodes: vec![args[0].clone()],
                    priority,
                    used: false,
                });
                Ok(TokenStream::new())
            }
        }
    }

    /// `when CONDITION { ... }` (parsed as `if __when(CONDITION) { ... }`): its
    /// equations and `reinit`s become a clause of the builder's `when`.
    fn when_clause(
        &mut self,
        i: &syn::ExprIf,
        c: &syn::ExprCall,
        initial: bool,
        elsewhen: bool,
    ) -> syn::Result<TokenStream> {
        if initial {
            return Err(syn::Error::new(
                c.span(),
                "a when clause belongs in `equation`, not `initial_equation`",
            ));
        }
        if self.in_when {
            return Err(syn::Error::new(c.span(), "when clauses do not nest"));
        }
        let mut condition = c.args[0].clone();
        with_samples(&mut condition);
        self.in_when = true;
        let body = self.block(&i.then_branch, false);
        self.in_when = false;
        let body = body?;
        let method = if elsewhen {
            quote!(elsewhen)
        } else {
            quote!(when)
        };
        Ok(quote_spanned!(c.span()=> {
            let __condition = #condition;
            __s.#method(__condition, |__s| #body);
        }))
    }

    /// `if rooted(x) { A } else { B }` / `if is_root(x) { A } else { B }`.
    fn graph_if(&mut self, i: &syn::ExprIf, which: &str, node: &Expr) -> syn::Result<TokenStream> {
        let k = key(node);
        let then = self.block(&i.then_branch, false)?;
        let els = match &i.else_branch {
            Some((_, e)) => self.else_block(e, false)?,
            None => quote!({}),
        };
        let capture = |b: &TokenStream| quote!(__s.capture(|__s| #b));
        let (a_eqs, b_eqs) = (capture(&then), capture(&els));
        if which == "rooted" {
            let Some(b) = self
                .branches
                .iter_mut()
                .rev()
                .find(|b| !b.used && b.keys.contains(&k))
            else {
                return Err(syn::Error::new(
                    node.span(),
                    "`rooted(..)` needs a preceding `branch(..)` declaring this orientation",
                ));
            };
            b.used = true;
            let (na, nb) = (&b.nodes[0], &b.nodes[1]);
            let first = b.keys[0] == k;
            let (ra, rb) = if first {
                (a_eqs, b_eqs)
            } else {
                (b_eqs, a_eqs)
            };
            Ok(quote!({
                let __a_rooted = #ra;
                let __b_rooted = #rb;
                __s.branch(&#na, &#nb, __a_rooted, __b_rooted);
            }))
        } else {
            let Some(p) = self
                .potential_roots
                .iter_mut()
                .rev()
                .find(|p| !p.used && p.keys[0] == k)
            else {
                return Err(syn::Error::new(
                    node.span(),
                    "`is_root(..)` needs a preceding `potential_root(..)` of this orientation",
                ));
            };
            p.used = true;
            let n = &p.nodes[0];
            let prio = p.priority.clone().map_or(quote!(0), |e| quote!(#e));
            Ok(quote!({
                let __if_root = #a_eqs;
                let __otherwise = #b_eqs;
                __s.potential_root(&#n, #prio, __if_root, __otherwise);
            }))
        }
    }

    fn expression(&mut self, e: &Expr, initial: bool) -> syn::Result<TokenStream> {
        match e {
            Expr::Assign(a) => {
                let (mut l, mut r) = (a.left.clone(), a.right.clone());
                // `initial()` in an equation (a friction element's start).
                if !initial {
                    with_samples(&mut l);
                    with_samples(&mut r);
                }
                let uses_builder = l != a.left || r != a.right;
                let span = a.eq_token.span;
                Ok(if initial {
                    quote_spanned!(span=> __s.initial_equate(#l, #r);)
                } else if uses_builder {
                    // Both sides first: they use the builder.
                    quote_spanned!(span=> {
                        let __lhs = #l;
                        let __rhs = #r;
                        __s.equate(__lhs, __rhs);
                    })
                } else {
                    quote_spanned!(span=> __s.equate(#l, #r);)
                })
            }
            Expr::Call(c) if call_name(e).is_some_and(|(n, _)| n == "connect") => {
                if c.args.len() != 2 {
                    return Err(syn::Error::new(
                        c.span(),
                        format!(
                            "connect takes two connectors, `connect(a.x, b.y)`; found {}",
                            c.args.len()
                        ),
                    ));
                }
                if initial {
                    return Err(syn::Error::new(
                        c.span(),
                        "connect belongs in `equation`, not `initial_equation`",
                    ));
                }
                let (a, b) = (&c.args[0], &c.args[1]);
                let a = quote_spanned!(a.span()=> &#a);
                let b = quote_spanned!(b.span()=> &#b);
                Ok(quote!(__s.connect_handles(#a, #b);))
            }
            Expr::Call(c) if call_name(e).is_some_and(|(n, _)| n == "reinit") => {
                if c.args.len() != 2 {
                    return Err(syn::Error::new(
                        c.span(),
                        "reinit takes a state and its new value, `reinit(v, -e * pre(v))`",
                    ));
                }
                if !self.in_when || initial {
                    return Err(syn::Error::new(
                        c.span(),
                        "reinit belongs inside a when clause: `when lt(h, 0.0) { reinit(v, ..); }`",
                    ));
                }
                let (state, value) = (&c.args[0], &c.args[1]);
                Ok(quote_spanned!(c.span()=> __s.reinit(#state, #value);))
            }
            Expr::Call(c) if call_name(e).is_some_and(|(n, _)| n == "terminate") => {
                if c.args.len() != 1 {
                    return Err(syn::Error::new(
                        c.span(),
                        "terminate takes the reason, `terminate(\"the path is done\")`",
                    ));
                }
                if !self.in_when || initial {
                    return Err(syn::Error::new(
                        c.span(),
                        "terminate belongs inside a when clause: `when ge(time, 2.0) { terminate(\"..\"); }`",
                    ));
                }
                let message = &c.args[0];
                Ok(quote_spanned!(c.span()=> __s.terminate(#message);))
            }
            Expr::Call(c) if call_name(e).is_some_and(|(n, _)| n == "assert") => {
                if c.args.len() != 2 {
                    return Err(syn::Error::new(
                        c.span(),
                        "assert takes a condition and a message, `assert(m.ge(0.0), \"...\")`",
                    ));
                }
                let (cond, message) = (&c.args[0], &c.args[1]);
                Ok(quote_spanned!(c.span()=> __s.assert(#cond, #message);))
            }
            Expr::Call(_)
                if call_name(e).is_some_and(|(n, _)| {
                    matches!(n.as_str(), "root" | "branch" | "potential_root")
                }) =>
            {
                let (name, c) = call_name(e).expect("checked");
                self.graph_call(&name, c, initial)
            }
            Expr::If(i) => {
                if let Some((name, c)) = call_name(&i.cond)
                    && (name == "__when" || name == "__elsewhen")
                {
                    return self.when_clause(i, c, initial, name == "__elsewhen");
                }
                if let Some((name, c)) = call_name(&i.cond)
                    && (name == "rooted" || name == "is_root")
                {
                    if initial {
                        return Err(syn::Error::new(
                            c.span(),
                            format!("`{name}` belongs in `equation`, not `initial_equation`"),
                        ));
                    }
                    if c.args.len() != 1 {
                        return Err(syn::Error::new(
                            c.span(),
                            format!("`{name}` takes one orientation"),
                        ));
                    }
                    let node = c.args[0].clone();
                    return self.graph_if(i, &name, &node);
                }
                let cond = &i.cond;
                let then = self.block(&i.then_branch, initial)?;
                let els = match &i.else_branch {
                    Some((_, e)) => {
                        let t = self.else_block(e, initial)?;
                        quote!(else #t)
                    }
                    None => TokenStream::new(),
                };
                Ok(quote!(if #cond #then #els))
            }
            Expr::ForLoop(f) => {
                let pat = &f.pat;
                let it = &f.expr;
                let body = self.block(&f.body, initial)?;
                Ok(quote!(for #pat in #it #body))
            }
            Expr::Block(b) => self.block(&b.block, initial),
            Expr::Match(m) => {
                let scrutinee = &m.expr;
                let mut arms = TokenStream::new();
                for arm in &m.arms {
                    let pat = &arm.pat;
                    let guard = arm.guard.as_ref().map(|(_, g)| quote!(if #g));
                    let body = match &*arm.body {
                        Expr::Block(b) => self.block(&b.block, initial)?,
                        other => {
                            let t = self.expression(other, initial)?;
                            quote!({ #t })
                        }
                    };
                    arms.extend(quote!(#pat #guard => #body,));
                }
                Ok(quote!(match #scrutinee { #arms }))
            }
            Expr::Binary(b) if matches!(b.op, syn::BinOp::Eq(_)) => Err(syn::Error::new(
                b.op.span(),
                "an equation is written `lhs = rhs;` (with a single `=`)",
            )),
            other => Err(syn::Error::new(
                other.span(),
                "expected an equation `lhs = rhs;`, `connect(a, b);`, `let`, `if`, `match` or `for`",
            )),
        }
    }
}

/// Translates a list of statements on its own (no graph declarations pending).
pub fn translate(stmts: &[Stmt], initial: bool) -> syn::Result<TokenStream> {
    let mut t = Translator::default();
    let mut out = t.translate(stmts, initial)?;
    out.extend(t.finish());
    Ok(out)
}

/// Registers the branches and potential roots that no conditional followed (their
/// equations are written unconditionally).
fn registrations(branches: Vec<Pending>, potential_roots: Vec<Pending>) -> TokenStream {
    let mut out = TokenStream::new();
    for b in branches.into_iter().filter(|b| !b.used) {
        let (a, c) = (&b.nodes[0], &b.nodes[1]);
        out.extend(quote!(__s.branch(&#a, &#c, ::std::vec::Vec::new(), ::std::vec::Vec::new());));
    }
    for p in potential_roots.into_iter().filter(|p| !p.used) {
        let n = &p.nodes[0];
        let prio = p.priority.map_or(quote!(0), |e| quote!(#e));
        out.extend(
            quote!(__s.potential_root(&#n, #prio, ::std::vec::Vec::new(), ::std::vec::Vec::new());),
        );
    }
    out
}
