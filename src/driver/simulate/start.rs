//! What a run starts from: the parameters (`--param`) and the initial state
//! (`--initial`: with configuration constraints, the coordinates given are
//! fixed and the others solved from `f(q) = 0`; the velocities given are
//! fixed and the others solved from the constraints, as for
//! `chaplygin linearize --at`, see [`configuration`]), each mistake an
//! [`InputError`] stated in one line.

use super::error::InputError;
use crate::driver::expression::constant;
use crate::runtime::linearize::Dynamics;
use crate::runtime::linearize::point::{configuration, solve_velocities, velocity_names};
use crate::runtime::nalgebra::DMatrix;
use chaplygin_codegen::interpret::InterpretedModel;

/// Sets `--param` values with `set`, which says whether the name was a
/// parameter; `known` lists them for the error.
pub fn set_parameters(
    known: &[&str],
    given: &[(String, f64)],
    set: &mut dyn FnMut(&str, f64) -> bool,
) -> Result<(), InputError> {
    for (name, value) in given {
        if !set(name, *value) {
            return Err(InputError::UnknownParameter {
                name: name.clone(),
                known: known.join(", "),
            });
        }
    }
    Ok(())
}

/// Sets the `given` parameter values on `model`; returns every
/// parameter's name and value.
///
/// # Errors
/// A name that is no parameter of the model.
pub fn with_parameters(
    model: &mut InterpretedModel,
    given: &[(String, f64)],
) -> Result<Vec<(String, f64)>, InputError> {
    let known = model.names().parameters.clone();
    let names: Vec<&str> = known.iter().map(String::as_str).collect();
    set_parameters(&names, given, &mut |name, value| {
        model.set_parameter(name, value).is_ok()
    })?;
    Ok(known
        .into_iter()
        .zip(model.parameter_values().iter().copied())
        .collect())
}

/// The `--initial` assignments with their values, expressions of the
/// `parameters` (name and value), evaluated.
pub(super) fn initial_values(
    given: &[(String, String)],
    parameters: &[(&str, f64)],
) -> Result<Vec<(String, f64)>, InputError> {
    given
        .iter()
        .map(|(name, text)| {
            constant(text, parameters)
                .map(|value| (name.clone(), value))
                .map_err(|error| InputError::InitialValue {
                    name: name.clone(),
                    text: text.clone(),
                    reason: error.to_string(),
                })
        })
        .collect()
}

/// The initial configuration and velocity.
pub(super) struct Start {
    pub(super) q: Vec<f64>,
    pub(super) qdot: Vec<f64>,
}

/// `A(q)` from `q`.
type ConstraintMatrix<'a> = dyn Fn(&[f64]) -> DMatrix<f64> + 'a;

/// What the initial state is checked and completed with.
pub(super) struct Kinematics<'a> {
    pub(super) coordinates: &'a [&'a str],
    pub(super) constraints: &'a [&'a str],
    pub(super) default_q: &'a [f64],
    /// The default velocity at a configuration.
    pub(super) default_motion: &'a dyn Fn(&[f64]) -> Vec<f64>,
    /// `A(q)`.
    pub(super) constraint_matrix: &'a ConstraintMatrix<'a>,
    /// The configuration constraints `f(q) = 0`, if the model declares any.
    pub(super) holonomic: Option<&'a dyn Dynamics>,
}

/// The initial state from the defaults and `--initial` (coordinates,
/// `dot(q)` velocities and `controller_states`): without a velocity given,
/// the default motion; else the velocities given, and the others solved
/// from `A(q) qdot = 0` (an error names those left free, or the constraint
/// the velocities given violate). With configuration constraints, the
/// coordinates not given are solved from `f(q) = 0` first (an error names
/// the constraint no choice of them meets, with its residual).
pub(super) fn initial_state(
    kinematics: &Kinematics<'_>,
    given: &[(String, f64)],
    controller_states: &mut [(&str, &mut f64)],
) -> Result<Start, InputError> {
    let coordinates = kinematics.coordinates;
    let mut q = kinematics.default_q.to_vec();
    let mut velocities: Vec<Option<f64>> = vec![None; coordinates.len()];
    let mut positions: Vec<Option<f64>> = vec![None; coordinates.len()];
    for (name, value) in given {
        if let Some(i) = coordinates.iter().position(|c| c == name) {
            q[i] = *value;
            positions[i] = Some(*value);
        } else if let Some(i) = coordinates
            .iter()
            .position(|c| name == &format!("dot({c})"))
        {
            velocities[i] = Some(*value);
        } else if let Some((_, state)) = controller_states.iter_mut().find(|(n, _)| n == name) {
            **state = *value;
        } else {
            return Err(unknown_initial(name, coordinates, controller_states));
        }
    }
    if let Some(holonomic) = kinematics.holonomic
        && !holonomic.holonomic().is_empty()
    {
        q = configuration(holonomic, &positions)?;
    }
    let qdot = if velocities.iter().all(Option::is_none) {
        (kinematics.default_motion)(&q)
    } else {
        let names: Vec<String> = coordinates.iter().map(|c| c.to_string()).collect();
        let constraints: Vec<String> = kinematics
            .constraints
            .iter()
            .map(|c| c.to_string())
            .collect();
        solve_velocities(
            &(kinematics.constraint_matrix)(&q),
            &constraints,
            &velocity_names(&names),
            &velocities,
        )?
    };
    Ok(Start { q, qdot })
}

/// The `--initial` assignments `given`, after the `defaults` when `given`
/// names no velocity (coordinates given keep their place: the default
/// velocities are solved at them).
pub(super) fn with_default_motion(
    given: &[(String, String)],
    defaults: &[(&str, &str)],
) -> Vec<(String, String)> {
    let moving = given.iter().any(|(name, _)| name.starts_with("dot("));
    let defaults = defaults
        .iter()
        .filter(|_| !moving)
        .map(|(name, text)| (name.to_string(), text.to_string()));
    defaults.chain(given.iter().cloned()).collect()
}

fn unknown_initial(
    name: &str,
    coordinates: &[&str],
    controller_states: &[(&str, &mut f64)],
) -> InputError {
    let velocities = coordinates.iter().map(|c| format!("dot({c})"));
    let known: Vec<String> = coordinates
        .iter()
        .map(|c| c.to_string())
        .chain(velocities)
        .chain(controller_states.iter().map(|(n, _)| n.to_string()))
        .collect();
    InputError::UnknownInitial {
        name: name.to_string(),
        states: if controller_states.is_empty() {
            ""
        } else {
            ", controller states"
        },
        known: known.join(", "),
    }
}
