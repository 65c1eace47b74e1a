//! What is wrong with a command's request, stated in one line.

use super::stop::StopError;
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
    /// A state assignment names no coordinate, velocity or controller
    /// state.
    #[error("{flag}: unknown name `{name}` (coordinates, `dot(q)` velocities{states}: {known})")]
    UnknownState {
        /// The flag it came with (`--initial`, `--at`).
        flag: String,
        /// What was given.
        name: String,
        /// ", controller states" when there are some.
        states: &'static str,
        /// The names there are.
        known: String,
    },
    /// A state assignment's value is not an expression of the parameters
    /// and the command's variables, or not finite.
    #[error("{flag} {name}={text}: {reason}")]
    StateValue {
        /// The flag it came with (`--initial`, `--at`).
        flag: String,
        /// What was given a value.
        name: String,
        /// The value as given.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
    /// `omega(F)` or `angles(F, seq)` names no frame.
    #[error("{flag} {name}: unknown frame `{frame}` (frames: {known})")]
    UnknownFrame {
        /// The flag it came with (`--initial`, `--at`).
        flag: String,
        /// What was given a value.
        name: String,
        /// The frame named.
        frame: String,
        /// The frames there are.
        known: String,
    },
    /// `omega(F)` or `angles(F, seq)` asks what the frame's coordinates
    /// cannot give.
    #[error("{flag} {name}: {reason}")]
    FrameState {
        /// The flag it came with (`--initial`, `--at`).
        flag: String,
        /// What was given a value.
        name: String,
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
    /// An `--input` law is not an expression of `t`, the parameters and
    /// the state.
    #[error("--input {name}={text}: {reason}")]
    InputLaw {
        /// The input.
        name: String,
        /// The law as given.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A `--prescribe` that cannot be followed: a name that is no
    /// coordinate or is given twice, a law not of `t` and the parameters,
    /// a coordinate the formulation or the constraints let no force move.
    #[error("--prescribe {name}: {reason}")]
    Prescribe {
        /// The coordinate as given, with its law where the law is wrong.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// The `--stop-when` condition.
    #[error(transparent)]
    Stop(#[from] StopError),
    /// The coordinates or velocities not given cannot be solved from the
    /// constraints (a configuration constraint no coordinate left unset
    /// meets is named with its residual).
    #[error(transparent)]
    Point(#[from] PointError),
    /// A combination the command does not run.
    #[error("{0}")]
    Unsupported(String),
}
