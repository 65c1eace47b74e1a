//! A model from its text simulated without recompiling: its emitted
//! functions' programs (`chaplygin_codegen::interpret`) run on the engine
//! it was loaded on (native code from the JIT, or the IR interpreter), in the
//! reduced, the Lagrange-d'Alembert or (with a symmetry) the momentum
//! formulation, with inputs given as functions of the time, the
//! configuration and its velocity ([`InputLaw`]).
//!
//! Both engines run the same straight-line programs the compiled code is
//! emitted from, so a `.model` file and the compiled model agree to
//! round-off.

mod surface;

use super::formulation::Formulation;
use crate::driver::Failure;
use crate::runtime::monitor::{gram_regularity, hadamard_ratio};
use crate::runtime::nalgebra::DMatrix;
use crate::runtime::projection::ProjectionError;
use crate::runtime::simulate::{GuardedValue, Regularity, SliceSystem};
use crate::runtime::system::next_chart;
use chaplygin_codegen::derive::MOMENTUM_WITH_HOLONOMIC;
pub(crate) use chaplygin_codegen::interpret::evaluated;
use chaplygin_codegen::interpret::{CallError, InterpretedModel};
use std::cell::Cell;
pub(crate) use surface::holonomic_residual;
use surface::{keeps_configuration, onto_surface};

/// `(q, alpha)` or `(q, qdot)` split at `n`.
fn split(x: &[f64], n: usize) -> (&[f64], &[f64]) {
    x.split_at(n)
}

/// `E(q, 0)` at the configuration `q` that leads the state `x`.
fn energy_at_rest(model: &InterpretedModel, x: &[f64]) -> f64 {
    let n = model.sizes().n;
    evaluated(model.energy(&x[..n], &vec![0.0; n]))
}

/// `u(t, q, qdot)`, written into a slice of the model's inputs.
pub type Law = Box<dyn Fn(f64, &[f64], &[f64], &mut [f64])>;

/// The inputs `u(t, q, qdot)` of the time, the configuration and its
/// velocity, as each formulation reads them off its state
/// ([`SliceSystem::configuration_velocity`]).
pub struct InputLaw {
    /// The law.
    pub law: Law,
    /// Whether the law reads `q` and `qdot`: else they are not computed
    /// (and given empty).
    pub reads_state: bool,
}

impl InputLaw {
    /// The inputs at `t` and the state `x` of `formulation`, written into
    /// `u`.
    fn apply(&self, formulation: &dyn Formulation, n: usize, t: f64, x: &[f64], u: &mut [f64]) {
        if self.reads_state {
            let (mut q, mut qdot) = (vec![0.0; n], vec![0.0; n]);
            formulation.configuration_velocity(x, &mut q, &mut qdot);
            (self.law)(t, &q, &qdot, u);
        } else {
            (self.law)(t, &[], &[], u);
        }
    }
}

/// The momentum formulation cannot represent an initial velocity.
#[derive(Debug, thiserror::Error)]
pub enum Unrepresentable {
    /// The velocity reconstructed from its momenta differs.
    #[error(
        "the momentum formulation cannot represent this initial velocity: dot({coordinate}) \
         reconstructed from the momenta is off by {error:e} (the momentum basis degenerates at \
         this shape; see `chaplygin derive`)"
    )]
    Reconstruction {
        /// The coordinate whose velocity is worst reconstructed.
        coordinate: String,
        /// By how much.
        error: f64,
    },
    /// The parameters make the momentum basis degenerate at every
    /// configuration.
    #[error(
        "the momentum formulation's basis degenerates at every configuration for these \
         parameters: {expression} (it is {value:e}); use --formulation reduced or lagrange"
    )]
    Parameters {
        /// The divisor that vanishes, described.
        expression: String,
        /// Its value.
        value: f64,
    },
}

/// The reduced form `x = (q, alpha)` of an interpreted model, in its
/// active chart of D (chart 0 at the start; see `Formulation::change_chart`).
pub struct InterpretedReduced {
    /// The model.
    pub model: InterpretedModel,
    /// The inputs, read in the active chart.
    pub inputs: InputLaw,
    chart: Cell<usize>,
}

impl InterpretedReduced {
    /// `model` driven by `inputs`, in chart 0.
    pub fn new(model: InterpretedModel, inputs: InputLaw) -> Self {
        Self {
            model,
            inputs,
            chart: Cell::new(0),
        }
    }

