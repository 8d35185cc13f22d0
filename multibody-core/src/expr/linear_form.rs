//! The coefficients of an expression that is linear in chosen leaves, in one pass.
//!
//! Sorting a linear block needs the coefficient of every block unknown in every
//! equation. Differentiating once per unknown walks (and rebuilds) the whole equation
//! each time. One walk
//! that splits each node into `rest + sum(coefficient * unknown)` keeps the subtrees
//! free of unknowns as they are and builds only what the unknowns touch.

use crate::hash::HashMap;

use super::{Arena, Id, Node};

/// `expression = rest + sum(coefficient * unknown)`, the coefficients and `rest` free
/// of the unknowns.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearForm {
    /// `(unknown, coefficient)`, each unknown once, in the order of first appearance
    /// (depth first); an unknown whose terms cancel is absent.
    pub coefficients: Vec<(usize, Id)>,
    /// The part free of the unknowns.
    pub rest: Id,
}

impl LinearForm {
    fn free(e: Id) -> Self {
        LinearForm {
            coefficients: Vec::new(),
            rest: e,
        }
    }
}

impl Arena {
    /// `e` as `rest + sum(coefficient * unknown)`, where `unknown(leaf)` numbers the
    /// leaves to collect (a `der(x)` leaf counts on its own, as in [`Arena::diff`]);
    /// `None` when `e` is not linear in them (a product of two of them, a power, one
    /// inside a function or a condition), and when all the unknowns of a sum in it
    /// cancel (`c (x + y) - c x - c y`: the node still holds them). The coefficients are
    /// those [`Arena::diff`] gives.
    pub fn linear_form(
        &mut self,
        e: Id,
        unknown: &dyn Fn(Id) -> Option<usize>,
    ) -> Option<LinearForm> {
        let mut memo = HashMap::default();
        self.linear_form_rec(e, unknown, true, &mut memo)
    }

    /// The coefficients of [`linear_form`](Self::linear_form) for each of `es`, sharing
    /// the work on their common subexpressions; the rest is not built.
    pub fn linear_coefficients(
        &mut self,
        es: &[Id],
        unknown: &dyn Fn(Id) -> Option<usize>,
    ) -> Vec<Option<Vec<(usize, Id)>>> {
        let mut memo = HashMap::default();
        es.iter()
            .map(|&e| {
                self.linear_form_rec(e, unknown, false, &mut memo)
                    .map(|f| f.coefficients)
            })
            .collect()
    }

    /// The form of `e`; its `rest` is left at 0 unless `with_rest`.
    fn linear_form_rec(
        &mut self,
        e: Id,
        unknown: &dyn Fn(Id) -> Option<usize>,
        with_rest: bool,
        memo: &mut HashMap<Id, Option<LinearForm>>,
    ) -> Option<LinearForm> {
        let node = *self.node(e);
        match node {
            Node::Const(_) => return Some(LinearForm::free(e)),
            Node::Var(_) | Node::Param(_) | Node::Time | Node::Der(_) => {
                return Some(match unknown(e) {
                    Some(j) => LinearForm {
                        coefficients: vec![(j, self.one())],
                        rest: self.zero(),
                    },
                    None => LinearForm::free(e),
                });
            }
            _ => {}
        }
        if let Some(f) = memo.get(&e) {
            return f.clone();
        }
        let form = match node {
            Node::Const(_) | Node::Var(_) | Node::Param(_) | Node::Time | Node::Der(_) => {
                unreachable!("leaves return above")
            }
            Node::Sum(ts, c) => {
                // The terms holding unknowns (few): the rest are kept as they are. The
                // pool only grows, so the range stays valid while the terms are read.
                let mut linear_terms: Vec<(usize, LinearForm)> = Vec::new();
                for idx in 0..ts.len() {
                    let (_, t) = self.terms(ts)[idx];
                    match self.linear_form_rec(t, unknown, with_rest, memo) {
                        Some(f) if f.coefficients.is_empty() => {}
                        Some(f) => linear_terms.push((idx, f)),
                        None => return remember(e, None, memo),
                    }
                }
                if linear_terms.is_empty() {
                    Some(LinearForm::free(e))
                } else {
                    let form = self.sum_of_forms(ts, f64::from_bits(c), &linear_terms, with_rest);
                    // Unknowns whose terms cancel are still in the node (the arena does
                    // not distribute `c (x + y) - c x`): it is not free of them, so no
                    // form; the caller differentiates instead.
                    (!form.coefficients.is_empty()).then_some(form)
                }
            }
            Node::Prod(fs) => {
                let mut linear_factor = None;
                for idx in 0..fs.len() {
                    let (b, n) = self.factors(fs)[idx];
                    let Some(f) = self.linear_form_rec(b, unknown, with_rest, memo) else {
                        return remember(e, None, memo);
                    };
                    if !f.coefficients.is_empty() {
                        if linear_factor.is_some() || n != 1 {
                            return remember(e, None, memo);
                        }
                        linear_factor = Some((idx, f));
                    }
                }
                match linear_factor {
                    None => Some(LinearForm::free(e)),
                    Some((i, f)) => {
                        let fs = self.factors(fs).to_vec();
                        let others: Vec<Id> = fs
                            .iter()
                            .enumerate()
                            .filter(|&(j, _)| j != i)
                            .map(|(_, &(b, n))| self.powi(b, n))
                            .collect();
                        let scale = self.product(&others);
                        let coefficients = f
                            .coefficients
                            .iter()
                            .map(|&(j, a)| (j, self.product(&[scale, a])))
                            .collect();
                        let rest = if with_rest {
                            self.product(&[scale, f.rest])
                        } else {
                            self.zero()
                        };
                        Some(LinearForm { coefficients, rest })
                    }
                }
            }
            Node::Pow(a, b) | Node::F2(_, a, b) | Node::Cmp(_, a, b) => {
                self.free_of_unknowns(e, &[a, b], unknown, with_rest, memo)
            }
            Node::F1(_, a) => self.free_of_unknowns(e, &[a], unknown, with_rest, memo),
            Node::If(c, a, b) => self.free_of_unknowns(e, &[c, a, b], unknown, with_rest, memo),
        };
        remember(e, form, memo)
    }

