//! `structural_simplify` for mechanisms: the core's simplification, preceded by the
//! checks that need to know what the components are (planar kinematic loops).

use multibody_core::Error;
use multibody_core::model::{ModelError, System};
use multibody_core::simplify::{
    self, PlanarLoops, SimplifiedSystem, SimplifyError, SimplifyOptions,
};

use crate::loops::{planar_loops, remove_planar_redundancy};

/// Simplifies a model with default options: see [`structural_simplify_with`].
pub fn structural_simplify(
    model: &(impl AsRef<System> + ?Sized),
) -> Result<SimplifiedSystem, Error> {
    structural_simplify_with(model, &SimplifyOptions::default())
}

/// Flattens `model`, checks its balance, eliminates aliases, reduces the index,
/// selects states, sorts and tears the equations, and compiles the residual, its
/// Jacobian and the observed variables
/// ([`multibody_core::simplify::structural_simplify_with`]).
///
/// Before that, closed kinematic loops whose revolute joints have parallel axes are
/// looked for: with [`PlanarLoops::Diagnose`] (the default) such a loop is an error
/// naming its joints ([`SimplifyError::PlanarLoop`]); with
/// [`PlanarLoops::RemoveRedundant`] one revolute joint of each becomes a planar cut and
/// the model runs unchanged.
pub fn structural_simplify_with(
    model: &(impl AsRef<System> + ?Sized),
    options: &SimplifyOptions,
) -> Result<SimplifiedSystem, Error> {
    let model = model.as_ref();
    simplify_mechanism(model, options).map_err(|e| missing_world(model, e))
}

/// [`structural_simplify_with`] without the diagnosis of a missing world.
fn simplify_mechanism(
    model: &System,
    options: &SimplifyOptions,
) -> Result<SimplifiedSystem, Error> {
    let loops = planar_loops(model);
    if loops.is_empty() {
        return simplify::structural_simplify_with(model, options);
    }
    match options.planar_loops {
        PlanarLoops::Diagnose => Err(SimplifyError::PlanarLoop {
            model: model.name.clone(),
            joints: loops[0].clone(),
        }
        .into()),
        PlanarLoops::RemoveRedundant => {
            let fixed = remove_planar_redundancy(model, &loops);
            log::info!(
                "model `{}`: {} planar loop(s) closed by planar cuts",
                model.name,
                loops.len()
            );
            simplify::structural_simplify_with(&fixed, options)
        }
    }
}

/// `e`, or, when it is about a name under `world` that the model does not have, the
/// error that says the model needs a `World` named `world`.
fn missing_world(model: &System, e: Error) -> Error {
    let refers_to_world = matches!(
        &e,
        Error::Model(m) if matches!(&**m, ModelError::UnknownName { name, .. }
            if name.starts_with("world."))
    );
    if !refers_to_world || model.subsystem("world").is_some() {
        return e;
    }
    let found = model
        .subsystems
        .iter()
        .filter(|s| s.type_name == WORLD_TYPE)
        .map(|s| s.name.clone())
        .collect();
    ModelError::MissingInner {
        model: model.name.clone(),
        name: "world".into(),
        type_name: WORLD_TYPE.into(),
        found,
    }
    .into()
}

/// The type name of [`crate::world::World`].
const WORLD_TYPE: &str = "MultiBody.World";
