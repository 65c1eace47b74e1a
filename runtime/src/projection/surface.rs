//! A formulation of a model with configuration constraints `f(q) = 0`
//! ([`Holonomic`]) kept on them. Every formulation keeps `f` only through
//! its velocity form `(df/dq) qdot = 0` (one of the constraint rows), so
//! that `f` drifts with the integrator's error; after each step [`Surface`]
//! projects the configuration onto `f(q) = 0` ([`super::configuration`]),
//! then the velocity onto `ker A(q)` at the projected configuration in the
//! kinetic-energy metric ([`super::dalembert_velocity`]), and the run
//! records `max |f(q)|`. Moving `q` changes the energy `T + V` by
//! `dE/dq . dq` at every step (with the discrete gradient, which keeps it
//! to round-off between projections, this was the whole drift), so the
//! projected velocity is then scaled by `s = sqrt((E - V(q)) / T(q, qdot))`
//! back to the energy `E` the step arrived with: a projection onto the
//! manifold of all the invariants (Hairer, Lubich & Wanner, *Geometric
//! Numerical Integration*, 2nd ed., section IV.4); the scaled velocity
//! stays in `ker A(q)`, and `s` differs from 1 by the small energy change.
//!
//! Each formulation's state starts with `q`; the rest is rebuilt exactly
//! from the projected `(q, qdot)`:
//!
//! - Lagrange-d'Alembert, `x = (q, qdot)`: `q` replaced, and the velocity
//!   projected by the formulation's own projection at the new `q`;
//! - reduced, `x = (q, alpha)`: `qdot = velocities(q, alpha)` before the
//!   projection, `alpha = momenta(q, qdot)` after it (exact on `ker A(q)`);
//! - momentum, `x = (q, rdot, p)`: `qdot` reconstructed before, and
//!   `(rdot, p)` of the projected `(q, qdot)` after
//!   ([`Momentum::initial_state`]). A model has a momentum form with a
//!   configuration constraint only when the symmetry moves `f` by
//!   constants along its orbits (its differential `df` invariant, as for a
//!   tilted trough `z = a y^2 - k x` under translations along `x`): a
//!   constraint invariant under the group restricts the shape velocities,
//!   which the momentum equation needs free.
//!
//! A model without configuration constraints (`H = 0`) is left to its
//! formulation: the wrapper then changes nothing.

use super::{ProjectionError, Settings, configuration, dalembert_velocity};
use crate::arrays::matrix_from_rows;
use crate::linalg::Square;
use crate::system::{
    Dalembert, Energy, Holonomic, Jacobian, LagrangeDalembert, Momenta, Momentum,
    MomentumEquations, OdeSystem, Reduced, Structured,
};
use nalgebra::{Const, SVector};

/// A formulation `S` of a model with `N` coordinates, its state of size `D`
/// kept on the model's configuration constraints after each step.
///
/// ```text
/// Surface::dalembert(Dalembert::new(&model, controller))
/// Surface::reduced(Reduced::new(&model, controller))
/// Surface::momentum(Momentum::new(&model, controller))
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Surface<S, const N: usize, const D: usize> {
    system: S,
    kept: Option<Kept<S, N, D>>,
    settings: Settings,
}

/// `q` moved onto `f(q) = 0` by a formulation `S`'s model.
type OntoConfiguration<S, const N: usize> =
    fn(&S, &[f64; N], Settings) -> Result<[f64; N], ProjectionError>;

/// The state of a formulation `S` at a projected configuration moving
/// with a velocity.
type StateAt<S, const N: usize, const D: usize> =
    fn(&S, &[f64; N], &[f64; N]) -> Result<[f64; D], ProjectionError>;

/// How the state of a formulation `S` is kept on `f(q) = 0`.
#[derive(Clone, Copy, Debug)]
struct Kept<S, const N: usize, const D: usize> {
    /// `q` onto `f(q) = 0` ([`configuration`]).
    configuration: OntoConfiguration<S, N>,
    /// `max |f(q)|`.
    residual: fn(&S, &[f64; N]) -> f64,
    /// The velocity `qdot` of a state.
    velocity: fn(&S, &[f64; D]) -> [f64; N],
    /// The state of a projected configuration moving with `qdot`.
    state: StateAt<S, N, D>,
}

/// A closed formulation's model.
trait Formulated {
    type Model;
    fn formulated_model(&self) -> &Self::Model;
}

impl<M, F, const N: usize, const C: usize, const P: usize> Formulated
    for Dalembert<'_, M, F, N, C, P>
where
    M: LagrangeDalembert<N, C, P>,
{
    type Model = M;
    fn formulated_model(&self) -> &M {
        self.model()
    }
}

impl<M, F, const P: usize> Formulated for Reduced<'_, M, F, P> {
    type Model = M;
    fn formulated_model(&self) -> &M {
        self.model()
    }
}

