//! What is wrong with a simulation's input, stated in one line.

use crate::runtime::linearize::PointError;

/// A problem with the command's input, stated in one line.
#[derive(Debug, thiserror::Error)]
pub enum InputError {
    /// `--param` names no parameter.
    #[error("unknown parameter `{name}` (parameters: {known})")]
    UnknownParameter {
        /// What was given.
        name: String,
        /// The parameters there are.
        known: String,
    },
    /// `--initial` names no coordinate, velocity or controller state.
    #[error("unknown initial value `{name}` (coordinates, `dot(q)` velocities{states}: {known})")]
    UnknownInitial {
        /// What was given.
        name: String,
        /// ", controller states" when there are some.
        states: &'static str,
        /// The names there are.
        known: String,
    },
    /// An `--initial` value is not a constant of the parameters.
    #[error("--initial {name}={text}: {reason}")]
    InitialValue {
        /// What was given a value.
        name: String,
        /// The value as given.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
    /// `--input` names no input.
    #[error("unknown input `{name}` (inputs: {known})")]
    UnknownInput {
        /// What was given.
        name: String,
        /// The inputs there are.
        known: String,
    },
    /// The coordinates or velocities not given cannot be solved from the
    /// constraints (a configuration constraint no coordinate left unset
    /// meets is named with its residual).
    #[error(transparent)]
    Point(#[from] PointError),
    /// A combination the command does not run.
    #[error("{0}")]
    Unsupported(String),
}
