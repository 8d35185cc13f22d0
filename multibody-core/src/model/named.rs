//! Naming a variable or parameter of a model: by its path as text, or by a typed
//! handle's field (`h.j1.phi`), so that results, start values and plots take either.

use std::borrow::Cow;

use crate::expr::Expr;

use super::typed::Signal;

/// Something that names a variable or parameter of a model: a path (`"j1.phi"`,
/// `"der(j1.w)"`) or a leaf of a typed handle (`h.j1.phi`, `h.source.y`).
pub trait Named {
    /// The full name.
    fn name(&self) -> Cow<'_, str>;
}

impl Named for str {
    fn name(&self) -> Cow<'_, str> {
        Cow::Borrowed(self)
    }
}

impl Named for String {
    fn name(&self) -> Cow<'_, str> {
        Cow::Borrowed(self.as_str())
    }
}

impl Named for super::SharedText {
    fn name(&self) -> Cow<'_, str> {
        Cow::Borrowed(self.as_ref())
    }
}

impl Named for Expr {
    /// The variable's or parameter's name; an expression that is no leaf names
    /// nothing of a model (its text, which no lookup finds).
    fn name(&self) -> Cow<'_, str> {
        match Expr::name(*self) {
            Some(n) => Cow::Owned(n),
            None => Cow::Owned(self.to_string()),
        }
    }
}

impl Named for Signal {
    fn name(&self) -> Cow<'_, str> {
        Named::name(&self.0)
    }
}

impl<N: Named + ?Sized> Named for &N {
    fn name(&self) -> Cow<'_, str> {
        (**self).name()
    }
}

/// The names of a list of [`Named`] things.
pub fn names<N: Named>(items: &[N]) -> Vec<String> {
    items.iter().map(|n| n.name().into_owned()).collect()
}
