//! Names, descriptions and units of variables and parameters: text that is almost
//! always a literal of a component's declaration or a name kept by the symbol table,
//! so it is kept as a `&'static str` when it is one (copying it touches no memory) and
//! shared behind an `Arc` otherwise.

use std::fmt;
use std::ops::Deref;
use std::sync::Arc;

/// A description or unit: a `&'static str` or a shared `Arc<str>`, read as a `str`.
///
/// Built from a string literal it costs nothing to copy; a model of 10 000 components
/// then keeps one copy of each description instead of one per component.
///
/// ```
/// use multibody_core::model::SharedText;
/// let unit = SharedText::from("rad/s");
/// let built = SharedText::from(format!("{}/s", "rad"));
/// assert_eq!(unit, built);
/// assert_eq!(&*unit, "rad/s");
/// assert!(SharedText::default().is_empty());
/// ```
#[derive(Clone)]
pub struct SharedText(Repr);

#[derive(Clone)]
enum Repr {
    Static(&'static str),
    Shared(Arc<str>),
}

impl SharedText {
    /// Whether the text is a `&'static str` (a literal, or a name kept by the symbol
    /// table): copying it touches no memory.
    pub fn is_static(&self) -> bool {
        matches!(self.0, Repr::Static(_))
    }

    /// The text.
    pub fn as_str(&self) -> &str {
        match &self.0 {
            Repr::Static(s) => s,
            Repr::Shared(s) => s,
        }
    }
}

impl Default for SharedText {
    /// The empty text.
    fn default() -> Self {
        SharedText(Repr::Static(""))
    }
}

impl Deref for SharedText {
    type Target = str;
    fn deref(&self) -> &str {
        self.as_str()
    }
}

impl AsRef<str> for SharedText {
    fn as_ref(&self) -> &str {
        self.as_str()
    }
}

impl From<&'static str> for SharedText {
    fn from(s: &'static str) -> Self {
        SharedText(Repr::Static(s))
    }
}

impl From<String> for SharedText {
    fn from(s: String) -> Self {
        SharedText(Repr::Shared(s.into()))
    }
}

impl From<Arc<str>> for SharedText {
    fn from(s: Arc<str>) -> Self {
        SharedText(Repr::Shared(s))
    }
}

impl std::borrow::Borrow<str> for SharedText {
    fn borrow(&self) -> &str {
        self.as_str()
    }
}

impl std::hash::Hash for SharedText {
    /// Hashes as the `str` it reads as (so a map keyed by texts is searched by `&str`).
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.as_str().hash(state)
    }
}

impl PartialEq for SharedText {
    fn eq(&self, other: &Self) -> bool {
        self.as_str() == other.as_str()
    }
}

impl Eq for SharedText {}

impl PartialEq<str> for SharedText {
    fn eq(&self, other: &str) -> bool {
        self.as_str() == other
    }
}

impl PartialEq<&str> for SharedText {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

impl fmt::Display for SharedText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl fmt::Debug for SharedText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self.as_str(), f)
    }
}

#[cfg(test)]
mod tests {
    use super::SharedText;

    #[test]
    fn literals_and_built_texts_compare_and_read_alike() {
        let a = SharedText::from("N.m");
        let b = SharedText::from(String::from("N.m"));
        let c = SharedText::from(std::sync::Arc::<str>::from("N.m"));
        assert_eq!(a, b);
        assert_eq!(b, c);
        assert_eq!(a, "N.m");
        assert_eq!(format!("{a} {b:?}"), "N.m \"N.m\"");
        assert_eq!(a.len(), 3);
        assert_ne!(a, SharedText::default());
        // A literal is not copied into a new allocation.
        let s: &'static str = "rad";
        assert_eq!(SharedText::from(s).as_str().as_ptr(), s.as_ptr());
    }
}