    /// The state `(q, alpha)` of `q` moving with `qdot`, in the chart that
    /// fits best at `q`, which becomes the active chart.
    pub fn initial_state(&self, q: &[f64], qdot: &[f64]) -> Result<Vec<f64>, CallError> {
        let model = &self.model;
        let fit = |chart| model.chart_fit(chart, q).unwrap_or(0.0);
        let best = (0..model.charts().len())
            .max_by(|&a, &b| fit(a).total_cmp(&fit(b)))
            .unwrap_or(0);
        let pivoted = model.pivoted_chart(q);
        let best = next_chart(model.charts().len(), best, fit, pivoted).unwrap_or(best);
        self.chart.set(best);
        let alpha = self.model.call_in_chart(best, "momenta", &[q, qdot])?;
        Ok(q.iter().chain(&alpha).copied().collect())
    }

    /// Moves `x` into `chart` through its velocity, and makes it active.
    fn move_to(&self, chart: usize, x: &mut [f64]) {
        let n = self.model.sizes().n;
        let (q, alpha) = split(x, n);
        let qdot = self.call("velocities", &[q, alpha]);
        let moved = evaluated(self.model.call_in_chart(chart, "momenta", &[q, &qdot]));
        x[n..].copy_from_slice(&moved);
        self.chart.set(chart);
    }

    /// The reduced item `name` in the active chart.
    fn call(&self, name: &str, arguments: &[&[f64]]) -> Vec<f64> {
        evaluated(self.model.call_in_chart(self.chart.get(), name, arguments))
    }
}

/// The Lagrange-d'Alembert form `x = (q, qdot)` of an interpreted model.
pub struct InterpretedDalembert {
    /// The model.
    pub model: InterpretedModel,
    /// The inputs.
    pub inputs: InputLaw,
}

/// The inputs `formulation` of `model` applies at `(t, x)`, as many as the
/// model has.
fn inputs_at(
    formulation: &dyn Formulation,
    model: &InterpretedModel,
    t: f64,
    x: &[f64],
) -> Vec<f64> {
    let mut u = vec![0.0; model.sizes().p];
    formulation.inputs(t, x, &mut u);
    u
}

/// The power `u . B(q)^T qdot` the inputs of `formulation` deliver at
/// `(t, x)`: with `w = qddot(u) - qddot(0)` of the Lagrange-d'Alembert
/// accelerations, the polarization `E(q, qdot + w) - E(q, qdot) - E(q, w)
/// + E(q, 0) = qdot^T g w` of the energy, as
/// `chaplygin_runtime::simulate::Observed::input_power` takes it.
fn input_power_of(
    formulation: &dyn Formulation,
    model: &InterpretedModel,
    t: f64,
    x: &[f64],
) -> f64 {
    let n = model.sizes().n;
    let (mut q, mut qdot) = (vec![0.0; n], vec![0.0; n]);
    formulation.configuration_velocity(x, &mut q, &mut qdot);
    let u = inputs_at(formulation, model, t, x);
    let (forced, _) = evaluated(model.acceleration(&q, &qdot, &u));
    let (free, _) = evaluated(model.acceleration(&q, &qdot, &vec![0.0; u.len()]));
    let w: Vec<f64> = forced.iter().zip(&free).map(|(a, b)| a - b).collect();
    let moved: Vec<f64> = qdot.iter().zip(&w).map(|(v, w)| v + w).collect();
    let energy = |velocity: &[f64]| evaluated(model.energy(&q, velocity));
    energy(&moved) - energy(&qdot) - energy(&w) + energy(&vec![0.0; n])
}

/// The largest `|A(q) qdot|`.
fn residual(model: &InterpretedModel, q: &[f64], qdot: &[f64]) -> f64 {
    evaluated(model.constraint_residual(q, qdot))
        .iter()
        .fold(0.0, |worst, r| worst.max(r.abs()))
}

