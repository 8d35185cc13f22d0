//! A DAE problem: a simplified system with parameter values, initial values and a time
//! span, solved by IDA.

use crate::hash::HashMap;

use crate::Error;
use crate::codegen::dae::{CompiledDae, InputLayout};
use crate::codegen::{ExtendedJacobian, ExtendedWorkspace, JacobianWorkspace, Workspace};
use crate::expr::{Arena, Id, Node};
use crate::names::{closest, number};
use crate::simplify::SimplifiedSystem;

use super::error::{InitError, SolveError};
use super::ida::{self, DaeFunctions, EvalError, IdaSettings, LinearSolver, OutputMode};
use super::init::{InitInput, initialize};
use super::options::{LinearSolverChoice, SolverOptions};
use super::solution::Solution;

/// What the initialization did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct InitReport {
    /// Start values assumed fixed to complete the initial conditions (name, value).
    pub assumed: Vec<(String, f64)>,
    /// Newton iterations used.
    pub iterations: usize,
    /// The unknowns the initialization iterated on (the tearing variables of its
    /// nonlinear blocks), by name. Orientation matrix entries are never among them.
    pub iteration_variables: Vec<String>,
}

/// A simplified system with values: tunable parameters, initial values and a time span.
/// Creating one runs the consistent initialization; the compiled functions of the
/// system are shared, so many problems of one system cost no recompilation.
#[derive(Clone, Debug)]
pub struct DaeProblem<'a> {
    sys: &'a SimplifiedSystem,
    tspan: (f64, f64),
    params: Vec<f64>,
    u0: Vec<f64>,
    up0: Vec<f64>,
    report: InitReport,
}

