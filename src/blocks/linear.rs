//! Linear blocks whose number of states follows from their parameters (MSL
//! `Blocks.Continuous.TransferFunction`, `StateSpace`, `CriticalDamping`): their states
//! are a [`StateVector`] sub-component.

use super::interfaces::*;
use crate::prelude::*;
use crate::{PathId, TypedComponent};

/// A vector of `n` unknowns `x[1]` .. `x[n]` (with start values), the states of a
/// linear block whose size is a structural parameter. Its variables are reached with
/// [`StateVectorHandle::x`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StateVector {
    /// Number of elements, default 0.
    pub n: usize,
    /// Start values (missing ones are 0), default none.
    pub start: Vec<f64>,
}

impl Component for StateVector {
    fn type_name(&self) -> String {
        "Blocks.StateVector".into()
    }

    fn build(&self, s: &mut System) {
        for i in 0..self.n {
            let start = self.start.get(i).copied().unwrap_or(0.0);
            s.variable(
                Variable::new(format!("x[{}]", i + 1))
                    .start(start)
                    .description(format!("state {}", i + 1)),
            );
        }
    }
}

/// Handle of a [`StateVector`] instance.
#[derive(Clone, Copy, Debug)]
pub struct StateVectorHandle {
    /// The instance's full path.
    pub path: PathId,
}

impl StateVectorHandle {
    /// Element `i` (from 0): the variable `x[i + 1]`.
    pub fn x(&self, i: usize) -> Expr {
        Expr::var(&multibody_core::model::member(
            &self.path.as_string(),
            &format!("x[{}]", i + 1),
        ))
    }
}

impl TypedComponent for StateVector {
    type Handle = StateVectorHandle;
    fn handle(path: &str) -> StateVectorHandle {
        StateVectorHandle {
            path: PathId::new(path),
        }
    }
}

/// `sum(a[i] x[i])` over the elements of `a`.
fn dot(a: &[f64], x: impl Fn(usize) -> Expr) -> Expr {
    a.iter()
        .enumerate()
        .fold(Expr::from(0.0), |acc, (i, &c)| acc + c * x(i))
}

/// The coefficients of [`TransferFunction`]: the numerator padded to the denominator's
/// length, the feed-through `d` and the scaling `a_end`.
fn transfer_coefficients(b: &[f64], a: &[f64]) -> (Vec<f64>, f64, f64) {
    let na = a.len();
    let mut bb = vec![0.0; na.saturating_sub(b.len())];
    bb.extend_from_slice(b);
    let d = bb.first().copied().unwrap_or(0.0) / a.first().copied().unwrap_or(1.0);
    let norm = a.iter().map(|v| v * v).sum::<f64>().sqrt();
    let last = a.last().copied().unwrap_or(1.0);
    let a_end = if last > 100.0 * f64::EPSILON * norm {
        last
    } else {
        1.0
    };
    (bb, d, a_end)
}

component! {
    /// A linear transfer function `y = (b[0] s^nb-1 + ... + b[nb-1]) / (a[0] s^na-1 + ...
    /// + a[na-1]) u` (MSL `Blocks.Continuous.TransferFunction`), in the controllable
    /// canonical form with states scaled by the last coefficient of `a` (`x_scaled`).
    #[type_name = "Blocks.TransferFunction"]
    pub struct TransferFunction {
        /// Numerator coefficients, highest power first, default `[1]`.
        structural b: Vec<f64> = vec![1.0];
        /// Denominator coefficients, highest power first (`a[0] != 0`), default `[1]`.
        structural a: Vec<f64> = vec![1.0];
        /// Initialization (MSL default: none).
        structural init: Init = Init::NoInit;
        /// Start values of the (unscaled) states, default 0.
        structural x_start: Vec<f64> = Vec::new();
        /// Start value of the output (with `Init::InitialOutput`), default 0.
        parameter y_start: f64 = 0.0;
        /// Input.
        connector u: RealInput;
        /// Output.
        connector y: RealOutput;
        /// The states, `x_scaled = x a_end`.
        component x_scaled: StateVector = StateVector {
            n: self.a.len().saturating_sub(1),
            start: {
                let (_, _, a_end) = transfer_coefficients(&self.b, &self.a);
                self.x_start.iter().map(|v| v * a_end).collect()
            },
        };
        equation {
            assert(!a.is_empty() && a[0] != 0.0, "a needs a nonzero first coefficient");
            assert(b.len() <= a.len(), "the transfer function must be proper: b no longer than a");
            let (bb, d, a_end) = transfer_coefficients(&b, &a);
            let nx = a.len().saturating_sub(1);
            let xs = |i: usize| x_scaled.x(i);
            if nx == 0 {
                y = d * u;
            } else {
                der(xs(0)) = (-dot(&a[1..], xs) + a_end * u) / a[0];
                for i in 1..nx {
                    der(xs(i)) = xs(i - 1);
                }
                let c: Vec<f64> = (1..a.len()).map(|i| bb[i] - d * a[i]).collect();
                y = dot(&c, xs) / a_end + d * u;
            }
        }
        initial_equation {
            let (_, _, a_end) = transfer_coefficients(&b, &a);
            let nx = a.len().saturating_sub(1);
            match init {
                Init::InitialState => {
                    for i in 0..nx {
                        x_scaled.x(i) = x_start.get(i).copied().unwrap_or(0.0) * a_end;
                    }
                }
                Init::SteadyState => {
                    for i in 0..nx {
                        der(x_scaled.x(i)) = 0.0;
                    }
                }
                Init::InitialOutput => {
                    y = y_start;
                    for i in 1..nx {
                        der(x_scaled.x(i)) = 0.0;
                    }
                }
                Init::NoInit => {}
            }
        }
    }
}