impl<M, F, const N: usize, const R: usize, const K: usize, const C: usize, const P: usize>
    Formulated for Momentum<'_, M, F, N, R, K, C, P>
where
    M: MomentumEquations<N, R, K, P> + LagrangeDalembert<N, C, P>,
{
    type Model = M;
    fn formulated_model(&self) -> &M {
        self.model()
    }
}

/// `q` moved onto `f(q) = 0` of `model` ([`configuration`], the
/// constraints named as declared).
fn onto_configuration<M, const N: usize, const H: usize>(
    model: &M,
    q: &[f64; N],
    settings: Settings,
) -> Result<[f64; N], ProjectionError>
where
    M: Holonomic<N, H>,
{
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
        &model.holonomic_names(),
        settings,
    )
    .map(Into::into)
}

/// `max |f(q)|` of `model`.
fn largest_holonomic<M, const N: usize, const H: usize>(model: &M, q: &[f64; N]) -> f64
where
    M: Holonomic<N, H>,
{
    model
        .holonomic_residual(q)
        .iter()
        .fold(0.0, |worst, f| worst.max(f.abs()))
}

/// How `S` is kept on its model's `H` configuration constraints, with the
/// formulation's `velocity` and `state`; `None` without any.
fn kept<S, const N: usize, const H: usize, const D: usize>(
    velocity: fn(&S, &[f64; D]) -> [f64; N],
    state: StateAt<S, N, D>,
) -> Option<Kept<S, N, D>>
where
    S: Formulated,
    S::Model: Holonomic<N, H>,
{
    (H > 0).then_some(Kept {
        configuration: |system, q, settings| {
            onto_configuration::<_, N, H>(system.formulated_model(), q, settings)
        },
        residual: |system, q| largest_holonomic::<_, N, H>(system.formulated_model(), q),
        velocity,
        state,
    })
}

/// The first `N` entries of `x`: every formulation's configuration `q`.
fn configuration_of<const N: usize, const D: usize>(x: &[f64; D]) -> [f64; N] {
    core::array::from_fn(|i| x[i])
}

/// The last `K` entries of `x`.
fn tail<const K: usize, const D: usize>(x: &[f64; D]) -> [f64; K] {
    core::array::from_fn(|i| x[D - K + i])
}

/// `(head, tail)` as one state of size `D = A + B`.
fn joined<const A: usize, const B: usize, const D: usize>(
    head: &[f64; A],
    tail: &[f64; B],
) -> [f64; D] {
    const { assert!(D == A + B, "a state joins its parts") };
    core::array::from_fn(|i| if i < A { head[i] } else { tail[i - A] })
}

impl<S, const N: usize, const D: usize> Surface<S, N, D> {
    fn with(system: S, kept: Option<Kept<S, N, D>>) -> Self {
        Self {
            system,
            kept,
            settings: Settings::default(),
        }
    }

    /// With Newton's `settings` for the configuration constraints.
    pub fn settings(mut self, settings: Settings) -> Self {
        self.settings = settings;
        self
    }

    /// The formulation without the configuration constraints.
    pub fn system(&self) -> &S {
        &self.system
    }

    /// Whether the model declares configuration constraints (which are
    /// then kept).
    pub fn keeps_configuration(&self) -> bool {
        self.kept.is_some()
    }

    /// `q` moved onto `f(q) = 0` (unchanged without configuration
    /// constraints).
    ///
    /// # Errors
    /// As [`configuration`].
    pub fn project_configuration(&self, q: &[f64; N]) -> Result<[f64; N], ProjectionError> {
        match &self.kept {
            Some(kept) => (kept.configuration)(&self.system, q, self.settings),
            None => Ok(*q),
        }
    }

    /// `x` with its configuration on `f(q) = 0` and its velocity on
    /// `ker A(q)` there at the energy of `x`, as the module documentation
    /// says; the formulation's own projection follows in the simulation
    /// loop.
    ///
    /// # Errors
    /// As [`configuration`] and [`super::velocity`].
    pub fn project_state(&self, x: [f64; D]) -> Result<[f64; D], ProjectionError>
    where
        S: Energy<[f64; D]>,
    {
        let Some(kept) = &self.kept else {
            return Ok(x);
        };
        let qdot = (kept.velocity)(&self.system, &x);
        let q = (kept.configuration)(&self.system, &configuration_of(&x), self.settings)?;
        let projected = (kept.state)(&self.system, &q, &qdot)?;
        let potential = self
            .system
            .energy(&(kept.state)(&self.system, &q, &[0.0; N])?);
        let kinetic = self.system.energy(&projected) - potential;
        let squared_scale = (self.system.energy(&x) - potential) / kinetic;
        if kinetic > 0.0 && squared_scale > 0.0 {
            let scale = squared_scale.sqrt();
            (kept.state)(&self.system, &q, &qdot.map(|v| v * scale))
        } else {
            Ok(projected)
        }
    }

