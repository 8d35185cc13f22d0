//! # multibody
//!
//! Acausal, equation-based modeling and simulation of multibody systems, with 1-D
//! mechanics, circuits and control blocks beside them: MSL's MultiBody library, or
//! Multibody.jl on ModelingToolkit, in Rust.
//!
//! A model is a set of components (bodies, joints, springs, motors, controllers) whose
//! connectors are connected. Each component brings its equations; [`structural_simplify`]
//! reduces the whole to a few states and residuals, [`DaeProblem`] integrates them with
//! SUNDIALS IDA, and the [`Solution`] gives back every variable of the model.
//!
//! # A tour by task
//!
//! ## Declare a component
//!
//! [`component!`] declares a component type: parameters (with units and defaults in their
//! docs), connectors, variables and equations, as in a Modelica model. The library's own
//! components are declared this way (see [`joints::Revolute`]); its syntax reference lists
//! every statement form.
//!
//! ```
//! use multibody::prelude::*;
//! use multibody::rotational::Flange;
//!
//! component! {
//!     /// A rotational inertia with viscous friction to the ground.
//!     pub struct LossyInertia {
//!         /// Moment of inertia [kg.m2], default 1.
//!         parameter J(min = 0.0): f64 = 1.0;
//!         /// Viscous friction coefficient [N.m.s/rad], default 0.1.
//!         parameter d: f64 = 0.1;
//!         /// The flange the inertia is mounted on.
//!         connector flange: Flange;
//!         /// Rotation angle [rad].
//!         variable phi(start = 1.0): Real;
//!         /// Angular velocity [rad/s].
//!         variable w: Real;
//!         equation {
//!             phi = flange.phi;
//!             w = der(phi);
//!             J * der(w) = flange.tau - d * w;
//!         }
//!     }
//! }
//! ```
//!
//! ## Assemble a model
//!
//! [`system!`] names instances and connects them. In its function form it defines a
//! function returning a [`Model`]: the assembled [`System`] together with a struct of
//! typed handles, one field per instance, through which variables and parameters are
//! named (`model.j1.phi`). Misspelt instances, connectors and parameters, and connections
//! of connectors of different types, are compile errors.
//!
//! ```
//! use multibody::joints::Revolute;
//! use multibody::parts::BodyShape;
//! use multibody::prelude::*;
//! use multibody::world::World;
//!
//! system! {
//!     /// A double pendulum of two rods of length `l` [m].
//!     pub fn double_pendulum(l: f64) -> DoublePendulum {
//!         world = World::default();
//!         j1 = Revolute::default();
//!         rod1 = BodyShape { r: [l, 0.0, 0.0], m: 1.0 };
//!         j2 = Revolute::default();
//!         rod2 = BodyShape { r: [l, 0.0, 0.0], m: 1.0 };
//!         connect(world.frame_b, j1.frame_a);
//!         connect(j1.frame_b, rod1.frame_a);
//!         connect(rod1.frame_b, j2.frame_a);
//!         connect(j2.frame_b, rod2.frame_a);
//!     }
//! }
//!
//! let model = double_pendulum(0.5);
//! assert_eq!(model.j2.phi.name().as_deref(), Some("j2.phi"));
//! assert_eq!(model.system().name, "double_pendulum");
//! ```
//!
//! What is only known at run time is assembled with builder calls on a [`System`]
//! ([`System::add`], [`System::connect`] by path), which the macro expands to.
//!
//! ```
//! use multibody::prelude::*;
//! use multibody::rotational::{Fixed, Inertia, Spring};
//!
//! let mut chain = System::new("chain");
//! chain.add("fixed", &Fixed::default());
//! let mut previous = "fixed.flange".to_string();
//! for k in 1..=3 {
//!     chain.add(&format!("spring{k}"), &Spring { c: 100.0, ..Spring::default() });
//!     chain.add(&format!("inertia{k}"), &Inertia::default());
//!     chain.connect(&previous, &format!("spring{k}.flange_a"));
//!     chain.connect(&format!("spring{k}.flange_b"), &format!("inertia{k}.flange_a"));
//!     previous = format!("inertia{k}.flange_b");
//! }
//! let ssys = structural_simplify(&chain)?;
//! assert_eq!(ssys.states().len(), 6);
//! # Ok::<(), multibody::Error>(())
//! ```
//!
//! ## Simplify
//!
//! [`structural_simplify`] flattens the model, eliminates aliases, reduces the index
//! (Pantelides), selects states (MSL's priorities; dynamic state selection where a
//! static choice degrades), sorts and tears the equations and compiles the residual.
//! The [`SimplifiedSystem`] tells what came out: states, algebraic unknowns, the
//! equations, and a Dymola-style translation report ([`SimplifiedSystem::statistics`]).
//! [`structural_simplify_with`] takes [`SimplifyOptions`]. A structurally singular model
//! is an error that names the equations and variables involved.
//!
//! ```
//! # use multibody::prelude::*;
//! # use multibody::rotational::{Fixed, Inertia, Spring};
//! # system! {
//! #     fn oscillator() -> Oscillator {
//! #         fixed = Fixed::default();
//! #         spring = Spring { c: 4.0 };
//! #         inertia = Inertia { phi_start: 1.0 };
//! #         connect(fixed.flange, spring.flange_a);
//! #         connect(spring.flange_b, inertia.flange_a);
//! #     }
//! # }
//! let model = oscillator();
//! let ssys = structural_simplify(&model)?;
//! assert_eq!(ssys.states(), ["inertia.phi", "inertia.w"]);
//! println!("{}", ssys.statistics());
//! for equation in ssys.equations() {
//!     println!("{equation}");
//! }
//! # Ok::<(), multibody::Error>(())
//! ```
//!
//! ## Solve
//!
//! A [`DaeProblem`] sets start values, parameter values and guesses (by handle or by
//! name) over a time span; [`DaeProblem::solve`] initializes the model consistently
//! and integrates it with the [`SolverOptions`] (tolerances, output times, step limits).
//! Other parameter values need a new problem, not a new compilation. Relations on
//! variables or time are events: the integration stops where one changes and restarts
//! (`when`, `reinit`, `sample` in [`component!`]); [`Solution::events`] lists them.
//!
//! ```
//! # use multibody::prelude::*;
//! # use multibody::rotational::{Fixed, Inertia, Spring};
//! # system! {
//! #     fn oscillator() -> Oscillator {
//! #         fixed = Fixed::default();
//! #         spring = Spring { c: 4.0 };
//! #         inertia = Inertia { phi_start: 1.0 };
//! #         connect(fixed.flange, spring.flange_a);
//! #         connect(spring.flange_b, inertia.flange_a);
//! #     }
//! # }
//! # let model = oscillator();
//! # let ssys = structural_simplify(&model)?;
//! let sol = DaeProblem::builder(&ssys, (0.0, 2.0))
//!     .value(model.inertia.phi, 0.5) // a start value
//!     .value(model.spring.c, 9.0) // a parameter
//!     .build()?
//!     .solve(&SolverOptions { rtol: 1e-8, ..SolverOptions::default() })?;
//! // phi = 0.5 cos(3 t)
//! assert!((sol.final_value(model.inertia.phi)? - 0.5 * 6.0f64.cos()).abs() < 1e-6);
//! # Ok::<(), multibody::Error>(())
//! ```
//!
//! ## Inputs, linearization and control design
//!
//! The model's inputs are signal inputs left unconnected ([`SimplifyOptions::open_inputs`])
//! or variables named in [`SimplifyOptions::inputs`]; each becomes a parameter of the
//! compiled model that a problem drives by a function of time or a table
//! ([`ProblemBuilder::input`], [`InputSignal`]), or holds at a value, without compiling
//! again. [`linearize`] gives the exact state-space model from those inputs to any
//! variables at a problem's initial point, a solution's point or a [`steady_state`];
//! [`LinearModel::poles`], [`LinearModel::frequency_response`], [`control::place_poles`]
//! and [`control::lqr`] work on it.
//!
//! ```
//! # use multibody::prelude::*;
//! use multibody::rotational::{Inertia, Torque};
//! use multibody::{SimplifyOptions, linearize, structural_simplify_with};
//!
//! let model = system! {
//!     name: "driven";
//!     torque = Torque::default();
//!     inertia = Inertia { J: 2.0 };
//!     connect(torque.flange, inertia.flange_a);
//! };
//! let options = SimplifyOptions { open_inputs: true, ..Default::default() };
//! let ssys = structural_simplify_with(&model, &options)?;
//! assert_eq!(ssys.inputs(), ["torque.tau"]);
//! let problem = DaeProblem::builder(&ssys, (0.0, 3.0))
//!     .input("torque.tau", |t: f64| t.sin())
//!     .build()?;
//! let sol = problem.solve(&SolverOptions { rtol: 1e-9, ..SolverOptions::default() })?;
//! // J phi'' = sin t from rest
//! assert!((sol.final_value("inertia.phi")? - (3.0 - 3.0f64.sin()) / 2.0).abs() < 1e-6);
//! let lin = linearize(&ssys, &problem.operating_point(), &["torque.tau"], &["inertia.w"])?;
//! assert_eq!(lin.states, ["inertia.phi", "inertia.w"]);
//! assert!((lin.b[(1, 0)] - 0.5).abs() < 1e-12); // 1 / J
//! # Ok::<(), multibody::Error>(())
//! ```
//!
//! ## Read results
//!
//! Every variable of the model can be read from the [`Solution`], not only the states:
//! [`Solution::get`] (the series at [`Solution::t`]), [`Solution::at`] (interpolated),
//! [`Solution::sample`], [`Solution::final_value`], derivatives as `"der(x)"`, parameter
//! values ([`Solution::parameter`]), declared units ([`Solution::unit`]), and CSV
//! ([`Solution::write_csv`], [`Solution::write_csv_all`]). A name that does not exist is
//! an error suggesting the closest ones.
//!
//! ```
//! # use multibody::prelude::*;
//! # use multibody::rotational::{Fixed, Inertia, Spring};
//! # system! {
//! #     fn oscillator() -> Oscillator {
//! #         fixed = Fixed::default();
//! #         spring = Spring { c: 4.0 };
//! #         inertia = Inertia { phi_start: 1.0 };
//! #         connect(fixed.flange, spring.flange_a);
//! #         connect(spring.flange_b, inertia.flange_a);
//! #     }
//! # }
//! # let model = oscillator();
//! # let ssys = structural_simplify(&model)?;
//! # let sol = DaeProblem::builder(&ssys, (0.0, 2.0)).build()?.solve(&SolverOptions::default())?;
//! let torque = sol.get(model.spring.tau)?; // a handle
//! let angle = sol.get("inertia.phi")?; // or a path
//! assert!((torque[0] - 4.0 * angle[0]).abs() < 1e-9); // tau = c phi
//! let accel = sol.at("der(inertia.w)", 1.0)?;
//! assert!((accel + 4.0 * sol.at(model.inertia.phi, 1.0)?).abs() < 1e-5);
//! assert_eq!(sol.unit(model.inertia.w).as_deref(), Some("rad/s"));
//! assert!(sol.get("inertia.omega").unwrap_err().to_string().contains("inertia.w"));
//! # Ok::<(), multibody::Error>(())
//! ```
//!
//! ## Plot
//!
//! [`plot()`] draws variables against time into a PNG; [`Figure`] arranges panels, titles
//! and overlays of several solutions (what `plot!` does in Julia). The y axes are
//! labelled with the variables' declared units.
//!
//! ```no_run
//! # use multibody::prelude::*;
//! # use multibody::rotational::{Fixed, Inertia, Spring};
//! # system! {
//! #     fn oscillator() -> Oscillator {
//! #         fixed = Fixed::default();
//! #         spring = Spring { c: 4.0 };
//! #         inertia = Inertia { phi_start: 1.0 };
//! #         connect(fixed.flange, spring.flange_a);
//! #         connect(spring.flange_b, inertia.flange_a);
//! #     }
//! # }
//! # let model = oscillator();
//! # let ssys = structural_simplify(&model)?;
//! let soft = DaeProblem::builder(&ssys, (0.0, 5.0)).build()?.solve(&SolverOptions::default())?;
//! let stiff = DaeProblem::builder(&ssys, (0.0, 5.0))
//!     .value(model.spring.c, 16.0)
//!     .build()?
//!     .solve(&SolverOptions::default())?;
//! plot(&soft, &[model.inertia.phi, model.inertia.w], "oscillator.png")?;
//! Figure::new()
//!     .title("Two springs")
//!     .labelled_panel(&soft, &[model.inertia.phi], "c = 4")
//!     .overlay(&stiff, &[model.inertia.phi], "c = 16")
//!     .labelled_panel(&soft, &[model.inertia.w], "c = 4")
//!     .overlay(&stiff, &[model.inertia.w], "c = 16")
//!     .save("springs.png")?;
//! # Ok::<(), multibody::Error>(())
//! ```
//!
//! ## Animate
//!
//! [`render`](render::render) draws a 3-D mechanism at chosen times into an animated GIF
//! (bodies by their shapes, joints, springs, world axes, a ground grid) from the solution
//! alone; [`render_frame`](render::render_frame) writes one PNG. See
//! [`RenderOptions`](render::RenderOptions) for the camera.
//!
//! ```no_run
//! # use multibody::joints::Revolute;
//! # use multibody::parts::BodyShape;
//! # use multibody::prelude::*;
//! # use multibody::world::World;
//! # system! {
//! #     fn pendulum() -> Pendulum {
//! #         world = World::default();
//! #         j1 = Revolute::default();
//! #         rod = BodyShape { r: [0.5, 0.0, 0.0] };
//! #         connect(world.frame_b, j1.frame_a);
//! #         connect(j1.frame_b, rod.frame_a);
//! #     }
//! # }
//! let model = pendulum();
//! let ssys = structural_simplify(&model)?;
//! let sol = DaeProblem::builder(&ssys, (0.0, 3.0)).build()?.solve(&SolverOptions::default())?;
//! let options = RenderOptions {
//!     camera: [0.5, 0.2, 2.0],
//!     look_at: [0.0, -0.25, 0.0],
//!     times: Some((0..=60).map(|k| 0.05 * k as f64).collect()),
//!     ..RenderOptions::default()
//! };
//! render(&model, &sol, "pendulum.gif", &options)?;
//! # Ok::<(), multibody::Error>(())
//! ```
//!
//! ## Errors
//!
//! Every fallible call returns [`Error`] (or one of the stage errors in [`error`] it
//! wraps). Messages name the component and variable by full path: a parameter outside
//! its range, a zero joint axis, a structurally singular model, an initialization that
//! does not converge, a value that became NaN during the solve. Library code never
//! prints; diagnostics go to the [`log`](https://docs.rs/log) crate.
//!
//! # Where the components are
//!
//! | module | MSL package |
//! |---|---|
//! | [`world`], [`parts`], [`joints`], [`forces`], [`sensors`], [`frames`], [`interfaces`] | `Mechanics.MultiBody` |
//! | [`rotational`] | `Mechanics.Rotational` |
//! | [`translational`] | `Mechanics.Translational` |
//! | [`electrical`] | `Electrical.Analog` |
//! | [`blocks`] | `Blocks` |
//! | [`robot_r3`] | `Mechanics.MultiBody.Examples.Systems.RobotR3` (OneAxis, FullRobot) |
//! | [`loops`] | planar-loop diagnosis for [`SimplifyOptions::planar_loops`] |

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
pub mod robot_r3;
pub mod rotational;
pub mod sensors;
mod tables;
pub mod translational;
pub mod world;

