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
use super::setup::{self, Asked, Setup};
use crate::driver::Failure;
use crate::gait_design::{self, Design, GaitModel, Jacobians, Optimum};
use crate::runtime::gait::{self, Cycle, GaitState, Locomotion, ShapeLoop};
use crate::runtime::linearize::GroupFactor;
use crate::runtime::record::Table;
use chaplygin_codegen::derive::MOMENTUM_WITH_HOLONOMIC;
use chaplygin_codegen::interpret::InterpretedModel;

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
    /// For a principally kinematic model, its connection's curvature on
    /// the plane of the first two shape coordinates, around the loop.
    pub curvature: Option<CurvatureGrid>,
}

/// The curvature `F = -dA + [A, A]` of a principally kinematic model's
/// connection (its `connection_curvature`) on the plane of two shape
/// coordinates, sampled on a square grid: the height functions whose
/// integral over the area a loop encloses is about its displacement
/// (exactly, for the rotation).
#[derive(Clone, Debug, PartialEq)]
pub struct CurvatureGrid {
    /// The plane's two shape coordinates.
    pub axes: [String; 2],
    /// The grid's values of the first.
    pub first: Vec<f64>,
    /// The grid's values of the second.
    pub second: Vec<f64>,
    /// `x`, `y` and `theta` of `F` at `(first[i], second[j])`, at
    /// `i * second.len() + j`; NaN where the connection is singular.
    pub components: [Vec<f64>; 3],
    /// The loop in the plane, one point per recorded step.
    pub path: Vec<(f64, f64)>,
}

/// Grid points per side of [`CurvatureGrid`].
pub const CURVATURE_GRID: usize = 121;

/// A model with an SE(2) symmetry, read from its text, as the runtime's
/// [`Locomotion`] and as a [`GaitModel`] (its Jacobians, divisor and, for
/// a principally kinematic model, curvature).
pub struct FromText<'m> {
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

impl GaitModel for FromText<'_> {
    fn divisor(&self, r: &[f64]) -> (f64, Vec<f64>) {
        let values = evaluated(self.model.call("connection_divisor", &[r]));
        (values[0], values[1..].to_vec())
    }

    fn jacobians(&self, r: &[f64], rdot: &[f64], p: &[f64]) -> Jacobians {
        let columns = 2 * r.len() + p.len();
        let rows = |name: &str| -> Vec<Vec<f64>> {
            let values = evaluated(self.model.call(name, &[r, rdot, p]));
            values.chunks_exact(columns).map(<[f64]>::to_vec).collect()
        };
        let body = rows("body_velocity_jacobian");
        let offset = se2_offset(self.model.symmetry());
        Jacobians {
            body_velocity: std::array::from_fn(|c| body[offset + c].clone()),
            momentum: rows("momentum_rhs_jacobian"),
        }
    }

    fn curvature(&self, r: &[f64]) -> Option<Vec<[f64; 3]>> {
        self.model.arguments("connection_curvature")?;
        let values = evaluated(self.model.call("connection_curvature", &[r]));
        let planes = self.shape.len() * (self.shape.len() - 1) / 2;
        let offset = se2_offset(self.model.symmetry());
        Some(
            (0..planes)
                .map(|plane| std::array::from_fn(|c| values[(offset + c) * planes + plane]))
                .collect(),
        )
    }
}

/// `model`'s locomotion: its SE(2) factor, its shape and momenta.
///
/// # Errors
/// A model without an SE(2) symmetry, momentum equation or shape.
pub fn locomotion<'m>(model: &'m InterpretedModel, label: &str) -> Result<FromText<'m>, GaitError> {
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
pub fn gait(loaded: Loaded, request: &GaitRequest) -> Result<GaitRun, Failure> {
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
    let asked = Asked {
        params: &request.params,
        ..Asked::default()
    };
    let setup = setup::resolve(loaded.model, &asked)?;
    let (model, label) = (&setup.model, &loaded.label);
    let parameters = setup.bound();
    let body = locomotion(model, label)?;
    let laws = laws(model, label, &body.shape, request, &parameters)?;
    let shape = |t: f64| -> (Vec<f64>, Vec<f64>) { laws.iter().map(|law| law.rate(t)).unzip() };
    let p0 = initial_momenta(&request.initial, body.momenta)?;
    let q0 = vec![0.0; model.sizes().n];
    refuse_pushed_momentum(&body, &shape, (&q0, request.period), label)?;
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
    let table = Table { columns, rows };
    let curvature = curvature_grid(&body, &table);
    Ok(GaitRun {
        table,
        cycles,
        curvature,
    })
}