    /// The sum node with terms `ts` and `constant`, where the terms at the indices of
    /// `linear_terms` have those forms (the others are free of the unknowns), as one
    /// form: coefficients merged per unknown (the rest only `with_rest`).
    fn sum_of_forms(
        &mut self,
        ts: super::Operands,
        constant: f64,
        linear_terms: &[(usize, LinearForm)],
        with_rest: bool,
    ) -> LinearForm {
        let rest = if with_rest {
            let mut rest_terms: Vec<(f64, Id)> = self
                .terms(ts)
                .iter()
                .map(|&(k, t)| (f64::from_bits(k), t))
                .collect();
            for (idx, f) in linear_terms {
                rest_terms[*idx].1 = f.rest;
            }
            self.linear_combination(constant, &rest_terms)
        } else {
            self.zero()
        };
        let mut coefficients: Vec<(usize, Id)> = Vec::new();
        let mut done = Vec::new();
        for (n, (_, f)) in linear_terms.iter().enumerate() {
            for &(j, _) in &f.coefficients {
                if done.contains(&j) {
                    continue;
                }
                done.push(j);
                // Every term's coefficient of unknown j, scaled by the term's factor.
                let terms: Vec<(f64, Id)> = linear_terms[n..]
                    .iter()
                    .filter_map(|(idx, g)| {
                        let k = f64::from_bits(self.terms(ts)[*idx].0);
                        g.coefficients.iter().find(|c| c.0 == j).map(|c| (k, c.1))
                    })
                    .collect();
                let a = self.linear_combination(0.0, &terms);
                if self.as_const(a) != Some(0.0) {
                    coefficients.push((j, a));
                }
            }
        }
        LinearForm { coefficients, rest }
    }

    /// `e` as free of the unknowns if its `operands` are, else `None`.
    fn free_of_unknowns(
        &mut self,
        e: Id,
        operands: &[Id],
        unknown: &dyn Fn(Id) -> Option<usize>,
        with_rest: bool,
        memo: &mut HashMap<Id, Option<LinearForm>>,
    ) -> Option<LinearForm> {
        for &a in operands {
            match self.linear_form_rec(a, unknown, with_rest, memo) {
                Some(f) if f.coefficients.is_empty() => {}
                _ => return None,
            }
        }
        Some(LinearForm::free(e))
    }
}

/// Records the form of `e` and returns it.
fn remember(
    e: Id,
    form: Option<LinearForm>,
    memo: &mut HashMap<Id, Option<LinearForm>>,
) -> Option<LinearForm> {
    memo.insert(e, form.clone());
    form
}
