//! Property: a fuzz-corpus model that compiles (a built-in model mutated as
//! the `expand` fuzz target mutates it, FUZZING.md), run through the
//! interpreter in the reduced form from a random admissible state for a
//! short time, never yields a NaN without an error: every run ends in a
//! finite state with finite rows, or in a structured error; a non-finite
//! step's error carries the finite state it started from.
//!
//! The admissible state: random coordinates and a random velocity projected
//! onto `ker A(q)` in the model's metric (`projection::velocity`).

#[path = "../../codegen/tests/support/mod.rs"]
mod support;

use chaplygin::runtime::Error;
use chaplygin::runtime::integrate::{DiscreteGradient, Midpoint, Rk4};
use chaplygin::runtime::linalg::Square;
use chaplygin::runtime::nalgebra::{Const, DMatrix, DVector};
use chaplygin::runtime::projection;
use chaplygin::runtime::record::Table;
use chaplygin::runtime::simulate::{
    Advance, Observed, REDUCED, Regularity, Simulation, SimulationError,
};
use chaplygin::runtime::system::{Energy, Jacobian, OdeSystem, Structured};
use chaplygin_codegen::interpret::InterpretedModel;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

/// An interpreted model's reduced form `x = (q, alpha)` of size `S`, at zero
/// input. The interpreter's calls are sized by the model itself, so a call
/// error is a defect and panics.
struct Reduced<'a, const S: usize> {
    model: &'a InterpretedModel,
    u: Vec<f64>,
}

fn array<const S: usize>(values: Vec<f64>) -> [f64; S] {
    core::array::from_fn(|i| values[i])
}

fn square<const S: usize>(values: Vec<f64>) -> [[f64; S]; S] {
    core::array::from_fn(|i| core::array::from_fn(|j| values[i * S + j]))
}

impl<const S: usize> OdeSystem<[f64; S]> for Reduced<'_, S> {
    fn rhs(&self, _t: f64, x: &[f64; S]) -> [f64; S] {
        array(self.model.reduced_rhs(x, &self.u).unwrap())
    }
}

impl<const S: usize> Jacobian<[f64; S]> for Reduced<'_, S>
where
    Const<S>: Square,
{
    fn jacobian(&self, _t: f64, x: &[f64; S]) -> [[f64; S]; S] {
        square(self.model.reduced_rhs_jacobian(x, &self.u).unwrap())
    }
}

impl<const S: usize> Energy<[f64; S]> for Reduced<'_, S> {
    fn energy(&self, x: &[f64; S]) -> f64 {
        self.model.hamiltonian(x).unwrap()
    }
}

impl<const S: usize> Structured<[f64; S]> for Reduced<'_, S>
where
    Const<S>: Square,
{
    fn structure_matrix(&self, x: &[f64; S]) -> [[f64; S]; S] {
        square(self.model.structure_matrix(x).unwrap())
    }

    fn energy_gradient(&self, x: &[f64; S]) -> [f64; S] {
        array(self.model.hamiltonian_gradient(x).unwrap())
    }

    fn forcing(&self, _t: f64, _x: &[f64; S]) -> [f64; S] {
        [0.0; S]
    }
}

impl<const S: usize> Observed<[f64; S]> for Reduced<'_, S> {
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

    fn inputs(&self, _t: f64, _x: &[f64; S], inputs: &mut [f64]) {
        inputs.copy_from_slice(&self.u);
    }

    /// `dH/dx . F`, none: the forcing is zero.
    fn input_power(&self, _t: f64, _x: &[f64; S]) -> f64 {
        0.0
    }

    fn configuration_velocity(&self, x: &[f64; S], q: &mut [f64], qdot: &mut [f64]) {
        let (configuration, alpha) = x.split_at(self.model.sizes().n);
        q.copy_from_slice(configuration);
        qdot.copy_from_slice(&self.model.velocities(configuration, alpha).unwrap());
    }

    fn constraint_residual(&self, x: &[f64; S]) -> f64 {
        let (q, alpha) = x.split_at(self.model.sizes().n);
        let qdot = self.model.velocities(q, alpha).unwrap();
        let residual = self.model.constraint_residual(q, &qdot).unwrap();
        residual.iter().fold(0.0, |worst, r| worst.max(r.abs()))
    }

    /// Never stops the run: the property is about what the integrators do
    /// wherever the run goes.
    fn regularity(&self, _x: &[f64; S]) -> Regularity {
        Regularity {
            quantity: REDUCED,
            value: 1.0,
            signed: false,
        }
    }
}

