//! A gait of a model read from its text (docs/INTERFACE.md section 9): its
//! shape coordinates follow prescribed periodic laws of `t` and the
//! parameters (`a=0.8*sin(t)`), their velocities the laws' exact time
//! derivatives; the group `SE(2)` and any other symmetry coordinate follow
//! from the momentum equation and the reconstruction, from zero momentum
//! unless given (`crate::runtime::gait`). Each cycle's net displacement is
//! the group motion in the body frame at the cycle's start.

use super::engine::Loaded;
use super::expression::{Expression, Scope};
use super::interpreted::evaluated;
use super::simulate::{borrowed, with_parameters};
use crate::runtime::gait::{self, Cycle, GaitState, Locomotion, ShapeLoop};
use crate::runtime::linearize::GroupFactor;
use crate::runtime::record::Table;
use chaplygin_codegen::derive::MOMENTUM_WITH_HOLONOMIC;
use chaplygin_codegen::interpret::InterpretedModel;
use std::error::Error;

/// A prescribed gait: the shape coordinates and their laws, the period,
/// how many cycles, the parameters and the initial momenta.
#[derive(Clone, Debug, PartialEq)]
pub struct GaitRequest {
    /// Each shape coordinate with its law, an expression of `t` and the
    /// parameters; every shape coordinate of the model, once.
    pub cycle: Vec<(String, String)>,
    /// The period `T`.
    pub period: f64,
    /// The cycles run.
    pub cycles: usize,
    /// RK4 steps per period.
    pub steps: usize,
    /// Parameters `NAME=VALUE`.
    pub params: Vec<(String, f64)>,
    /// Initial momenta `pI=VALUE` (zero unless given).
    pub initial: Vec<(String, f64)>,
}

/// A gait that cannot be run.
#[derive(Debug, thiserror::Error)]
pub enum GaitError {
    /// The model has no SE(2) symmetry, or no momentum equation.
    #[error("`{model}`: {reason}")]
    Model {
        /// The model.
        model: String,
        /// What it lacks.
        reason: String,
    },
    /// The laws do not name each shape coordinate once.
    #[error("--cycle: {reason} (the shape coordinates of `{model}`: {shape})")]
    Shape {
        /// The model.
        model: String,
        /// What is wrong.
        reason: String,
        /// The model's shape coordinates.
        shape: String,
    },
    /// A law is not an expression of `t` and the parameters.
    #[error("--cycle {name}={text}: {reason}")]
    Law {
        /// The shape coordinate.
        name: String,
        /// The law as given.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
    /// An initial value names no momentum.
    #[error("--initial {name}: not a momentum of the gait ({known})")]
    Initial {
        /// What was given.
        name: String,
        /// The momenta.
        known: String,
    },
    /// The period or the number of cycles or steps.
    #[error("{0}")]
    Span(String),
}

/// A gait's recorded rows (`t`, the coordinates, the momenta `p1..pK`)
/// and each cycle's displacement.
pub struct GaitRun {
    /// Every step's row.
    pub table: Table,
    /// Each cycle, in order.
    pub cycles: Vec<Cycle>,
}

/// A model with an SE(2) symmetry, read from its text, as the runtime's
/// [`Locomotion`].
struct FromText<'m> {
    model: &'m InterpretedModel,
    group: [usize; 3],
    shape: Vec<usize>,
    momenta: usize,
}

impl Locomotion for FromText<'_> {
    fn coordinate_count(&self) -> usize {
        self.model.sizes().n
    }

    fn group(&self) -> [usize; 3] {
        self.group
    }

    fn shape_indices(&self) -> Vec<usize> {
        self.shape.clone()
    }

    fn momentum_count(&self) -> usize {
        self.momenta
    }

    fn momentum_rhs(&self, r: &[f64], rdot: &[f64], p: &[f64]) -> Vec<f64> {
        evaluated(self.model.call("momentum_rhs", &[r, rdot, p]))
    }

    fn reconstructed_velocity(&self, q: &[f64], rdot: &[f64], p: &[f64]) -> Vec<f64> {
        evaluated(self.model.reconstructed_velocity(q, rdot, p))
    }

    fn inputs_push_momentum(&self, q: &[f64]) -> bool {
        let coupling = evaluated(self.model.call("momentum_input_matrix", &[q]));
        coupling.iter().any(|&entry| entry != 0.0)
    }
}

/// `model`'s locomotion: its SE(2) factor, its shape and momenta.
fn locomotion<'m>(model: &'m InterpretedModel, label: &str) -> Result<FromText<'m>, GaitError> {
    let lacks = |reason: &str| GaitError::Model {
        model: label.to_string(),
        reason: reason.to_string(),
    };
    let group = model
        .symmetry()
        .iter()
        .find_map(|factor| match *factor {
            GroupFactor::Se2 { x, y, theta } => Some([x, y, theta]),
            _ => None,
        })
        .ok_or_else(|| {
            lacks("a gait moves a body in the plane: the model declares no se2 symmetry")
        })?;
    let momenta = model
        .arguments("momentum_rhs")
        .map(|arguments| arguments[2].1)
        .ok_or_else(|| {
            lacks(&format!(
                "the momentum equation is {MOMENTUM_WITH_HOLONOMIC}"
            ))
        })?;
    let shape = model.shape().unwrap_or_default();
    if shape.is_empty() {
        return Err(lacks(
            "its symmetry moves every coordinate: there is no shape for a gait to prescribe",
        ));
    }
    Ok(FromText {
        model,
        group,
        shape,
        momenta,
    })
}

