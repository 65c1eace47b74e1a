//! The state a command names: its assignments `q=EXPR` and `dot(q)=EXPR`
//! (`--initial`, `--at`), and a controller's states, read once as
//! expressions of the parameters and the command's variables
//! ([`StateFamily`]); at the variables' values, the values they give
//! ([`Assigned`]); and a run's start ([`Start`]): with configuration
//! constraints, the coordinates given are fixed and the others solved from
//! `f(q) = 0`; the velocities given are fixed and the others solved from
//! `A(q) qdot = 0`, as for `chaplygin linearize --at`; without a velocity
//! given, the default motion.

use super::error::InputError;
use crate::driver::catalog::Motion;
use crate::driver::expression::{Expression, ExpressionError, Point, Scope, constant};
use crate::runtime::linearize::Dynamics;
use crate::runtime::linearize::point::{configuration, solve_velocities, velocity_names};
use crate::runtime::nalgebra::DMatrix;
use chaplygin_codegen::interpret::{InterpretedModel, evaluated};

/// What a state assignment sets.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Slot {
    /// The coordinate of this index.
    Coordinate(usize),
    /// The velocity of the coordinate of this index.
    Velocity(usize),
    /// The controller state of this index.
    Controller(usize),
}

/// The state assignments of a command, each an expression of the
/// parameters (at their values) and the command's variables.
#[derive(Clone, Debug, PartialEq)]
pub struct StateFamily {
    flag: String,
    variables: Vec<String>,
    assignments: Vec<Assignment>,
    coordinates: usize,
    controller_states: usize,
}

/// One assignment: what it sets and its expression, with its text.
#[derive(Clone, Debug, PartialEq)]
struct Assignment {
    slot: Slot,
    name: String,
    text: String,
    value: Expression,
}

/// The values the assignments give at the variables' values: `None`
/// where nothing is given.
#[derive(Clone, Debug, PartialEq)]
pub struct Assigned {
    /// The coordinates.
    pub q: Vec<Option<f64>>,
    /// Their velocities.
    pub qdot: Vec<Option<f64>>,
    /// The controller's states.
    pub controller: Vec<Option<f64>>,
}

/// The names a state assignment may set or read.
pub(super) struct StateNames<'a> {
    /// The flag the assignments come with, for messages.
    pub flag: &'a str,
    /// The coordinates.
    pub coordinates: &'a [&'a str],
    /// A controller's states.
    pub controller: &'a [&'a str],
    /// The parameters' names and values.
    pub parameters: &'a [(&'a str, f64)],
    /// The command's variables.
    pub variables: &'a [&'a str],
}

impl StateFamily {
    /// The assignments `given` read against `names`.
    ///
    /// # Errors
    /// A name that is no coordinate, velocity or controller state, or an
    /// expression that is not one of the parameters and the variables.
    pub(super) fn new(
        names: &StateNames<'_>,
        given: &[(String, String)],
    ) -> Result<Self, InputError> {
        let assignments = given
            .iter()
            .map(|(name, text)| {
                let slot = slot(names, name)?;
                let value = expression(names, text).map_err(|reason| InputError::StateValue {
                    flag: names.flag.to_string(),
                    name: name.clone(),
                    text: text.clone(),
                    reason,
                })?;
                Ok(Assignment {
                    slot,
                    name: name.clone(),
                    text: text.clone(),
                    value,
                })
            })
            .collect::<Result<_, InputError>>()?;
        Ok(Self {
            flag: names.flag.to_string(),
            variables: names.variables.iter().map(|v| v.to_string()).collect(),
            assignments,
            coordinates: names.coordinates.len(),
            controller_states: names.controller.len(),
        })
    }

    /// Whether an assignment reads `variable`.
    pub fn reads(&self, variable: &str) -> bool {
        (self.variables.iter().position(|v| v == variable))
            .is_some_and(|i| self.assignments.iter().any(|a| a.value.reads_variable(i)))
    }

    /// The values at `variables`, the variables' values in the order they
    /// were declared.
    ///
    /// # Errors
    /// A value that is not finite there.
    pub fn at(&self, variables: &[f64]) -> Result<Assigned, InputError> {
        let n = self.coordinates;
        let mut assigned = Assigned {
            q: vec![None; n],
            qdot: vec![None; n],
            controller: vec![None; self.controller_states],
        };
        let point = Point {
            variables,
            ..Point::default()
        };
        for assignment in &self.assignments {
            let value = assignment.value.at(&point);
            if !value.is_finite() {
                return Err(InputError::StateValue {
                    flag: self.flag.clone(),
                    name: assignment.name.clone(),
                    text: assignment.text.clone(),
                    reason: format!("the value {value} is not finite"),
                });
            }
            let entry = match assignment.slot {
                Slot::Coordinate(i) => &mut assigned.q[i],
                Slot::Velocity(i) => &mut assigned.qdot[i],
                Slot::Controller(i) => &mut assigned.controller[i],
            };
            *entry = Some(value);
        }
        Ok(assigned)
    }
}

