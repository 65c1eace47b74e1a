//! A model read from its text at sizes fixed at compile time: [`Fixed`]
//! implements the runtime's formulation traits (`ReducedPortHamiltonian`
//! with its charts, `LagrangeDalembert`, `Linearization`, `Holonomic`,
//! `Momenta`, `MomentumEquations`, `ModelNames`, `Domain`) over an
//! [`InterpretedModel`], whatever engine runs its programs, so that the
//! runtime's systems (`Reduced`, `Dalembert`, `Momentum`, the projection,
//! the interconnection with a controller) and `Simulation` run on it as on
//! a generated struct.
//!
//! The sizes are checked once, by [`Fixed::new`]; the reduced state's
//! `S = 2 N - C` and the momenta's `K = N - C` are checked where the
//! traits are instantiated (a mismatch does not compile). With the sizes
//! right, a call fails only for an item the model does not derive (the
//! momentum equation of a model without a symmetry): its values are NaN,
//! which a run reports as a non-finite state.
//!
//! The reduced form's items in chart 0 and the compiled charts, the
//! output, the mass and constraint matrices, the energy, the constraint
//! residual, the holonomic residual and Jacobian and the momentum items
//! that return one array are evaluated into the array they return
//! ([`InterpretedModel::call_in_chart_into`], the inputs gathered in a
//! buffer of the calling thread): after the first calls have grown it,
//! they allocate nothing on the JIT, as a generated struct's. The
//! interpreter keeps its values in such a buffer too. What is computed from
//! several items (`acceleration` with its multipliers, the linearization's
//! Jacobians, the regularity measures, the run-time charts, a change of
//! chart) still returns vectors, and allocates.

use super::{CallError, InterpretedModel};
use chaplygin_runtime::arrays::leading;
use chaplygin_runtime::linearize::{AccelerationJacobian, GroupFactor, Linearization};
use chaplygin_runtime::monitor::constraint_regularity;
use chaplygin_runtime::system::{
    Domain, Guard, Holonomic, LagrangeDalembert, ModelNames, Momenta, MomentumEquations,
    ReducedPortHamiltonian,
};

/// A size of [`Fixed`] that differs from the model's.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the model has {model} {what}, the fixed sizes say {fixed}")]
pub struct SizeMismatch {
    /// Which size (`coordinates`, `constraint rows`, `inputs`,
    /// `configuration constraints`, `shape coordinates`, `momenta of the
    /// momentum equation`).
    pub what: &'static str,
    /// The model's.
    pub model: usize,
    /// The one asked for.
    pub fixed: usize,
}

/// An [`InterpretedModel`] with `N` coordinates, `C` constraint rows, `P`
/// inputs and `H` configuration constraints, and, where it derives the
/// momentum equation, `R` shape coordinates and `MP` momenta (0 and 0
/// where it does not), seen through the runtime's traits.
///
/// ```
/// use chaplygin_codegen::interpret::{Fixed, InterpretedModel};
/// use chaplygin_runtime::integrate::DiscreteGradient;
/// use chaplygin_runtime::law::Feedback;
/// use chaplygin_runtime::record::Table;
/// use chaplygin_runtime::simulate::Simulation;
/// use chaplygin_runtime::system::Reduced;
///
/// let sleigh = InterpretedModel::from_source(
///     "pub struct Sleigh {
///          coordinates: [x, y, theta],
///          parameters: [m = 1.0, inertia = 0.1, a = 0.5],
///          kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
///              + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
///          constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
///      }",
/// )
/// .expect("the model derives");
/// let sleigh = Fixed::<3, 1, 0, 0>::new(&sleigh).expect("the sizes match");
/// let system = Reduced::new(&sleigh, Feedback(|_t, _x: &[f64; 5]| []));
/// let x0 = system.initial_state::<3, 2, 5>(&[0.0, 0.0, 0.3], &[1.0, 0.3, 0.5]);
/// let summary = Simulation::new(DiscreteGradient::default())
///     .span(0.0, 5.0)
///     .step(0.01)
///     .run(&system, x0, &mut Table::new())
///     .expect("the sleigh runs");
/// assert!(summary.energy_drift < 1e-12);
/// ```
pub struct Fixed<
    'a,
    const N: usize,
    const C: usize,
    const P: usize,
    const H: usize,
    const R: usize = 0,
    const MP: usize = 0,
