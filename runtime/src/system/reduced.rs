//! The reduced form closed by a controller ([`Reduced`]), in the active
//! chart of D.

use super::next_chart;
use super::{Energy, Jacobian, Momenta, OdeSystem, ReducedPortHamiltonian, Structured};
use crate::law::{Constant, Controller};
use crate::linalg::Square;
use core::cell::Cell;
use nalgebra::Const;

/// A model in its reduced form closed by a [`Controller`]: an
/// [`OdeSystem`] in `x = (q, alpha)` with `u = controller(t, x)`, in the
/// active chart of D ([`ReducedPortHamiltonian::charts`]; chart 0, or the
/// best at the start with [`Reduced::initial_state`], changed by the
/// simulation loop where it degenerates). The controller is asked for the
/// input in the active chart ([`Controller::chart_input`]), so that a law
/// of the configuration and velocity reads the velocity of the state in it
/// ([`crate::law::ChartFeedback`]).
#[derive(Clone, Debug)]
pub struct Reduced<'a, M, F, const P: usize> {
    model: &'a M,
    controller: F,
    chart: Cell<usize>,
}

impl<'a, M, F, const P: usize> Reduced<'a, M, F, P> {
    /// `model` driven by `controller`: a [`Constant`], a closure `u(t)`,
    /// a [`crate::law::Feedback`] `u(t, x)`, or a
    /// [`crate::law::ChartFeedback`] `u(chart, t, x)`.
    pub fn new(model: &'a M, controller: F) -> Self {
        Self {
            model,
            controller,
            chart: Cell::new(0),
        }
    }

    /// The active chart.
    pub fn chart(&self) -> usize {
        self.chart.get()
    }

    /// Makes `chart` the active chart (the state must be given in it).
    pub fn set_chart(&self, chart: usize) {
        self.chart.set(chart);
    }

    /// The state `(q, alpha)` of the configuration `q` moving with `qdot`
    /// (a velocity the constraints allow), in the chart that fits best at
    /// `q` (a run-time chart where no generated one fits,
    /// [`next_chart`]), which becomes the active chart;
    /// `S = N + K`.
    pub fn initial_state<const N: usize, const K: usize, const S: usize>(
        &self,
        q: &[f64; N],
        qdot: &[f64; N],
    ) -> [f64; S]
    where
        M: ReducedPortHamiltonian<S, P> + Momenta<N, K>,
    {
        const { assert!(S == N + K, "the state (q, alpha) has S = N + K entries") };
        let model = self.model;
        let configuration: [f64; S] = core::array::from_fn(|i| if i < N { q[i] } else { 0.0 });
        let fit = |chart| model.chart_fit(chart, &configuration);
        let best = (0..model.charts())
            .max_by(|&a, &b| fit(a).total_cmp(&fit(b)))
            .unwrap_or(0);
        let pivoted = model.pivoted_chart(&configuration);
        let best = next_chart(model.charts(), best, fit, pivoted).unwrap_or(best);
        self.set_chart(best);
        let alpha = self.model.chart_momenta(best, q, qdot);
        core::array::from_fn(|i| if i < N { q[i] } else { alpha[i - N] })
    }

    /// The model.
    pub fn model(&self) -> &'a M {
        self.model
    }

    /// The controller.
    pub fn controller(&self) -> &F {
        &self.controller
    }
}

impl<'a, M, const P: usize> Reduced<'a, M, Constant<P>, P> {
    /// `model` driven by the constant input `u`.
    pub fn constant(model: &'a M, u: [f64; P]) -> Self {
        Self::new(model, Constant(u))
    }
}

impl<M, F, const S: usize, const P: usize> OdeSystem<[f64; S]> for Reduced<'_, M, F, P>
where
    M: ReducedPortHamiltonian<S, P>,
    F: Controller<S, P>,
{
    fn rhs(&self, t: f64, x: &[f64; S]) -> [f64; S] {
        let chart = self.chart();
        let u = self.controller.chart_input(chart, t, x);
        self.model.chart_rhs(chart, x, &u)
    }
}

impl<M, F, const S: usize, const P: usize> Jacobian<[f64; S]> for Reduced<'_, M, F, P>
where
    M: ReducedPortHamiltonian<S, P>,
    F: Controller<S, P>,
    Const<S>: Square,
{
    /// `df/dx + G(x) du/dx`: the model's exact Jacobian at fixed `u`, and
    /// the feedback's through the input matrix.
    fn jacobian(&self, t: f64, x: &[f64; S]) -> [[f64; S]; S] {
        let chart = self.chart();
        let u = self.controller.chart_input(chart, t, x);
        let mut jacobian = self.model.chart_rhs_jacobian(chart, x, &u);
        let (g, du) = (
            self.model.chart_input_matrix(chart, x),
            self.controller.chart_input_jacobian(chart, t, x),
        );
        for (row, g_row) in jacobian.iter_mut().zip(&g) {
            for (j, entry) in row.iter_mut().enumerate() {
                *entry += (0..P).map(|l| g_row[l] * du[l][j]).sum::<f64>();
            }
        }
        jacobian
    }
}

impl<M, F, const S: usize, const P: usize> Energy<[f64; S]> for Reduced<'_, M, F, P>
where
    M: ReducedPortHamiltonian<S, P>,
    F: Controller<S, P>,
{
    fn energy(&self, x: &[f64; S]) -> f64 {
        self.model.chart_hamiltonian(self.chart(), x)
    }
}

impl<M, F, const S: usize, const P: usize> Structured<[f64; S]> for Reduced<'_, M, F, P>
where
    M: ReducedPortHamiltonian<S, P>,
    F: Controller<S, P>,
    Const<S>: Square,
{
    fn structure_matrix(&self, x: &[f64; S]) -> [[f64; S]; S] {
        self.model.chart_structure_matrix(self.chart(), x)
    }

    fn energy_gradient(&self, x: &[f64; S]) -> [f64; S] {
        self.model.chart_hamiltonian_gradient(self.chart(), x)
    }

    /// `G(x) u(t, x)`.
    fn forcing(&self, t: f64, x: &[f64; S]) -> [f64; S] {
        let chart = self.chart();
        let (g, u) = (
            self.model.chart_input_matrix(chart, x),
            self.controller.chart_input(chart, t, x),
        );
        core::array::from_fn(|i| (0..P).map(|l| g[i][l] * u[l]).sum())
    }
}