/// What `name` sets.
fn slot(names: &StateNames<'_>, name: &str) -> Result<Slot, InputError> {
    let coordinates = names.coordinates;
    if let Some(i) = coordinates.iter().position(|c| *c == name) {
        return Ok(Slot::Coordinate(i));
    }
    if let Some(i) = (coordinates.iter()).position(|c| name == format!("dot({c})")) {
        return Ok(Slot::Velocity(i));
    }
    if let Some(i) = names.controller.iter().position(|c| *c == name) {
        return Ok(Slot::Controller(i));
    }
    let velocities = coordinates.iter().map(|c| format!("dot({c})"));
    let known: Vec<String> = (coordinates.iter().map(|c| c.to_string()))
        .chain(velocities)
        .chain(names.controller.iter().map(|c| c.to_string()))
        .collect();
    Err(InputError::UnknownState {
        flag: names.flag.to_string(),
        name: name.to_string(),
        states: if names.controller.is_empty() {
            ""
        } else {
            ", controller states"
        },
        known: known.join(", "),
    })
}

/// `text` read as an expression of the parameters and the variables.
fn expression(names: &StateNames<'_>, text: &str) -> Result<Expression, String> {
    let scope = Scope {
        parameters: names.parameters,
        variables: names.variables,
        ..Scope::default()
    };
    let value = Expression::parse(text, &scope).map_err(|error| match error {
        ExpressionError::UnknownName { name, .. } => {
            let parameters = names.parameters.iter().map(|(p, _)| *p);
            let known: Vec<&str> = parameters.chain(names.variables.iter().copied()).collect();
            format!("unknown name `{name}` (known: {}, pi)", known.join(", "))
        }
        ExpressionError::Invalid(reason) => reason,
    })?;
    match value.reads_time() {
        true => Err("`t` is not known here: use numbers, parameters and variables".into()),
        false => Ok(value),
    }
}

/// The initial configuration and velocity of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct Start {
    /// The configuration.
    pub q: Vec<f64>,
    /// Its velocity.
    pub qdot: Vec<f64>,
}

/// Where a run starts where its assignments leave the state open.
#[derive(Clone, Copy, Debug, Default)]
pub struct Origin<'a> {
    /// The configuration; `None` for `q = 0`.
    pub q: Option<&'a [f64]>,
    /// The motion; `None` for rest.
    pub motion: Option<Motion>,
}

/// The start of `model` from `assigned` and the `origin`: the coordinates
/// given, the others the origin's (with configuration constraints, solved
/// from `f(q) = 0`); the velocities given and the others solved from the
/// constraints, or without a velocity given, the origin's motion (its
/// `dot(q)` expressions of the `parameters` solved as given ones are).
///
/// # Errors
/// Velocities the constraints do not determine or that violate them, a
/// configuration constraint no choice of the coordinates not given meets,
/// or a default velocity that does not read.
pub(super) fn start(
    model: &InterpretedModel,
    origin: &Origin<'_>,
    assigned: &Assigned,
    parameters: &[(&str, f64)],
) -> Result<Start, InputError> {
    let n = assigned.q.len();
    let mut q = origin.q.map_or_else(|| vec![0.0; n], <[f64]>::to_vec);
    for (entry, given) in q.iter_mut().zip(&assigned.q) {
        *entry = given.unwrap_or(*entry);
    }
    if !model.holonomic().is_empty() {
        q = configuration(model, &assigned.q)?;
    }
    let given_velocity = assigned.qdot.iter().any(Option::is_some);
    let qdot = match origin.motion {
        _ if given_velocity => solved_velocities(model, &q, &assigned.qdot)?,
        Some(Motion::Momenta(alpha)) => evaluated(model.velocities(&q, alpha)),
        Some(Motion::Velocities(defaults)) => {
            let velocities = default_velocities(model, defaults, parameters)?;
            solved_velocities(model, &q, &velocities)?
        }
        None => vec![0.0; n],
    };
    Ok(Start { q, qdot })
}

/// The velocities `given`, the others solved from `A(q) qdot = 0`.
fn solved_velocities(
    model: &InterpretedModel,
    q: &[f64],
    given: &[Option<f64>],
) -> Result<Vec<f64>, InputError> {
    let names = model.names();
    let a = evaluated(model.constraint_matrix(q));
    let a = DMatrix::from_row_slice(names.constraints.len(), q.len(), &a);
    Ok(solve_velocities(
        &a,
        &names.constraints,
        &velocity_names(&names.coordinates),
        given,
    )?)
}

/// A built-in's default velocities, `dot(q)` expressions of the
/// `parameters`.
fn default_velocities(
    model: &InterpretedModel,
    defaults: &[(&str, &str)],
    parameters: &[(&str, f64)],
) -> Result<Vec<Option<f64>>, InputError> {
    let velocities = velocity_names(&model.names().coordinates);
    let mut qdot = vec![None; velocities.len()];
    for (name, text) in defaults {
        let value = constant(text, parameters).map_err(|error| InputError::StateValue {
            flag: "the default motion".into(),
            name: name.to_string(),
            text: text.to_string(),
            reason: error.to_string(),
        })?;
        let i = (velocities.iter().position(|v| v == name))
            .ok_or_else(|| InputError::Unsupported(format!("no velocity `{name}`")))?;
        qdot[i] = Some(value);
    }
    Ok(qdot)
}
