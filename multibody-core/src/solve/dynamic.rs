//! Dynamic state selection at run time: which candidates each group of dynamic states
//! selects, when to change, and the point the integration restarts from.
//!
//! The quality of a selection `S` of a group (one candidate per state) is how strongly
//! the velocities of all candidates depend on those of the selected ones: with
//! `N = d(der(q)) / d(xd)` (a column per state, computed from the observed function
//! with unit state velocities), it is `max |N N_S^-1|`, at least 1. Where the selected
//! candidates cannot parametrize the constraints, it grows without bound. After every
//! step the current selection is compared with the best one (greedy largest volume of
//! the rows of `N`), and the solver switches when the best is clearly better.

use crate::codegen::dae::InputLayout;
use crate::codegen::{Tape, Workspace};
use crate::simplify::dynamic_states::{DynamicStateGroup, GroupOutputs, StaticGroup};

/// A static choice whose measure exceeds this has degraded: the model is solved with
/// dynamic states instead.
const STATIC_LIMIT: f64 = 8.0;
/// Switch when the current selection's measure exceeds the best one's by this factor.
const HYSTERESIS: f64 = 2.0;
/// ... and is at least this large (any selection is good enough below).
const GOOD_ENOUGH: f64 = 2.0;

/// Evaluates the observed function around a point.
pub(crate) struct Observer<'a> {
    tape: &'a Tape,
    layout: InputLayout,
    ws: Workspace,
    inputs: Vec<f64>,
    /// Outputs at the point itself.
    pub(crate) base: Vec<f64>,
    out: Vec<f64>,
    /// The signals that drive the model's inputs.
    drivers: super::inputs::Drivers,
}

impl<'a> Observer<'a> {
    pub(crate) fn new(tape: &'a Tape, layout: InputLayout) -> Self {
        Observer {
            tape,
            layout,
            ws: tape.workspace(),
            inputs: vec![0.0; layout.len()],
            base: vec![0.0; tape.n_outputs()],
            out: vec![0.0; tape.n_outputs()],
            drivers: Default::default(),
        }
    }

    /// The same observer with the model's inputs driven by `drivers`.
    pub(crate) fn with_drivers(mut self, drivers: super::inputs::Drivers) -> Self {
        self.drivers = drivers;
        self
    }

    /// Loads the point `(t, y, yp)` with parameters `params` and evaluates `base`;
    /// false when the observed function fails there.
    pub(crate) fn load(&mut self, t: f64, y: &[f64], yp: &[f64], params: &[f64]) -> bool {
        let l = self.layout;
        self.inputs[InputLayout::TIME] = t;
        for (j, &p) in params.iter().enumerate().take(l.n_params) {
            self.inputs[l.param(j)] = p;
        }
        for k in 0..l.n {
            self.inputs[l.u(k)] = y[k];
            self.inputs[l.up(k)] = yp[k];
        }
        if self.drivers.load(t, &mut self.inputs, l).is_err() {
            return false;
        }
        self.tape
            .eval(&self.inputs, &mut self.ws, &mut self.base)
            .is_ok()
            && self.base.iter().all(|v| v.is_finite())
    }

    /// `N` of a group at the loaded point: per candidate, its velocity's change per unit
    /// change of each velocity state (row-major, `k x s`).
    fn sensitivity(&mut self, outputs: &GroupOutputs) -> Option<Vec<f64>> {
        let l = self.layout;
        let (k, s) = (outputs.derivative.len(), outputs.velocity_state.len());
        let mut n = vec![0.0; k * s];
        for j in 0..s {
            let slot = l.u(outputs.velocity_state[j]);
            let saved = self.inputs[slot];
            self.inputs[slot] = saved + 1.0;
            let ok = self
                .tape
                .eval(&self.inputs, &mut self.ws, &mut self.out)
                .is_ok();
            self.inputs[slot] = saved;
            if !ok {
                return None;
            }
            for i in 0..k {
                let d = outputs.derivative[i];
                n[i * s + j] = self.out[d] - self.base[d];
            }
        }
        n.iter().all(|v| v.is_finite()).then_some(n)
    }
}

