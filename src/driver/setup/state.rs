//! The state a command names: its assignments `q=EXPR` and `dot(q)=EXPR`
//! (`--initial`, `--at`), and a controller's states, read once as
//! expressions of the parameters and the command's variables
//! ([`StateFamily`]); at the variables' values, the values they give
//! ([`Assigned`]); and a run's start ([`Start`]): with configuration
//! constraints, the coordinates given are fixed and the others solved from
//! `f(q) = 0`; the velocities given are fixed and the others solved from
//! `A(q) qdot = 0`, as for `chaplygin linearize --at`; without a velocity
//! given, the default motion. `omega(F)=[..]` and `angles(F, seq)=[..]`
//! give a frame's state by how it turns (`setup::frames`).

use super::error::InputError;
use super::frames::{self, AngularVelocity, FrameSlot, Frames};
use crate::driver::catalog::Motion;
use crate::driver::expression::{Expression, ExpressionError, Point, Scope, constant};
use crate::runtime::linearize::Dynamics;
use crate::runtime::linearize::point::{configuration, solve_velocities, velocity_names};
use crate::runtime::nalgebra::DMatrix;
use chaplygin_codegen::interpret::{InterpretedModel, evaluated};
use chaplygin_codegen::model::{FrameTurn, TurnedBy};

/// What a state assignment sets.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Slot {
    /// The coordinate of this index.
    Coordinate(usize),
    /// The velocity of the coordinate of this index.
    Velocity(usize),
    /// The controller state of this index.
    Controller(usize),
    /// A component (0, 1, 2) of what a frame's assignment sets.
    Frame(FrameSlot, usize),
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
    turns: Vec<FrameTurn>,
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
    /// The frames' angular velocities asked (`omega(F)`).
    pub angular_velocities: Vec<AngularVelocity>,
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
    /// The model's frames.
    pub frames: Frames<'a>,
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
        let mut assignments = Vec::new();
        for (name, text) in given {
            for (slot, text) in slots(names, name, text)? {
                let value = expression(names, text).map_err(|reason| InputError::StateValue {
                    flag: names.flag.to_string(),
                    name: name.clone(),
                    text: text.to_string(),
                    reason,
                })?;
                assignments.push(Assignment {
                    slot,
                    name: name.clone(),
                    text: text.to_string(),
                    value,
                });
            }
        }
        Ok(Self {
            flag: names.flag.to_string(),
            variables: names.variables.iter().map(|v| v.to_string()).collect(),
            assignments,
            coordinates: names.coordinates.len(),
            controller_states: names.controller.len(),
            turns: names.frames.turns.to_vec(),
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
            angular_velocities: Vec::new(),
        };
        let mut angles: Vec<(usize, [usize; 3], [f64; 3])> = Vec::new();
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
                Slot::Frame(FrameSlot::Omega(frame), k) => {
                    self.angular_velocity(&mut assigned, &assignment.name, frame)
                        .omega[k] = value;
                    continue;
                }
                Slot::Frame(FrameSlot::Angles(frame, axes), k) => {
                    match angles.iter_mut().find(|(f, ..)| *f == frame) {
                        Some((_, _, values)) => values[k] = value,
                        None => {
                            let mut values = [0.0; 3];
                            values[k] = value;
                            angles.push((frame, axes, values));
                        }
                    }
                    continue;
                }
            };
            *entry = Some(value);
        }
        for (frame, axes, values) in angles {
            let TurnedBy::EulerParameters(indices) = self.turns[frame].by else {
                continue;
            };
            let e = frames::euler_parameters(axes, values);
            for (i, entry) in indices.into_iter().zip(e) {
                assigned.q[i] = Some(entry);
            }
        }
        Ok(assigned)
    }

    /// The derivatives of the coordinates and velocities assigned in the
    /// variable of index `variable` at `variables` (0 where none is
    /// assigned), by forward differentiation of their expressions.
    ///
    /// # Errors
    /// An assignment of a frame's turn or angular velocity, or of a
    /// controller state: give the coordinates and `dot(q)` instead.
    pub fn slopes(
        &self,
        variables: &[f64],
        variable: usize,
    ) -> Result<(Vec<f64>, Vec<f64>), InputError> {
        let mut slopes = (vec![0.0; self.coordinates], vec![0.0; self.coordinates]);
        let point = Point {
            variables,
            ..Point::default()
        };
        for assignment in &self.assignments {
            let (_, slope) = assignment.value.slope(&point, variable);
            match assignment.slot {
                Slot::Coordinate(i) => slopes.0[i] = slope,
                Slot::Velocity(i) => slopes.1[i] = slope,
                Slot::Controller(_) | Slot::Frame(..) => {
                    return Err(InputError::FrameState {
                        flag: self.flag.clone(),
                        name: assignment.name.clone(),
                        reason: "a steady motion is found from the coordinates and `dot(q)`: \
                                 give those"
                            .into(),
                    });
                }
            }
        }
        Ok(slopes)
    }

    /// The angular velocity asked of `frame` by the assignment `name`,
    /// added at zero where new.
    fn angular_velocity<'s>(
        &self,
        assigned: &'s mut Assigned,
        name: &str,
        frame: usize,
    ) -> &'s mut AngularVelocity {
        let at = (assigned.angular_velocities.iter()).position(|w| w.frame == frame);
        let at = at.unwrap_or_else(|| {
            assigned.angular_velocities.push(AngularVelocity {
                given: (self.flag.clone(), name.to_string()),
                frame,
                omega: [0.0; 3],
            });
            assigned.angular_velocities.len() - 1
        });
        &mut assigned.angular_velocities[at]
    }
}