/// The Hadamard ratio of `A g^-1 A^T` at `q`.
fn multiplier_regularity(model: &InterpretedModel, q: &[f64]) -> Regularity {
    let sizes = model.sizes();
    let (g, a) = (
        evaluated(model.mass_matrix(q)),
        evaluated(model.constraint_matrix(q)),
    );
    let (g, a) = (
        DMatrix::from_row_slice(sizes.n, sizes.n, &g),
        DMatrix::from_row_slice(sizes.c, sizes.n, &a),
    );
    Regularity {
        quantity: crate::runtime::simulate::MULTIPLIERS,
        value: gram_regularity(g, &a),
        signed: false,
    }
}

impl SliceSystem for InterpretedReduced {
    fn state_names(&self) -> Vec<String> {
        let names = self.model.names();
        names
            .coordinates
            .iter()
            .chain(&names.momenta)
            .cloned()
            .collect()
    }

    fn input_names(&self) -> Vec<String> {
        self.model.names().inputs.clone()
    }

    fn rhs(&self, t: f64, x: &[f64], xdot: &mut [f64]) {
        let u = inputs_at(self, &self.model, t, x);
        xdot.copy_from_slice(&self.call("reduced_rhs", &[x, &u]));
    }

    /// The model's exact Jacobian at fixed `u`, and a feedback's
    /// `B(x) du/dx`, `du/dx` by central differences, as the compiled
    /// reduced form's.
    fn jacobian(&self, t: f64, x: &[f64], jacobian: &mut [f64]) {
        let u = inputs_at(self, &self.model, t, x);
        jacobian.copy_from_slice(&self.call("reduced_rhs_jacobian", &[x, &u]));
        if self.inputs.reads_state {
            let b = self.call("input_matrix", &[x]);
            add_feedback(self, (t, x), &b, jacobian);
        }
    }

    fn energy(&self, x: &[f64]) -> f64 {
        self.call("hamiltonian", &[x])[0]
    }

    /// `H(q, 0)`: the momenta of a velocity zero are zero.
    fn energy_at_rest(&self, x: &[f64]) -> f64 {
        let n = self.model.sizes().n;
        let rest: Vec<f64> = (0..x.len())
            .map(|i| if i < n { x[i] } else { 0.0 })
            .collect();
        self.energy(&rest)
    }

    fn is_structured(&self) -> bool {
        true
    }

    fn structure_matrix(&self, x: &[f64], j: &mut [f64]) {
        j.copy_from_slice(&self.call("structure_matrix", &[x]));
    }

    fn energy_gradient(&self, x: &[f64], gradient: &mut [f64]) {
        gradient.copy_from_slice(&self.call("hamiltonian_gradient", &[x]));
    }

    /// `F = G(x) u`.
    fn forcing(&self, t: f64, x: &[f64], forcing: &mut [f64]) {
        let b = self.call("input_matrix", &[x]);
        let u = inputs_at(self, &self.model, t, x);
        let p = u.len();
        for (i, f) in forcing.iter_mut().enumerate() {
            *f = (0..p).map(|l| b[i * p + l] * u[l]).sum();
        }
    }

    fn inputs(&self, t: f64, x: &[f64], inputs: &mut [f64]) {
        self.inputs.apply(self, self.model.sizes().n, t, x, inputs);
    }

    fn input_power(&self, t: f64, x: &[f64]) -> f64 {
        input_power_of(self, &self.model, t, x)
    }

    /// `qdot = velocities(q, alpha)` in the active chart.
    fn configuration_velocity(&self, x: &[f64], q: &mut [f64], qdot: &mut [f64]) {
        let (configuration, alpha) = split(x, self.model.sizes().n);
        q.copy_from_slice(configuration);
        qdot.copy_from_slice(&self.call("velocities", &[configuration, alpha]));
    }

    fn constraint_residual(&self, x: &[f64]) -> f64 {
        let (q, alpha) = split(x, self.model.sizes().n);
        residual(&self.model, q, &self.call("velocities", &[q, alpha]))
    }

    /// `det[A; V^T]` over its rows' norms, as the compiled models' `regularity`.
    fn regularity(&self, x: &[f64]) -> Regularity {
        let q = &x[..self.model.sizes().n];
        Regularity {
            quantity: crate::runtime::simulate::REDUCED,
            value: evaluated(self.model.chart_regularity(self.chart.get(), q)),
            signed: true,
        }
    }