/// `max |N N_S^-1|` for the selection `sel` (rows of `n`, `k x s`); infinite when
/// `N_S` is singular.
fn measure(n: &[f64], s: usize, sel: &[usize]) -> f64 {
    let k = n.len() / s;
    // Solve N_S^T Z = N^T, i.e. rows z_i = n_i N_S^-1, by Gaussian elimination with
    // partial pivoting on N_S^T (s x s).
    let mut a = vec![0.0; s * s];
    for (r, &i) in sel.iter().enumerate() {
        for c in 0..s {
            // a = N_S^T: a[c][r] = N[i][c]
            a[c * s + r] = n[i * s + c];
        }
    }
    let mut perm: Vec<usize> = (0..s).collect();
    for col in 0..s {
        let p = (col..s)
            .max_by(|&x, &y| a[x * s + col].abs().total_cmp(&a[y * s + col].abs()))
            .expect("a row");
        if a[p * s + col].abs() < 1e-300 {
            return f64::INFINITY;
        }
        if p != col {
            for c in 0..s {
                a.swap(p * s + c, col * s + c);
            }
            perm.swap(p, col);
        }
        for r in col + 1..s {
            let f = a[r * s + col] / a[col * s + col];
            for c in col..s {
                a[r * s + c] -= f * a[col * s + c];
            }
            a[r * s + col] = f;
        }
    }
    let mut worst: f64 = 0.0;
    let mut b = vec![0.0; s];
    for i in 0..k {
        // b = P n_i^T, forward and back substitution.
        for (r, &pr) in perm.iter().enumerate() {
            b[r] = n[i * s + pr];
        }
        for r in 0..s {
            for c in 0..r {
                b[r] -= a[r * s + c] * b[c];
            }
        }
        for r in (0..s).rev() {
            for c in r + 1..s {
                b[r] -= a[r * s + c] * b[c];
            }
            b[r] /= a[r * s + r];
        }
        worst = b.iter().fold(worst, |w, v| w.max(v.abs()));
    }
    worst
}

/// The selection of largest volume, chosen greedily: rows of `n` by the length of what
/// they add to those chosen before, each weighted by `weights` (the candidates'
/// preference).
fn best_selection(n: &[f64], s: usize, weights: &[f64]) -> Vec<usize> {
    let k = n.len() / s;
    let mut rows: Vec<Vec<f64>> = (0..k)
        .map(|i| {
            n[i * s..(i + 1) * s]
                .iter()
                .map(|v| v * weights[i])
                .collect()
        })
        .collect();
    let mut chosen = Vec::with_capacity(s);
    for _ in 0..s {
        let norm = |r: &Vec<f64>| r.iter().map(|v| v * v).sum::<f64>();
        let Some(best) = (0..k)
            .filter(|i| !chosen.contains(i))
            .max_by(|&a, &b| norm(&rows[a]).total_cmp(&norm(&rows[b])))
        else {
            break;
        };
        chosen.push(best);
        let pivot = rows[best].clone();
        let p2 = norm(&pivot);
        if p2 == 0.0 {
            continue;
        }
        for (i, r) in rows.iter_mut().enumerate() {
            if i == best || chosen.contains(&i) {
                continue;
            }
            let f = r.iter().zip(&pivot).map(|(a, b)| a * b).sum::<f64>() / p2;
            for (a, b) in r.iter_mut().zip(&pivot) {
                *a -= f * b;
            }
        }
    }
    chosen
}

/// What the monitor decided at a point.
pub(crate) struct Decision {
    /// The new selection of each group (the current one where it stays).
    pub selections: Vec<Vec<usize>>,
}

