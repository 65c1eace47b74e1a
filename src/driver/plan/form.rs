//! The formulations a plan transcribes (docs/MATH.md sections 2, 3 and
//! 4; docs/INTERFACE.md section 13, `--formulation`): the state `x` a
//! node holds, and how it moves, `xdot = f(x, u)`, with `f`'s exact first
//! and second derivatives.
//!
//! ```text
//! lagrange   x = (q, qdot)       f = (qdot, qddot(q, qdot, u))
//! reduced    x = (q, alpha)      f = (J(x) - R(x)) dH/dx + B(x) u,        qdot = X(q) alpha
//! momentum   x = (q, rdot, p)    f = (qdot, rddot, pdot),                 qdot = g(q) xi(r, rdot, p)
//! ```
//!
//! `alpha` are the `k` reduced momenta of chart 0 of the constraints'
//! distribution; `r` the shape coordinates and `p` the momenta of the
//! nonholonomic momentum equation, `qdot` reconstructed from the body
//! velocity `xi` by the group (`momentum_form_rhs`). In every form the
//! first `n` rows of `f` are the velocities `qdot`, which do not depend
//! on `u`; the derivatives of `f` are the model's exact ones
//! (`acceleration_jacobian`, `reduced_rhs_jacobian`,
//! `momentum_form_jacobian`, and their Hessians), and a cost's gradient
//! by `x` goes through those rows. The Hessian of the Lagrangian uses
//! them as well (`src/driver/plan/hessian.rs`): the costs' curvature
//! through `qdot(x)` joins the model's weights on those rows.
//!
//! The costs, the start, the goal and the bounds name `q` and `dot(q)`.
//! Where the state does not hold a velocity, an end fixes the state's
//! second part (`alpha`, or `(rdot, p)`) where its velocities do: 0 where
//! the given velocities are 0 and their rows of `d qdot / dx` have full
//! rank (the differential drive's wheel rates), the state of `(q, qdot)`
//! where every coordinate and velocity is given; any other condition is
//! refused. A bound on a velocity the state holds (the shape's, in the
//! momentum form) bounds that entry; on any other, it is refused.
//!
//! A model with several charts is planned in the reduced form in chart 0,
//! the one `simulate` starts in where it fits: a plan one of whose nodes
//! `simulate` would move to another chart (`next_chart`) is refused,
//! pointing to the Lagrange form, which needs no chart. The momentum
//! form needs the model's symmetry and its momentum equation.
//!
//! The configuration constraints `f(q) = 0` are invariants of each flow
//! (the velocities are tangent to them): the scheme keeps them to its
//! order, `plan.csv`'s `holonomic_residual`.

use crate::driver::interpreted::{
    lagrange_rhs_jacobian, momentum_state_names, momentum_unsupported,
};
use crate::runtime::system::next_chart;
use chaplygin_codegen::interpret::{InterpretedModel, RowCurvatures, evaluated};

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
    /// `x = (q, rdot, p)`: the nonholonomic momentum equation.
    Momentum,
}

