//! `--param NAME=VALUE`: the model's parameters and a controller's gains,
//! set by name.

use super::error::InputError;
use chaplygin_codegen::interpret::InterpretedModel;

/// Sets `--param` values with `set`, which says whether the name was a
/// parameter; `known` lists them for the error.
///
/// # Errors
/// A name `set` does not take.
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
