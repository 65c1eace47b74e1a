//! The formulations a plan transcribes (docs/MATH.md, "Reduced
//! port-Hamiltonian form"; docs/INTERFACE.md section 13, `--formulation`).
//!
//! The Lagrange-d'Alembert form moves `x = (q, qdot)` by `f(x, u) = (qdot,
//! qddot(q, qdot, u))`. The reduced form moves `x = (q, alpha)`, `alpha`
//! the `k` reduced momenta of chart 0 of the constraints' distribution, by
//!
//! ```text
//! xdot = f(x, u) = (J(x) - R(x)) dH/dx + B(x) u,      qdot = X(q) alpha,
//! df/dx = reduced_rhs_jacobian(x, u),                 df/du = B(x),
//! ```
//!
//! the first `n` rows of `f` being the velocities `X(q) alpha`, linear in
//! `alpha`, and their rows of `df/dx` the velocities' exact derivatives.
//! The costs, the start, the goal and the bounds keep naming `q` and
//! `dot(q)`: a cost reads `dot(q) = X(q) alpha` at each stage, its
//! gradient by `x` through those rows. An end fixes its momenta where its
//! velocities do: `alpha = 0` where the given velocities are 0 and their
//! rows of `X(q)` have rank `k` (the differential drive's wheel rates),
//! `alpha = momenta(q, qdot)` where every coordinate and velocity is
//! given; any other condition or bound on a velocity is refused, the
//! reduced state not holding `dot(q)`. The
//! reduced form's exact second derivatives are not programs of the model:
//! its plans use the L-BFGS Hessian.
//!
//! A model with several charts is planned in chart 0, the one `simulate`
//! starts in where it fits: a plan one of whose nodes `simulate` would
//! move to another chart (`next_chart`) is refused, pointing to the
//! Lagrange form, which needs no chart.
//!
//! The configuration constraints `f(q) = 0` are invariants of the reduced
//! flow as of the Lagrange one (`X(q) alpha` is tangent to them): the
//! scheme keeps them to its order, `plan.csv`'s `holonomic_residual`.

use super::resolve::RequestError;
use super::transcription::StagePoint;
use crate::runtime::nalgebra::DMatrix;
use crate::runtime::system::next_chart;
use chaplygin_codegen::interpret::{InterpretedModel, evaluated};

/// Why a reduced plan is written in chart 0, as `plan.json` says.
pub const CHART_REASON: &str = "chart 0, the one simulate starts in where it fits; every node \
     lies where simulate would keep it (else the plan fails)";

/// The formulation whose state a plan's nodes hold.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Form {
    /// `x = (q, qdot)`: the Lagrange-d'Alembert equations.
    #[default]
    Lagrange,
    /// `x = (q, alpha)` in chart 0: the reduced port-Hamiltonian form.
    Reduced,
}

impl Form {
    /// Its name, as `--formulation` and `plan.json` give it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Lagrange => "lagrange",
            Self::Reduced => "reduced",
        }
    }

    /// The size of the state: `2n`, or `n + k`.
    pub fn state(self, model: &InterpretedModel) -> usize {
        let sizes = model.sizes();
        match self {
            Self::Lagrange => 2 * sizes.n,
            Self::Reduced => sizes.s,
        }
    }

    /// The names of the state's entries: the coordinates, then `dot(q)`
    /// or the reduced momenta.
    pub fn state_names(self, model: &InterpretedModel) -> Vec<String> {
        let names = model.names();
        let second: Vec<String> = match self {
            Self::Lagrange => (names.coordinates.iter())
                .map(|q| format!("dot({q})"))
                .collect(),
            Self::Reduced => names.momenta.clone(),
        };
        names.coordinates.iter().cloned().chain(second).collect()
    }

    /// The chart the state is written in: chart 0 for the reduced form of
    /// a model with constraints, none otherwise.
    pub fn chart(self, model: &InterpretedModel) -> Option<usize> {
        (self == Self::Reduced && model.sizes().c > 0).then_some(0)
    }
}

/// `f(x, u)` of the reduced form.
pub(super) fn rhs(model: &InterpretedModel, x: &[f64], u: &[f64]) -> Vec<f64> {
    evaluated(model.reduced_rhs(x, u))
}

/// `df/dx` (s x s) and `df/du = B(x)` (s x p) of the reduced form,
/// row-major.
pub(super) fn rhs_jacobian(model: &InterpretedModel, x: &[f64], u: &[f64]) -> (Vec<f64>, Vec<f64>) {
    (
        evaluated(model.reduced_rhs_jacobian(x, u)),
        evaluated(model.input_matrix(x)),
    )
}

/// `qdot = X(q) alpha` at `x = (q, alpha)`.
pub(super) fn velocities(model: &InterpretedModel, x: &[f64]) -> Vec<f64> {
    let n = model.sizes().n;
    evaluated(model.velocities(&x[..n], &x[n..]))
}

