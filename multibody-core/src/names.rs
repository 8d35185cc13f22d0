//! Names: lookup by name, and suggestions for messages about unknown names.

use std::sync::OnceLock;

use crate::model::SharedText;

use crate::hash::HashMap;

/// A list of names with a lookup by name that is built on the first lookup, so a
/// system compiled once and solved many times hashes its names once, and one that is
/// never asked for a name by its text never hashes them at all. The list itself may be
/// made on first use too ([`NameIndex::lazy`]): compiling a large model then touches
/// none of its names.
#[derive(Default)]
pub struct NameIndex {
    names: OnceLock<Vec<SharedText>>,
    /// What makes `names` when it is first asked for (`None` when they were given).
    source: Option<NameSource>,
    /// The index of `names` (the first of equal names wins a lookup).
    index: OnceLock<HashMap<SharedText, usize>>,
}

/// A function that lists names.
type NameSource = Box<dyn Fn() -> Vec<SharedText> + Send + Sync>;

impl std::fmt::Debug for NameIndex {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("NameIndex")
            .field("names", &self.names.get())
            .finish_non_exhaustive()
    }
}

impl NameIndex {
    /// An index of these names.
    pub fn new(names: Vec<SharedText>) -> Self {
        NameIndex {
            names: OnceLock::from(names),
            source: None,
            index: OnceLock::new(),
        }
    }

    /// An index whose names `source` lists when they are first asked for.
    pub fn lazy(source: impl Fn() -> Vec<SharedText> + Send + Sync + 'static) -> Self {
        NameIndex {
            names: OnceLock::new(),
            source: Some(Box::new(source)),
            index: OnceLock::new(),
        }
    }

    /// The names, in order.
    pub fn names(&self) -> &[SharedText] {
        self.names
            .get_or_init(|| self.source.as_ref().map(|f| f()).unwrap_or_default())
    }

    /// The position of `name` (the first of equal names wins).
    pub fn position(&self, name: &str) -> Option<usize> {
        let index = self.index.get_or_init(|| {
            let names = self.names();
            let mut map = HashMap::default();
            map.reserve(names.len());
            for (i, n) in names.iter().enumerate() {
                map.entry(n.clone()).or_insert(i);
            }
            map
        });
        index.get(name).copied()
    }

    /// Up to `n` names closest to `name` (see [`closest`]).
    pub fn closest(&self, name: &str, n: usize) -> Vec<String> {
        closest(name, self.names().iter().map(|s| &**s), n)
    }
}

/// Edit distance between two strings (Levenshtein, by characters).
pub fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut cur = vec![0; b.len() + 1];
    for i in 1..=a.len() {
        cur[0] = i;
        for j in 1..=b.len() {
            let sub = prev[j - 1] + usize::from(a[i - 1] != b[j - 1]);
            cur[j] = sub.min(prev[j] + 1).min(cur[j - 1] + 1);
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len()]
}

/// Up to `n` candidates closest to `name`, nearest first (ties in the candidates' order).
///
/// Paths are compared as paths: a candidate that keeps `name`'s first and last component
/// and adds components between them (`b1.body.m` for `b1.m`) comes first, fewer added
/// first; then candidates of the same first component (the same instance) close in the
/// rest; then the others: those ending in `name`'s last component by how far their
/// instances are, the rest by edit distance.
pub fn closest<'a>(
    name: &str,
    candidates: impl IntoIterator<Item = &'a str>,
    n: usize,
) -> Vec<String> {
    let mut scored: Vec<((usize, usize), usize, &str)> = candidates
        .into_iter()
        .enumerate()
        .map(|(i, c)| (path_distance(name, c), i, c))
        .collect();
    scored.sort();
    let mut out: Vec<String> = Vec::with_capacity(n);
    for (_, _, c) in scored {
        if out.len() == n {
            break;
        }
        if !out.iter().any(|o| o == c) {
            out.push(c.to_string());
        }
    }
    out
}

/// How far candidate `c` is from `name`: (tier, distance within the tier), see
/// [`closest`].
fn path_distance(name: &str, c: &str) -> (usize, usize) {
    let (first, last) = (first_component(name), last_component(name));
    let (c_first, c_last) = (first_component(c), last_component(c));
    let name_parts = name.split('.').count();
    let c_parts = c.split('.').count();
    if name_parts >= 2 && first == c_first && last == c_last && c_parts > name_parts {
        return (0, c_parts - name_parts);
    }
    if name_parts >= 2 && first == c_first {
        let rest = &name[first.len()..];
        let d = edit_distance(rest, &c[c_first.len()..]);
        if 2 * d <= rest.chars().count().max(4) {
            return (1, d);
        }
    }
    if c_last == last && name_parts >= 2 {
        // The same quantity of another instance: how far the instances are apart.
        let d = edit_distance(first, c_first) + c_parts.abs_diff(name_parts);
        return (2, d.saturating_sub(1));
    }
    (2, edit_distance(name, c))
}