    /// With configuration constraints, `(q, qdot = velocities(q, alpha))`
    /// kept on them (`onto_surface`) and `alpha = momenta(q, qdot)` of
    /// the result, both in the active chart; without, the state cannot
    /// leave the constraints.
    fn project(&self, x: &mut [f64]) -> Result<(), ProjectionError> {
        if !keeps_configuration(&self.model) {
            return Ok(());
        }
        let (q, alpha) = x.split_at_mut(self.model.sizes().n);
        let chart = self.chart.get();
        let mut qdot = evaluated(self.model.call_in_chart(chart, "velocities", &[q, alpha]));
        onto_surface(&self.model, q, &mut qdot)?;
        alpha.copy_from_slice(&evaluated(self.model.call_in_chart(
            chart,
            "momenta",
            &[q, &qdot],
        )));
        Ok(())
    }

    fn domain(&self, x: &[f64]) -> Vec<GuardedValue<'_>> {
        evaluated(self.model.domain(&x[..self.model.sizes().n]))
    }

    fn dependent_rows(&self, x: &[f64]) -> Vec<String> {
        evaluated(self.model.dependent_rows(&x[..self.model.sizes().n]))
    }

    fn holonomic_residual(&self, x: &[f64]) -> Option<f64> {
        holonomic_residual(&self.model, &x[..self.model.sizes().n])
    }

    fn chart(&self) -> Option<usize> {
        (self.model.sizes().c > 0).then(|| self.chart.get())
    }

    /// As the compiled reduced form's (`Observed::change_chart`): the state
    /// moves into the next chart through its velocity.
    fn change_chart(&self, x: &mut [f64]) -> bool {
        let (model, active) = (&self.model, self.chart.get());
        let n = model.sizes().n;
        let fit = |chart| evaluated(model.chart_fit(chart, &x[..n]));
        let pivoted = model.pivoted_chart(&x[..n]);
        let Some(next) = next_chart(model.charts().len(), active, fit, pivoted) else {
            return false;
        };
        self.move_to(next, x);
        true
    }

    /// As the compiled reduced form's (`Observed::change_to_pivoted_chart`).
    fn change_to_pivoted_chart(&self, x: &mut [f64]) -> bool {
        let n = self.model.sizes().n;
        match self.model.pivoted_chart(&x[..n]) {
            Some(pivoted) if pivoted != self.chart.get() => {
                self.move_to(pivoted, x);
                true
            }
            _ => false,
        }
    }
}

impl Formulation for InterpretedReduced {
    fn engine(&self) -> &'static str {
        self.model.engine().name()
    }

    fn state_of(&self, q: &[f64], qdot: &[f64]) -> Result<Vec<f64>, Failure> {
        Ok(self.initial_state(q, qdot)?)
    }
}

impl SliceSystem for InterpretedDalembert {
    fn state_names(&self) -> Vec<String> {
        let coordinates = &self.model.names().coordinates;
        let velocities = coordinates.iter().map(|q| format!("dot({q})"));
        coordinates.iter().cloned().chain(velocities).collect()
    }

    fn input_names(&self) -> Vec<String> {
        self.model.names().inputs.clone()
    }

    fn rhs(&self, t: f64, x: &[f64], xdot: &mut [f64]) {
        let (q, qdot) = split(x, self.model.sizes().n);
        let u = inputs_at(self, &self.model, t, x);
        let (qddot, _) = evaluated(self.model.acceleration(q, qdot, &u));
        xdot[..q.len()].copy_from_slice(qdot);
        xdot[q.len()..].copy_from_slice(&qddot);
    }

    /// The model's exact Jacobian at fixed `u`
    /// ([`lagrange_rhs_jacobian`]), and a feedback's `(df/du) du/dx`.
    fn jacobian(&self, t: f64, x: &[f64], jacobian: &mut [f64]) {
        let u = inputs_at(self, &self.model, t, x);
        let (by_x, by_u) = lagrange_rhs_jacobian(&self.model, x, &u);
        jacobian.copy_from_slice(&by_x);
        if self.inputs.reads_state {
            add_feedback(self, (t, x), &by_u, jacobian);
        }
    }

    fn energy(&self, x: &[f64]) -> f64 {
        let (q, qdot) = split(x, self.model.sizes().n);
        evaluated(self.model.energy(q, qdot))
    }

    fn energy_at_rest(&self, x: &[f64]) -> f64 {
        energy_at_rest(&self.model, x)
    }

