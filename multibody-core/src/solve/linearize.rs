//! Linearization of a simplified system at an operating point: the state-space model
//! `dx = A x + B u`, `y = C x + D u` in the system's states, exact (forward-mode
//! derivatives of the compiled residual and observed functions through every block
//! solved inside), the algebraic unknowns eliminated.
//!
//! The DAE `F(t, v, v', p) = 0` is linearized in its unknowns `v` (the states `x`, whose
//! derivatives appear, and the algebraic unknowns `z`), their derivatives and the
//! parameters chosen as inputs: `F_v' dv' + F_v dv + F_p dp = 0`. Solving it for the
//! states' derivatives and the algebraic unknowns (an index-1 system at the point)
//! gives `A` and `B`; the observed outputs' derivatives give `C` and `D`.

use nalgebra::{Complex, DMatrix};

use crate::Error;
use crate::codegen::Tape;
use crate::codegen::dae::InputLayout;
use crate::simplify::SimplifiedSystem;

use super::error::SolveError;

/// Where a system is linearized: a consistent point of its unknowns, their derivatives
/// and the parameters (from [`DaeProblem::operating_point`](super::DaeProblem::operating_point)
/// or [`Solution::operating_point`](super::Solution::operating_point)).
#[derive(Clone, Debug, PartialEq)]
pub struct OperatingPoint {
    /// Time \[s\].
    pub t: f64,
    /// The unknowns, in the order of [`SimplifiedSystem::unknowns`].
    pub u: Vec<f64>,
    /// Their time derivatives.
    pub up: Vec<f64>,
    /// Every parameter's value.
    pub params: Vec<f64>,
}

/// A linear state-space model `dx/dt = A x + B u`, `y = C x + D u` (deviations from the
/// operating point), with the names of its states, inputs and outputs.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearModel {
    /// System matrix (states x states).
    pub a: DMatrix<f64>,
    /// Input matrix (states x inputs).
    pub b: DMatrix<f64>,
    /// Output matrix (outputs x states).
    pub c: DMatrix<f64>,
    /// Feed-through matrix (outputs x inputs).
    pub d: DMatrix<f64>,
    /// The states (the system's differential unknowns).
    pub states: Vec<String>,
    /// The inputs (parameters).
    pub inputs: Vec<String>,
    /// The outputs (variables).
    pub outputs: Vec<String>,
}

/// An eigenvalue of a [`LinearModel`] with its natural frequency and damping.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pole {
    /// The eigenvalue \[1/s\].
    pub value: Complex<f64>,
    /// Natural frequency `|value|` \[rad/s\].
    pub frequency: f64,
    /// Damping ratio `-Re(value) / |value|` (1 for a pole at 0).
    pub damping: f64,
}

impl LinearModel {
    /// The eigenvalues of `A`, sorted by real part, then imaginary part.
    pub fn eigenvalues(&self) -> Vec<Complex<f64>> {
        if self.a.is_empty() {
            return Vec::new();
        }
        let mut values: Vec<Complex<f64>> = self.a.complex_eigenvalues().iter().copied().collect();
        values.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
        values
    }

    /// The frequency response `C (i w I - A)^-1 B + D` at the angular frequency `w`
    /// \[rad/s\] (outputs x inputs); `None` where `i w` is an eigenvalue.
    pub fn frequency_response(&self, w: f64) -> Option<DMatrix<Complex<f64>>> {
        let n = self.a.nrows();
        let complex = |m: &DMatrix<f64>| m.map(|v| Complex::new(v, 0.0));
        let mut s_minus_a = -complex(&self.a);
        for i in 0..n {
            s_minus_a[(i, i)] += Complex::new(0.0, w);
        }
        let x = s_minus_a.lu().solve(&complex(&self.b))?;
        Some(complex(&self.c) * x + complex(&self.d))
    }

    /// The eigenvalues with their natural frequencies and damping ratios.
    pub fn poles(&self) -> Vec<Pole> {
        self.eigenvalues()
            .into_iter()
            .map(|value| {
                let frequency = value.norm();
                let damping = if frequency > 0.0 {
                    -value.re / frequency
                } else {
                    1.0
                };
                Pole {
                    value,
                    frequency,
                    damping,
                }
            })
            .collect()
    }
}

