//! What the simulation loop observes of a system ([`Observed`]): its
//! columns, inputs, configuration and velocity, energy, constraint residual
//! and regularity measure ([`Regularity`]), for each formulation closed by
//! its controller; and how it keeps a state on the constraint manifold
//! after a step ([`Observed::project`]).

use crate::control::{Interconnection, PortHamiltonianController};
use crate::law::Controller;
use crate::linalg::Square;
use crate::monitor::{dependent_rows, momentum_regularity};
use crate::projection::{self, ProjectionError, Surface};
use crate::system::{
    Dalembert, Domain, Energy, Guard, LagrangeDalembert, ModelNames, Momentum, MomentumEquations,
    Reduced, ReducedPortHamiltonian, next_chart, split,
};
use nalgebra::{Const, DMatrix};
use std::borrow::Cow;

/// A regularity measure's value at a state, and what it measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Regularity {
    /// What degenerates where the measure vanishes.
    pub quantity: &'static str,
    /// The measure, scale-free, at most 1 in magnitude.
    pub value: f64,
    /// Whether the measure changes sign where it is crossed, so that a
    /// crossing between two steps is detected too.
    pub signed: bool,
}

/// A system the simulation loop can run and record: its columns, inputs,
/// energy, constraint residual and regularity at a state.
pub trait Observed<X>: Energy<X> {
    /// The names of the state's entries, in order.
    fn state_names(&self) -> Vec<String>;
    /// The names of the inputs, in order.
    fn input_names(&self) -> Vec<String>;
    /// The inputs applied at `(t, x)`, written into `inputs` (as many as
    /// [`Observed::input_names`]).
    fn inputs(&self, t: f64, x: &X, inputs: &mut [f64]);
    /// The power the inputs deliver to the mechanism at `(t, x)`,
    /// `u . B(q)^T qdot`: the rate of the work a run's power balance
    /// integrates ([`super::Summary::power_balance`]).
    fn input_power(&self, t: f64, x: &X) -> f64;
    /// The configuration `q` and its velocity `qdot` at `x`, written into
    /// `q` and `qdot` (as long as the model's coordinates): what a law of
    /// the mechanics `u(t, q, qdot)` or a stop condition reads, whatever
    /// the formulation's state.
    fn configuration_velocity(&self, x: &X, q: &mut [f64], qdot: &mut [f64]);
    /// The energy at rest at `x`'s configuration: its velocities zero,
    /// any controller's states kept (the potential energy, springs
    /// included). The energy above it is the kinetic energy, the scale of a
    /// run's energy drift ([`super::Summary::energy_drift`]), which a
    /// constant added to the potential does not change. By default 0: all
    /// of the energy counts as kinetic.
    fn energy_at_rest(&self, _x: &X) -> f64 {
        0.0
    }
    /// The largest `|A(q) qdot|` at `x`.
    fn constraint_residual(&self, x: &X) -> f64;
    /// The regularity measure at `x`.
    fn regularity(&self, x: &X) -> Regularity;
    /// `x` moved back onto the constraint manifold after a step
    /// ([`crate::projection`]). The formulations whose state cannot leave it
    /// (the reduced form, the momentum equation) keep the default: `x`.
    ///
    /// # Errors
    /// A constraint the projection cannot meet.
    fn project(&self, x: X) -> Result<X, ProjectionError> {
        Ok(x)
    }
    /// The largest `|f(q)|` of the configuration constraints the system
    /// keeps, `None` when it keeps none (no `holonomic_residual` column).
    fn holonomic_residual(&self, _x: &X) -> Option<f64> {
        None
    }
    /// The active chart of D, `None` for a formulation with one chart (no
    /// `chart` column).
    fn chart(&self) -> Option<usize> {
        None
    }
    /// The model's guarded expressions at `x` ([`crate::system::Domain`]),
    /// none by default.
    fn domain(&self, _x: &X) -> Vec<GuardedValue<'_>> {
        Vec::new()
    }
    /// The names of the constraint rows that are dependent at `x`
    /// ([`crate::monitor::dependent_rows`]); none where they are
    /// independent, and by default.
    fn dependent_rows(&self, _x: &X) -> Vec<String> {
        Vec::new()
    }
    /// Where the active chart fits worse than [`crate::system::CHART_SWITCH`] times the
    /// best chart at `x`, makes the best one active and moves `x` into it
    /// (the same configuration and velocity); whether it did. By default
    /// (one chart) it never does.
    fn change_chart(&self, _x: &mut X) -> bool {
        false
    }
    /// Moves `x` into the run-time chart partial pivoting picks at its
    /// configuration ([`crate::partition`]), unless that chart is active
    /// or there is none; whether it did. The simulation loop does so where
    /// a step fails in another chart, and takes the step again.
    fn change_to_pivoted_chart(&self, _x: &mut X) -> bool {
        false
    }
}