    fn inputs(&self, t: f64, x: &[f64], inputs: &mut [f64]) {
        self.inputs.apply(self, self.model.sizes().n, t, x, inputs);
    }

    fn input_power(&self, t: f64, x: &[f64]) -> f64 {
        input_power_of(self, &self.model, t, x)
    }

    fn configuration_velocity(&self, x: &[f64], q: &mut [f64], qdot: &mut [f64]) {
        let (configuration, velocity) = split(x, self.model.sizes().n);
        q.copy_from_slice(configuration);
        qdot.copy_from_slice(velocity);
    }

    fn constraint_residual(&self, x: &[f64]) -> f64 {
        let (q, qdot) = split(x, self.model.sizes().n);
        residual(&self.model, q, qdot)
    }

    /// The Hadamard ratio of `A g^-1 A^T`, as the compiled models'
    /// `constraint_regularity`.
    fn regularity(&self, x: &[f64]) -> Regularity {
        multiplier_regularity(&self.model, &x[..self.model.sizes().n])
    }

    /// The configuration onto `f(q) = 0`, with configuration constraints,
    /// and the velocity onto `ker A(q)` in the metric `g(q)`
    /// (`onto_surface`).
    fn project(&self, x: &mut [f64]) -> Result<(), ProjectionError> {
        let (q, qdot) = x.split_at_mut(self.model.sizes().n);
        onto_surface(&self.model, q, qdot)
    }

    fn domain(&self, x: &[f64]) -> Vec<GuardedValue<'_>> {
        evaluated(self.model.domain(&x[..self.model.sizes().n]))
    }

    fn dependent_rows(&self, x: &[f64]) -> Vec<String> {
        evaluated(self.model.dependent_rows(&x[..self.model.sizes().n]))
    }

    fn holonomic_residual(&self, x: &[f64]) -> Option<f64> {
        holonomic_residual(&self.model, &x[..self.model.sizes().n])
    }
}

impl Formulation for InterpretedDalembert {
    fn engine(&self) -> &'static str {
        self.model.engine().name()
    }

    fn state_of(&self, q: &[f64], qdot: &[f64]) -> Result<Vec<f64>, Failure> {
        Ok(q.iter().chain(qdot).copied().collect())
    }
}

/// The derivative of `f: x -> y` (`m` values) at `x` by central
/// differences, row-major (`m` rows): a feedback law's `du/dx`, the law
/// having no symbolic form.
fn central_differences(x: &[f64], m: usize, f: impl Fn(&[f64], &mut [f64])) -> Vec<f64> {
    let d = x.len();
    let (mut plus, mut minus) = (vec![0.0; m], vec![0.0; m]);
    let mut shifted = x.to_vec();
    let mut derivative = vec![0.0; m * d];
    for j in 0..d {
        let step = f64::EPSILON.cbrt() * x[j].abs().max(1.0);
        shifted[j] = x[j] + step;
        f(&shifted, &mut plus);
        shifted[j] = x[j] - step;
        f(&shifted, &mut minus);
        shifted[j] = x[j];
        for i in 0..m {
            derivative[i * d + j] = (plus[i] - minus[i]) / (2.0 * step);
        }
    }
    derivative
}

/// Adds a feedback law's share `(df/du) du/dx` to `jacobian` (d x d,
/// row-major) at `(t, x)`, `by_u = df/du` (d x p, row-major) and `du/dx`
/// by central differences of the law.
fn add_feedback(
    formulation: &dyn Formulation,
    (t, x): (f64, &[f64]),
    by_u: &[f64],
    jacobian: &mut [f64],
) {
    let (d, p) = (x.len(), by_u.len() / x.len());
    let du = central_differences(x, p, |x, u| formulation.inputs(t, x, u));
    for (i, row) in jacobian.chunks_mut(d).enumerate() {
        for (j, entry) in row.iter_mut().enumerate() {
            *entry += (0..p).map(|l| by_u[i * p + l] * du[l * d + j]).sum::<f64>();
        }
    }
}

