//! Translation of equation sections into builder calls.
//!
//! `lhs = rhs;` becomes `__s.equate(lhs, rhs)`, `connect(a, b);` becomes
//! `__s.connect_handles(&a, &b)`; `let`, `if` and `for` stay Rust (structural choices
//! made while building); anything else is an error pointing at the statement.

use proc_macro2::TokenStream;
use quote::{quote, quote_spanned};
use syn::spanned::Spanned;
use syn::{Expr, Stmt};

/// Translates a list of statements.
pub fn translate(stmts: &[Stmt], initial: bool) -> syn::Result<TokenStream> {
    let mut out = TokenStream::new();
    for s in stmts {
        out.extend(statement(s, initial)?);
    }
    Ok(out)
}

fn statement(s: &Stmt, initial: bool) -> syn::Result<TokenStream> {
    match s {
        Stmt::Local(l) => Ok(quote!(#l)),
        Stmt::Item(i) => Ok(quote!(#i)),
        Stmt::Macro(m) => Ok(quote!(#m)),
        Stmt::Expr(e, semi) => {
            let needs_semi = matches!(e, Expr::Assign(_) | Expr::Call(_));
            if needs_semi && semi.is_none() {
                return Err(syn::Error::new(e.span(), "an equation ends with `;`"));
            }
            expression(e, initial)
        }
    }
}

fn block(b: &syn::Block, initial: bool) -> syn::Result<TokenStream> {
    let inner = translate(&b.stmts, initial)?;
    Ok(quote!({ #inner }))
}

fn expression(e: &Expr, initial: bool) -> syn::Result<TokenStream> {
    match e {
        Expr::Assign(a) => {
            let (l, r) = (&a.left, &a.right);
            let span = a.eq_token.span;
            Ok(if initial {
                quote_spanned!(span=> __s.initial_equate(#l, #r);)
            } else {
                quote_spanned!(span=> __s.equate(#l, #r);)
            })
        }
        Expr::Call(c) if is_connect(&c.func) => {
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
        Expr::If(i) => {
            let cond = &i.cond;
            let then = block(&i.then_branch, initial)?;
            let els = match &i.else_branch {
                Some((_, e)) => {
                    let t = match &**e {
                        Expr::Block(b) => block(&b.block, initial)?,
                        other @ Expr::If(_) => {
                            let t = expression(other, initial)?;
                            quote!({ #t })
                        }
                        other => {
                            return Err(syn::Error::new(other.span(), "expected a block"));
                        }
                    };
                    quote!(else #t)
                }
                None => TokenStream::new(),
            };
            Ok(quote!(if #cond #then #els))
        }
        Expr::ForLoop(f) => {
            let pat = &f.pat;
            let it = &f.expr;
            let body = block(&f.body, initial)?;
            Ok(quote!(for #pat in #it #body))
        }
        Expr::Block(b) => block(&b.block, initial),
        Expr::Match(m) => {
            let scrutinee = &m.expr;
            let mut arms = TokenStream::new();
            for arm in &m.arms {
                let pat = &arm.pat;
                let guard = arm.guard.as_ref().map(|(_, g)| quote!(if #g));
                let body = match &*arm.body {
                    Expr::Block(b) => block(&b.block, initial)?,
                    other => {
                        let t = expression(other, initial)?;
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

fn is_connect(f: &Expr) -> bool {
    matches!(f, Expr::Path(p) if p.path.is_ident("connect"))
}