/// `u . B(q)^T qdot` from the Lagrange-d'Alembert accelerations, which
/// are affine in `u`: with `w = qddot(u) - qddot(0)`, `g w = B u + A^T dl`
/// and `A qdot = 0`, so the power is `qdot^T g w`, the polarization
/// `E(q, qdot + w) - E(q, qdot) - E(q, w) + E(q, 0)` of the energy
/// `E = 1/2 qdot^T g qdot + V`.
fn dalembert_input_power<M, const N: usize, const C: usize, const P: usize>(
    model: &M,
    q: &[f64; N],
    qdot: &[f64; N],
    u: &[f64; P],
) -> f64
where
    M: LagrangeDalembert<N, C, P>,
{
    let (forced, _) = model.acceleration(q, qdot, u);
    let (free, _) = model.acceleration(q, qdot, &[0.0; P]);
    let w: [f64; N] = core::array::from_fn(|i| forced[i] - free[i]);
    let moved: [f64; N] = core::array::from_fn(|i| qdot[i] + w[i]);
    model.energy(q, &moved) - model.energy(q, qdot) - model.energy(q, &w)
        + model.energy(q, &[0.0; N])
}

/// A guarded expression of a model at a state ([`Observed::domain`]).
#[derive(Clone, Debug, PartialEq)]
pub struct GuardedValue<'a> {
    /// What it guards, where, and what must hold (borrowed from the model:
    /// checking the domain after every step copies no text).
    pub description: Cow<'a, str>,
    /// What must hold.
    pub guard: Guard,
    /// Its value.
    pub value: f64,
}

impl GuardedValue<'_> {
    /// Whether the guard fails at this value where it held at `reference`
    /// (a positive value turned non-positive, or a divisor's sign lost;
    /// NaN fails).
    pub fn fails_from(&self, reference: f64) -> bool {
        match self.guard {
            Guard::Positive => reference > 0.0 && (self.value <= 0.0 || self.value.is_nan()),
            Guard::NonZero => {
                let kept = self.value * reference;
                reference != 0.0 && (kept <= 0.0 || kept.is_nan())
            }
        }
    }

    /// Whether the guard fails at this value on its own.
    pub fn fails(&self) -> bool {
        match self.guard {
            Guard::Positive => self.value <= 0.0 || self.value.is_nan(),
            Guard::NonZero => !(self.value != 0.0 && self.value.is_finite()),
        }
    }
}

/// The guarded expressions of `model` at the configuration `q`.
fn domain_of<'a, M: Domain>(model: &'a M, q: &[f64]) -> Vec<GuardedValue<'a>> {
    let guards = model.guards();
    let mut values = vec![0.0; guards.len()];
    model.domain(q, &mut values);
    guards
        .iter()
        .zip(values)
        .map(|(&(description, guard), value)| GuardedValue {
            description: Cow::Borrowed(description),
            guard,
            value,
        })
        .collect()
}

/// The names of `model`'s constraint rows that are dependent at `q`.
fn dependent_rows_of<M: Domain + ModelNames>(model: &M, q: &[f64]) -> Vec<String> {
    let constraints = model.constraint_names();
    let (c, n) = (constraints.len(), model.coordinate_names().len());
    let mut rows = vec![0.0; c * n];
    if !model.constraint_rows(&q[..n], &mut rows) {
        return Vec::new();
    }
    dependent_rows(&DMatrix::from_row_slice(c, n, &rows))
        .into_iter()
        .map(|i| constraints[i].to_string())
        .collect()
}