/// A state `(q, alpha)` at the coordinates `q` moving with the admissible
/// velocity nearest `v`, or `None` where the metric or the rows do not
/// allow one.
fn admissible_state(model: &InterpretedModel, q: &[f64], v: &[f64]) -> Option<Vec<f64>> {
    let sizes = model.sizes();
    let metric = DMatrix::from_row_slice(sizes.n, sizes.n, &model.mass_matrix(q).ok()?);
    let rows = DMatrix::from_row_slice(sizes.c, sizes.n, &model.constraint_matrix(q).ok()?);
    let qdot = projection::velocity(metric, &rows, &DVector::from_column_slice(v)).ok()?;
    let alpha = model.momenta(q, qdot.as_slice()).ok()?;
    let x: Vec<f64> = q.iter().chain(&alpha).copied().collect();
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Runs `method` for 0.5 s from `x0`; panics on a NaN that is not an error.
fn run_without_silent_nan<M, const S: usize>(model: &InterpretedModel, x0: &[f64], method: M)
where
    M: for<'a> Advance<Reduced<'a, S>, [f64; S]>,
    Const<S>: Square,
{
    let system = Reduced::<S> {
        model,
        u: vec![0.0; model.sizes().p],
    };
    let mut table = Table::new();
    let outcome = Simulation::new(method).span(0.0, 0.5).step(0.05).run(
        &system,
        array(x0.to_vec()),
        &mut table,
    );
    match &outcome {
        Ok(summary) => {
            assert!(
                summary.state.iter().all(|v| v.is_finite()),
                "{:?}",
                summary.state
            );
        }
        Err(SimulationError::Integration(Error::NonFinite { state, .. })) => {
            assert!(state.iter().all(|v| v.is_finite()), "{state:?}");
        }
        Err(_) => {}
    }
    for row in &table.rows {
        let state = &row[..=S];
        assert!(
            state.iter().all(|v| v.is_finite()),
            "a NaN row without an error: {row:?}"
        );
    }
}

/// Every integrator on the state `x0` of dimension `S`.
fn run_all<const S: usize>(model: &InterpretedModel, x0: &[f64])
where
    Const<S>: Square,
{
    run_without_silent_nan::<_, S>(model, x0, Rk4);
    run_without_silent_nan::<_, S>(model, x0, Midpoint::default());
    run_without_silent_nan::<_, S>(model, x0, DiscreteGradient::default());
}

/// [`run_all`] at the dimension of `x0` (2 to 12; larger states are not run).
fn run_at_dimension(model: &InterpretedModel, x0: &[f64]) {
    macro_rules! dispatch {
        ($($s:literal)*) => {
            match x0.len() {
                $($s => run_all::<$s>(model, x0),)*
                _ => {}
            }
        };
    }
    dispatch!(2 3 4 5 6 7 8 9 10 11 12);
}

fn config() -> Config {
    Config {
        cases: 48,
        rng_seed: RngSeed::Fixed(0x0dd_ba11),
        failure_persistence: None,
        ..Config::default()
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn a_compiled_fuzz_model_never_yields_a_silent_nan(
        pick in any::<u8>(),
        mutations in proptest::collection::vec(any::<u8>(), 0..24),
        coordinates in proptest::collection::vec(-1.5..1.5f64, 12),
        velocity in proptest::collection::vec(-1.0..1.0f64, 12),
    ) {
        let text = support::mutate::mutated_model(pick, &mutations);
        let Ok(model) = InterpretedModel::from_source(&text) else {
            return Ok(());
        };
        let n = model.sizes().n;
        if n > coordinates.len() {
            return Ok(());
        }
        if let Some(x0) = admissible_state(&model, &coordinates[..n], &velocity[..n]) {
            run_at_dimension(&model, &x0);
        }
    }
}