/// `df/dx` (2n x 2n) and `df/du` (2n x p) of the Lagrange-d'Alembert
/// form `f = (qdot, qddot(q, qdot, u))` at `x = (q, qdot)`, row-major: the
/// identity's rows `qdot`, then the exact `acceleration_jacobian`.
pub fn lagrange_rhs_jacobian(
    model: &InterpretedModel,
    x: &[f64],
    u: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let (n, p) = (model.sizes().n, model.sizes().p);
    let s = 2 * n;
    let (q, qdot) = x.split_at(n);
    let (by_q, by_qdot, by_u) = evaluated(model.acceleration_jacobian(q, qdot, u));
    let mut fx = vec![0.0; s * s];
    let mut fu = vec![0.0; s * p];
    for k in 0..n {
        fx[k * s + n + k] = 1.0;
        let row = (n + k) * s;
        fx[row..row + n].copy_from_slice(&by_q[k * n..(k + 1) * n]);
        fx[row + n..row + s].copy_from_slice(&by_qdot[k * n..(k + 1) * n]);
        fu[(n + k) * p..(n + k + 1) * p].copy_from_slice(&by_u[k * p..(k + 1) * p]);
    }
    (fx, fu)
}

/// Why `model` has no momentum formulation, if it has none: no symmetry,
/// or holonomic constraints (its momentum equation is
/// [`MOMENTUM_WITH_HOLONOMIC`]).
pub fn momentum_unsupported(model: &InterpretedModel) -> Option<String> {
    if model.shape().is_none() {
        return Some("the model declares no symmetry: the momentum formulation needs one".into());
    }
    model
        .arguments("momentum_rhs")
        .is_none()
        .then(|| format!("the momentum formulation is {MOMENTUM_WITH_HOLONOMIC}"))
}

/// The names of the momentum formulation's state `(q, rdot, p)`: the
/// coordinates, `dot(r)` for the shape velocities, `p1..pK`.
pub fn momentum_state_names(model: &InterpretedModel) -> Vec<String> {
    let coordinates = &model.names().coordinates;
    let shape = model.shape().unwrap_or_default();
    let shape_velocities = shape.iter().map(|&i| format!("dot({})", coordinates[i]));
    let k = model.arguments("momentum_rhs").map_or(0, |a| a[2].1);
    let momenta = (1..=k).map(|i| format!("p{i}"));
    coordinates
        .iter()
        .cloned()
        .chain(shape_velocities)
        .chain(momenta)
        .collect()
}

/// The momentum equation `x = (q, rdot, p)` of an interpreted model with a
/// symmetry (MATH.md section 4), as the compiled `system::Momentum`:
///
/// ```text
/// qdot  = reconstructed_velocity(q, rdot, p)
/// rddot = shape_acceleration(r, rdot, p, u)
/// pdot  = momentum_rhs(r, rdot, p) + momentum_input_matrix(q) u
/// ```
pub struct InterpretedMomentum {
    /// The model.
    pub model: InterpretedModel,
    /// The indices of the shape coordinates `r` in `q`.
    pub shape: Vec<usize>,
    /// The inputs, read at the reconstructed velocity.
    pub inputs: InputLaw,
}

impl InterpretedMomentum {
    /// The momentum formulation of `model`.
    ///
    /// # Errors
    /// Why the model has none ([`momentum_unsupported`]).
    pub fn new(model: InterpretedModel, inputs: InputLaw) -> Result<Self, String> {
        if let Some(reason) = momentum_unsupported(&model) {
            return Err(reason);
        }
        let shape = model.shape().unwrap_or_default();
        Ok(Self {
            model,
            shape,
            inputs,
        })
    }

    /// The state `(q, rdot, p)` of `q` moving with `qdot`, checked: the
    /// velocity reconstructed from it must be `qdot` again (to `1e-9`
    /// relative), which fails where the derived momentum basis `e(r)`
    /// degenerates at this shape.
    pub fn initial_state(&self, q: &[f64], qdot: &[f64]) -> Result<Vec<f64>, Unrepresentable> {
        let divisors = evaluated(self.model.basis_divisors());
        if let Some(zero) = divisors.into_iter().find(|divisor| divisor.fails()) {
            return Err(Unrepresentable::Parameters {
                expression: zero.description.into_owned(),
                value: zero.value,
            });
        }
        let x = self.state(q, qdot);
        let (_, reconstructed) = self.reconstructed(&x);
        let scale = qdot.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        let names = &self.model.names().coordinates;
        match reconstructed
            .iter()
            .zip(qdot)
            .enumerate()
            .map(|(i, (a, b))| (i, (a - b).abs()))
            .max_by(|a, b| a.1.total_cmp(&b.1))
        {
            Some((i, error)) if error > 1e-9 * scale || error.is_nan() => {
                Err(Unrepresentable::Reconstruction {
                    coordinate: names[i].clone(),
                    error,
                })
            }
            _ => Ok(x),
        }
    }