/// Decides after each step whether a group should select other candidates.
pub(crate) fn check(
    observer: &mut Observer<'_>,
    groups: &[DynamicStateGroup],
    t: f64,
    y: &[f64],
    yp: &[f64],
    params: &[f64],
) -> Option<Decision> {
    if !observer.load(t, y, yp, params) {
        return None;
    }
    let mut selections = Vec::with_capacity(groups.len());
    let mut change = false;
    for g in groups {
        let current = g.selected(params);
        let s = g.n_states();
        let Some(n) = observer.sensitivity(&g.outputs) else {
            selections.push(current);
            continue;
        };
        let now = measure(&n, s, &current);
        if now <= GOOD_ENOUGH {
            selections.push(current);
            continue;
        }
        let weights: Vec<f64> = g
            .priorities
            .iter()
            .map(|p| 1.0 + p.max(0.0) / 10.0)
            .collect();
        let mut best = best_selection(&n, s, &weights);
        best.sort_unstable();
        let better = measure(&n, s, &best);
        if now > HYSTERESIS * better {
            log::debug!(
                "dynamic state selection at t = {t}: candidates {best:?} (measure {better:.3}) \
                 replace {current:?} (measure {now:.3})"
            );
            selections.push(best);
            change = true;
        } else {
            selections.push(current);
        }
    }
    change.then_some(Decision { selections })
}

/// Whether the static choice of a group has degraded at the point (`t`, `y`, `yp`): its
/// measure is large, or it cannot be evaluated.
pub(crate) fn static_degraded(
    observer: &mut Observer<'_>,
    groups: &[StaticGroup],
    t: f64,
    y: &[f64],
    yp: &[f64],
    params: &[f64],
) -> bool {
    if !observer.load(t, y, yp, params) {
        return true;
    }
    groups.iter().any(|g| {
        let s = g.chosen().len();
        match observer.sensitivity(&g.outputs) {
            Some(n) => {
                let m = measure(&n, s, g.chosen());
                if m > STATIC_LIMIT {
                    log::debug!("at t = {t} the static choice of states measures {m:.3}");
                }
                m > STATIC_LIMIT
            }
            None => true,
        }
    })
}

/// The point the integration restarts from after the groups switch to `selections`
/// (parameters already set in `params`): the same configuration, the dynamic states
/// now the newly selected candidates, their derivatives the candidates' velocities and
/// accelerations. `observer` must hold the point (`load`).
pub(crate) fn restart_point(
    observer: &Observer<'_>,
    groups: &[DynamicStateGroup],
    selections: &[Vec<usize>],
    y: &[f64],
    yp: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let (mut y, mut yp) = (y.to_vec(), yp.to_vec());
    let base = &observer.base;
    for (g, sel) in groups.iter().zip(selections) {
        for (j, &i) in sel.iter().enumerate() {
            let o = &g.outputs;
            let (x, xd) = (o.state[j], o.velocity_state[j]);
            y[x] = base[o.candidate[i]];
            y[xd] = base[o.derivative[i]];
            yp[x] = y[xd];
            if let Some(&a) = base.get(o.acceleration[i]) {
                yp[xd] = a;
            }
        }
    }
    (y, yp)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_measure_is_one_for_a_selection_that_maps_straight_and_grows_near_singularity() {
        // Candidates (q1, q2) with q2' = 3 q1': selecting q1 measures 3, q2 measures 1.
        let n = [1.0, 3.0];
        assert_eq!(measure(&n, 1, &[0]), 3.0);
        assert!((measure(&n, 1, &[1]) - 1.0).abs() < 1e-15);
        assert_eq!(best_selection(&n, 1, &[1.0; 2]), vec![1]);
        // Two states among three candidates, the third the sum of the first two.
        let n = [1.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        assert!((measure(&n, 2, &[0, 1]) - 1.0).abs() < 1e-15);
        assert!((measure(&n, 2, &[0, 2]) - 1.0).abs() < 1e-15);
        // Nearly parallel rows make a poor pair.
        let n = [1.0, 0.0, 1.0, 1e-6, 0.0, 1.0];
        assert!(measure(&n, 2, &[0, 1]) > 1e5);
        let mut best = best_selection(&n, 2, &[1.0; 3]);
        best.sort_unstable();
        assert!(best == vec![0, 2] || best == vec![1, 2], "{best:?}");
        // A singular selection measures infinity.
        assert_eq!(measure(&[1.0, 1.0, 2.0, 2.0], 2, &[0, 1]), f64::INFINITY);
    }
}
