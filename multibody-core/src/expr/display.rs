//! Readable infix display.

use super::{Arena, Id, Node};

/// Names the leaves of an arena when displaying.
pub trait NameResolver {
    /// Name of variable `i`.
    fn var(&self, i: u32) -> String;
    /// Name of parameter `i`.
    fn param(&self, i: u32) -> String;
}

/// Formats a number compactly: `2`, `0.5`, `1e-12`.
pub(crate) fn fmt_num(x: f64) -> String {
    let a = x.abs();
    if a == 0.0 || (1e-4..1e15).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

// Precedence levels: 0 comparison / if, 1 sum, 2 product, 3 power, 4 atom.
impl Arena {
    /// Infix text of `e` with leaf names from `names`.
    pub fn display(&self, e: Id, names: &dyn NameResolver) -> String {
        let mut s = String::new();
        self.fmt_rec(e, names, 0, &mut s);
        s
    }

    fn fmt_rec(&self, e: Id, names: &dyn NameResolver, outer: u8, s: &mut String) {
        let (prec, text) = self.fmt_node(e, names);
        if prec < outer {
            s.push('(');
            s.push_str(&text);
            s.push(')');
        } else {
            s.push_str(&text);
        }
    }

    fn sub_text(&self, e: Id, names: &dyn NameResolver, outer: u8) -> String {
        let mut s = String::new();
        self.fmt_rec(e, names, outer, &mut s);
        s
    }

    fn fmt_node(&self, e: Id, names: &dyn NameResolver) -> (u8, String) {
        match self.node(e) {
            Node::Const(b) => {
                let x = f64::from_bits(*b);
                (if x < 0.0 { 1 } else { 4 }, fmt_num(x))
            }
            Node::Var(i) => (4, names.var(*i)),
            Node::Param(i) => (4, names.param(*i)),
            Node::Time => (4, "time".into()),
            Node::Der(x) => (4, format!("der({})", self.sub_text(*x, names, 0))),
            Node::Sum(ts, c) => {
                let mut out = String::new();
                for (i, &(k, t)) in self.terms(*ts).iter().enumerate() {
                    let k = f64::from_bits(k);
                    let body = self.sub_text(t, names, 2);
                    let mag = k.abs();
                    let term = if mag == 1.0 {
                        body
                    } else {
                        format!("{}*{}", fmt_num(mag), body)
                    };
                    if i == 0 {
                        if k < 0.0 {
                            out.push('-');
                        }
                    } else {
                        out.push_str(if k < 0.0 { " - " } else { " + " });
                    }
                    out.push_str(&term);
                }
                let c = f64::from_bits(*c);
                if c != 0.0 {
                    out.push_str(if c < 0.0 { " - " } else { " + " });
                    out.push_str(&fmt_num(c.abs()));
                }
                (1, out)
            }
            Node::Prod(fs) => {
                let fmt_factor = |b: Id, n: i32| {
                    if n == 1 {
                        self.sub_text(b, names, 3)
                    } else {
                        format!("{}^{}", self.sub_text(b, names, 4), n)
                    }
                };
                let num: Vec<String> = self
                    .factors(*fs)
                    .iter()
                    .filter(|f| f.1 > 0)
                    .map(|&(b, n)| fmt_factor(b, n))
                    .collect();
                let den: Vec<String> = self
                    .factors(*fs)
                    .iter()
                    .filter(|f| f.1 < 0)
                    .map(|&(b, n)| fmt_factor(b, -n))
                    .collect();
                let mut out = if num.is_empty() {
                    "1".to_string()
                } else {
                    num.join("*")
                };
                if !den.is_empty() {
                    out.push('/');
                    if den.len() == 1 {
                        out.push_str(&den[0]);
                    } else {
                        out.push('(');
                        out.push_str(&den.join("*"));
                        out.push(')');
                    }
                }
                (2, out)
            }
            Node::Pow(a, b) => (
                3,
                format!(
                    "{}^{}",
                    self.sub_text(*a, names, 4),
                    self.sub_text(*b, names, 4)
                ),
            ),
            Node::F1(f, a) => (4, format!("{}({})", f.name(), self.sub_text(*a, names, 0))),
            Node::F2(f, a, b) => (
                4,
                format!(
                    "{}({}, {})",
                    f.name(),
                    self.sub_text(*a, names, 0),
                    self.sub_text(*b, names, 0)
                ),
            ),
            Node::Cmp(op, a, b) => (
                0,
                format!(
                    "{} {} {}",
                    self.sub_text(*a, names, 1),
                    op.symbol(),
                    self.sub_text(*b, names, 1)
                ),
            ),
            Node::If(c, a, b) => (
                0,
                format!(
                    "if {} then {} else {}",
                    self.sub_text(*c, names, 0),
                    self.sub_text(*a, names, 1),
                    self.sub_text(*b, names, 1)
                ),
            ),
        }
    }
}