> {
    model: &'a InterpretedModel,
    coordinates: Vec<&'a str>,
    momenta: Vec<&'a str>,
    inputs: Vec<&'a str>,
    constraints: Vec<&'a str>,
    holonomic: [&'a str; H],
    guards: Vec<(&'a str, Guard)>,
    basis_divisors: Vec<&'a str>,
    shape: [usize; R],
}

/// `names` as borrowed strings.
fn borrowed(names: &[String]) -> Vec<&str> {
    names.iter().map(String::as_str).collect()
}

/// `Err` unless `model == fixed`.
fn same(what: &'static str, model: usize, fixed: usize) -> Result<(), SizeMismatch> {
    match model == fixed {
        true => Ok(()),
        false => Err(SizeMismatch { what, model, fixed }),
    }
}

impl<
    'a,
    const N: usize,
    const C: usize,
    const P: usize,
    const H: usize,
    const R: usize,
    const MP: usize,
> Fixed<'a, N, C, P, H, R, MP>
{
    /// `model` at these sizes.
    ///
    /// # Errors
    /// The first size that differs from the model's.
    pub fn new(model: &'a InterpretedModel) -> Result<Self, SizeMismatch> {
        let (sizes, names) = (model.sizes(), model.names());
        same("coordinates", sizes.n, N)?;
        same("constraint rows", sizes.c, C)?;
        same("inputs", sizes.p, P)?;
        same("configuration constraints", names.holonomic.len(), H)?;
        let (shape, momentum_size) = match model.arguments("momentum_rhs") {
            Some(_) => {
                let shape = model.shape().unwrap_or_default();
                let momentum_size = N.saturating_sub(shape.len() + C);
                (shape, momentum_size)
            }
            None => (Vec::new(), 0),
        };
        same("shape coordinates", shape.len(), R)?;
        same("momenta of the momentum equation", momentum_size, MP)?;
        Ok(Self {
            model,
            coordinates: borrowed(&names.coordinates),
            momenta: borrowed(&names.momenta),
            inputs: borrowed(&names.inputs),
            constraints: borrowed(&names.constraints),
            holonomic: core::array::from_fn(|i| names.holonomic[i].as_str()),
            guards: model
                .guards
                .iter()
                .map(|(description, guard)| (description.as_str(), *guard))
                .collect(),
            basis_divisors: borrowed(&model.basis_divisors),
            shape: core::array::from_fn(|i| shape[i]),
        })
    }

    /// The model.
    pub fn model(&self) -> &'a InterpretedModel {
        self.model
    }
}

/// The `L` values of a call, NaN where it fails (see the module
/// documentation).
fn vector<const L: usize>(values: Result<Vec<f64>, CallError>) -> [f64; L] {
    let values = values.unwrap_or_default();
    core::array::from_fn(|i| values.get(i).copied().unwrap_or(f64::NAN))
}

/// The `ROWS x COLUMNS` row-major values of a call, NaN where it fails.
fn matrix<const ROWS: usize, const COLUMNS: usize>(
    values: Result<Vec<f64>, CallError>,
) -> [[f64; COLUMNS]; ROWS] {
    let values = values.unwrap_or_default();
    core::array::from_fn(|i| {
        core::array::from_fn(|j| values.get(i * COLUMNS + j).copied().unwrap_or(f64::NAN))
    })
}

/// A scalar call's value, NaN where it fails.
fn scalar(value: Result<f64, CallError>) -> f64 {
    value.unwrap_or(f64::NAN)
}

impl<
    const N: usize,
    const C: usize,
    const P: usize,
    const H: usize,
    const R: usize,
    const MP: usize,
> Fixed<'_, N, C, P, H, R, MP>
{
    /// The `L` values of the item `name` in `chart`, evaluated into the
    /// array ([`InterpretedModel::call_in_chart_into`]); NaN where the call
    /// fails.
    fn vector_in<const L: usize>(
        &self,
        chart: usize,
        name: &str,
        arguments: &[&[f64]],
    ) -> [f64; L] {
        let mut values = [0.0; L];
        match self
            .model
            .call_in_chart_into(chart, name, arguments, &mut values)
        {
            Ok(()) => values,
            Err(_) => [f64::NAN; L],
        }
    }

    /// The `ROWS x COLUMNS` row-major values of the item `name` in
    /// `chart`, evaluated into the array; NaN where the call fails.
    fn matrix_in<const ROWS: usize, const COLUMNS: usize>(
        &self,
        chart: usize,
        name: &str,
        arguments: &[&[f64]],
    ) -> [[f64; COLUMNS]; ROWS] {
        let mut values = [[0.0; COLUMNS]; ROWS];
        let into = values.as_flattened_mut();
        match self.model.call_in_chart_into(chart, name, arguments, into) {
            Ok(()) => values,
            Err(_) => [[f64::NAN; COLUMNS]; ROWS],
        }
    }

    /// `(q, qdot)` of the state `x = (q, alpha)` in `chart`.
    fn configuration_velocity(&self, chart: usize, x: &[f64]) -> ([f64; N], [f64; N]) {
        let (q, alpha) = x.split_at(N);
        let qdot = self.vector_in(chart, "velocities", &[q, alpha]);
        (leading(q), qdot)
    }

    /// The largest `|A(q) qdot|` of the state `x` in `chart`.
    fn violation(&self, chart: usize, x: &[f64]) -> f64 {
        let (q, qdot) = self.configuration_velocity(chart, x);
        let residual: [f64; C] = LagrangeDalembert::constraint_residual(self, &q, &qdot);
        residual
            .iter()
            .fold(0.0, |worst: f64, r| worst.max(r.abs()))
    }
}

impl<
    const N: usize,
    const C: usize,
    const P: usize,
    const H: usize,
    const R: usize,
    const MP: usize,
    const S: usize,
> ReducedPortHamiltonian<S, P> for Fixed<'_, N, C, P, H, R, MP>
{
    fn reduced_rhs(&self, x: &[f64; S], u: &[f64; P]) -> [f64; S] {
        self.chart_rhs(0, x, u)
    }

    fn reduced_rhs_jacobian(&self, x: &[f64; S], u: &[f64; P]) -> [[f64; S]; S] {
        self.chart_rhs_jacobian(0, x, u)
    }

    fn hamiltonian(&self, x: &[f64; S]) -> f64 {
        self.chart_hamiltonian(0, x)
    }

    fn hamiltonian_gradient(&self, x: &[f64; S]) -> [f64; S] {
        self.chart_hamiltonian_gradient(0, x)
    }

    fn structure_matrix(&self, x: &[f64; S]) -> [[f64; S]; S] {
        self.chart_structure_matrix(0, x)
    }

    fn input_matrix(&self, x: &[f64; S]) -> [[f64; P]; S] {
        self.chart_input_matrix(0, x)
    }

    fn output(&self, x: &[f64; S]) -> [f64; P] {
        self.vector_in(0, "output", &[x])
    }

    fn output_jacobian(&self, x: &[f64; S]) -> [[f64; S]; P] {
        self.matrix_in(0, "output_jacobian", &[x])
    }

    fn constraint_violation(&self, x: &[f64; S]) -> f64 {
        self.violation(0, x)
    }

    fn regularity(&self, x: &[f64; S]) -> f64 {
        self.chart_regularity(0, x)
    }

    fn charts(&self) -> usize {
        const { assert!(S + C == 2 * N, "the reduced state has S = 2 N - C entries") };
        self.model.charts().len()
    }

    fn chart_fit(&self, chart: usize, x: &[f64; S]) -> f64 {
        self.model.chart_fit(chart, &x[..N]).unwrap_or(0.0)
    }

    fn pivoted_chart(&self, x: &[f64; S]) -> Option<usize> {
        self.model.pivoted_chart(&x[..N])
    }

    /// With constraint rows, the run-time charts as well as those derived
    /// at build time.
    fn switches_charts(&self) -> bool {
        C > 0
    }

    fn change_chart(&self, from: usize, to: usize, x: &[f64; S]) -> [f64; S] {
        let (q, qdot) = self.configuration_velocity(from, x);
        let alpha = self.model.call_in_chart(to, "momenta", &[&q, &qdot]);
        let alpha = alpha.unwrap_or_default();
        core::array::from_fn(|i| match i < N {
            true => q[i],
            false => alpha.get(i - N).copied().unwrap_or(f64::NAN),
        })
    }

    fn chart_rhs(&self, chart: usize, x: &[f64; S], u: &[f64; P]) -> [f64; S] {
        self.vector_in(chart, "reduced_rhs", &[x, u])
    }

    fn chart_rhs_jacobian(&self, chart: usize, x: &[f64; S], u: &[f64; P]) -> [[f64; S]; S] {
        self.matrix_in(chart, "reduced_rhs_jacobian", &[x, u])
    }

    fn chart_hamiltonian(&self, chart: usize, x: &[f64; S]) -> f64 {
        self.vector_in::<1>(chart, "hamiltonian", &[x])[0]
    }

    fn chart_hamiltonian_gradient(&self, chart: usize, x: &[f64; S]) -> [f64; S] {
        self.vector_in(chart, "hamiltonian_gradient", &[x])
    }

    fn chart_structure_matrix(&self, chart: usize, x: &[f64; S]) -> [[f64; S]; S] {
        self.matrix_in(chart, "structure_matrix", &[x])
    }

    fn chart_input_matrix(&self, chart: usize, x: &[f64; S]) -> [[f64; P]; S] {
        self.matrix_in(chart, "input_matrix", &[x])
    }

    fn chart_constraint_violation(&self, chart: usize, x: &[f64; S]) -> f64 {
        self.violation(chart, x)
    }

    fn chart_regularity(&self, chart: usize, x: &[f64; S]) -> f64 {
        scalar(self.model.chart_regularity(chart, &x[..N]))
    }
}

impl<
    const N: usize,
    const C: usize,
    const P: usize,
    const H: usize,
    const R: usize,
    const MP: usize,
> LagrangeDalembert<N, C, P> for Fixed<'_, N, C, P, H, R, MP>
{
    fn acceleration(&self, q: &[f64; N], qdot: &[f64; N], u: &[f64; P]) -> ([f64; N], [f64; C]) {
        match self.model.acceleration(q, qdot, u) {
            Ok((qddot, lambda)) => (vector(Ok(qddot)), vector(Ok(lambda))),
            Err(error) => (vector(Err(error.clone())), vector(Err(error))),
        }
    }

    fn energy(&self, q: &[f64; N], qdot: &[f64; N]) -> f64 {
        self.vector_in::<1>(0, "energy", &[q, qdot])[0]
    }

    fn constraint_residual(&self, q: &[f64; N], qdot: &[f64; N]) -> [f64; C] {
        self.vector_in(0, "constraint_residual", &[q, qdot])
    }

    fn constraint_regularity(&self, q: &[f64; N]) -> f64 {
        constraint_regularity(
            &Linearization::<N, C, P>::mass_matrix(self, q),
            &Linearization::<N, C, P>::constraint_matrix(self, q),
        )
    }
}

impl<
    const N: usize,
    const C: usize,
    const P: usize,
    const H: usize,
    const R: usize,
    const MP: usize,
> Linearization<N, C, P> for Fixed<'_, N, C, P, H, R, MP>
{
    fn symmetry(&self) -> &[GroupFactor] {
        self.model.symmetry()
    }

    fn mass_matrix(&self, q: &[f64; N]) -> [[f64; N]; N] {
        self.matrix_in(0, "mass_matrix", &[q])
    }

    fn constraint_matrix(&self, q: &[f64; N]) -> [[f64; N]; C] {
        self.matrix_in(0, "constraint_matrix", &[q])
    }

    fn acceleration_jacobian(
        &self,
        q: &[f64; N],
        qdot: &[f64; N],
        u: &[f64; P],
    ) -> AccelerationJacobian<N, P> {
        match self.model.acceleration_jacobian(q, qdot, u) {
            Ok((by_q, by_qdot, by_u)) => (matrix(Ok(by_q)), matrix(Ok(by_qdot)), matrix(Ok(by_u))),
            Err(error) => (
                matrix(Err(error.clone())),
                matrix(Err(error.clone())),
                matrix(Err(error)),
            ),
        }
    }
}

impl<
    const N: usize,
    const C: usize,
    const P: usize,
    const H: usize,
    const R: usize,
    const MP: usize,
> Holonomic<N, H> for Fixed<'_, N, C, P, H, R, MP>
{
    fn holonomic_names(&self) -> [&str; H] {
        self.holonomic
    }

    fn holonomic_residual(&self, q: &[f64; N]) -> [f64; H] {
        self.vector_in(0, "holonomic_residual", &[q])
    }

    fn holonomic_jacobian(&self, q: &[f64; N]) -> [[f64; N]; H] {
        self.matrix_in(0, "holonomic_jacobian", &[q])
    }
}

impl<
    const N: usize,
    const C: usize,
    const P: usize,
    const H: usize,
    const R: usize,
    const MP: usize,
    const K: usize,
> Momenta<N, K> for Fixed<'_, N, C, P, H, R, MP>
{
    fn momenta(&self, q: &[f64; N], qdot: &[f64; N]) -> [f64; K] {
        self.chart_momenta(0, q, qdot)
    }

    fn velocities(&self, q: &[f64; N], alpha: &[f64; K]) -> [f64; N] {
        self.chart_velocities(0, q, alpha)
    }

    fn chart_momenta(&self, chart: usize, q: &[f64; N], qdot: &[f64; N]) -> [f64; K] {
        const { assert!(K + C == N, "the reduced momenta are K = N - C") };
        self.vector_in(chart, "momenta", &[q, qdot])
    }

    fn chart_velocities(&self, chart: usize, q: &[f64; N], alpha: &[f64; K]) -> [f64; N] {
        self.vector_in(chart, "velocities", &[q, alpha])
    }
}

impl<
    const N: usize,
    const C: usize,
    const P: usize,
    const H: usize,
    const R: usize,
    const MP: usize,
> MomentumEquations<N, R, MP, P> for Fixed<'_, N, C, P, H, R, MP>
{
    fn shape_indices(&self) -> [usize; R] {
        self.shape
    }

    fn momentum(&self, q: &[f64; N], qdot: &[f64; N]) -> [f64; MP] {
        self.vector_in(0, "momentum", &[q, qdot])
    }

    fn momentum_rhs(&self, r: &[f64; R], rdot: &[f64; R], p: &[f64; MP]) -> [f64; MP] {
        self.vector_in(0, "momentum_rhs", &[r, rdot, p])
    }

    fn momentum_input_matrix(&self, q: &[f64; N]) -> [[f64; P]; MP] {
        self.matrix_in(0, "momentum_input_matrix", &[q])
    }

    fn shape_acceleration(
        &self,
        r: &[f64; R],
        rdot: &[f64; R],
        p: &[f64; MP],
        u: &[f64; P],
    ) -> [f64; R] {
        vector(self.model.shape_acceleration(r, rdot, p, u))
    }

    fn reconstructed_velocity(&self, q: &[f64; N], rdot: &[f64; R], p: &[f64; MP]) -> [f64; N] {
        vector(self.model.reconstructed_velocity(q, rdot, p))
    }

    fn basis_divisor_names(&self) -> &[&str] {
        &self.basis_divisors
    }

    fn basis_divisors(&self, values: &mut [f64]) {
        let found = self.model.call("basis_divisors", &[]).unwrap_or_default();
        values.fill(f64::NAN);
        values
            .iter_mut()
            .zip(found)
            .for_each(|(value, found)| *value = found);
    }
}

impl<
    const N: usize,
    const C: usize,
    const P: usize,
    const H: usize,
    const R: usize,
    const MP: usize,
> ModelNames for Fixed<'_, N, C, P, H, R, MP>
{
    fn coordinate_names(&self) -> &[&str] {
        &self.coordinates
    }

    fn momentum_names(&self) -> &[&str] {
        &self.momenta
    }

    fn input_names(&self) -> &[&str] {
        &self.inputs
    }

    fn constraint_names(&self) -> &[&str] {
        &self.constraints
    }
}

impl<
    const N: usize,
    const C: usize,
    const P: usize,
    const H: usize,
    const R: usize,
    const MP: usize,
> Domain for Fixed<'_, N, C, P, H, R, MP>
{
    fn guards(&self) -> &[(&str, Guard)] {
        &self.guards
    }

    fn domain(&self, q: &[f64], values: &mut [f64]) {
        let found = self.model.call("domain", &[q]).unwrap_or_default();
        values.fill(f64::NAN);
        values
            .iter_mut()
            .zip(found)
            .for_each(|(value, found)| *value = found);
    }

    fn constraint_rows(&self, q: &[f64], rows: &mut [f64]) -> bool {
        match self.model.constraint_matrix(q) {
            Ok(found) if found.len() == rows.len() => {
                rows.copy_from_slice(&found);
                true
            }
            _ => false,
        }
    }
}