    /// `max |f(q)|` at `x`, `None` without configuration constraints.
    pub fn holonomic_residual(&self, x: &[f64; D]) -> Option<f64> {
        let kept = self.kept.as_ref()?;
        Some((kept.residual)(&self.system, &configuration_of(x)))
    }
}

impl<'a, M, F, const N: usize, const C: usize, const P: usize, const D: usize>
    Surface<Dalembert<'a, M, F, N, C, P>, N, D>
where
    M: LagrangeDalembert<N, C, P>,
{
    /// The Lagrange-d'Alembert equations kept on the model's `H`
    /// configuration constraints; their own velocity projection
    /// ([`super::dalembert_velocity`]) moves the velocity onto
    /// `ker A(q)` at the projected configuration.
    pub fn dalembert<const H: usize>(system: Dalembert<'a, M, F, N, C, P>) -> Self
    where
        M: Holonomic<N, H>,
    {
        let kept = kept::<Dalembert<'a, M, F, N, C, P>, N, H, D>(
            |_, x| tail::<N, D>(x),
            |_, q, qdot| Ok(joined(q, qdot)),
        );
        Self::with(system, kept)
    }
}

impl<'a, M, F, const N: usize, const P: usize, const D: usize> Surface<Reduced<'a, M, F, P>, N, D> {
    /// The reduced form `(q, alpha)` kept on the model's `H` configuration
    /// constraints (`C` constraint rows, `K` momenta, `D = N + K`), in the
    /// active chart of D.
    pub fn reduced<const C: usize, const K: usize, const H: usize>(
        system: Reduced<'a, M, F, P>,
    ) -> Self
    where
        M: LagrangeDalembert<N, C, P> + Momenta<N, K> + Holonomic<N, H>,
    {
        let kept = kept::<Reduced<'a, M, F, P>, N, H, D>(
            |system, x| {
                let model = system.model();
                model.chart_velocities(system.chart(), &configuration_of(x), &tail::<K, D>(x))
            },
            |system, q, qdot| {
                let qdot = dalembert_velocity::<M, N, C, P>(system.model(), q, qdot)?;
                let alpha = system.model().chart_momenta(system.chart(), q, &qdot);
                Ok(joined(q, &alpha))
            },
        );
        Self::with(system, kept)
    }
}

impl<
    'a,
    M,
    F,
    const N: usize,
    const R: usize,
    const K: usize,
    const C: usize,
    const P: usize,
    const D: usize,
> Surface<Momentum<'a, M, F, N, R, K, C, P>, N, D>
where
    M: MomentumEquations<N, R, K, P> + LagrangeDalembert<N, C, P>,
{
    /// The momentum equation `(q, rdot, p)` kept on the model's `H`
    /// configuration constraints.
    pub fn momentum<const H: usize>(system: Momentum<'a, M, F, N, R, K, C, P>) -> Self
    where
        M: Holonomic<N, H>,
    {
        let kept = kept::<Momentum<'a, M, F, N, R, K, C, P>, N, H, D>(
            |system, x| system.configuration_velocity(x).1,
            |system, q, qdot| {
                let qdot = dalembert_velocity::<M, N, C, P>(system.model(), q, qdot)?;
                Ok(system.initial_state(q, &qdot))
            },
        );
        Self::with(system, kept)
    }
}

impl<S: OdeSystem<[f64; D]>, const N: usize, const D: usize> OdeSystem<[f64; D]>
    for Surface<S, N, D>
{
    fn rhs(&self, t: f64, x: &[f64; D]) -> [f64; D] {
        self.system.rhs(t, x)
    }
}

impl<S: Jacobian<[f64; D]>, const N: usize, const D: usize> Jacobian<[f64; D]> for Surface<S, N, D>
where
    Const<D>: Square,
{
    fn jacobian(&self, t: f64, x: &[f64; D]) -> [[f64; D]; D] {
        self.system.jacobian(t, x)
    }
}

impl<S: Energy<[f64; D]>, const N: usize, const D: usize> Energy<[f64; D]> for Surface<S, N, D> {
    fn energy(&self, x: &[f64; D]) -> f64 {
        self.system.energy(x)
    }
}

impl<S: Structured<[f64; D]>, const N: usize, const D: usize> Structured<[f64; D]>
    for Surface<S, N, D>
where
    Const<D>: Square,
{
    fn structure_matrix(&self, x: &[f64; D]) -> [[f64; D]; D] {
        self.system.structure_matrix(x)
    }

    fn energy_gradient(&self, x: &[f64; D]) -> [f64; D] {
        self.system.energy_gradient(x)
    }

    fn forcing(&self, t: f64, x: &[f64; D]) -> [f64; D] {
        self.system.forcing(t, x)
    }
}
