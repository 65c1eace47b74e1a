//! Systems whose state's size is known only at run time, seen through
//! slices ([`SliceSystem`]), and their simulation compiled here once
//! ([`Simulation::run_sized`]).
//!
//! A model loaded at run time (from a `.model` file, compiled by the JIT or
//! interpreted) or any formulation picked at run time has a state of a size
//! its type does not carry. [`SliceSystem`] is the object-safe view of such
//! a closed system `xdot = f(t, x)`, with what the simulation loop observes
//! ([`Observed`]); [`RunTimeSized`] turns it back into a system on
//! `Vec<f64>` states ([`crate::state`]), which the integrators and the loop
//! run as they run a generated model.
//!
//! The integrators and the loop are generic, so their code is generated
//! where a concrete system is named. [`Simulation::run_sized`] names
//! [`RunTimeSized`] here, with every integrator of [`SizedMethod`]: the
//! loop and the integrators of every run-time-sized run are compiled with
//! this crate, optimized wherever it is (`Cargo.toml`'s profiles), not with
//! each caller.

use super::{
    Advance, GuardedValue, Observed, Regularity, Simulation, SimulationError, StopCondition,
    Summary,
};
use crate::integrate::{self, Controlled, DiscreteGradient, DormandPrince, Effort, Midpoint, Rk4};
use crate::projection::ProjectionError;
use crate::record::Recorder;
use crate::system::{Energy, Jacobian, OdeSystem, Structured};
use nalgebra::DMatrix;

/// A closed system `xdot = f(t, x)` on slices whose length is the state's
/// size, with what the simulation loop observes (the methods of
/// [`Observed`], [`Jacobian`] and [`Structured`], row-major matrices
/// written into slices).
pub trait SliceSystem {
    /// The names of the state's entries (their number is the dimension).
    fn state_names(&self) -> Vec<String>;
    /// The names of the inputs.
    fn input_names(&self) -> Vec<String>;
    /// `f(t, x)` into `xdot`.
    fn rhs(&self, t: f64, x: &[f64], xdot: &mut [f64]);
    /// `df/dx` into `jacobian`, row-major.
    fn jacobian(&self, t: f64, x: &[f64], jacobian: &mut [f64]);
    /// The stored energy.
    fn energy(&self, x: &[f64]) -> f64;
    /// The stored energy at rest at `x`'s configuration (see
    /// [`Observed::energy_at_rest`]).
    fn energy_at_rest(&self, x: &[f64]) -> f64;
    /// Whether [`SliceSystem::structure_matrix`],
    /// [`SliceSystem::energy_gradient`] and [`SliceSystem::forcing`] are
    /// available (by default not).
    fn is_structured(&self) -> bool {
        false
    }
    /// Of `f = J dH/dx + F`, the structure matrix `J` into `j`, row-major;
    /// by default nothing is written (see [`SliceSystem::is_structured`]).
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
    /// The active chart of D, if the system has several (see
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

/// A [`SliceSystem`] as a system on states whose size is known at run time
/// (`Vec<f64>`).
#[derive(Clone, Copy)]
pub struct RunTimeSized<'a>(pub &'a dyn SliceSystem);

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

/// The integrator of a run-time-sized run: a one-step method with fixed
/// steps or with its step following the tolerances ([`Controlled`]), or
/// Dormand-Prince.
#[derive(Clone, Debug, PartialEq)]
pub enum SizedMethod {
    /// [`Rk4`], fixed steps.
    Rk4(Rk4),
    /// [`Midpoint`], fixed steps.
    Midpoint(Midpoint),
    /// [`DiscreteGradient`], fixed steps (the system must be structured).
    DiscreteGradient(DiscreteGradient),
    /// [`Rk4`] within the tolerances.
    ControlledRk4(Controlled<Rk4>),
    /// [`Midpoint`] within the tolerances.
    ControlledMidpoint(Controlled<Midpoint>),
    /// [`DiscreteGradient`] within the tolerances.
    ControlledDiscreteGradient(Controlled<DiscreteGradient>),
    /// [`DormandPrince`].
    DormandPrince(DormandPrince),
}

impl Advance<RunTimeSized<'_>, Vec<f64>> for SizedMethod {
    fn advance(
        &self,
        system: &RunTimeSized<'_>,
        start: (f64, &Vec<f64>),
        t_next: f64,
        effort: &mut Effort,
    ) -> Result<Vec<f64>, integrate::Error> {
        match self {
            Self::Rk4(method) => method.advance(system, start, t_next, effort),
            Self::Midpoint(method) => method.advance(system, start, t_next, effort),
            Self::DiscreteGradient(method) => method.advance(system, start, t_next, effort),
            Self::ControlledRk4(method) => method.advance(system, start, t_next, effort),
            Self::ControlledMidpoint(method) => method.advance(system, start, t_next, effort),
            Self::ControlledDiscreteGradient(method) => {
                method.advance(system, start, t_next, effort)
            }
            Self::DormandPrince(method) => method.advance(system, start, t_next, effort),
        }
    }
}

/// The stop condition of a run-time-sized run, if any.
pub type SizedStop<'a> = Option<&'a dyn StopCondition<Vec<f64>>>;

impl Simulation<SizedMethod, SizedStop<'_>> {
    /// [`Simulation::run_with_progress`] for `system`, on states of the
    /// size `x0` has.
    ///
    /// # Errors
    /// As [`Simulation::run`].
    pub fn run_sized(
        &self,
        system: &dyn SliceSystem,
        x0: Vec<f64>,
        recorder: &mut dyn Recorder,
        progress: &mut dyn FnMut(f64),
    ) -> Result<Summary<Vec<f64>>, SimulationError> {
        self.run_with_progress(&RunTimeSized(system), x0, &mut &mut *recorder, progress)
    }
}