/// What `name = text` sets: one slot, or the three of a frame's
/// `[a, b, c]`, each with its text.
fn slots<'t>(
    names: &StateNames<'_>,
    name: &str,
    text: &'t str,
) -> Result<Vec<(Slot, &'t str)>, InputError> {
    let Some(frame_slot) = frames::frame_slot(names.flag, name, names.frames) else {
        return Ok(vec![(slot(names, name)?, text)]);
    };
    let frame_slot = frame_slot?;
    let entries = frames::components(text).ok_or_else(|| InputError::StateValue {
        flag: names.flag.to_string(),
        name: name.to_string(),
        text: text.to_string(),
        reason: "expected three values `[a, b, c]`".to_string(),
    })?;
    Ok((0..3)
        .map(|k| (Slot::Frame(frame_slot, k), entries[k]))
        .collect())
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
    let mut given_q = assigned.q.clone();
    frames::unturned_where_unset(model.turns(), &mut given_q);
    let mut q = origin.q.map_or_else(|| vec![0.0; n], <[f64]>::to_vec);
    for (entry, given) in q.iter_mut().zip(&given_q) {
        *entry = given.unwrap_or(*entry);
    }
    if !model.holonomic().is_empty() {
        q = configuration(model, &given_q)?;
    }
    let given_qdot = with_angular_velocities(model, &q, assigned)?;
    let given_velocity = given_qdot.iter().any(Option::is_some);
    let qdot = match origin.motion {
        _ if given_velocity => solved_velocities(model, &q, &given_qdot)?,
        Some(Motion::Momenta(alpha)) => evaluated(model.velocities(&q, alpha)),
        Some(Motion::Velocities(defaults)) => {
            let velocities = default_velocities(model, defaults, parameters)?;
            solved_velocities(model, &q, &velocities)?
        }
        None => vec![0.0; n],
    };
    Ok(Start { q, qdot })
}

/// The velocities given by `dot(q)` and by `omega(F)` at `q`.
///
/// # Errors
/// A frame's angular velocity its coordinates cannot give, or a velocity
/// given both ways.
fn with_angular_velocities(
    model: &InterpretedModel,
    q: &[f64],
    assigned: &Assigned,
) -> Result<Vec<Option<f64>>, InputError> {
    let mut qdot = assigned.qdot.clone();
    for asked in &assigned.angular_velocities {
        for (i, rate) in frames::coordinate_rates(model, q, asked)? {
            if qdot[i].is_some() {
                let (flag, name) = asked.given.clone();
                let coordinate = &model.names().coordinates[i];
                return Err(InputError::FrameState {
                    flag,
                    name,
                    reason: format!("sets dot({coordinate}), which is also given"),
                });
            }
            qdot[i] = Some(rate);
        }
    }
    Ok(qdot)
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