pub use mechanism::{structural_simplify, structural_simplify_with};
pub use multibody_core::Error;
/// Controller design on linear models: pole placement and the linear-quadratic
/// regulator.
pub use multibody_core::control;
pub use multibody_core::expr::Expr;
pub use multibody_core::model::{
    Component, Connector, ConnectorHandle, Model, Named, Parameter, PathId, Real, Signal,
    StateSelect, System, TypedComponent, VarKind, Variable,
};
/// The linear algebra of [`LinearModel`] (`DMatrix`, `Complex`): the `nalgebra` crate.
pub use multibody_core::nalgebra;
pub use multibody_core::simplify::{
    DynamicStates, EventRelation, PhaseTimes, PlanarLoops, SimplifiedSystem, SimplifyOptions,
    StateCandidates, Statistics,
};
pub use multibody_core::solve::{
    DaeProblem, EnsembleOptions, Event, IdaStats, InitReport, InputSignal, LinearModel,
    LinearSolver, Method, OperatingPoint, Pole, ProblemBuilder, Segment, Solution, SolverOptions,
    SteadyStateOptions, Termination, linearize, linearize_in, solve_ensemble, steady_state,
};
#[doc = include_str!("../docs/macros/component.md")]
pub use multibody_macros::component;
#[doc = include_str!("../docs/macros/connector.md")]
pub use multibody_macros::connector;
#[doc = include_str!("../docs/macros/system.md")]
pub use multibody_macros::system;

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
pub use plot::{Figure, PlotOptions, plot, plot_figure};