impl Form {
    /// Its name, as `--formulation` and `plan.json` give it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Lagrange => "lagrange",
            Self::Reduced => "reduced",
            Self::Momentum => "momentum",
        }
    }

    /// Why `model` cannot be planned in this form, if it cannot.
    pub fn unsupported(self, model: &InterpretedModel) -> Option<String> {
        (self == Self::Momentum)
            .then(|| momentum_unsupported(model))
            .flatten()
    }

    /// The size of the state: `2n`, `n + k`, or `n + R + K`.
    pub fn state(self, model: &InterpretedModel) -> usize {
        let sizes = model.sizes();
        match self {
            Self::Lagrange => 2 * sizes.n,
            Self::Reduced => sizes.s,
            Self::Momentum => model.momentum_form_size().unwrap_or(0),
        }
    }

    /// The names of the state's entries: the coordinates, then `dot(q)`,
    /// the reduced momenta, or `dot(r)` and `p1..pK`.
    pub fn state_names(self, model: &InterpretedModel) -> Vec<String> {
        let names = model.names();
        let coordinates = names.coordinates.iter().cloned();
        match self {
            Self::Lagrange => {
                let dotted = names.coordinates.iter().map(|q| format!("dot({q})"));
                coordinates.chain(dotted).collect()
            }
            Self::Reduced => coordinates.chain(names.momenta.iter().cloned()).collect(),
            Self::Momentum => momentum_state_names(model),
        }
    }

    /// The chart the state is written in: chart 0 for the reduced form of
    /// a model with constraints, none otherwise.
    pub fn chart(self, model: &InterpretedModel) -> Option<usize> {
        (self == Self::Reduced && model.sizes().c > 0).then_some(0)
    }

    /// The state's column holding the velocity `dot(q_i)`, if it holds it.
    pub fn velocity_column(self, model: &InterpretedModel, i: usize) -> Option<usize> {
        let n = model.sizes().n;
        match self {
            Self::Lagrange => Some(n + i),
            Self::Reduced => None,
            Self::Momentum => (model.shape().unwrap_or_default().iter())
                .position(|&j| j == i)
                .map(|a| n + a),
        }
    }

    /// The state of `q` moving with `qdot`.
    pub fn state_of(self, model: &InterpretedModel, q: &[f64], qdot: &[f64]) -> Vec<f64> {
        let second = match self {
            Self::Lagrange => qdot.to_vec(),
            Self::Reduced => evaluated(model.call_in_chart(0, "momenta", &[q, qdot])),
            Self::Momentum => {
                let shape = model.shape().unwrap_or_default();
                let rdot = shape.iter().map(|&i| qdot[i]);
                let p = evaluated(model.call("momentum", &[q, qdot]));
                rdot.chain(p).collect()
            }
        };
        q.iter().copied().chain(second).collect()
    }

    /// `f(x, u)`.
    pub(super) fn rhs(self, model: &InterpretedModel, x: &[f64], u: &[f64]) -> Vec<f64> {
        match self {
            Self::Lagrange => {
                let (q, qdot) = x.split_at(model.sizes().n);
                let (qddot, _) = evaluated(model.acceleration(q, qdot, u));
                qdot.iter().chain(&qddot).copied().collect()
            }
            Self::Reduced => evaluated(model.reduced_rhs(x, u)),
            Self::Momentum => evaluated(model.momentum_form_rhs(x, u)),
        }
    }

    /// `df/dx` (s x s) and `df/du` (s x p), row-major.
    pub(super) fn rhs_jacobian(
        self,
        model: &InterpretedModel,
        x: &[f64],
        u: &[f64],
    ) -> (Vec<f64>, Vec<f64>) {
        match self {
            Self::Lagrange => lagrange_rhs_jacobian(model, x, u),
            Self::Reduced => (
                evaluated(model.reduced_rhs_jacobian(x, u)),
                evaluated(model.input_matrix(x)),
            ),
            Self::Momentum => evaluated(model.momentum_form_jacobian(x, u)),
        }
    }

    /// The second derivatives of the rows of `f` by `(x, u)`, to be
    /// weighted ([`Form::rhs_hessian`]): in the Lagrange form those of
    /// `qddot`, the model's `acceleration_curvatures` (the first `n` rows,
    /// `qdot`, are linear).
    pub(super) fn rhs_curvatures(
        self,
        model: &InterpretedModel,
        (x, u): (&[f64], &[f64]),
    ) -> RowCurvatures {
        match self {
            Self::Lagrange => {
                let (q, qdot) = x.split_at(model.sizes().n);
                evaluated(model.acceleration_curvatures(q, qdot, u))
            }
            Self::Reduced => evaluated(model.reduced_rhs_curvatures(x, u)),
            Self::Momentum => evaluated(model.momentum_form_curvatures(x, u)),
        }
    }

    /// The Hessian of `weights^T f` by `(x, u)` ((s + p)^2, row-major) from
    /// `f`'s [`Form::rhs_curvatures`] at a point: in the Lagrange form with
    /// the last `n` weights.
    pub(super) fn rhs_hessian(
        self,
        model: &InterpretedModel,
        curvatures: &RowCurvatures,
        weights: &[f64],
    ) -> Vec<f64> {
        let linear = match self {
            Self::Lagrange => model.sizes().n,
            Self::Reduced | Self::Momentum => 0,
        };
        evaluated(curvatures.hessian(&weights[linear..]))
    }

    /// The velocities `qdot` at the state `x`.
    pub(super) fn velocities(self, model: &InterpretedModel, x: &[f64]) -> Vec<f64> {
        let n = model.sizes().n;
        let (q, second) = x.split_at(n);
        match self {
            Self::Lagrange => second.to_vec(),
            Self::Reduced => evaluated(model.velocities(q, second)),
            Self::Momentum => {
                let rdot = model.shape().map_or(0, |shape| shape.len());
                let (rdot, p) = second.split_at(rdot);
                evaluated(model.reconstructed_velocity(q, rdot, p))
            }
        }
    }

    /// A function's gradient by the state `x` from its gradients by `q`
    /// and `qdot` at `(x, u)`: `(g_q, 0) + g_qdot^T d qdot/dx`, `d qdot/dx`
    /// the first `n` rows of `df/dx`.
    pub(super) fn state_gradient(
        self,
        model: &InterpretedModel,
        (x, u): (&[f64], &[f64]),
        (by_q, by_qdot): (&[f64], &[f64]),
    ) -> Vec<f64> {
        if self == Self::Lagrange {
            return [by_q, by_qdot].concat();
        }
        let s = x.len();
        let (by_x, _) = self.rhs_jacobian(model, x, u);
        let mut gradient = by_q.to_vec();
        gradient.resize(s, 0.0);
        for (g, row) in by_qdot.iter().zip(by_x.chunks(s)) {
            for (out, d) in gradient.iter_mut().zip(row) {
                *out += g * d;
            }
        }
        gradient
    }
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
mod momentum_tests;
#[cfg(test)]
mod reduced_tests;
#[cfg(test)]
mod tests;