/// The reduced form's measure (see [`crate::monitor::reduced_regularity`]).
pub const REDUCED: &str = "reduced form's det[A; V^T] (constraint rows and momentum basis)";

/// The momentum form's measure (see [`crate::monitor::momentum_regularity`]).
pub const RECONSTRUCTION: &str =
    "momentum form's reconstruction det[A; E_r; h g] (constraint rows, shape and momentum basis)";

/// The Lagrange-d'Alembert form's measure (see
/// [`crate::monitor::constraint_regularity`]).
pub const MULTIPLIERS: &str = "multiplier system's Gram matrix A g^-1 A^T";

/// The largest `|A(q) qdot|` of the Lagrange-d'Alembert equations.
fn largest_residual<M, const N: usize, const C: usize, const P: usize>(
    model: &M,
    q: &[f64; N],
    qdot: &[f64; N],
) -> f64
where
    M: LagrangeDalembert<N, C, P>,
{
    let residual = model.constraint_residual(q, qdot);
    residual.iter().fold(0.0, |worst, r| worst.max(r.abs()))
}

/// The Gram matrix's measure at the configuration `q`.
fn multiplier_regularity<M, const N: usize, const C: usize, const P: usize>(
    model: &M,
    q: &[f64; N],
) -> Regularity
where
    M: LagrangeDalembert<N, C, P>,
{
    Regularity {
        quantity: MULTIPLIERS,
        value: model.constraint_regularity(q),
        signed: false,
    }
}

/// `q` and the velocity `qdot` of a reduced state `x = (q, alpha)`: the
/// first block row of the reduced form, `qdot = g^-1 h^T alpha` (MATH.md
/// section 3), which the inputs do not enter, in `chart`.
fn reduced_configuration_velocity<M, const S: usize, const P: usize>(
    model: &M,
    chart: usize,
    x: &[f64; S],
    q: &mut [f64],
    qdot: &mut [f64],
) where
    M: ReducedPortHamiltonian<S, P>,
{
    let n = q.len();
    q.copy_from_slice(&x[..n]);
    qdot.copy_from_slice(&model.chart_rhs(chart, x, &[0.0; P])[..n]);
}

/// `x` with its entries from `n` on zero: a state `(q, alpha)` at rest.
fn at_rest<const S: usize>(x: &[f64; S], n: usize) -> [f64; S] {
    core::array::from_fn(|i| if i < n { x[i] } else { 0.0 })
}

fn owned(names: &[&str]) -> Vec<String> {
    names.iter().map(|name| name.to_string()).collect()
}

