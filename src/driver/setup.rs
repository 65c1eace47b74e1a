//! A command's request resolved once against its model into a plain value
//! that the command consumes: [`resolve`] turns the request's text
//! assignments ([`Asked`]) into a [`Setup`]. `simulate`, `linearize`,
//! `map` and `gait` each call it once and read what they need from the
//! value; nothing here calls back into a command
//! (docs/guide/how-it-works.md, "A request's way").
//!
//! - `parameters`: `--param NAME=VALUE`, set on the model, a
//!   controller's gains beside them ([`Controls`]);
//! - [`state`]: the state assignments (`--initial`, `--at`), expressions
//!   of the parameters and the command's variables (a sweep variable, a
//!   speed) read once ([`StateFamily`]), and for a run its [`Start`]
//!   solved: the coordinates not given from `f(q) = 0`, the velocities not
//!   given from `A(q) qdot = 0`, else the default motion ([`Origin`]);
//! - [`inputs`]: the `--input` laws of `t`, the parameters and the state;
//! - [`stop`]: the `--stop-when` condition.
//!
//! Each mistake is an [`InputError`] stated in one line.

mod error;
mod frames;
pub mod inputs;
mod parameters;
pub mod state;
pub mod stop;

pub use error::InputError;
pub use frames::AngularVelocity;
pub use inputs::InputSchedule;
pub use parameters::{set_parameters, with_parameters};
pub use state::{Assigned, Origin, Start, StateFamily};
pub use stop::{Comparison, StopError};

use super::expression::Scope;
use chaplygin_codegen::interpret::InterpretedModel;
use state::StateNames;

/// What a command asks, as given: text assignments not yet read against
/// the model. Empty by default.
#[derive(Clone, Copy, Debug, Default)]
pub struct Asked<'a> {
    /// `NAME=VALUE`: the model's parameters and the controller's gains.
    pub params: &'a [(String, f64)],
    /// The flag the state assignments come with, for messages
    /// (`--initial`, `--at`).
    pub state_flag: &'a str,
    /// `q=EXPR`, `dot(q)=EXPR` and the controller's states `NAME=EXPR`.
    pub state: &'a [(String, String)],
    /// Names the state's expressions may read besides the parameters,
    /// their values given where the state is read ([`StateFamily::at`]).
    pub variables: &'a [&'a str],
    /// `NAME=EXPR`: the input laws.
    pub inputs: &'a [(String, String)],
    /// `--stop-when COND`.
    pub stop_when: Option<&'a str>,
    /// Where a run starts unless the state assignments say otherwise;
    /// `None` for a command that runs from no state of its own.
    pub start: Option<Origin<'a>>,
    /// The controller's own names.
    pub controls: Controls<'a>,
}

/// A controller's names beside the model's, each with its default: its
/// gains, set as parameters are, and its states, given as initial values
/// are.
#[derive(Clone, Copy, Debug, Default)]
pub struct Controls<'a> {
    /// The gains.
    pub gains: &'a [(&'a str, f64)],
    /// The states.
    pub states: &'a [(&'a str, f64)],
}

/// A request resolved against its model.
pub struct Setup {
    /// The model, its parameters set.
    pub model: InterpretedModel,
    /// Every parameter's name and value, then the controller's gains.
    pub parameters: Vec<(String, f64)>,
    /// The state assignments, read.
    pub state: StateFamily,
    /// The start, where [`Asked::start`] asks for one.
    pub start: Option<Start>,
    /// The controller's states, as [`Controls::states`] orders them.
    pub controller_states: Vec<f64>,
    /// The input laws.
    pub inputs: InputSchedule,
    /// The stop condition.
    pub stop: Option<Comparison>,
}

impl Setup {
    /// The parameters' (and the gains') names and values, borrowed.
    pub fn bound(&self) -> Vec<(&str, f64)> {
        (self.parameters.iter())
            .map(|(name, value)| (name.as_str(), *value))
            .collect()
    }
}

/// `asked` read against `model`, its parameters set on it.
///
/// # Errors
/// An unknown name, an expression that does not read, a start the
/// constraints do not determine.
pub fn resolve(mut model: InterpretedModel, asked: &Asked<'_>) -> Result<Setup, InputError> {
    let parameters = parameters(&mut model, asked)?;
    let names = model.names().clone();
    let coordinates: Vec<&str> = names.coordinates.iter().map(String::as_str).collect();
    let inputs: Vec<&str> = names.inputs.iter().map(String::as_str).collect();
    let bound: Vec<(&str, f64)> = (parameters.iter())
        .map(|(name, value)| (name.as_str(), *value))
        .collect();
    let controller: Vec<&str> = asked.controls.states.iter().map(|(n, _)| *n).collect();
    let state = StateFamily::new(
        &StateNames {
            flag: asked.state_flag,
            coordinates: &coordinates,
            controller: &controller,
            parameters: &bound,
            variables: asked.variables,
            frames: frames::Frames {
                names: &names.frames,
                turns: model.turns(),
            },
        },
        asked.state,
    )?;
    let schedule = InputSchedule::new(
        &inputs,
        asked.inputs,
        &bound,
        (asked.variables, &coordinates),
    )?;
    let scope = Scope {
        parameters: &bound,
        coordinates: &coordinates,
        inputs: &inputs,
        ..Scope::default()
    };
    let stop = (asked.stop_when)
        .map(|text| Comparison::parse(text, &scope))
        .transpose()?;
    let (start, controller_states) = match &asked.start {
        Some(origin) => {
            let assigned = state.at(&[])?;
            let start = state::start(&model, origin, &assigned, &bound)?;
            let defaults = asked.controls.states.iter().map(|(_, value)| *value);
            let states = (assigned.controller.iter().zip(defaults))
                .map(|(given, default)| given.unwrap_or(default))
                .collect();
            (Some(start), states)
        }
        None => (None, Vec::new()),
    };
    Ok(Setup {
        model,
        parameters,
        state,
        start,
        controller_states,
        inputs: schedule,
        stop,
    })
}

/// Sets the model's parameters and the controller's gains from
/// `asked.params`; every parameter's name and value, then the gains'.
fn parameters(
    model: &mut InterpretedModel,
    asked: &Asked<'_>,
) -> Result<Vec<(String, f64)>, InputError> {
    let mut gains: Vec<(String, f64)> = (asked.controls.gains.iter())
        .map(|(name, value)| (name.to_string(), *value))
        .collect();
    let names = model.names().parameters.clone();
    let known: Vec<&str> = (names.iter().map(String::as_str))
        .chain(asked.controls.gains.iter().map(|(name, _)| *name))
        .collect();
    set_parameters(&known, asked.params, &mut |name, value| {
        match gains.iter_mut().find(|(gain, _)| gain == name) {
            Some((_, gain)) => *gain = value,
            None => return model.set_parameter(name, value).is_ok(),
        }
        true
    })?;
    let values = model.parameter_values().iter().copied();
    Ok(names.into_iter().zip(values).chain(gains).collect())
}