component! {
    /// A single-input, single-output linear system `der(x) = A x + B u`, `y = C x + D u`
    /// (MSL `Blocks.Continuous.StateSpace` with one input and one output).
    #[type_name = "Blocks.StateSpace"]
    pub struct StateSpace {
        /// System matrix, rows of `n`, default `[[1]]`.
        structural A: Vec<Vec<f64>> = vec![vec![1.0]];
        /// Input vector (`n`), default `[1]`.
        structural B: Vec<f64> = vec![1.0];
        /// Output vector (`n`), default `[1]`.
        structural C: Vec<f64> = vec![1.0];
        /// Feed-through, default 0.
        parameter D: f64 = 0.0;
        /// Initialization (MSL default: none).
        structural init: Init = Init::NoInit;
        /// Start values of the states, default 0.
        structural x_start: Vec<f64> = Vec::new();
        /// Input.
        connector u: RealInput;
        /// Output.
        connector y: RealOutput;
        /// The states.
        component x: StateVector = StateVector { n: self.A.len(), start: self.x_start.clone() };
        equation {
            let n = A.len();
            assert(
                A.iter().all(|r| r.len() == n) && B.len() == n && C.len() == n,
                "A must be n x n and B, C of length n"
            );
            if A.iter().all(|r| r.len() == n) && B.len() == n && C.len() == n {
                let xi = |i: usize| x.x(i);
                for i in 0..n {
                    der(xi(i)) = dot(&A[i], xi) + B[i] * u;
                }
                y = dot(&C, xi) + D * u;
            } else {
                y = D * u;
            }
        }
        initial_equation {
            let n = A.len();
            match init {
                Init::InitialState => {
                    for i in 0..n {
                        x.x(i) = x_start.get(i).copied().unwrap_or(0.0);
                    }
                }
                Init::SteadyState => {
                    for i in 0..n {
                        der(x.x(i)) = 0.0;
                    }
                }
                Init::InitialOutput | Init::NoInit => {}
            }
        }
    }
}

/// `alpha` of [`CriticalDamping`]: `sqrt(2^(1/n) - 1)` normalized (the amplitude is
/// 1/sqrt(2) at `f`), else 1.
fn critical_alpha(n: usize, normalized: bool) -> f64 {
    if normalized {
        (2f64.powf(1.0 / n.max(1) as f64) - 1.0).sqrt()
    } else {
        1.0
    }
}

component! {
    /// `n` equal first-order lags in a row (MSL `Blocks.Continuous.CriticalDamping`): a
    /// filter without overshoot; with `normalized` its amplitude is 1/sqrt(2) at the
    /// cut-off frequency `f`, else each lag has `f`.
    #[type_name = "Blocks.CriticalDamping"]
    pub struct CriticalDamping {
        /// Order of the filter (at least 1), default 2.
        structural n: usize = 2;
        /// Cut-off frequency [Hz], default 1.
        parameter f(min = 0.0): f64 = 1.0;
        /// Whether `f` is the filter's -3 dB frequency (default true).
        structural normalized: bool = true;
        /// Initialization (MSL default: none).
        structural init: Init = Init::NoInit;
        /// Start values of the states, default 0.
        structural x_start: Vec<f64> = Vec::new();
        /// Input.
        connector u: RealInput;
        /// Output.
        connector y: RealOutput;
        /// The lags' outputs.
        component x: StateVector = StateVector { n: self.n, start: self.x_start.clone() };
        equation {
            assert(n >= 1, "the order n must be at least 1");
            let w = 2.0 * PI * f / critical_alpha(n, normalized);
            if n >= 1 {
                der(x.x(0)) = (u - x.x(0)) * w;
                for i in 1..n {
                    der(x.x(i)) = (x.x(i - 1) - x.x(i)) * w;
                }
                y = x.x(n - 1);
            } else {
                y = u;
            }
        }
        initial_equation {
            match init {
                Init::InitialState => {
                    for i in 0..n {
                        x.x(i) = x_start.get(i).copied().unwrap_or(0.0);
                    }
                }
                Init::SteadyState => {
                    for i in 0..n {
                        der(x.x(i)) = 0.0;
                    }
                }
                Init::InitialOutput => {
                    y = x_start.last().copied().unwrap_or(0.0);
                }
                Init::NoInit => {}
            }
        }
    }
}
