//! The compiled functions of a simplified system: residual `F(t, u, u')`, its sparse
//! Jacobian `dF/du + cj dF/du'`, and the observed variables.
//!
//! All tapes read the same inputs, laid out by [`InputLayout`]:
//! `[t, p_0 .. p_m, u_0 .. u_n, u'_0 .. u'_n]`.

use std::sync::Arc;

use crate::expr::{Arena, Id};

use super::{
    CodegenError, DEFAULT_MAX_FILL, DaeJacobian, ExtendedJacobian, Stmt, Tape, TapeBuilder,
};

/// Positions of the inputs of the compiled tapes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InputLayout {
    /// Number of parameter inputs.
    pub n_params: usize,
    /// Number of unknowns.
    pub n: usize,
}

impl InputLayout {
    /// Slot of time.
    pub const TIME: usize = 0;

    /// Slot of parameter `j`.
    pub fn param(&self, j: usize) -> usize {
        1 + j
    }

    /// Slot of unknown `k`.
    pub fn u(&self, k: usize) -> usize {
        1 + self.n_params + k
    }

    /// Slot of the derivative of unknown `k`.
    pub fn up(&self, k: usize) -> usize {
        1 + self.n_params + self.n + k
    }

    /// Total number of inputs.
    pub fn len(&self) -> usize {
        1 + self.n_params + 2 * self.n
    }

    /// Whether there are no inputs (never: time is always one).
    pub fn is_empty(&self) -> bool {
        false
    }
}

/// A row of the DAE residual: an equation's residual, or a state's derivative
/// computed explicitly.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ResidualRow {
    /// The residual of an equation (iteration block).
    Equation {
        /// The expression.
        residual: Id,
        /// The reduced equation it comes from.
        equation: usize,
    },
    /// `u'[state] - value`: the derivative of a state is computed as `value` (a leaf).
    StateDerivative {
        /// Index in the unknowns of the state.
        state: usize,
        /// The leaf holding the computed derivative.
        value: Id,
    },
}

/// The compiled functions of a simplified system.
#[derive(Clone, Debug)]
pub struct CompiledDae {
    /// Input layout of every tape here.
    pub layout: InputLayout,
    /// The residual: one output per unknown.
    pub residual: Tape,
    /// The Jacobian pattern, colouring and evaluator for [`Self::residual`], built on
    /// first use (see [`Self::jacobian`]).
    jacobian: std::sync::OnceLock<DaeJacobian>,
    /// The extended Jacobian of [`Self::residual`] when it is much sparser than
    /// [`Self::jacobian`], built on first use (see [`Self::extended`]).
    extended: std::sync::OnceLock<Option<ExtendedJacobian>>,
    /// Whether [`Self::residual`] is an explicit ODE, found on first use (see
    /// [`Self::is_explicit_ode`]).
    explicit: std::sync::OnceLock<bool>,
    /// Every observable variable, one output each, named by [`Self::observed_names`]
    /// (shared by every problem and solution made from this system).
    pub observed: Arc<Tape>,
    /// Names of the outputs of [`Self::observed`], with their lookup (shared like it).
    pub observed_names: Arc<crate::names::NameIndex>,
}

/// What the code generator needs to know about a system.
pub(crate) struct DaeSpec<'a> {
    pub steps: &'a [Stmt],
    /// Leaves read from `u` (in order of the unknowns).
    pub unknowns: &'a [Id],
    /// Leaves read from `u'`, with the index of their unknown.
    pub derivative_inputs: &'a [(Id, usize)],
    pub rows: &'a [ResidualRow],
    /// Observed outputs.
    pub observed: &'a [Id],
    /// Their names: exactly one per entry of `observed`, in the same order (a lazy
    /// index lets compiling touch no name).
    pub observed_names: Arc<crate::names::NameIndex>,
    pub n_params: usize,
    /// Names of leaves, for messages.
    pub names: &'a dyn Fn(Id) -> String,
}

/// Binds time, parameters, unknowns and their derivatives, then adds the steps.
fn builder<'a>(
    arena: &'a Arena,
    leaves: &Leaves,
    spec: &DaeSpec<'a>,
    layout: InputLayout,
) -> Result<TapeBuilder<'a>, CodegenError> {
    let mut b = TapeBuilder::new(arena, layout.len()).with_names(spec.names);
    // Parameters change only between problems: what depends on nothing else is
    // computed once per workspace and parameter set.
    b.invariant_inputs(layout.param(0)..layout.param(layout.n_params));
    if let Some(t) = leaves.time {
        b.input(t, InputLayout::TIME);
    }
    for (j, &p) in leaves.params.iter().enumerate() {
        b.input(p, layout.param(j));
    }
    for (k, &u) in spec.unknowns.iter().enumerate() {
        b.input(u, layout.u(k));
    }
    for &(leaf, k) in spec.derivative_inputs {
        b.input(leaf, layout.up(k));
    }
    for s in spec.steps {
        b.stmt(s)?;
    }
    Ok(b)
}

/// Leaves that exist in the arena before compilation (created with `&mut Arena`).
pub(crate) struct Leaves {
    pub time: Option<Id>,
    pub params: Vec<Id>,
}

impl Leaves {
    /// Creates the time and parameter leaves.
    pub(crate) fn new(arena: &mut Arena, n_params: usize) -> Leaves {
        Leaves {
            time: Some(arena.time()),
            params: (0..n_params).map(|j| arena.param(j as u32)).collect(),
        }
    }
}