/// The error of a linearization.
fn failed(sys: &SimplifiedSystem, t: f64, message: String) -> Error {
    SolveError {
        model: sys.model.name.clone(),
        t,
        flag: "LINEARIZE".into(),
        message,
    }
    .into()
}

/// Directions seeded at once.
const LANES: usize = 32;

/// The derivatives of `tape`'s outputs `rows` with respect to the inputs `slots` at
/// `inputs`: `rows.len() x slots.len()`.
fn derivatives(
    tape: &Tape,
    inputs: &[f64],
    rows: &[usize],
    slots: &[usize],
) -> Result<DMatrix<f64>, String> {
    let n_in = tape.n_inputs();
    let n_out = tape.n_outputs();
    let mut out = vec![0.0; n_out];
    let mut ws = tape.workspace();
    let mut result = DMatrix::zeros(rows.len(), slots.len());
    for (chunk, cols) in slots.chunks(LANES).enumerate() {
        let lanes = cols.len();
        let mut seeds = vec![0.0; n_in * lanes];
        for (lane, &slot) in cols.iter().enumerate() {
            seeds[slot * lanes + lane] = 1.0;
        }
        let mut tangents = vec![0.0; n_out * lanes];
        tape.forward(inputs, &seeds, lanes, &mut ws, &mut out, &mut tangents)
            .map_err(|e| e.message)?;
        for (i, &r) in rows.iter().enumerate() {
            for lane in 0..lanes {
                result[(i, chunk * LANES + lane)] = tangents[r * lanes + lane];
            }
        }
    }
    if result.iter().any(|v| !v.is_finite()) {
        return Err("a derivative is not finite there".into());
    }
    Ok(result)
}

/// Linearizes `sys` at `at` with the parameters `inputs` as inputs and the variables
/// `outputs` as outputs (both by full name): see the module documentation.
pub fn linearize(
    sys: &SimplifiedSystem,
    at: &OperatingPoint,
    inputs: &[&str],
    outputs: &[&str],
) -> Result<LinearModel, Error> {
    let c = &sys.compiled;
    let layout: InputLayout = c.layout;
    let n = layout.n;
    if at.u.len() != n || at.up.len() != n || at.params.len() < layout.n_params {
        return Err(failed(
            sys,
            at.t,
            "the operating point does not belong to this system".into(),
        ));
    }
    let params = sys.parameter_index();
    let input_params: Vec<usize> = inputs
        .iter()
        .map(|&name| {
            params.position(name).ok_or_else(|| {
                failed(
                    sys,
                    at.t,
                    format!("`{name}` is not a parameter of the model (an input is a parameter)"),
                )
            })
        })
        .collect::<Result<_, _>>()?;
    let observed = &sys.compiled.observed_names;
    let output_rows: Vec<usize> = outputs
        .iter()
        .map(|&name| {
            observed.position(name).ok_or_else(|| {
                failed(
                    sys,
                    at.t,
                    format!("`{name}` is not a variable of the model"),
                )
            })
        })
        .collect::<Result<_, _>>()?;
    let mut values = vec![0.0; layout.len()];
    values[InputLayout::TIME] = at.t;
    for (j, &p) in at.params.iter().enumerate().take(layout.n_params) {
        values[layout.param(j)] = p;
    }
    for k in 0..n {
        values[layout.u(k)] = at.u[k];
        values[layout.up(k)] = at.up[k];
    }
    let differential: Vec<usize> = (0..n)
        .filter(|&k| sys.sorted.mass_matrix_diagonal[k] == 1.0)
        .collect();
    let algebraic: Vec<usize> = (0..n)
        .filter(|&k| sys.sorted.mass_matrix_diagonal[k] != 1.0)
        .collect();
    let u_slots: Vec<usize> = (0..n).map(|k| layout.u(k)).collect();
    let up_slots: Vec<usize> = differential.iter().map(|&k| layout.up(k)).collect();
    let p_slots: Vec<usize> = input_params.iter().map(|&j| layout.param(j)).collect();
    let mut slots = u_slots.clone();
    slots.extend(&up_slots);
    slots.extend(&p_slots);
    let rows: Vec<usize> = (0..n).collect();
    let jac = derivatives(&c.residual, &values, &rows, &slots)
        .map_err(|m| failed(sys, at.t, format!("the residual: {m}")))?;
    let (nx, nz, m) = (differential.len(), algebraic.len(), input_params.len());
    let f_u = jac.columns(0, n);
    let f_up = jac.columns(n, nx);
    let f_p = jac.columns(n + nx, m);
    // K [dx'; dz] = -(F_x dx + F_p dp).
    let mut k = DMatrix::zeros(n, n);
    k.columns_mut(0, nx).copy_from(&f_up);
    for (col, &a) in algebraic.iter().enumerate() {
        k.set_column(nx + col, &f_u.column(a));
    }
    let mut rhs = DMatrix::zeros(n, nx + m);
    for (col, &d) in differential.iter().enumerate() {
        rhs.set_column(col, &(-f_u.column(d)));
    }
    rhs.columns_mut(nx, m).copy_from(&(-f_p));
    let lu = k.lu();
    let solved = lu
        .solve(&rhs)
        .filter(|s| s.iter().all(|v| v.is_finite()))
        .ok_or_else(|| {
            failed(
                sys,
                at.t,
                "the states' derivatives and the algebraic unknowns are not determined there \
             (the system is not of index 1 at the point)"
                    .into(),
            )
        })?;
    let a = solved.view((0, 0), (nx, nx)).into_owned();
    let b = solved.view((0, nx), (nx, m)).into_owned();
    // dz = Z_x dx + Z_p dp.
    let z_x = solved.view((nx, 0), (nz, nx)).into_owned();
    let z_p = solved.view((nx, nx), (nz, m)).into_owned();
    // Outputs: y = h(t, v, v', p).
    let h = derivatives(&c.observed, &values, &output_rows, &slots)
        .map_err(|m| failed(sys, at.t, format!("the outputs: {m}")))?;
    let h_u = h.columns(0, n);
    let h_up = h.columns(n, nx);
    let h_p = h.columns(n + nx, m);
    let mut h_x = DMatrix::zeros(outputs.len(), nx);
    for (col, &d) in differential.iter().enumerate() {
        h_x.set_column(col, &h_u.column(d));
    }
    let mut h_z = DMatrix::zeros(outputs.len(), nz);
    for (col, &a_k) in algebraic.iter().enumerate() {
        h_z.set_column(col, &h_u.column(a_k));
    }
    let c_mat = &h_x + &h_z * &z_x + h_up * &a;
    let d_mat = h_z * z_p + h_up * &b + h_p;
    let unknowns = sys.unknowns();
    Ok(LinearModel {
        a,
        b,
        c: c_mat,
        d: d_mat,
        states: differential.iter().map(|&k| unknowns[k].clone()).collect(),
        inputs: inputs.iter().map(|s| s.to_string()).collect(),
        outputs: outputs.iter().map(|s| s.to_string()).collect(),
    })
}