    /// The state `(q, rdot, p)` of `q` moving with `qdot`.
    fn state(&self, q: &[f64], qdot: &[f64]) -> Vec<f64> {
        let rdot = self.shape.iter().map(|&i| qdot[i]);
        let p = evaluated(self.model.call("momentum", &[q, qdot]));
        q.iter().copied().chain(rdot).chain(p).collect()
    }

    /// `(q, rdot, p)` of `x`.
    fn split<'x>(&self, x: &'x [f64]) -> (&'x [f64], &'x [f64], &'x [f64]) {
        let (q, rest) = x.split_at(self.model.sizes().n);
        let (rdot, p) = rest.split_at(self.shape.len());
        (q, rdot, p)
    }

    /// The configuration and its reconstructed velocity at `x`.
    fn reconstructed<'x>(&self, x: &'x [f64]) -> (&'x [f64], Vec<f64>) {
        let (q, rdot, p) = self.split(x);
        (q, evaluated(self.model.reconstructed_velocity(q, rdot, p)))
    }
}

impl SliceSystem for InterpretedMomentum {
    fn state_names(&self) -> Vec<String> {
        momentum_state_names(&self.model)
    }

    fn input_names(&self) -> Vec<String> {
        self.model.names().inputs.clone()
    }

    /// The model's `momentum_form_rhs` at the inputs applied.
    fn rhs(&self, t: f64, x: &[f64], xdot: &mut [f64]) {
        let u = inputs_at(self, &self.model, t, x);
        xdot.copy_from_slice(&evaluated(self.model.momentum_form_rhs(x, &u)));
    }

    /// The model's exact `momentum_form_jacobian` at fixed `u`, and a
    /// feedback's `(df/du) du/dx`.
    fn jacobian(&self, t: f64, x: &[f64], jacobian: &mut [f64]) {
        let u = inputs_at(self, &self.model, t, x);
        let (by_x, by_u) = evaluated(self.model.momentum_form_jacobian(x, &u));
        jacobian.copy_from_slice(&by_x);
        if self.inputs.reads_state {
            add_feedback(self, (t, x), &by_u, jacobian);
        }
    }

    /// The energy at the reconstructed velocity.
    fn energy(&self, x: &[f64]) -> f64 {
        let (q, qdot) = self.reconstructed(x);
        evaluated(self.model.energy(q, &qdot))
    }

    fn energy_at_rest(&self, x: &[f64]) -> f64 {
        energy_at_rest(&self.model, x)
    }

    fn inputs(&self, t: f64, x: &[f64], inputs: &mut [f64]) {
        self.inputs.apply(self, self.model.sizes().n, t, x, inputs);
    }

    fn input_power(&self, t: f64, x: &[f64]) -> f64 {
        input_power_of(self, &self.model, t, x)
    }

    fn configuration_velocity(&self, x: &[f64], q: &mut [f64], qdot: &mut [f64]) {
        let (configuration, velocity) = self.reconstructed(x);
        q.copy_from_slice(configuration);
        qdot.copy_from_slice(&velocity);
    }

    fn constraint_residual(&self, x: &[f64]) -> f64 {
        let (q, qdot) = self.reconstructed(x);
        residual(&self.model, q, &qdot)
    }

    /// The Hadamard ratio of the reconstruction `[A; E_r; h g]`, as the
    /// compiled momentum adapter's (`momentum_regularity`).
    fn regularity(&self, x: &[f64]) -> Regularity {
        let n = self.model.sizes().n;
        let q = &x[..n];
        let mut rows = evaluated(self.model.constraint_matrix(q));
        for &i in &self.shape {
            rows.extend((0..n).map(|j| f64::from(u8::from(i == j))));
        }
        let columns: Vec<Vec<f64>> = (0..n)
            .map(|j| {
                let unit: Vec<f64> = (0..n).map(|i| f64::from(u8::from(i == j))).collect();
                evaluated(self.model.call("momentum", &[q, &unit]))
            })
            .collect();
        let k = columns.first().map_or(0, Vec::len);
        rows.extend((0..k).flat_map(|i| columns.iter().map(move |column| column[i])));
        let value = if rows.len() == n * n {
            hadamard_ratio(DMatrix::from_row_slice(n, n, &rows))
        } else {
            0.0
        };
        Regularity {
            quantity: crate::runtime::simulate::RECONSTRUCTION,
            value,
            signed: true,
        }
    }