impl<M, F, const S: usize, const P: usize> Observed<[f64; S]> for Reduced<'_, M, F, P>
where
    M: ReducedPortHamiltonian<S, P> + ModelNames + Domain,
    F: Controller<S, P>,
{
    fn domain(&self, x: &[f64; S]) -> Vec<GuardedValue<'_>> {
        domain_of(self.model(), &x[..self.model().coordinate_names().len()])
    }

    fn dependent_rows(&self, x: &[f64; S]) -> Vec<String> {
        dependent_rows_of(self.model(), &x[..self.model().coordinate_names().len()])
    }

    fn state_names(&self) -> Vec<String> {
        let model = self.model();
        owned(&[model.coordinate_names(), model.momentum_names()].concat())
    }

    fn input_names(&self) -> Vec<String> {
        owned(self.model().input_names())
    }

    fn inputs(&self, t: f64, x: &[f64; S], inputs: &mut [f64]) {
        let chart = Reduced::chart(self);
        inputs.copy_from_slice(&self.controller().chart_input(chart, t, x));
    }

    /// `u . y` with the collocated output `y = Bbar^T dHbar/dx` of the
    /// active chart, which equals `B(q)^T qdot`.
    fn input_power(&self, t: f64, x: &[f64; S]) -> f64 {
        let chart = Reduced::chart(self);
        let u = self.controller().chart_input(chart, t, x);
        let b = self.model().chart_input_matrix(chart, x);
        let gradient = self.model().chart_hamiltonian_gradient(chart, x);
        (b.iter().zip(gradient))
            .map(|(row, g)| g * row.iter().zip(&u).map(|(b, u)| b * u).sum::<f64>())
            .sum()
    }

    fn configuration_velocity(&self, x: &[f64; S], q: &mut [f64], qdot: &mut [f64]) {
        reduced_configuration_velocity(self.model(), Reduced::chart(self), x, q, qdot);
    }

    /// `H(q, 0)`: the momenta of a velocity zero are zero.
    fn energy_at_rest(&self, x: &[f64; S]) -> f64 {
        let rest = at_rest(x, self.model().coordinate_names().len());
        self.model().chart_hamiltonian(self.chart(), &rest)
    }

    fn constraint_residual(&self, x: &[f64; S]) -> f64 {
        self.model().chart_constraint_violation(self.chart(), x)
    }

    fn regularity(&self, x: &[f64; S]) -> Regularity {
        Regularity {
            quantity: REDUCED,
            value: self.model().chart_regularity(self.chart(), x),
            signed: true,
        }
    }

    fn chart(&self) -> Option<usize> {
        self.model().switches_charts().then(|| Reduced::chart(self))
    }

    fn change_chart(&self, x: &mut [f64; S]) -> bool {
        let (model, active) = (self.model(), Reduced::chart(self));
        let fit = |chart| model.chart_fit(chart, x);
        let Some(next) = next_chart(model.charts(), active, fit, model.pivoted_chart(x)) else {
            return false;
        };
        *x = model.change_chart(active, next, x);
        self.set_chart(next);
        true
    }

    fn change_to_pivoted_chart(&self, x: &mut [f64; S]) -> bool {
        let (model, active) = (self.model(), Reduced::chart(self));
        match model.pivoted_chart(x) {
            Some(pivoted) if pivoted != active => {
                *x = model.change_chart(active, pivoted, x);
                self.set_chart(pivoted);
                true
            }
            _ => false,
        }
    }
}

impl<M, F, const N: usize, const C: usize, const P: usize, const D: usize> Observed<[f64; D]>
    for Dalembert<'_, M, F, N, C, P>
where
    M: LagrangeDalembert<N, C, P> + ModelNames + Domain,
    F: Controller<D, P>,
{
    fn domain(&self, x: &[f64; D]) -> Vec<GuardedValue<'_>> {
        domain_of(self.model(), &x[..self.model().coordinate_names().len()])
    }

    fn dependent_rows(&self, x: &[f64; D]) -> Vec<String> {
        dependent_rows_of(self.model(), &x[..self.model().coordinate_names().len()])
    }

    fn state_names(&self) -> Vec<String> {
        let coordinates = self.model().coordinate_names();
        let velocities = coordinates.iter().map(|q| format!("dot({q})"));
        owned(coordinates).into_iter().chain(velocities).collect()
    }

    fn input_names(&self) -> Vec<String> {
        owned(self.model().input_names())
    }

    fn inputs(&self, t: f64, x: &[f64; D], inputs: &mut [f64]) {
        inputs.copy_from_slice(&self.controller().input(t, x));
    }

    fn input_power(&self, t: f64, x: &[f64; D]) -> f64 {
        let (q, qdot) = split::<N, D>(x);
        dalembert_input_power(self.model(), &q, &qdot, &self.controller().input(t, x))
    }

    fn configuration_velocity(&self, x: &[f64; D], q: &mut [f64], qdot: &mut [f64]) {
        q.copy_from_slice(&x[..N]);
        qdot.copy_from_slice(&x[N..]);
    }

    /// `E(q, 0)`.
    fn energy_at_rest(&self, x: &[f64; D]) -> f64 {
        self.model().energy(&split::<N, D>(x).0, &[0.0; N])
    }

    fn constraint_residual(&self, x: &[f64; D]) -> f64 {
        let (q, qdot) = split::<N, D>(x);
        largest_residual(self.model(), &q, &qdot)
    }

    fn regularity(&self, x: &[f64; D]) -> Regularity {
        multiplier_regularity(self.model(), &split::<N, D>(x).0)
    }

    /// The velocity onto `ker A(q)` in the kinetic-energy metric
    /// ([`projection::dalembert_velocity`]).
    fn project(&self, x: [f64; D]) -> Result<[f64; D], ProjectionError> {
        let (q, qdot) = split::<N, D>(&x);
        let qdot = projection::dalembert_velocity(self.model(), &q, &qdot)?;
        Ok(core::array::from_fn(
            |i| if i < N { q[i] } else { qdot[i - N] },
        ))
    }
}