/// [`linearize`] in the chosen `states` (variables by full name, as many as the system
/// has states, for instance a cart's position and a pendulum's angle with their speeds
/// rather than what state selection chose): the model in `z = T x`, `T` the
/// linearization of the chosen variables in the system's states, which must be
/// invertible there (the chosen variables determine the state).
pub fn linearize_in(
    sys: &SimplifiedSystem,
    at: &OperatingPoint,
    inputs: &[&str],
    outputs: &[&str],
    states: &[&str],
) -> Result<LinearModel, Error> {
    let n = sys.states().len();
    if states.len() != n {
        return Err(failed(
            sys,
            at.t,
            format!("{} states chosen, the system has {n}", states.len()),
        ));
    }
    let all: Vec<&str> = states.iter().chain(outputs).copied().collect();
    let lin = linearize(sys, at, inputs, &all)?;
    let t = lin.c.rows(0, n).into_owned();
    if lin.d.rows(0, n).iter().any(|v| *v != 0.0) {
        return Err(failed(
            sys,
            at.t,
            "a chosen state depends on an input directly (it cannot be a state)".into(),
        ));
    }
    let t_inv = t.clone().try_inverse().ok_or_else(|| {
        failed(
            sys,
            at.t,
            format!(
                "the chosen variables {} do not determine the state there",
                states.join(", ")
            ),
        )
    })?;
    let m = outputs.len();
    Ok(LinearModel {
        a: &t * &lin.a * &t_inv,
        b: &t * &lin.b,
        c: lin.c.rows(n, m) * &t_inv,
        d: lin.d.rows(n, m).into_owned(),
        states: states.iter().map(|s| s.to_string()).collect(),
        inputs: lin.inputs,
        outputs: outputs.iter().map(|s| s.to_string()).collect(),
    })
}