/// Compiles the residual and the observed function (their Jacobians are analysed on
/// first use: [`CompiledDae::jacobian`], [`CompiledDae::extended`]).
pub(crate) fn compile_dae(
    arena: &mut Arena,
    spec: &DaeSpec<'_>,
) -> Result<CompiledDae, CodegenError> {
    let leaves = Leaves::new(arena, spec.n_params);
    let layout = InputLayout {
        n_params: spec.n_params,
        n: spec.unknowns.len(),
    };
    let arena: &Arena = arena;
    let mut b = builder(arena, &leaves, spec, layout)?;
    for row in spec.rows {
        match *row {
            ResidualRow::Equation { residual, .. } => {
                b.output(residual)?;
            }
            ResidualRow::StateDerivative { state, value } => {
                b.output_input_minus(layout.up(state), value)?;
            }
        }
    }
    let n_rows = spec.rows.len();
    // The observed variables are outputs of the same builder: the statements are
    // compiled once for both tapes.
    for &e in spec.observed {
        b.output(e)?;
    }
    let residual = b.build_outputs(0..n_rows);
    let observed = Arc::new(b.build_outputs(n_rows..n_rows + spec.observed.len()));
    Ok(CompiledDae {
        layout,
        residual,
        // Analysed on first use: a solve with the parameters specialized (the default)
        // analyses the specialized residual instead, never this one.
        jacobian: std::sync::OnceLock::new(),
        extended: std::sync::OnceLock::new(),
        explicit: std::sync::OnceLock::new(),
        observed,
        observed_names: spec.observed_names.clone(),
    })
}

impl CompiledDae {
    /// The residual and its Jacobians specialized to the parameter values `params`
    /// (one per parameter input; see [`Tape::specialize`]): what folds with those
    /// values is folded, so a problem whose parameters are zero or one where a model
    /// allows any value pays nothing for that generality. The observed function is
    /// shared unchanged.
    ///
    /// # Panics
    /// If `params` does not have [`InputLayout::n_params`] values.
    pub fn specialize(&self, params: &[f64]) -> CompiledDae {
        let values: Vec<Option<f64>> = params.iter().copied().map(Some).collect();
        self.specialize_partly(&values)
    }

    /// [`Self::specialize`] to the parameters with a value (`Some`); the others (those
    /// that events change) stay inputs.
    pub fn specialize_partly(&self, params: &[Option<f64>]) -> CompiledDae {
        CompiledDae {
            layout: self.layout,
            residual: self.residual.specialize_partly(params),
            jacobian: std::sync::OnceLock::new(),
            extended: std::sync::OnceLock::new(),
            explicit: std::sync::OnceLock::new(),
            observed: self.observed.clone(),
            observed_names: self.observed_names.clone(),
        }
    }

    /// Whether the residual is `u' - g(t, u)`: output `k` is `u'_k` minus a value
    /// that depends on no derivative input (or `u'_k` alone). Such a system is the
    /// explicit ODE `u' = g(t, u)`, with `g = -F(t, u, 0)` and `dg/du = -dF/du`.
    /// Found once per compiled system.
    pub fn is_explicit_ode(&self) -> bool {
        *self.explicit.get_or_init(|| {
            let (n, up) = (self.layout.n, self.layout.up(0));
            self.residual.is_explicit_in(n, up)
        })
    }

    /// Whether the plain and the extended Jacobian have been analysed yet (each is on
    /// its first use): compiling analyses neither, and a solve with specialized
    /// parameters analyses those of the specialized residual only.
    pub fn jacobians_analysed(&self) -> (bool, bool) {
        (self.jacobian.get().is_some(), self.extended.get().is_some())
    }

    /// The extended Jacobian of [`Self::residual`] when it is worth its extra rows (see
    /// [`prefer_extended`]); sparse solvers then use it. Analysed on the first call
    /// (with the plain Jacobian too, when that is needed to decide).
    pub fn extended(&self) -> Option<&ExtendedJacobian> {
        self.extended
            .get_or_init(|| {
                let (n, u, up) = (self.layout.n, self.layout.u(0), self.layout.up(0));
                let extended = ExtendedJacobian::new(&self.residual, n, u, up, DEFAULT_MAX_FILL);
                // The plain Jacobian needs at least as many colours as its densest row
                // has entries: when that alone rules it out, it is not built.
                let use_extended =
                    self.residual
                        .column_degree_reaches(n, u, up, 2 * extended.n_colors())
                        || prefer_extended(self.jacobian(), &extended);
                use_extended.then_some(extended)
            })
            .as_ref()
    }

    /// The Jacobian pattern, colouring and evaluator for [`Self::residual`] (the
    /// reduced one, without the extended Jacobian's intermediate unknowns).
    pub fn jacobian(&self) -> &DaeJacobian {
        self.jacobian.get_or_init(|| {
            DaeJacobian::new(
                &self.residual,
                self.layout.n,
                self.layout.u(0),
                self.layout.up(0),
            )
        })
    }
}

/// Whether the extended Jacobian is worth its extra rows: it must need at most half the
/// colours (forward passes over the tape, each of which also solves every linear system
/// of the tape once more) of the plain one. On a 20-link pendulum (13 instead of 40
/// colours) the whole integration took 17 % less time with it, on a 100-link one
/// (13 instead of 200) several times less.
pub fn prefer_extended(plain: &DaeJacobian, extended: &ExtendedJacobian) -> bool {
    extended.n_colors() * 2 <= plain.n_colors()
}
