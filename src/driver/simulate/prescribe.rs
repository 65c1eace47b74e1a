//! `--prescribe NAME=EXPR`: a coordinate `q_j` that follows a law `f_j(t)`
//! of the time and the parameters exactly, the rheonomic constraint
//! `q_j = f_j(t)`. The model is derived again with a generalized force
//! `force(q_j)` along each prescribed coordinate, an input after the
//! declared ones whose column of `B(q)` is the unit vector `e_j`
//! (`InterpretedModel::with_coordinate_forces_on`). The forces `tau` are
//! the input law that makes the prescribed accelerations the laws' second
//! derivatives. The Lagrange-d'Alembert accelerations are affine in the
//! inputs, so with the declared inputs `u`:
//!
//! ```text
//! qddot_P(u, tau) = a_0 + M tau,   a_0 = qddot_P(u, 0),
//! M_jk = qddot_j(u, e_k) - a_0_j,  tau = M^-1 (f''(t) - a_0),
//! ```
//!
//! `m + 1` evaluations and one `m x m` solve for `m` prescribed
//! coordinates, `f''` by the laws' exact second-order forward
//! differentiation (`Expression::jet`). Every formulation reads its inputs
//! at the same `(q, qdot)`, so the one law drives them all; the run starts
//! on the laws, `q_j = f_j(0)` and `dot(q_j) = f_j'(0)`, and the
//! prescribed coordinates then follow them to the integrator's accuracy.
//! `M_jj` vanishes where the constraints fix `q_j` (no force moves it),
//! which is refused at the start.

use super::{Controller, FormulationChoice, Request};
use crate::driver::expression::{Expression, Scope};
use crate::driver::interpreted::evaluated;
use crate::driver::setup::InputError;
use crate::runtime::nalgebra::{DMatrix, DVector};
use chaplygin_codegen::interpret::InterpretedModel;

/// The prescribed coordinates of a request, checked against the model.
pub(super) struct Prescribed {
    /// Each prescribed coordinate's index, in the order given.
    pub indices: Vec<usize>,
    /// Each one's law as given.
    texts: Vec<String>,
}

/// The forces that keep the prescribed coordinates on their laws.
pub(super) struct Forces {
    /// The model with the forces among its inputs.
    model: InterpretedModel,
    /// Each prescribed coordinate's index and law.
    laws: Vec<(usize, Expression)>,
    /// The input slot of the first force (the declared inputs' count).
    first: usize,
}

/// A `--prescribe` error on `name`.
fn refused(name: &str, reason: impl Into<String>) -> InputError {
    InputError::Prescribe {
        name: name.to_string(),
        reason: reason.into(),
    }
}

impl Prescribed {
    /// The coordinates `request` prescribes, each a coordinate of `model`
    /// given once, not given by `--initial` too, and one the formulation
    /// drives by a force.
    ///
    /// # Errors
    /// A name that is not a coordinate, or is given twice or also by
    /// `--initial`; a controller; the momentum formulation and a
    /// coordinate that is not a shape coordinate.
    pub fn of(model: &InterpretedModel, request: &Request) -> Result<Prescribed, InputError> {
        let names = model.names();
        let mut indices = Vec::new();
        for (name, _) in &request.prescribe {
            let index = coordinate(model, name)?;
            if indices.contains(&index) {
                return Err(refused(name, "given twice"));
            }
            let velocity = format!("dot({name})");
            let initial = request.initial.iter().map(|(given, _)| given);
            if let Some(given) = initial
                .into_iter()
                .find(|g| **g == *name || **g == velocity)
            {
                return Err(refused(
                    name,
                    format!(
                        "--initial gives {given} too; a prescribed coordinate starts on its law"
                    ),
                ));
            }
            indices.push(index);
        }
        if !indices.is_empty() && request.controller != Controller::None {
            return Err(refused(
                &names.coordinates[indices[0]],
                "runs with --controller none only",
            ));
        }
        if request.formulation == FormulationChoice::Momentum {
            shape_only(model, &indices)?;
        }
        let texts = request
            .prescribe
            .iter()
            .map(|(_, text)| text.clone())
            .collect();
        Ok(Prescribed { indices, texts })
    }

    /// Whether no coordinate is prescribed.
    pub fn is_empty(&self) -> bool {
        self.indices.is_empty()
    }

    /// The laws read against the `parameters` (name and value).
    ///
    /// # Errors
    /// A law that is not an expression of `t` and the parameters.
    fn laws(
        &self,
        model: &InterpretedModel,
        parameters: &[(&str, f64)],
    ) -> Result<Vec<(usize, Expression)>, InputError> {
        let coordinates: Vec<&str> = model
            .names()
            .coordinates
            .iter()
            .map(String::as_str)
            .collect();
        let scope = Scope {
            parameters,
            coordinates: &coordinates,
            ..Scope::default()
        };
        let read = |(&index, text): (&usize, &String)| {
            let name = format!("{}={text}", coordinates[index]);
            let law = Expression::parse(text, &scope).map_err(|e| refused(&name, e.to_string()))?;
            match law.reads_state() {
                true => Err(refused(
                    &name,
                    "the law reads the state; it is of `t` and the parameters alone",
                )),
                false => Ok((index, law)),
            }
        };
        self.indices.iter().zip(&self.texts).map(read).collect()
    }

