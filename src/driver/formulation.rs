//! One formulation of one model, closed by its controller, seen through
//! slices, so that every model and formulation runs through the same
//! simulation loop.
//!
//! [`Formulation`] is the object-safe view; [`Typed`] gives it to a
//! fixed-size structured runtime system (the snakeboard under its energy
//! controller); [`RunTimeSized`] turns it back into a runtime system on
//! states of the size it has at run time, which the runtime's integrators
//! and simulation loop run as they run a generated model.

use crate::driver::Failure;
use crate::runtime::arrays::leading;
use crate::runtime::linalg::Square;
use crate::runtime::nalgebra::{Const, DMatrix};
use crate::runtime::projection::ProjectionError;
use crate::runtime::simulate::{GuardedValue, Observed, Regularity};
use crate::runtime::system::{Energy, Jacobian, OdeSystem, Structured};

/// A closed system `xdot = f(t, x)` with what the simulation loop observes.
pub trait Formulation {
    /// The names of the state's entries (their number is the dimension).
    fn state_names(&self) -> Vec<String>;
    /// The names of the inputs.
    fn input_names(&self) -> Vec<String>;
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
    /// `f(t, x)` into `xdot`.
    fn rhs(&self, t: f64, x: &[f64], xdot: &mut [f64]);
    /// `df/dx` into `jacobian`, row-major.
    fn jacobian(&self, t: f64, x: &[f64], jacobian: &mut [f64]);
    /// The stored energy.
    fn energy(&self, x: &[f64]) -> f64;
    /// The stored energy at rest at `x`'s configuration (see
    /// [`Observed::energy_at_rest`]).
    fn energy_at_rest(&self, x: &[f64]) -> f64;
    /// Whether [`Formulation::structure_matrix`],
    /// [`Formulation::energy_gradient`] and [`Formulation::forcing`] are
    /// available (by default not).
    fn is_structured(&self) -> bool {
        false
    }
    /// Of `f = J dH/dx + F`, the structure matrix `J` into `j`, row-major;
    /// by default nothing is written (see [`Formulation::is_structured`]).
    fn structure_matrix(&self, _x: &[f64], _j: &mut [f64]) {}
    /// Of `f = J dH/dx + F`, `dH/dx` into `gradient`; by default nothing is
    /// written.
    fn energy_gradient(&self, _x: &[f64], _gradient: &mut [f64]) {}
    /// Of `f = J dH/dx + F`, the forcing `F` into `forcing`; by default
    /// nothing is written.
    fn forcing(&self, _t: f64, _x: &[f64], _forcing: &mut [f64]) {}
    /// The inputs applied at `(t, x)`.
    fn inputs(&self, t: f64, x: &[f64], inputs: &mut [f64]);
    /// The power the inputs deliver at `(t, x)` (see
    /// [`Observed::input_power`]).
    fn input_power(&self, t: f64, x: &[f64]) -> f64;
    /// The configuration and its velocity at `x` (see
    /// [`Observed::configuration_velocity`]).
    fn configuration_velocity(&self, x: &[f64], q: &mut [f64], qdot: &mut [f64]);
    /// The largest `|A(q) qdot|`.
    fn constraint_residual(&self, x: &[f64]) -> f64;
    /// The regularity measure.
    fn regularity(&self, x: &[f64]) -> Regularity;
    /// `x` moved back onto the constraint manifold after a step (see
    /// [`Observed::project`]); by default left as it is.
    ///
    /// # Errors
    /// A constraint the projection cannot meet.
    fn project(&self, _x: &mut [f64]) -> Result<(), ProjectionError> {
        Ok(())
    }
    /// The largest `|f(q)|` of the configuration constraints kept, if any.
    fn holonomic_residual(&self, _x: &[f64]) -> Option<f64> {
        None
    }
    /// The model's guarded expressions at `x` (see [`Observed::domain`]).
    fn domain(&self, _x: &[f64]) -> Vec<GuardedValue<'_>> {
        Vec::new()
    }
    /// The constraint rows dependent at `x` (see
    /// [`Observed::dependent_rows`]).
    fn dependent_rows(&self, _x: &[f64]) -> Vec<String> {
        Vec::new()
    }
    /// The active chart of D, if the formulation has several (see
    /// [`Observed::chart`]).
    fn chart(&self) -> Option<usize> {
        None
    }
    /// Moves `x` into a better chart where the active one degenerates (see
    /// [`Observed::change_chart`]); whether it did.
    fn change_chart(&self, _x: &mut [f64]) -> bool {
        false
    }
    /// Moves `x` into the run-time chart partial pivoting picks (see
    /// [`Observed::change_to_pivoted_chart`]); whether it did.
    fn change_to_pivoted_chart(&self, _x: &mut [f64]) -> bool {
        false
    }
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