/// The curvature of `body` on the plane of its first two shape
/// coordinates, on a square grid around the loop the `table` records
/// (twice its extent, and at least 1 across); `None` for a model that
/// carries momentum or has fewer than two shape coordinates.
fn curvature_grid(body: &FromText<'_>, table: &Table) -> Option<CurvatureGrid> {
    let model = body.model;
    model.arguments("connection_curvature")?;
    let [a, b] = [*body.shape.first()?, *body.shape.get(1)?];
    let offset = se2_offset(model.symmetry());
    let column = |i: usize| -> Vec<f64> { table.rows.iter().map(|row| row[1 + i]).collect() };
    let path: Vec<(f64, f64)> = column(a).into_iter().zip(column(b)).collect();
    let span = |values: &mut dyn Iterator<Item = f64>| {
        let (low, high) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(v), h.max(v))
        });
        ((low + high) / 2.0, (high - low).max(0.5))
    };
    let (centre_a, extent_a) = span(&mut path.iter().map(|p| p.0));
    let (centre_b, extent_b) = span(&mut path.iter().map(|p| p.1));
    let half = extent_a.max(extent_b);
    let axis = |centre: f64| -> Vec<f64> {
        (0..CURVATURE_GRID)
            .map(|k| centre - half + 2.0 * half * k as f64 / (CURVATURE_GRID - 1) as f64)
            .collect()
    };
    let (first, second) = (axis(centre_a), axis(centre_b));
    let planes = body.shape.len() * (body.shape.len() - 1) / 2;
    let mut components: [Vec<f64>; 3] = Default::default();
    let mut r = vec![0.0; body.shape.len()];
    for &u in &first {
        for &v in &second {
            (r[0], r[1]) = (u, v);
            let f = evaluated(model.call("connection_curvature", &[&r]));
            for (k, values) in components.iter_mut().enumerate() {
                let value = f.get((offset + k) * planes).copied().unwrap_or(f64::NAN);
                values.push(value);
            }
        }
    }
    let names = &model.names().coordinates;
    Some(CurvatureGrid {
        axes: [names[a].clone(), names[b].clone()],
        first,
        second,
        components,
        path,
    })
}

/// Where the `se2` factor's `(v1, v2, omega)` start in the body velocity.
fn se2_offset(symmetry: &[GroupFactor]) -> usize {
    symmetry
        .iter()
        .take_while(|factor| !matches!(factor, GroupFactor::Se2 { .. }))
        .count()
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

/// An optimal gait's request: the design and the parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct OptimalGaitRequest {
    /// What to optimize.
    pub design: Design,
    /// Parameters `NAME=VALUE`.
    pub params: Vec<(String, f64)>,
}

/// The optimal loop, its laws as `--cycle` takes them, and its run.
pub struct OptimalGait {
    /// The loop found and its evaluation.
    pub optimum: Optimum,
    /// The shape coordinates, in the model's order.
    pub shape: Vec<String>,
    /// Each shape coordinate's name and law (`--cycle NAME=EXPR`).
    pub laws: Vec<(String, String)>,
    /// The optimal loop run as a prescribed gait.
    pub run: GaitRun,
}

/// The loop of `request.design` that moves the `loaded` model furthest
/// from rest (docs/INTERFACE.md section 9, `crate::gait_design`), and its
/// run from its printed laws.
///
/// # Errors
/// A model without an SE(2) symmetry, momentum equation or two shape
/// coordinates, whose inputs push its momentum (at eight shapes spread
/// over the survey's box), a bad request, no loop off the singular set,
/// or the run's errors.
pub fn optimal_gait(loaded: Loaded, request: &OptimalGaitRequest) -> Result<OptimalGait, Failure> {
    let asked = Asked {
        params: &request.params,
        ..Asked::default()
    };
    let Setup { model, .. } = setup::resolve(loaded.model, &asked)?;
    let label = loaded.label;
    let body = locomotion(&model, &label)?;
    let extent = request.design.extent;
    let spread = |t: f64| -> (Vec<f64>, Vec<f64>) {
        (0..body.shape.len())
            .map(|i| {
                let phase = t + i as f64;
                (extent * phase.sin(), extent * phase.cos())
            })
            .unzip()
    };
    let q0 = vec![0.0; model.sizes().n];
    refuse_pushed_momentum(&body, &spread, (&q0, 2.0 * std::f64::consts::PI), &label)?;
    let optimum = gait_design::optimize(&body, &request.design)?;
    let names = &model.names().coordinates;
    let shape: Vec<String> = body.shape.iter().map(|&i| names[i].clone()).collect();
    let laws = optimum.shape_loop.laws(&shape);
    let gait_request = GaitRequest {
        cycle: laws.clone(),
        period: request.design.period,
        cycles: 1,
        steps: request.design.steps,
        params: request.params.clone(),
        initial: Vec::new(),
    };
    let loaded = Loaded {
        model: model.clone(),
        label,
        built_in: None,
        fallback: None,
    };
    let run = gait(loaded, &gait_request)?;
    Ok(OptimalGait {
        optimum,
        shape,
        laws,
        run,
    })
}