impl<
    M,
    F,
    const N: usize,
    const R: usize,
    const K: usize,
    const C: usize,
    const P: usize,
    const D: usize,
> Observed<[f64; D]> for Momentum<'_, M, F, N, R, K, C, P>
where
    M: MomentumEquations<N, R, K, P> + LagrangeDalembert<N, C, P> + ModelNames + Domain,
    F: Controller<D, P>,
    Const<N>: Square,
{
    /// The model's guarded expressions and the momentum basis's divisors
    /// ([`MomentumEquations::basis_divisor_names`]), which must not vanish.
    fn domain(&self, x: &[f64; D]) -> Vec<GuardedValue<'_>> {
        let mut guards = domain_of(self.model(), &x[..N]);
        let divisors = self.model().basis_divisor_names();
        let mut values = vec![0.0; divisors.len()];
        self.model().basis_divisors(&mut values);
        guards.extend(
            divisors
                .iter()
                .zip(values)
                .map(|(description, value)| GuardedValue {
                    description: Cow::Borrowed(description),
                    guard: Guard::NonZero,
                    value,
                }),
        );
        guards
    }

    fn dependent_rows(&self, x: &[f64; D]) -> Vec<String> {
        dependent_rows_of(self.model(), &x[..self.model().coordinate_names().len()])
    }

    /// The coordinates, `dot(r)` for the shape velocities, `p1..pK`.
    fn state_names(&self) -> Vec<String> {
        let coordinates = self.model().coordinate_names();
        let shape = self.model().shape_indices();
        let shape_velocities = shape.map(|i| format!("dot({})", coordinates[i]));
        let momenta = (1..=K).map(|i| format!("p{i}"));
        owned(coordinates)
            .into_iter()
            .chain(shape_velocities)
            .chain(momenta)
            .collect()
    }

    fn input_names(&self) -> Vec<String> {
        owned(self.model().input_names())
    }

    fn inputs(&self, t: f64, x: &[f64; D], inputs: &mut [f64]) {
        inputs.copy_from_slice(&self.controller().input(t, x));
    }

    fn input_power(&self, t: f64, x: &[f64; D]) -> f64 {
        let (q, qdot) = Momentum::configuration_velocity(self, x);
        dalembert_input_power(self.model(), &q, &qdot, &self.controller().input(t, x))
    }

    /// `q` and the reconstructed velocity.
    fn configuration_velocity(&self, x: &[f64; D], q: &mut [f64], qdot: &mut [f64]) {
        let (configuration, velocity) = Momentum::configuration_velocity(self, x);
        q.copy_from_slice(&configuration);
        qdot.copy_from_slice(&velocity);
    }

    /// `E(q, 0)`.
    fn energy_at_rest(&self, x: &[f64; D]) -> f64 {
        let q: [f64; N] = core::array::from_fn(|i| x[i]);
        LagrangeDalembert::energy(self.model(), &q, &[0.0; N])
    }

    fn constraint_residual(&self, x: &[f64; D]) -> f64 {
        let (q, qdot) = Momentum::configuration_velocity(self, x);
        largest_residual(self.model(), &q, &qdot)
    }

    /// What the reconstruction of `qdot` inverts (see
    /// [`crate::monitor::momentum_regularity`]).
    fn regularity(&self, x: &[f64; D]) -> Regularity {
        let q: [f64; N] = core::array::from_fn(|i| x[i]);
        let model = self.model();
        Regularity {
            quantity: RECONSTRUCTION,
            value: momentum_regularity(
                |v| model.constraint_residual(&q, v),
                |v| model.momentum(&q, v),
                &model.shape_indices(),
            ),
            signed: true,
        }
    }
}

impl<M, K, const S: usize, const NC: usize, const P: usize, const D: usize> Observed<[f64; D]>
    for Interconnection<M, K, S, NC, P>
