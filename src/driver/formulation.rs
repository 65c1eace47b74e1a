//! One formulation of one model, closed by its controller, seen through
//! slices, so that every model and formulation runs through the same
//! simulation loop.
//!
//! [`Formulation`] is the runtime's object-safe [`SliceSystem`] with the
//! engine that runs it and the state of a configuration and velocity;
//! [`Typed`] gives it to a fixed-size structured runtime system (the
//! snakeboard under its energy controller). The runtime runs it on states of
//! the size it has at run time (`Simulation::run_sized`), as it runs a
//! generated model.

use crate::driver::Failure;
use crate::runtime::arrays::leading;
use crate::runtime::linalg::Square;
use crate::runtime::nalgebra::Const;
use crate::runtime::projection::ProjectionError;
use crate::runtime::simulate::{GuardedValue, Observed, Regularity, SliceSystem};
use crate::runtime::system::{Jacobian, Structured};

/// A closed system `xdot = f(t, x)` with what the simulation loop observes
/// ([`SliceSystem`]), the engine that runs it, and the state of a
/// configuration and velocity.
pub trait Formulation: SliceSystem {
    /// What runs the model's functions: the engine's name (`jit`,
    /// `interpret`).
    fn engine(&self) -> &'static str;
    /// The state of the configuration `q` moving with `qdot`; a
    /// formulation with charts makes the one that fits best at `q` active.
    ///
    /// # Errors
    /// A velocity the formulation cannot represent, or a formulation whose
    /// state is not made of `(q, qdot)` alone (a controller's).
    fn state_of(&self, q: &[f64], qdot: &[f64]) -> Result<Vec<f64>, Failure>;
}

/// A fixed-size structured runtime system as a [`Formulation`], its
/// model's functions run by the engine it names.
pub struct Typed<T, const D: usize> {
    system: T,
    engine: &'static str,
}

impl<T: Observed<[f64; D]> + Jacobian<[f64; D]> + Structured<[f64; D]>, const D: usize> Typed<T, D>
where
    Const<D>: Square,
{
    /// `system`, run by `engine`.
    pub fn structured(system: T, engine: &'static str) -> Self {
        Self { system, engine }
    }
}

fn flatten<const D: usize>(matrix: &[[f64; D]; D], into: &mut [f64]) {
    into.copy_from_slice(matrix.as_flattened());
}

impl<T: Observed<[f64; D]> + Jacobian<[f64; D]> + Structured<[f64; D]>, const D: usize> SliceSystem
    for Typed<T, D>
where
    Const<D>: Square,
{
    fn state_names(&self) -> Vec<String> {
        self.system.state_names()
    }

    fn input_names(&self) -> Vec<String> {
        self.system.input_names()
    }

    fn rhs(&self, t: f64, x: &[f64], xdot: &mut [f64]) {
        xdot.copy_from_slice(&self.system.rhs(t, &leading(x)));
    }

    fn jacobian(&self, t: f64, x: &[f64], jacobian: &mut [f64]) {
        flatten(&self.system.jacobian(t, &leading(x)), jacobian);
    }

    fn energy(&self, x: &[f64]) -> f64 {
        self.system.energy(&leading(x))
    }

    fn energy_at_rest(&self, x: &[f64]) -> f64 {
        self.system.energy_at_rest(&leading(x))
    }

    fn is_structured(&self) -> bool {
        true
    }

    fn structure_matrix(&self, x: &[f64], j: &mut [f64]) {
        flatten(&self.system.structure_matrix(&leading(x)), j);
    }

    fn energy_gradient(&self, x: &[f64], gradient: &mut [f64]) {
        gradient.copy_from_slice(&self.system.energy_gradient(&leading(x)));
    }

    fn forcing(&self, t: f64, x: &[f64], forcing: &mut [f64]) {
        forcing.copy_from_slice(&self.system.forcing(t, &leading(x)));
    }

    fn inputs(&self, t: f64, x: &[f64], inputs: &mut [f64]) {
        self.system.inputs(t, &leading(x), inputs);
    }

    fn input_power(&self, t: f64, x: &[f64]) -> f64 {
        self.system.input_power(t, &leading(x))
    }

    fn configuration_velocity(&self, x: &[f64], q: &mut [f64], qdot: &mut [f64]) {
        self.system.configuration_velocity(&leading(x), q, qdot);
    }

    fn constraint_residual(&self, x: &[f64]) -> f64 {
        self.system.constraint_residual(&leading(x))
    }

    fn regularity(&self, x: &[f64]) -> Regularity {
        self.system.regularity(&leading(x))
    }

    fn project(&self, x: &mut [f64]) -> Result<(), ProjectionError> {
        x.copy_from_slice(&self.system.project(leading(x))?);
        Ok(())
    }

    fn holonomic_residual(&self, x: &[f64]) -> Option<f64> {
        self.system.holonomic_residual(&leading(x))
    }

    fn domain(&self, x: &[f64]) -> Vec<GuardedValue<'_>> {
        self.system.domain(&leading(x))
    }

    fn dependent_rows(&self, x: &[f64]) -> Vec<String> {
        self.system.dependent_rows(&leading(x))
    }

    fn chart(&self) -> Option<usize> {
        self.system.chart()
    }

    fn change_chart(&self, x: &mut [f64]) -> bool {
        let mut state = leading(x);
        let changed = self.system.change_chart(&mut state);
        x.copy_from_slice(&state);
        changed
    }

    fn change_to_pivoted_chart(&self, x: &mut [f64]) -> bool {
        let mut state = leading(x);
        let changed = self.system.change_to_pivoted_chart(&mut state);
        x.copy_from_slice(&state);
        changed
    }
}

impl<T: Observed<[f64; D]> + Jacobian<[f64; D]> + Structured<[f64; D]>, const D: usize> Formulation
    for Typed<T, D>
where
    Const<D>: Square,
{
    /// Not made of `(q, qdot)` alone: the controller's states complete it.
    fn state_of(&self, _q: &[f64], _qdot: &[f64]) -> Result<Vec<f64>, Failure> {
        Err("a closed loop's state includes its controller's: it is not a configuration's and a velocity's".into())
    }

    fn engine(&self) -> &'static str {
        self.engine
    }
}
