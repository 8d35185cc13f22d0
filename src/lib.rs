//! # multibody
//!
//! Acausal, equation-based modeling and simulation of multibody systems, with 1-D
//! mechanics, circuits and control blocks beside them. Components are declared once
//! with [`component!`] (parameters with defaults and docs, connectors, variables,
//! equations like `der(phi) = w;`), models are assembled with [`system!`] (or plain
//! builder calls), reduced by [`structural_simplify`] to states, algebraic unknowns and
//! residuals with a mass matrix, integrated by SUNDIALS IDA, and read back by name.
//!
//! ```
//! use multibody::prelude::*;
//! use multibody::rotational::{Damper, Fixed, Inertia, Spring};
//!
//! let model = system! {
//!     name: "oscillator";
//!     fixed = Fixed::default();
//!     spring = Spring { c: 4.0 };
//!     damper = Damper { d: 0.4 };
//!     inertia = Inertia { J: 1.0, phi_start: 1.0 };
//!     connect(fixed.flange, spring.flange_a);
//!     connect(spring.flange_b, inertia.flange_a);
//!     connect(fixed.flange, damper.flange_a);
//!     connect(damper.flange_b, inertia.flange_a);
//! };
//! let ssys = structural_simplify(&model)?;
//! // MSL's damper prefers its relative angle and speed as states.
//! assert_eq!(ssys.states(), ["damper.phi_rel", "damper.w_rel"]);
//! let sol = DaeProblem::new(&ssys, &[], (0.0, 10.0))?.solve(&SolverOptions::default())?;
//! // The damped oscillation from 1 rad at rest, in closed form:
//! // phi = exp(-delta t) (cos(wd t) + delta / wd sin(wd t)),
//! // delta = d / (2 J) = 0.2, wd = sqrt(c / J - delta^2).
//! let (delta, wd) = (0.2, (4.0f64 - 0.04).sqrt());
//! let phi = sol.get("inertia.phi")?;
//! for (t, p) in sol.t().iter().zip(&phi) {
//!     let exact = (-delta * t).exp() * ((wd * t).cos() + delta / wd * (wd * t).sin());
//!     // The default rtol is 1e-6: over three periods the error stays near 2e-6.
//!     assert!((p - exact).abs() < 1e-5, "phi({t}) = {p}, exact {exact}");
//! }
//! # Ok::<(), multibody::Error>(())
//! ```

extern crate self as multibody;

pub mod blocks;
pub mod electrical;
pub mod forces;
pub mod frames;
pub mod functions;
pub mod interfaces;
pub mod joints;
pub mod loops;
mod mechanism;
mod numeric;
pub mod parts;
pub mod render;
pub mod rotational;
pub mod sensors;
pub mod translational;
pub mod world;

pub use mechanism::{structural_simplify, structural_simplify_with};
pub use multibody_core::Error;
pub use multibody_core::expr::Expr;
pub use multibody_core::model::{
    Component, Connector, ConnectorHandle, Model, Named, Parameter, PathId, Real, Signal,
    StateSelect, System, TypedComponent, VarKind, Variable,
};
pub use multibody_core::simplify::{
    DynamicStates, PhaseTimes, PlanarLoops, SimplifiedSystem, SimplifyOptions, StateCandidates,
    Statistics,
};
pub use multibody_core::solve::{
    DaeProblem, IdaStats, InitReport, LinearSolverChoice, ProblemBuilder, Segment, Solution,
    SolverOptions,
};
pub use multibody_macros::{component, connector, system};
pub use plot::{Figure, PlotOptions, plot, plot_figure};

/// Plots of solutions: variables against time by name or handle, with their units, in
/// panels, several solutions overlaid ([`Figure`]); and the panels underneath
/// ([`plot_panels`](plot::plot_panels)) for curves of any data.
pub mod plot {
    pub use multibody_core::plot::{
        Figure, Panel, PlotError, PlotOptions, Series, plot, plot_figure, plot_panels,
    };
}

/// The errors of each stage, which [`Error`] wraps: match on them to tell what failed.
pub mod error {
    pub use multibody_core::Error;
    pub use multibody_core::codegen::CodegenError;
    pub use multibody_core::model::ModelError;
    pub use multibody_core::plot::PlotError;
    pub use multibody_core::simplify::SimplifyError;
    pub use multibody_core::solve::{InitError, SolutionError, SolveError};
}

/// What a model file needs: the macros, the builder types, the solver and plots, and
/// the functions used in equations.
pub mod prelude {
    pub use crate::frames::{Mat3, Orientation, Vec3};
    pub use crate::functions::*;
    pub use crate::render::{RenderOptions, render};
    pub use crate::{
        Component, ConnectorHandle, DaeProblem, Expr, Figure, Model, Named, PlotOptions, Real,
        Signal, SimplifiedSystem, Solution, SolverOptions, StateSelect, System, TypedComponent,
        Variable, component, connector, plot, plot_figure, structural_simplify, system,
    };
}

/// Paths used by the code the macros generate. Not a public API.
#[doc(hidden)]
pub mod __private {
    pub use multibody_core::expr::Expr;
    pub use multibody_core::model::{
        Component, Connector, ConnectorHandle, Model, Parameter, ParameterType, PathId, Signal,
        Signal3, StateSelect, StructuralValue, System, TypedComponent, VarKind, Variable,
        VariableType, declare_signal, declare_signal3, member, signal_at, signal3_at,
    };

    /// The start value of a vector variable, element by element: one value for all,
    /// three numbers, three expressions, or (`Option`) none.
    pub trait VectorStart {
        /// The three start values, if any.
        fn elements(self) -> Option<[Expr; 3]>;
    }

    impl VectorStart for f64 {
        fn elements(self) -> Option<[Expr; 3]> {
            Some([Expr::constant(self); 3])
        }
    }

    impl VectorStart for [f64; 3] {
        fn elements(self) -> Option<[Expr; 3]> {
            Some(self.map(Expr::constant))
        }
    }

    impl VectorStart for multibody_core::expr::Vec3 {
        fn elements(self) -> Option<[Expr; 3]> {
            Some(self.0)
        }
    }

    impl<T: VectorStart> VectorStart for Option<T> {
        fn elements(self) -> Option<[Expr; 3]> {
            self.and_then(T::elements)
        }
    }

    /// The functions equations use (`der`, `sin`, ...).
    pub mod dsl {
        pub use crate::functions::*;
        pub use multibody_core::model::StateSelect;
    }
}