/// Evaluates parameter values: bindings may refer to other parameters.
#[allow(clippy::result_large_err)] // evaluated once per problem, reported to the user
pub(crate) fn parameter_values(
    sys: &SimplifiedSystem,
    overrides: &HashMap<usize, f64>,
) -> Result<Vec<f64>, InitError> {
    crate::model::evaluate_bindings(&sys.arena, &sys.parameter_values, overrides).map_err(
        |missing| InitError::BadValue {
            model: sys.name.clone(),
            message: format!(
                "the values of {} depend on each other or on variables",
                missing
                    .iter()
                    .map(|&j| format!("`{}`", sys.parameters[j].name))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        },
    )
}

/// Checks the components' conditions on the parameter values `params`.
#[allow(clippy::result_large_err)] // evaluated once per problem, reported to the user
fn check_assertions(sys: &SimplifiedSystem, params: &[f64]) -> Result<(), InitError> {
    for a in &sys.assertions {
        if eval_with_params(&sys.arena, a.condition, params) != Some(0.0) {
            continue;
        }
        let values: Vec<String> = sys
            .arena
            .leaves(a.condition)
            .into_iter()
            .filter_map(|l| match sys.arena.node(l) {
                Node::Param(j) => Some(format!(
                    "{} = {}",
                    sys.parameters[*j as usize].name, params[*j as usize]
                )),
                _ => None,
            })
            .collect();
        return Err(InitError::AssertionFailed {
            model: sys.name.clone(),
            component: a.component.clone(),
            type_name: a.type_name.clone(),
            message: a.message.to_string(),
            values: values.join(", "),
        });
    }
    Ok(())
}

fn eval_with_params(arena: &Arena, e: Id, params: &[f64]) -> Option<f64> {
    arena.eval(e, &|n: &Node| match n {
        Node::Param(k) => params.get(*k as usize).copied(),
        Node::Time => None,
        _ => None,
    })
}

impl<'a> DaeProblem<'a> {
    /// A problem over `tspan` with `values`: a parameter name sets that parameter; a
    /// variable name sets its start value and makes it fixed (an initial condition).
    /// Everything else keeps the model's defaults. Runs the initialization.
    pub fn new(
        sys: &'a SimplifiedSystem,
        values: &[(&str, f64)],
        tspan: (f64, f64),
    ) -> Result<Self, Error> {
        Self::new_with_guesses(sys, values, &[], tspan)
    }

    /// Like [`new`](Self::new), with iteration guesses for variables (used by the
    /// initialization's Newton iterations only; not fixed).
    pub fn new_with_guesses(
        sys: &'a SimplifiedSystem,
        values: &[(&str, f64)],
        guesses: &[(&str, f64)],
        tspan: (f64, f64),
    ) -> Result<Self, Error> {
        if !(tspan.0.is_finite() && tspan.1.is_finite() && tspan.1 > tspan.0) {
            return Err(InitError::BadValue {
                model: sys.name.clone(),
                message: format!(
                    "the time span ({}, {}) must be finite and increasing",
                    number(tspan.0),
                    number(tspan.1)
                ),
            }
            .into());
        }
        // Shorter spans than this are lost in the rounding of the times themselves (or
        // underflow inside the integrator's step-size estimates).
        let shortest = (100.0 * f64::EPSILON * tspan.0.abs().max(tspan.1.abs())).max(1e-200);
        if tspan.1 - tspan.0 < shortest {
            return Err(InitError::BadValue {
                model: sys.name.clone(),
                message: format!(
                    "the time span ({}, {}) is too short to integrate: the end must exceed \
                     the start by at least {}",
                    number(tspan.0),
                    number(tspan.1),
                    number(shortest)
                ),
            }
            .into());
        }
        // Name lookups only when names are given: hashing every name of a large model
        // costs more than the rest of the set-up.
        let by_name = !(values.is_empty() && guesses.is_empty());
        let index = |names: &mut dyn Iterator<Item = &'a str>| -> HashMap<&'a str, usize> {
            if by_name {
                names.enumerate().map(|(i, n)| (n, i)).collect()
            } else {
                HashMap::default()
            }
        };
        let var_index = index(&mut sys.variables.iter().map(|v| &*v.name));
        let param_index = index(&mut sys.parameters.iter().map(|p| &*p.name));
        let unknown = |name: &str| {
            let candidates = sys
                .variables
                .iter()
                .map(|v| &*v.name)
                .chain(sys.parameters.iter().map(|p| &*p.name));
            InitError::UnknownName {
                model: sys.name.clone(),
                name: name.to_string(),
                suggestions: closest(name, candidates, 3),
            }
        };
        let mut param_overrides = HashMap::default();
        let mut start_overrides = HashMap::default();
        let bad = |message: String| -> Error {
            InitError::BadValue {
                model: sys.name.clone(),
                message,
            }
            .into()
        };
        let mut given: HashMap<&str, ()> = HashMap::default();
        for &(name, v) in values {
            if given.insert(name, ()).is_some() {
                return Err(bad(format!("`{name}` is given twice in the values")));
            }
            if !v.is_finite() {
                return Err(bad(format!(
                    "the value {v} given for `{name}` is not finite"
                )));
            }
            if let Some(&j) = param_index.get(name) {
                if sys.evaluated_parameters[j] {
                    return Err(bad(format!(
                        "parameter `{name}` was evaluated at compile time (declared `evaluate`, or SimplifyOptions::evaluate_parameters); simplify the model again to change it"
                    )));
                }
                param_overrides.insert(j, v);
            } else if let Some(&i) = var_index.get(name) {
                start_overrides.insert(i, v);
            } else {
                return Err(unknown(name).into());
            }
        }
        let mut guess_values = vec![None; sys.variables.len()];
        let mut guessed: HashMap<&str, ()> = HashMap::default();
        for &(name, v) in guesses {
            if guessed.insert(name, ()).is_some() {
                return Err(bad(format!("`{name}` is given twice in the guesses")));
            }
            if !v.is_finite() {
                return Err(bad(format!(
                    "the guess {v} given for `{name}` is not finite"
                )));
            }
            match var_index.get(name) {
                Some(&i) => guess_values[i] = Some(v),
                None if param_index.contains_key(name) => {
                    return Err(bad(format!(
                        "`{name}` is a parameter: give its value with the values, not as a guess"
                    )));
                }
                None => return Err(unknown(name).into()),
            }
        }
        let params = parameter_values(sys, &param_overrides)?;
        if let Some(j) = params.iter().position(|p| !p.is_finite()) {
            return Err(bad(format!(
                "parameter `{}` evaluates to {}",
                sys.parameters[j].name, params[j]
            )));
        }
        check_assertions(sys, &params)?;
        let mut starts = Vec::with_capacity(sys.variables.len());
        let mut fixed = Vec::with_capacity(sys.variables.len());
        for (i, v) in sys.variables.iter().enumerate() {
            if let Some(&s) = start_overrides.get(&i) {
                starts.push(Some(s));
                fixed.push(true);
                continue;
            }
            let s = match sys.starts[i] {
                Some(e) => {
                    let value = eval_with_params(&sys.arena, e, &params).ok_or_else(|| {
                        bad(format!(
                            "the start value of `{}` is not an expression of parameters",
                            v.name
                        ))
                    })?;
                    if !value.is_finite() {
                        return Err(bad(format!(
                            "the start value of `{}` evaluates to {value}",
                            v.name
                        )));
                    }
                    Some(value)
                }
                None => None,
            };
            starts.push(s);
            fixed.push(v.fixed);
        }
        let init = initialize(InitInput {
            sys,
            t0: tspan.0,
            params,
            starts,
            fixed,
            guesses: guess_values,
        })?;
        // u0 and u'0 from the slot values.
        let mut u0 = Vec::with_capacity(sys.unknowns.len());
        let mut up0 = Vec::with_capacity(sys.unknowns.len());
        for &l in &sys.unknowns {
            let s = sys.slot_of.get(l).expect("an unknown is a slot");
            u0.push(init.slot_values[s]);
            up0.push(sys.var_diff[s].map_or(0.0, |d| init.slot_values[d]));
        }
        Ok(DaeProblem {
            sys,
            tspan,
            params: init.params,
            u0,
            up0,
            report: InitReport {
                assumed: init.assumed,
                iterations: init.iterations,
                iteration_variables: init.iteration_variables,
            },
        })
    }

    /// The consistent initial unknowns `u(t0)`, in the order of
    /// [`SimplifiedSystem::unknowns`].
    pub fn initial_unknowns(&self) -> &[f64] {
        &self.u0
    }

    /// The consistent initial derivatives `u'(t0)`.
    pub fn initial_derivatives(&self) -> &[f64] {
        &self.up0
    }

    /// The parameter values (including those computed at initialization), in the
    /// order of [`SimplifiedSystem::parameters`].
    pub fn parameter_values(&self) -> &[f64] {
        &self.params
    }

    /// What the initialization assumed and how it went.
    pub fn init_report(&self) -> &InitReport {
        &self.report
    }

    /// The time span.
    pub fn tspan(&self) -> (f64, f64) {
        self.tspan
    }

    /// The system.
    pub fn system(&self) -> &SimplifiedSystem {
        self.sys
    }

    /// The residual `F(t0, u0, u'0)` at the initial values (all zero when they are
    /// consistent).
    pub fn initial_residual(&self) -> Vec<f64> {
        let c = &self.sys.compiled;
        let mut f = CompiledFunctions::new(c, &self.params, false);
        let mut out = vec![0.0; self.u0.len()];
        let _ = f.residual(self.tspan.0, &self.u0, &self.up0, &mut out);
        out
    }

    /// Integrates with IDA.
    pub fn solve(&self, options: &SolverOptions) -> Result<Solution, Error> {
        let sys = self.sys;
        if let Err(message) = options.check(self.tspan) {
            return Err(SolveError {
                model: sys.name.clone(),
                t: self.tspan.0,
                flag: "BAD_OPTION".into(),
                message,
            }
            .into());
        }
        let specialized;
        let c = if options.specialize_parameters && sys.compiled.layout.n_params > 0 {
            specialized = sys.compiled.specialize(&self.params);
            &specialized
        } else {
            &sys.compiled
        };
        let n = self.u0.len();
        let (linear_solver, extended) = match options.linear_solver {
            LinearSolverChoice::Auto if n <= 24 => (LinearSolver::Dense, false),
            LinearSolverChoice::Auto | LinearSolverChoice::Sparse => {
                (LinearSolver::SparseLu, c.extended().is_some())
            }
            LinearSolverChoice::SparsePlain => (LinearSolver::SparseLu, false),
            LinearSolverChoice::Dense => (LinearSolver::Dense, false),
            LinearSolverChoice::DenseDifferenceQuotient => {
                (LinearSolver::DenseDifferenceQuotient, false)
            }
        };
        let settings = IdaSettings {
            rtol: options.rtol,
            atol: options.atol,
            atol_vector: None,
            max_step: options.max_step,
            initial_step: options.initial_step,
            max_steps: options.max_steps,
            id: sys.mass_matrix_diagonal.clone(),
            suppress_alg: options.suppress_alg,
            linear_solver,
            calc_ic: false,
        };
        let output = match &options.output_times {
            Some(times) => {
                let mut ts: Vec<f64> = times
                    .iter()
                    .copied()
                    .filter(|&t| t > self.tspan.0 && t <= self.tspan.1)
                    .collect();
                ts.sort_by(f64::total_cmp);
                ts.dedup();
                if ts.last() != Some(&self.tspan.1) {
                    ts.push(self.tspan.1);
                }
                OutputMode::Times(ts)
            }
            None => OutputMode::EveryStep {
                t_end: self.tspan.1,
            },
        };
        let mut f = CompiledFunctions::new(c, &self.params, extended);
        let mut t_out = Vec::new();
        let mut u_out = Vec::new();
        let mut up_out = Vec::new();
        let mut steps_left = options.max_points;
        let mut exceeded = None;
        let result = ida::integrate(
            &mut f,
            self.tspan.0,
            &self.u0,
            &self.up0,
            &settings,
            &output,
            &mut |t, u, up| {
                if steps_left == 0 {
                    exceeded = Some(t);
                    return false;
                }
                steps_left -= 1;
                t_out.push(t);
                u_out.extend_from_slice(u);
                up_out.extend_from_slice(up);
                true
            },
        );
        if let Some(t) = exceeded {
            return Err(SolveError {
                model: sys.name.clone(),
                t,
                flag: "MAX_POINTS".into(),
                message: format!(
                    "more than {} reported points (SolverOptions::max_points)",
                    options.max_points
                ),
            }
            .into());
        }
        let stats = result.map_err(|e| SolveError {
            model: sys.name.clone(),
            t: e.t,
            flag: e.flag.clone(),
            message: e.message.clone(),
        })?;
        if options.project_outputs {
            let n = self.u0.len();
            let mut plain = CompiledFunctions::new(c, &self.params, false);
            let found = super::project::Projection::new(
                &mut plain,
                &sys.mass_matrix_diagonal,
                self.tspan.0,
                &self.u0,
                &self.up0,
            );
            if let Some(mut projection) = found {
                for (k, &t) in t_out.iter().enumerate() {
                    let span = k * n..(k + 1) * n;
                    projection.apply(&mut plain, t, &mut u_out[span.clone()], &up_out[span]);
                }
            }
        }
        Ok(Solution::new(
            sys.name.clone(),
            c.observed.clone(),
            c.observed_names.clone(),
            c.layout,
            self.params.clone(),
            sys.parameter_index(),
            sys.mass_matrix_diagonal.iter().map(|&m| m == 1.0).collect(),
            t_out,
            u_out,
            up_out,
            stats,
            self.report.clone(),
        ))
    }
}

/// The compiled residual and Jacobian with their workspaces, as IDA's callbacks.
pub(crate) struct CompiledFunctions<'c> {
    c: &'c CompiledDae,
    inputs: Vec<f64>,
    ws: Workspace,
    /// Workspace of the plain Jacobian, made on first use.
    jws: Option<JacobianWorkspace>,
    /// The extended Jacobian and its workspace, when it is used (asked of `c` once, in
    /// [`Self::new`]: the first call analyses it).
    ews: Option<(&'c ExtendedJacobian, ExtendedWorkspace)>,
    layout: InputLayout,
}

impl<'c> CompiledFunctions<'c> {
    /// Functions of `c` at parameter values `params`; `extended` selects the extended
    /// Jacobian (when `c` has one; sparse LU only).
    pub(crate) fn new(c: &'c CompiledDae, params: &[f64], extended: bool) -> Self {
        let layout = c.layout;
        let mut inputs = vec![0.0; layout.len()];
        for (j, &p) in params.iter().enumerate().take(layout.n_params) {
            inputs[layout.param(j)] = p;
        }
        CompiledFunctions {
            c,
            inputs,
            ws: c.residual.workspace(),
            jws: None,
            // Asked only when wanted: the first call analyses the extended Jacobian.
            ews: extended
                .then(|| c.extended())
                .flatten()
                .map(|e| (e, e.workspace(&c.residual))),
            layout,
        }
    }

    fn load(&mut self, t: f64, y: &[f64], yp: &[f64]) {
        let n = self.layout.n;
        self.inputs[InputLayout::TIME] = t;
        if n > 0 {
            let u0 = self.layout.u(0);
            self.inputs[u0..u0 + n].copy_from_slice(y);
            let up0 = self.layout.up(0);
            self.inputs[up0..up0 + n].copy_from_slice(yp);
        }
    }
}

impl DaeFunctions for CompiledFunctions<'_> {
    fn len(&self) -> usize {
        self.layout.n
    }

    fn residual(
        &mut self,
        t: f64,
        y: &[f64],
        yp: &[f64],
        out: &mut [f64],
    ) -> Result<(), EvalError> {
        self.load(t, y, yp);
        self.c.residual.eval(&self.inputs, &mut self.ws, out)?;
        if let Some(i) = out.iter().position(|v| !v.is_finite()) {
            return Err(EvalError {
                message: format!("residual {i} is not finite at t = {t}"),
                recoverable: true,
            });
        }
        Ok(())
    }

    fn jacobian_pattern(&self) -> Option<(Vec<usize>, Vec<usize>)> {
        match &self.ews {
            Some((e, _)) => Some((e.col_ptr.clone(), e.row_idx.clone())),
            None => Some((
                self.c.jacobian().col_ptr.clone(),
                self.c.jacobian().row_idx.clone(),
            )),
        }
    }

    fn jacobian_dimension(&self) -> usize {
        match &self.ews {
            Some((e, _)) => e.dimension(),
            None => self.layout.n,
        }
    }

    fn jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        yp: &[f64],
        cj: f64,
        values: &mut [f64],
    ) -> Result<(), EvalError> {
        self.load(t, y, yp);
        match &mut self.ews {
            Some((e, ews)) => e.eval(&self.c.residual, &self.inputs, cj, ews, values),
            None => {
                let c = self.c;
                let jws = self
                    .jws
                    .get_or_insert_with(|| c.jacobian().workspace(&c.residual));
                c.jacobian()
                    .eval(&c.residual, &self.inputs, cj, jws, values)
            }
        }
    }
}