where
    M: ReducedPortHamiltonian<S, P> + ModelNames + Domain,
    K: PortHamiltonianController<S, NC, P>,
{
    fn domain(&self, x: &[f64; D]) -> Vec<GuardedValue<'_>> {
        domain_of(&self.plant, &x[..self.plant.coordinate_names().len()])
    }

    fn dependent_rows(&self, x: &[f64; D]) -> Vec<String> {
        dependent_rows_of(&self.plant, &x[..self.plant.coordinate_names().len()])
    }

    fn state_names(&self) -> Vec<String> {
        let plant = &self.plant;
        owned(&[plant.coordinate_names(), plant.momentum_names(), &K::STATES].concat())
    }

    fn input_names(&self) -> Vec<String> {
        owned(self.plant.input_names())
    }

    fn inputs(&self, _t: f64, z: &[f64; D], inputs: &mut [f64]) {
        inputs.copy_from_slice(&self.input(z));
    }

    /// None from outside: the controller's ports exchange power with the
    /// plant's, and the energy counts both.
    fn input_power(&self, _t: f64, _z: &[f64; D]) -> f64 {
        0.0
    }

    /// The plant's (in its chart 0).
    fn configuration_velocity(&self, z: &[f64; D], q: &mut [f64], qdot: &mut [f64]) {
        reduced_configuration_velocity(&self.plant, 0, &Self::split(z).0, q, qdot);
    }

    /// The plant's `H(q, 0)` and the controller's energy.
    fn energy_at_rest(&self, z: &[f64; D]) -> f64 {
        let (x, xc) = Self::split(z);
        let rest = at_rest(&x, self.plant.coordinate_names().len());
        self.plant.hamiltonian(&rest) + self.controller.energy(&xc)
    }

    fn constraint_residual(&self, z: &[f64; D]) -> f64 {
        self.plant.constraint_violation(&Self::split(z).0)
    }

    fn regularity(&self, z: &[f64; D]) -> Regularity {
        Regularity {
            quantity: REDUCED,
            value: self.plant.regularity(&Self::split(z).0),
            signed: true,
        }
    }
}

impl<S, const N: usize, const D: usize> Observed<[f64; D]> for Surface<S, N, D>
where
    S: Observed<[f64; D]>,
{
    fn state_names(&self) -> Vec<String> {
        self.system().state_names()
    }

    fn input_names(&self) -> Vec<String> {
        self.system().input_names()
    }

    fn inputs(&self, t: f64, x: &[f64; D], inputs: &mut [f64]) {
        self.system().inputs(t, x, inputs);
    }

    fn input_power(&self, t: f64, x: &[f64; D]) -> f64 {
        self.system().input_power(t, x)
    }

    fn configuration_velocity(&self, x: &[f64; D], q: &mut [f64], qdot: &mut [f64]) {
        self.system().configuration_velocity(x, q, qdot);
    }

    fn energy_at_rest(&self, x: &[f64; D]) -> f64 {
        self.system().energy_at_rest(x)
    }

    fn constraint_residual(&self, x: &[f64; D]) -> f64 {
        self.system().constraint_residual(x)
    }

    fn regularity(&self, x: &[f64; D]) -> Regularity {
        self.system().regularity(x)
    }

    /// The configuration onto `f(q) = 0` and the velocity onto `ker A(q)`
    /// there ([`Surface::project_state`]), then the formulation's own
    /// projection.
    fn project(&self, x: [f64; D]) -> Result<[f64; D], ProjectionError> {
        self.system().project(self.project_state(x)?)
    }

    fn holonomic_residual(&self, x: &[f64; D]) -> Option<f64> {
        Surface::holonomic_residual(self, x)
    }

    fn domain(&self, x: &[f64; D]) -> Vec<GuardedValue<'_>> {
        self.system().domain(x)
    }

    fn dependent_rows(&self, x: &[f64; D]) -> Vec<String> {
        self.system().dependent_rows(x)
    }

    fn chart(&self) -> Option<usize> {
        self.system().chart()
    }

    fn change_chart(&self, x: &mut [f64; D]) -> bool {
        self.system().change_chart(x)
    }

    fn change_to_pivoted_chart(&self, x: &mut [f64; D]) -> bool {
        self.system().change_to_pivoted_chart(x)
    }
}