/// Plots of solutions: variables against time by name or handle, with their units, in
/// panels, several solutions overlaid ([`Figure`]); of linear models (Bode diagrams,
/// poles); and the panels underneath ([`plot_panels`](plot::plot_panels)) for curves of
/// any data.
pub mod plot {
    pub use multibody_core::plot::{
        Figure, Panel, PlotError, PlotOptions, Series, plot, plot_bode, plot_figure, plot_panels,
        plot_poles,
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
    pub use std::f64::consts::PI;
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

    /// A structural parameter's value on its way to [`System::record_structural`]:
    /// `(&Recorded(&v)).numbers()` is its numbers when its type is a
    /// [`StructuralValue`], `None` otherwise (autoref specialization).
    pub struct Recorded<'a, T>(pub &'a T);

    /// The numbers of a [`StructuralValue`] (the preferred method of [`Recorded`]).
    pub trait RecordsNumbers {
        /// The value as numbers.
        fn numbers(&self) -> Option<Vec<f64>>;
    }

    impl<T: StructuralValue> RecordsNumbers for Recorded<'_, T> {
        fn numbers(&self) -> Option<Vec<f64>> {
            self.0.structural_values()
        }
    }

    /// Nothing, for a type that is not a [`StructuralValue`] (the fallback method of
    /// [`Recorded`], found one autoref later).
    pub trait RecordsNothing {
        /// `None`.
        fn numbers(&self) -> Option<Vec<f64>>;
    }

    impl<T> RecordsNothing for &Recorded<'_, T> {
        fn numbers(&self) -> Option<Vec<f64>> {
            None
        }
    }

    /// The functions equations use (`der`, `sin`, ...).
    pub mod dsl {
        pub use crate::functions::*;
        pub use multibody_core::model::StateSelect;
    }
}