    /// With configuration constraints, `q` and the reconstructed `qdot`
    /// kept on them (`onto_surface`) and `(rdot, p)` of the result;
    /// without, the state cannot leave the constraints.
    fn project(&self, x: &mut [f64]) -> Result<(), ProjectionError> {
        if !keeps_configuration(&self.model) {
            return Ok(());
        }
        let (q, qdot) = self.reconstructed(x);
        let (mut q, mut qdot) = (q.to_vec(), qdot);
        onto_surface(&self.model, &mut q, &mut qdot)?;
        x.copy_from_slice(&self.state(&q, &qdot));
        Ok(())
    }

    /// The model's guarded expressions and the momentum basis's divisors.
    fn domain(&self, x: &[f64]) -> Vec<GuardedValue<'_>> {
        let mut guards = evaluated(self.model.domain(&x[..self.model.sizes().n]));
        guards.extend(evaluated(self.model.basis_divisors()));
        guards
    }

    fn dependent_rows(&self, x: &[f64]) -> Vec<String> {
        evaluated(self.model.dependent_rows(&x[..self.model.sizes().n]))
    }

    fn holonomic_residual(&self, x: &[f64]) -> Option<f64> {
        holonomic_residual(&self.model, &x[..self.model.sizes().n])
    }
}

impl Formulation for InterpretedMomentum {
    fn engine(&self) -> &'static str {
        self.model.engine().name()
    }

    fn state_of(&self, q: &[f64], qdot: &[f64]) -> Result<Vec<f64>, Failure> {
        Ok(self.initial_state(q, qdot)?)
    }
}

#[cfg(test)]
mod tests {
    use super::central_differences;
    use crate::driver::catalog::lookup;
    use crate::driver::engine::{EngineChoice, load};
    use crate::driver::simulate::{FormulationChoice, Request, prepare};

    /// The snakeboard's Jacobian `df/dx` in each formulation under a
    /// feedback law that reads its coordinates and velocities: the exact
    /// one of the model at fixed `u` (`acceleration_jacobian`,
    /// `reduced_rhs_jacobian`, `momentum_form_jacobian`) with the law's
    /// share, against central differences of the closed right-hand side.
    #[test]
    fn every_formulations_jacobian_is_the_derivative_of_its_closed_rhs() {
        let laws = [
            ("u_torso", "0.4*sin(t) - 2*psi + 0.3*dot(x)*dot(theta)"),
            ("u_wheels", "-3*phi - dot(phi) + 0.5*dot(y)"),
        ];
        let initial = [
            ("dot(psi)", "0.3"),
            ("dot(phi)", "-0.2"),
            ("dot(x)", "0.5"),
            ("psi", "0.4"),
        ];
        for formulation in [
            FormulationChoice::Lagrange,
            FormulationChoice::Reduced,
            FormulationChoice::Momentum,
        ] {
            let loaded = load(&lookup("snakeboard").expect("built in"), EngineChoice::Jit);
            let request = Request {
                formulation,
                inputs: laws.map(|(u, law)| (u.into(), law.into())).to_vec(),
                initial: initial.map(|(v, value)| (v.into(), value.into())).to_vec(),
                ..Request::default()
            };
            let prepared = prepare(loaded.expect("derives"), &request).expect("prepares");
            let (system, x) = (&*prepared.formulation, &prepared.x0);
            let d = x.len();
            let mut exact = vec![0.0; d * d];
            system.jacobian(0.3, x, &mut exact);
            let numeric = central_differences(x, d, |x, xdot| system.rhs(0.3, x, xdot));
            let largest = numeric.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for (k, (a, b)) in exact.iter().zip(&numeric).enumerate() {
                assert!(
                    (a - b).abs() < 1e-6 * largest,
                    "{formulation:?} ({}, {}): {a} vs {b}",
                    k / d,
                    k % d
                );
            }
        }
    }
}