/// `d qdot / dx` (n x s, row-major): the velocities' rows of `df/dx`.
fn velocities_jacobian(model: &InterpretedModel, point: &StagePoint) -> Vec<f64> {
    let (n, s) = (model.sizes().n, model.sizes().s);
    let (mut by_x, _) = rhs_jacobian(model, &point.x, &point.u);
    by_x.truncate(n * s);
    by_x
}

/// A function's gradient by `x = (q, alpha)` from its gradients by `q`
/// and `qdot` at `point`: `(g_q, 0) + g_qdot^T d qdot/dx`.
pub(super) fn state_gradient(
    model: &InterpretedModel,
    point: &StagePoint,
    (by_q, by_qdot): (&[f64], &[f64]),
) -> Vec<f64> {
    let s = model.sizes().s;
    let by_x = velocities_jacobian(model, point);
    let mut gradient = by_q.to_vec();
    gradient.resize(s, 0.0);
    for (g, row) in by_qdot.iter().zip(by_x.chunks(s)) {
        for (out, d) in gradient.iter_mut().zip(row) {
            *out += g * d;
        }
    }
    gradient
}

/// The momenta `alpha = momenta(q, qdot)` in chart 0.
pub(super) fn momenta(model: &InterpretedModel, q: &[f64], qdot: &[f64]) -> Vec<f64> {
    evaluated(model.call_in_chart(0, "momenta", &[q, qdot]))
}

/// The momenta an end's conditions fix, from its coordinates `q` (its
/// first guess) and its given coordinates and velocities (`None` where
/// not given): none where no velocity is given; 0 where the given ones
/// are 0 and determine `alpha` (their rows of `X(q)` have rank `k`);
/// `momenta(q, qdot)` where every coordinate and velocity is given.
///
/// # Errors
/// [`RequestError::ReducedVelocities`] for any other end.
pub(super) fn end_momenta(
    model: &InterpretedModel,
    (flag, q): (&'static str, &[f64]),
    (given_q, given_qdot): (&[Option<f64>], &[Option<f64>]),
) -> Result<Option<Vec<f64>>, RequestError> {
    if given_qdot.iter().all(Option::is_none) {
        return Ok(None);
    }
    let at_rest = given_qdot.iter().flatten().all(|v| *v == 0.0);
    if at_rest && determines_momenta(model, q, given_qdot) {
        return Ok(Some(vec![0.0; model.sizes().k]));
    }
    let (coordinates, velocities): (Vec<f64>, Vec<f64>) = (
        given_q.iter().flatten().copied().collect(),
        given_qdot.iter().flatten().copied().collect(),
    );
    let n = model.sizes().n;
    if coordinates.len() == n && velocities.len() == n {
        return Ok(Some(momenta(model, &coordinates, &velocities)));
    }
    let names = Form::Lagrange.state_names(model);
    let given = given_q.iter().chain(given_qdot);
    let missing: Vec<String> = (given.zip(names))
        .filter(|(v, _)| v.is_none())
        .map(|(_, name)| name)
        .collect();
    let missing = missing.join(", ");
    Err(RequestError::ReducedVelocities { flag, missing })
}

/// Whether the `given` velocities' rows of `X(q)` have rank `k`.
fn determines_momenta(model: &InterpretedModel, q: &[f64], given: &[Option<f64>]) -> bool {
    let k = model.sizes().k;
    let rows: Vec<usize> = (0..given.len()).filter(|&i| given[i].is_some()).collect();
    let columns: Vec<Vec<f64>> = (0..k)
        .map(|j| {
            let unit: Vec<f64> = (0..k).map(|i| f64::from(u8::from(i == j))).collect();
            evaluated(model.velocities(q, &unit))
        })
        .collect();
    let by_alpha = DMatrix::from_fn(rows.len(), k, |r, j| columns[j][rows[r]]);
    by_alpha.rank(RANK_TOLERANCE) == k
}

/// The singular value below which `X(q)`'s given rows lose rank, an
/// absolute one: `X`'s entries are of order one in the catalog's models.
const RANK_TOLERANCE: f64 = 1e-9;

/// The first node of `states` (rows of `q` first) that `simulate` would
/// move out of chart 0.
pub(super) fn leaves_chart<'a>(
    model: &InterpretedModel,
    states: impl Iterator<Item = &'a [f64]>,
) -> Option<usize> {
    let charts = model.charts().len();
    let n = model.sizes().n;
    states.enumerate().find_map(|(node, x)| {
        let q = &x[..n];
        let fit = |chart| model.chart_fit(chart, q).unwrap_or(0.0);
        next_chart(charts, 0, fit, model.pivoted_chart(q)).map(|_| node)
    })
}

#[cfg(test)]
mod tests;