/// The laws of `request` in the order of the model's shape coordinates.
fn laws(
    model: &InterpretedModel,
    label: &str,
    shape: &[usize],
    request: &GaitRequest,
    parameters: &[(&str, f64)],
) -> Result<Vec<Expression>, GaitError> {
    let coordinates = &model.names().coordinates;
    let names: Vec<&str> = shape.iter().map(|&i| coordinates[i].as_str()).collect();
    let mismatch = |reason: String| GaitError::Shape {
        model: label.to_string(),
        reason,
        shape: names.join(", "),
    };
    let scope = Scope {
        parameters,
        ..Scope::default()
    };
    let mut laws = vec![None; names.len()];
    for (name, text) in &request.cycle {
        let i = (names.iter().position(|n| n == name))
            .ok_or_else(|| mismatch(format!("`{name}` is not a shape coordinate")))?;
        if laws[i].is_some() {
            return Err(mismatch(format!("`{name}` has two laws")));
        }
        let law = Expression::parse(text, &scope).map_err(|error| GaitError::Law {
            name: name.clone(),
            text: text.clone(),
            reason: error.to_string(),
        })?;
        laws[i] = Some(law);
    }
    let missing: Vec<&str> = (names.iter().zip(&laws))
        .filter(|(_, law)| law.is_none())
        .map(|(name, _)| *name)
        .collect();
    match missing.is_empty() {
        true => Ok(laws.into_iter().flatten().collect()),
        false => Err(mismatch(format!("no law for {}", missing.join(", ")))),
    }
}

/// The initial momenta `p1..pK` from `given`, zero where not given.
fn initial_momenta(given: &[(String, f64)], count: usize) -> Result<Vec<f64>, GaitError> {
    let names: Vec<String> = (1..=count).map(|i| format!("p{i}")).collect();
    let mut p = vec![0.0; count];
    for (name, value) in given {
        let i = (names.iter().position(|n| n == name)).ok_or_else(|| GaitError::Initial {
            name: name.clone(),
            known: match names.is_empty() {
                true => "none: the model carries no momentum".into(),
                false => names.join(", "),
            },
        })?;
        p[i] = *value;
    }
    Ok(p)
}

/// Runs `request` on the `loaded` model from the identity (every
/// coordinate zero but the shape's, which start on their laws).
///
/// # Errors
/// A model without an SE(2) symmetry or momentum equation, inputs that
/// push the momentum, laws that do not name each shape coordinate once as
/// an expression of `t` and the parameters, a bad span, or an I/O error
/// of the table.
pub fn gait(loaded: Loaded, request: &GaitRequest) -> Result<GaitRun, Box<dyn Error>> {
    if !(request.period > 0.0 && request.period.is_finite())
        || request.cycles == 0
        || request.steps == 0
    {
        return Err(GaitError::Span(format!(
            "--period must be positive and finite, --cycles and the steps at least 1 (period {}, cycles {}, steps {})",
            request.period, request.cycles, request.steps
        ))
        .into());
    }
    let Loaded {
        mut model, label, ..
    } = loaded;
    let values = with_parameters(&mut model, &request.params)?;
    let parameters = borrowed(&values);
    let body = locomotion(&model, &label)?;
    let laws = laws(&model, &label, &body.shape, request, &parameters)?;
    let shape = |t: f64| -> (Vec<f64>, Vec<f64>) { laws.iter().map(|law| law.rate(t)).unzip() };
    let p0 = initial_momenta(&request.initial, body.momenta)?;
    let q0 = vec![0.0; model.sizes().n];
    refuse_pushed_momentum(&body, &shape, (&q0, request.period), &label)?;
    let mut columns = vec!["t".to_string()];
    columns.extend(model.names().coordinates.iter().cloned());
    columns.extend((1..=body.momenta).map(|i| format!("p{i}")));
    let mut rows = Vec::new();
    let shape_loop = ShapeLoop {
        shape: &shape,
        period: request.period,
    };
    let cycles = gait::run(
        &body,
        &shape_loop,
        (&q0, &p0),
        (request.cycles, request.steps),
        &mut |t, state: &GaitState| {
            rows.push(
                [t].into_iter()
                    .chain(state.q.iter().chain(&state.p).copied())
                    .collect(),
            );
        },
    );
    Ok(GaitRun {
        table: Table { columns, rows },
        cycles,
    })
}

/// An error where the inputs enter the momentum equation at eight shapes
/// along the loop: a prescribed shape does not determine the motion there.
fn refuse_pushed_momentum(
    body: &FromText<'_>,
    shape: &dyn Fn(f64) -> (Vec<f64>, Vec<f64>),
    (q0, period): (&[f64], f64),
    label: &str,
) -> Result<(), GaitError> {
    let pushed = (0..8).any(|k| {
        let mut q = q0.to_vec();
        for (&i, value) in body.shape.iter().zip(shape(period * f64::from(k) / 8.0).0) {
            q[i] = value;
        }
        body.inputs_push_momentum(&q)
    });
    match pushed {
        false => Ok(()),
        true => Err(GaitError::Model {
            model: label.to_string(),
            reason: "the inputs enter the momentum equation (h B is not zero): a prescribed shape does not determine the motion".into(),
        }),
    }
}