    /// The initial values the laws give at `t = 0`, `q=f(0)` and
    /// `dot(q)=f'(0)`, as `--initial` takes them (each number written so
    /// that it reads back exactly).
    ///
    /// # Errors
    /// A law that is not an expression of `t` and the parameters, or not
    /// finite at the start.
    pub fn starts(
        &self,
        model: &InterpretedModel,
        parameters: &[(&str, f64)],
    ) -> Result<Vec<(String, String)>, InputError> {
        let names = &model.names().coordinates;
        let mut starts = Vec::new();
        for ((index, law), text) in self.laws(model, parameters)?.into_iter().zip(&self.texts) {
            let jet = law.jet(0.0);
            if !(jet.value.is_finite() && jet.slope.is_finite()) {
                let name = format!("{}={text}", names[index]);
                return Err(refused(&name, "the law or its rate is not finite at t = 0"));
            }
            starts.push((names[index].clone(), format!("{:?}", jet.value)));
            starts.push((format!("dot({})", names[index]), format!("{:?}", jet.slope)));
        }
        Ok(starts)
    }

    /// The forces on `forced`, the model with them among its inputs after
    /// the `declared` inputs, its parameters set to `parameters`.
    ///
    /// # Errors
    /// A law that is not an expression of `t` and the parameters.
    pub fn forces(
        &self,
        forced: InterpretedModel,
        declared: usize,
        parameters: &[(&str, f64)],
    ) -> Result<Forces, InputError> {
        Ok(Forces {
            laws: self.laws(&forced, parameters)?,
            model: forced,
            first: declared,
        })
    }
}

/// The index of the coordinate `name`.
fn coordinate(model: &InterpretedModel, name: &str) -> Result<usize, InputError> {
    let names = model.names();
    if let Some(index) = names.coordinates.iter().position(|c| c == name) {
        return Ok(index);
    }
    let reason = match names.parameters.iter().any(|p| p == name) {
        true => format!("`{name}` is a parameter, not a coordinate (set it with --param)"),
        false => format!(
            "`{name}` is not a coordinate (coordinates: {})",
            names.coordinates.join(", ")
        ),
    };
    Err(refused(name, reason))
}

/// The momentum formulation integrates the shape velocities: a force
/// prescribes only a shape coordinate there (a model without a symmetry
/// is refused the formulation itself).
fn shape_only(model: &InterpretedModel, indices: &[usize]) -> Result<(), InputError> {
    let Some(shape) = model.shape() else {
        return Ok(());
    };
    match indices.iter().find(|index| !shape.contains(index)) {
        Some(&index) => Err(refused(
            &model.names().coordinates[index],
            "the momentum formulation prescribes shape coordinates only; use --formulation \
             reduced or lagrange",
        )),
        None => Ok(()),
    }
}

impl Forces {
    /// The forces at `t`, `(q, qdot)`, written into their slots of `u`
    /// (the declared inputs already there).
    pub fn apply(&self, t: f64, q: &[f64], qdot: &[f64], u: &mut [f64]) {
        let (free, response) = self.response(q, qdot, u);
        let wanted = (self.laws.iter().zip(&free)).map(|((_, law), a)| law.jet(t).curvature - a);
        let tau = response
            .lu()
            .solve(&DVector::from_iterator(free.len(), wanted));
        for k in 0..free.len() {
            u[self.first + k] = tau.as_ref().map_or(f64::NAN, |tau| tau[k]);
        }
    }

    /// `(a_0, M)` at `(q, qdot)` and the declared inputs of `u`: the
    /// prescribed accelerations without the forces, and their response to
    /// each force; the forces' slots of `u` are left zero.
    fn response(&self, q: &[f64], qdot: &[f64], u: &mut [f64]) -> (Vec<f64>, DMatrix<f64>) {
        let m = self.laws.len();
        let prescribed = |u: &[f64]| -> Vec<f64> {
            let (qddot, _) = evaluated(self.model.acceleration(q, qdot, u));
            self.laws.iter().map(|(index, _)| qddot[*index]).collect()
        };
        u[self.first..].fill(0.0);
        let free = prescribed(u);
        let mut response = DMatrix::zeros(m, m);
        for k in 0..m {
            u[self.first + k] = 1.0;
            let pushed = prescribed(u);
            u[self.first + k] = 0.0;
            for j in 0..m {
                response[(j, k)] = pushed[j] - free[j];
            }
        }
        (free, response)
    }

    /// Refuses a prescribed coordinate the constraints fix at `q`: its
    /// acceleration's response to its own force, `M_jj`, against the
    /// unconstrained `1 / g_jj`, is below `1e-12`.
    ///
    /// # Errors
    /// The first coordinate no force moves.
    pub fn check_at(&self, q: &[f64], qdot: &[f64]) -> Result<(), InputError> {
        let n = q.len();
        let g = evaluated(self.model.mass_matrix(q));
        let mut u = vec![0.0; self.model.sizes().p];
        let (_, response) = self.response(q, qdot, &mut u);
        for (k, (index, _)) in self.laws.iter().enumerate() {
            let relative = response[(k, k)] * g[index * n + index];
            if relative.is_nan() || relative.abs() <= 1e-12 {
                let name = &self.model.names().coordinates[*index];
                return Err(refused(
                    name,
                    format!("the constraints fix {name}: no force along it moves it"),
                ));
            }
        }
        Ok(())
    }
}