/// `a` of `a.b.c` (up to an index: `a` of `a[2].b`).
fn first_component(path: &str) -> &str {
    path.split(['.', '[']).next().unwrap_or(path)
}

/// `c` of `a.b.c`.
fn last_component(path: &str) -> &str {
    path.rsplit('.').next().unwrap_or(path)
}

/// `text`, or, when it is longer than `max` characters, its beginning and the number of
/// characters left out (`a = b + ... (1 400 more characters)`).
pub fn elide(text: &str, max: usize) -> String {
    let n = text.chars().count();
    if n <= max {
        return text.to_string();
    }
    let head: String = text.chars().take(max).collect();
    format!("{head} ... ({} more characters)", n - max)
}

/// Formats a list of names as `a, b, c` (at most `max` of them, then `... (N more)`).
pub fn list(names: &[String], max: usize) -> String {
    if names.len() <= max {
        names.join(", ")
    } else {
        format!(
            "{}, ... ({} more)",
            names[..max].join(", "),
            names.len() - max
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_and_suggestions() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        let c = ["j1.phi", "j1.w", "j2.s", "j2.v"];
        assert_eq!(closest("j1.ph", c, 2), vec!["j1.phi", "j1.w"]);
        assert_eq!(closest("j3.s", c, 1), vec!["j2.s"]);
        // A component of an instance is found through its sub-component.
        let c = [
            "j1.w",
            "j1.a",
            "j2.s",
            "b1.body.m",
            "b1.frame_a.f[1]",
            "b2.body.m",
        ];
        assert_eq!(closest("b1.m", c, 2), vec!["b1.body.m", "b2.body.m"]);
        // A typo in the variable keeps to its instance.
        assert_eq!(closest("j1.ww", c, 1), vec!["j1.w"]);
        // A typo in the instance: edit distance over the whole path.
        assert_eq!(closest("b3.body.m", c, 2), vec!["b1.body.m", "b2.body.m"]);
        assert_eq!(
            list(&["a".into(), "b".into(), "c".into()], 2),
            "a, b, ... (1 more)"
        );
    }

    #[test]
    fn name_index_finds_positions_and_suggests() {
        let names: Vec<SharedText> = ["j1.phi", "j1.w", "j2.s", "j1.phi"]
            .iter()
            .map(|&s| SharedText::from(s))
            .collect();
        let index = NameIndex::new(names);
        assert_eq!(index.position("j2.s"), Some(2));
        // The first of equal names wins.
        assert_eq!(index.position("j1.phi"), Some(0));
        assert_eq!(index.position("j2.v"), None);
        assert_eq!(index.closest("j2.v", 1), vec!["j2.s"]);
        assert_eq!(index.names().len(), 4);
    }

    #[test]
    fn a_lazy_index_lists_its_names_once_on_first_use() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        let calls = std::sync::Arc::new(AtomicUsize::new(0));
        let counter = calls.clone();
        let index = NameIndex::lazy(move || {
            counter.fetch_add(1, Ordering::SeqCst);
            vec![SharedText::from("x"), SharedText::from("der(x)")]
        });
        assert_eq!(calls.load(Ordering::SeqCst), 0, "nothing listed before use");
        assert_eq!(index.position("der(x)"), Some(1));
        assert_eq!(index.names().len(), 2);
        assert_eq!(index.closest("der(y)", 1), vec!["der(x)"]);
        assert_eq!(calls.load(Ordering::SeqCst), 1, "listed once");
        assert!(NameIndex::default().names().is_empty());
    }
}

/// A number as messages write it: plainly when that is short (`0.25`, `1500`), in
/// scientific notation otherwise (`1e-300`, `2.5e12`).
pub fn number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e9).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

#[cfg(test)]
mod number_tests {
    use super::number;

    #[test]
    fn numbers_read_short() {
        assert_eq!(number(0.25), "0.25");
        assert_eq!(number(-1500.0), "-1500");
        assert_eq!(number(1e-300), "1e-300");
        assert_eq!(number(2.5e12), "2.5e12");
        assert_eq!(number(f64::NAN), "NaN");
        assert_eq!(number(0.0), "0");
    }
}