impl<T: Observed<[f64; D]> + Jacobian<[f64; D]> + Structured<[f64; D]>, const D: usize> Formulation
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

    /// Not made of `(q, qdot)` alone: the controller's states complete it.
    fn state_of(&self, _q: &[f64], _qdot: &[f64]) -> Result<Vec<f64>, Failure> {
        Err("a closed loop's state includes its controller's: it is not a configuration's and a velocity's".into())
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

    fn engine(&self) -> &'static str {
        self.engine
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

/// A [`Formulation`] as a runtime system on states whose size is known at
/// run time (`Vec<f64>`, see [`crate::runtime::state`]): what the
/// simulation loop runs for every model and formulation of the command line.
pub struct RunTimeSized<'a>(pub &'a dyn Formulation);

impl RunTimeSized<'_> {
    /// A square matrix over `x` written row-major by `write`.
    fn square(x: &[f64], write: impl FnOnce(&mut [f64])) -> DMatrix<f64> {
        let n = x.len();
        let mut matrix = DMatrix::zeros(n, n);
        // nalgebra stores columns one after the other: rows written in
        // order are the transpose's columns.
        write(matrix.as_mut_slice());
        matrix.transpose_mut();
        matrix
    }
}

impl OdeSystem<Vec<f64>> for RunTimeSized<'_> {
    fn rhs(&self, t: f64, x: &Vec<f64>) -> Vec<f64> {
        let mut xdot = vec![0.0; x.len()];
        self.0.rhs(t, x, &mut xdot);
        xdot
    }
}

impl Jacobian<Vec<f64>> for RunTimeSized<'_> {
    fn jacobian(&self, t: f64, x: &Vec<f64>) -> DMatrix<f64> {
        Self::square(x, |rows| self.0.jacobian(t, x, rows))
    }
}

impl Energy<Vec<f64>> for RunTimeSized<'_> {
    fn energy(&self, x: &Vec<f64>) -> f64 {
        self.0.energy(x)
    }
}

impl Structured<Vec<f64>> for RunTimeSized<'_> {
    fn structure_matrix(&self, x: &Vec<f64>) -> DMatrix<f64> {
        Self::square(x, |j| self.0.structure_matrix(x, j))
    }

    fn energy_gradient(&self, x: &Vec<f64>) -> Vec<f64> {
        let mut gradient = vec![0.0; x.len()];
        self.0.energy_gradient(x, &mut gradient);
        gradient
    }

    fn forcing(&self, t: f64, x: &Vec<f64>) -> Vec<f64> {
        let mut forcing = vec![0.0; x.len()];
        self.0.forcing(t, x, &mut forcing);
        forcing
    }
}

impl Observed<Vec<f64>> for RunTimeSized<'_> {
    fn state_names(&self) -> Vec<String> {
        self.0.state_names()
    }

    fn input_names(&self) -> Vec<String> {
        self.0.input_names()
    }

    fn inputs(&self, t: f64, x: &Vec<f64>, inputs: &mut [f64]) {
        self.0.inputs(t, x, inputs);
    }

    fn input_power(&self, t: f64, x: &Vec<f64>) -> f64 {
        self.0.input_power(t, x)
    }

    fn configuration_velocity(&self, x: &Vec<f64>, q: &mut [f64], qdot: &mut [f64]) {
        self.0.configuration_velocity(x, q, qdot);
    }

    fn energy_at_rest(&self, x: &Vec<f64>) -> f64 {
        self.0.energy_at_rest(x)
    }

    fn constraint_residual(&self, x: &Vec<f64>) -> f64 {
        self.0.constraint_residual(x)
    }

    fn regularity(&self, x: &Vec<f64>) -> Regularity {
        self.0.regularity(x)
    }

    fn project(&self, mut x: Vec<f64>) -> Result<Vec<f64>, ProjectionError> {
        self.0.project(&mut x)?;
        Ok(x)
    }

    fn holonomic_residual(&self, x: &Vec<f64>) -> Option<f64> {
        self.0.holonomic_residual(x)
    }

    fn domain(&self, x: &Vec<f64>) -> Vec<GuardedValue<'_>> {
        self.0.domain(x)
    }

    fn dependent_rows(&self, x: &Vec<f64>) -> Vec<String> {
        self.0.dependent_rows(x)
    }

    fn chart(&self) -> Option<usize> {
        self.0.chart()
    }

    fn change_chart(&self, x: &mut Vec<f64>) -> bool {
        self.0.change_chart(x)
    }

    fn change_to_pivoted_chart(&self, x: &mut Vec<f64>) -> bool {
        self.0.change_to_pivoted_chart(x)
    }
}
