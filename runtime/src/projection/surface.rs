//! The Lagrange-d'Alembert form of a model with configuration constraints
//! `f(q) = 0` ([`Holonomic`]), kept on them: after each step the
//! configuration is projected onto `f(q) = 0`, then the velocity onto
//! `ker A(q)` (see [`super`]), and the run records `max |f(q)|`.

use super::{ProjectionError, Settings, configuration};
use crate::arrays::matrix_from_rows;
use crate::law::Controller;
use crate::system::{Dalembert, Energy, Holonomic, Jacobian, LagrangeDalembert, OdeSystem};
use nalgebra::{Const, SVector};

/// A model's Lagrange-d'Alembert equations closed by a controller, as
/// [`Dalembert`], with its `H` configuration constraints kept: `N`
/// coordinates, `C` constraint rows (the velocity forms of the `H`
/// among them), `P` inputs, `D = 2 N` states.
#[derive(Clone, Copy, Debug)]
pub struct Surface<'a, M, F, const N: usize, const C: usize, const P: usize, const H: usize> {
    equations: Dalembert<'a, M, F, N, C, P>,
    settings: Settings,
}

impl<'a, M, F, const N: usize, const C: usize, const P: usize, const H: usize>
    Surface<'a, M, F, N, C, P, H>
where
    M: LagrangeDalembert<N, C, P> + Holonomic<N, H>,
{
    /// `model` driven by `controller` (as [`Dalembert::new`]), projected
    /// with Newton's default [`Settings`].
    pub fn new(model: &'a M, controller: F) -> Self {
        Self {
            equations: Dalembert::new(model, controller),
            settings: Settings::default(),
        }
    }

    /// With Newton's `settings` for the configuration constraints.
    pub fn settings(mut self, settings: Settings) -> Self {
        self.settings = settings;
        self
    }

    /// The equations without the configuration constraints.
    pub fn equations(&self) -> &Dalembert<'a, M, F, N, C, P> {
        &self.equations
    }

    /// `q` moved onto `f(q) = 0`.
    ///
    /// # Errors
    /// As [`configuration`].
    pub fn project_configuration(&self, q: &[f64; N]) -> Result<[f64; N], ProjectionError> {
        let model = self.equations.model();
        let constraint = |q: &SVector<f64, N>| {
            let q: [f64; N] = (*q).into();
            (
                SVector::<f64, H>::from(model.holonomic_residual(&q)),
                matrix_from_rows(&model.holonomic_jacobian(&q)),
            )
        };
        configuration::<Const<N>, Const<H>>(
            SVector::from(*q),
            constraint,
            &M::HOLONOMIC,
            self.settings,
        )
        .map(Into::into)
    }
}

impl<M, F, const N: usize, const C: usize, const P: usize, const H: usize, const D: usize>
    OdeSystem<D> for Surface<'_, M, F, N, C, P, H>
where
    M: LagrangeDalembert<N, C, P>,
    F: Controller<D, P>,
{
    fn rhs(&self, t: f64, x: &[f64; D]) -> [f64; D] {
        self.equations.rhs(t, x)
    }
}

impl<M, F, const N: usize, const C: usize, const P: usize, const H: usize, const D: usize>
    Jacobian<D> for Surface<'_, M, F, N, C, P, H>
where
    M: LagrangeDalembert<N, C, P>,
    F: Controller<D, P>,
{
    fn jacobian(&self, t: f64, x: &[f64; D]) -> [[f64; D]; D] {
        self.equations.jacobian(t, x)
    }
}

impl<M, F, const N: usize, const C: usize, const P: usize, const H: usize, const D: usize> Energy<D>
    for Surface<'_, M, F, N, C, P, H>
where
    M: LagrangeDalembert<N, C, P>,
    F: Controller<D, P>,
{
    fn energy(&self, x: &[f64; D]) -> f64 {
        self.equations.energy(x)
    }
}
