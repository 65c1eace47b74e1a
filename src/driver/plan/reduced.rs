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
//! reduced state not holding `dot(q)`. The Hessian of the Lagrangian is
//! exact as in the Lagrange form (`src/driver/plan/hessian.rs`): the
//! model's `reduced_rhs_hessian`, `d^2 (w^T f)/d(x, u)^2`, the exact
//! `reduced_rhs_jacobian` differentiated forward, and the costs' through
//! `dot(q) = X(q) alpha` by the second-order chain rule.
//!
//! A model with several charts is planned in chart 0, the one `simulate`
//! starts in where it fits: a plan one of whose nodes `simulate` would
//! move to another chart (`next_chart`) is refused, pointing to the
//! Lagrange form, which needs no chart.
//!
//! The configuration constraints `f(q) = 0` are invariants of the reduced
//! flow as of the Lagrange one (`X(q) alpha` is tangent to them): the
//! scheme keeps them to its order, `plan.csv`'s `holonomic_residual`.

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

/// The Hessian of `weights^T f` by `(x, u)` ((s + p)^2, row-major).
pub(super) fn rhs_hessian(
    model: &InterpretedModel,
    (x, u): (&[f64], &[f64]),
    weights: &[f64],
) -> Vec<f64> {
    evaluated(model.reduced_rhs_hessian(x, u, weights))
}

/// `qdot = X(q) alpha` at `x = (q, alpha)`.
pub(super) fn velocities(model: &InterpretedModel, x: &[f64]) -> Vec<f64> {
    let n = model.sizes().n;
    evaluated(model.velocities(&x[..n], &x[n..]))
}

/// `d qdot / dx` (n x s, row-major) at `(x, u)`: the velocities' rows of
/// `df/dx`.
fn velocities_jacobian(model: &InterpretedModel, (x, u): (&[f64], &[f64])) -> Vec<f64> {
    let (n, s) = (model.sizes().n, model.sizes().s);
    let (mut by_x, _) = rhs_jacobian(model, x, u);
    by_x.truncate(n * s);
    by_x
}

/// A function's gradient by `x = (q, alpha)` from its gradients by `q`
/// and `qdot` at the state `x` and inputs `u`: `(g_q, 0) + g_qdot^T d
/// qdot/dx`.
pub(super) fn state_gradient(
    model: &InterpretedModel,
    (x, u): (&[f64], &[f64]),
    (by_q, by_qdot): (&[f64], &[f64]),
) -> Vec<f64> {
    let s = model.sizes().s;
    let by_x = velocities_jacobian(model, (x, u));
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
