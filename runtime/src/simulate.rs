//! The simulation loop: a formulation closed by its controller (an
//! [`Observed`] system), an integrator ([`Advance`]), a time span and step,
//! and a [`Recorder`].
//!
//! ```text
//! Simulation::new(Midpoint::default()).span(0.0, 30.0).step(0.01)
//!     .run(&Reduced::new(&board, controller), x0, &mut CsvRecorder::create("trajectory.csv")?)
//! ```
//!
//! At every step the loop checks the state is finite, and the formulation's
//! regularity measure ([`crate::monitor`]): the run stops with
//! [`SimulationError::Singular`], naming the time, the configuration and the
//! quantity, when the measure falls below the threshold or changes sign
//! within a step (a signed measure crossing zero between two steps). The
//! rows recorded until then stay recorded and the recorder is finished
//! (flushed) on every exit.

use crate::control::{Interconnection, PortHamiltonianController};
use crate::integrate::{self, DiscreteGradient, DormandPrince, FixedStep, Midpoint, Rk4};
use crate::law::Controller;
use crate::record::Recorder;
use crate::system::{
    Dalembert, Energy, LagrangeDalembert, ModelNames, Momentum, MomentumEquations, OdeSystem,
    Reduced, ReducedPortHamiltonian, split,
};

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
pub trait Observed<const D: usize>: Energy<D> {
    /// The names of the state's entries, in order.
    fn state_names(&self) -> Vec<String>;
    /// The names of the inputs, in order.
    fn input_names(&self) -> Vec<String>;
    /// The inputs applied at `(t, x)`, written into `inputs` (as many as
    /// [`Observed::input_names`]).
    fn inputs(&self, t: f64, x: &[f64; D], inputs: &mut [f64]);
    /// The largest `|A(q) qdot|` at `x`.
    fn constraint_residual(&self, x: &[f64; D]) -> f64;
    /// The regularity measure at `x`.
    fn regularity(&self, x: &[f64; D]) -> Regularity;
}

/// The reduced form's measure (see [`crate::monitor::reduced_regularity`]).
pub const REDUCED: &str = "reduced form's det[A; V^T] (constraint rows and momentum basis)";

/// The Lagrange-d'Alembert form's measure (see
/// [`crate::monitor::constraint_regularity`]).
pub const MULTIPLIERS: &str = "multiplier system's Gram matrix A g^-1 A^T";

fn owned(names: &[&str]) -> Vec<String> {
    names.iter().map(|name| name.to_string()).collect()
}

impl<M, F, const S: usize, const P: usize> Observed<S> for Reduced<'_, M, F, P>
where
    M: ReducedPortHamiltonian<S, P> + ModelNames,
    F: Controller<S, P>,
{
    fn state_names(&self) -> Vec<String> {
        owned(&[M::COORDINATES, M::MOMENTA].concat())
    }

    fn input_names(&self) -> Vec<String> {
        owned(M::INPUTS)
    }

    fn inputs(&self, t: f64, x: &[f64; S], inputs: &mut [f64]) {
        inputs.copy_from_slice(&self.controller().input(t, x));
    }

    fn constraint_residual(&self, x: &[f64; S]) -> f64 {
        self.model().constraint_violation(x)
    }

    fn regularity(&self, x: &[f64; S]) -> Regularity {
        Regularity {
            quantity: REDUCED,
            value: self.model().regularity(x),
            signed: true,
        }
    }
}

impl<M, F, const N: usize, const C: usize, const P: usize, const D: usize> Observed<D>
    for Dalembert<'_, M, F, N, C, P>
where
    M: LagrangeDalembert<N, C, P> + ModelNames,
    F: Controller<D, P>,
{
    fn state_names(&self) -> Vec<String> {
        let velocities = M::COORDINATES.iter().map(|q| format!("dot({q})"));
        owned(M::COORDINATES)
            .into_iter()
            .chain(velocities)
            .collect()
    }

    fn input_names(&self) -> Vec<String> {
        owned(M::INPUTS)
    }

    fn inputs(&self, t: f64, x: &[f64; D], inputs: &mut [f64]) {
        inputs.copy_from_slice(&self.controller().input(t, x));
    }

    fn constraint_residual(&self, x: &[f64; D]) -> f64 {
        let (q, qdot) = split::<N, D>(x);
        let residual = self.model().constraint_residual(&q, &qdot);
        residual.iter().fold(0.0, |worst, r| worst.max(r.abs()))
    }

    fn regularity(&self, x: &[f64; D]) -> Regularity {
        let (q, _) = split::<N, D>(x);
        Regularity {
            quantity: MULTIPLIERS,
            value: self.model().constraint_regularity(&q),
            signed: false,
        }
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
> Observed<D> for Momentum<'_, M, F, N, R, K, C, P>
where
    M: MomentumEquations<N, R, K, P> + LagrangeDalembert<N, C, P> + ModelNames,
    F: Controller<D, P>,
{
    /// The coordinates, `dot(r)` for the shape velocities, `p1..pK`.
    fn state_names(&self) -> Vec<String> {
        let shape_velocities = M::SHAPE.map(|i| format!("dot({})", M::COORDINATES[i]));
        let momenta = (1..=K).map(|i| format!("p{i}"));
        owned(M::COORDINATES)
            .into_iter()
            .chain(shape_velocities)
            .chain(momenta)
            .collect()
    }

    fn input_names(&self) -> Vec<String> {
        owned(M::INPUTS)
    }

    fn inputs(&self, t: f64, x: &[f64; D], inputs: &mut [f64]) {
        inputs.copy_from_slice(&self.controller().input(t, x));
    }

    fn constraint_residual(&self, x: &[f64; D]) -> f64 {
        let (q, qdot) = self.configuration_velocity(x);
        let residual = self.model().constraint_residual(&q, &qdot);
        residual.iter().fold(0.0, |worst, r| worst.max(r.abs()))
    }

    fn regularity(&self, x: &[f64; D]) -> Regularity {
        let q: [f64; N] = core::array::from_fn(|i| x[i]);
        Regularity {
            quantity: MULTIPLIERS,
            value: self.model().constraint_regularity(&q),
            signed: false,
        }
    }
}

impl<M, K, const S: usize, const NC: usize, const P: usize, const D: usize> Observed<D>
    for Interconnection<M, K, S, NC, P>
where
    M: ReducedPortHamiltonian<S, P> + ModelNames,
    K: PortHamiltonianController<S, NC, P>,
{
    fn state_names(&self) -> Vec<String> {
        owned(&[M::COORDINATES, M::MOMENTA, &K::STATES].concat())
    }

    fn input_names(&self) -> Vec<String> {
        owned(M::INPUTS)
    }

    fn inputs(&self, _t: f64, z: &[f64; D], inputs: &mut [f64]) {
        inputs.copy_from_slice(&self.input(z));
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

/// An integrator as the simulation loop uses it: from `x` at `t` to the
/// state at `t_next`.
pub trait Advance<S, const D: usize> {
    /// The state at `t_next`.
    ///
    /// # Errors
    /// The integrator's [`integrate::Error`].
    fn advance(
        &self,
        system: &S,
        t: f64,
        x: &[f64; D],
        t_next: f64,
    ) -> Result<[f64; D], integrate::Error>;
}

macro_rules! one_step_advances {
    ($($method:ty),*) => {$(
        /// One step of size `t_next - t`.
        impl<S, const D: usize> Advance<S, D> for $method
        where
            $method: FixedStep<S, D>,
        {
            fn advance(
                &self,
                system: &S,
                t: f64,
                x: &[f64; D],
                t_next: f64,
            ) -> Result<[f64; D], integrate::Error> {
                self.step(system, t, x, t_next - t)
            }
        }
    )*};
}

one_step_advances!(Rk4, Midpoint, DiscreteGradient);

/// Adaptive steps to `t_next` within the tolerances.
impl<S: OdeSystem<D>, const D: usize> Advance<S, D> for DormandPrince {
    fn advance(
        &self,
        system: &S,
        t: f64,
        x: &[f64; D],
        t_next: f64,
    ) -> Result<[f64; D], integrate::Error> {
        Ok(self.integrate(system, (t, *x), t_next)?.x)
    }
}

/// Why a simulation stopped early.
#[derive(Debug, thiserror::Error)]
pub enum SimulationError {
    /// The settings cannot describe a run.
    #[error("invalid simulation: {reason}")]
    Settings {
        /// What is wrong.
        reason: String,
    },
    /// The integrator failed (non-finite state, Newton failure, step size
    /// underflow, too many steps).
    #[error(transparent)]
    Integration(#[from] integrate::Error),
    /// The formulation degenerates at this configuration.
    #[error(
        "singular configuration at t = {t}: the {quantity} {how} ({value:.3e}, threshold {threshold:.0e}) at {}",
        named(state_names, state)
    )]
    Singular {
        /// Time of the first state found singular.
        t: f64,
        /// What degenerates.
        quantity: &'static str,
        /// `"vanishes"`, or `"changed sign in the step to t"` for a crossing.
        how: &'static str,
        /// The regularity measure there.
        value: f64,
        /// The threshold it fell below.
        threshold: f64,
        /// The state's names.
        state_names: Vec<String>,
        /// The state.
        state: Vec<f64>,
    },
    /// The recorder failed.
    #[error("recording failed at t = {t}: {source}")]
    Recording {
        /// Time of the row that failed.
        t: f64,
        /// The I/O error.
        source: std::io::Error,
    },
}

/// `name = value, ...`.
fn named(names: &[String], values: &[f64]) -> String {
    let pairs: Vec<String> = names
        .iter()
        .zip(values)
        .map(|(name, value)| format!("{name} = {value:.6}"))
        .collect();
    pairs.join(", ")
}

/// What a finished run measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary<const D: usize> {
    /// Steps taken.
    pub steps: usize,
    /// The final time.
    pub t: f64,
    /// The final state.
    pub state: [f64; D],
    /// The largest `|E(t) - E(0)|` over the steps, divided by `|E(0)|` when
    /// that is not zero.
    pub energy_drift: f64,
    /// The largest constraint residual over the steps.
    pub max_constraint_residual: f64,
    /// The smallest `|regularity|` over the steps.
    pub min_regularity: f64,
}

/// A simulation's settings: the integrator, the time span, the step, how
/// often to record, and the regularity threshold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Simulation<M> {
    method: M,
    span: (f64, f64),
    step: f64,
    record_every: usize,
    singular_below: f64,
}

impl<M> Simulation<M> {
    /// A run with `method` over `[0, 10]` with steps of `0.01`, recording
    /// every step, stopping where the regularity measure falls below `1e-6`.
    pub fn new(method: M) -> Self {
        Self {
            method,
            span: (0.0, 10.0),
            step: 0.01,
            record_every: 1,
            singular_below: 1e-6,
        }
    }

    /// From `t0` to `t_end`.
    pub fn span(mut self, t0: f64, t_end: f64) -> Self {
        self.span = (t0, t_end);
        self
    }

    /// The step of a fixed-step method; for an adaptive method, the interval
    /// between checked and recorded states.
    pub fn step(mut self, step: f64) -> Self {
        self.step = step;
        self
    }

    /// Record every `n`-th step (and the last).
    pub fn record_every(mut self, n: usize) -> Self {
        self.record_every = n;
        self
    }

    /// Stop where `|regularity| < threshold`.
    pub fn singular_below(mut self, threshold: f64) -> Self {
        self.singular_below = threshold;
        self
    }

    /// The number of steps: the span over the step, the last step shortened
    /// to end at `t_end` exactly.
    fn steps(&self) -> Result<usize, SimulationError> {
        let (t0, t_end) = self.span;
        let invalid = |reason: String| Err(SimulationError::Settings { reason });
        if !(t0.is_finite() && t_end.is_finite() && t_end > t0) {
            return invalid(format!("the span [{t0}, {t_end}] is empty or not finite"));
        }
        if !(self.step.is_finite() && self.step > 0.0) {
            return invalid(format!("the step {} is not positive", self.step));
        }
        if self.record_every == 0 {
            return invalid("record_every must be at least 1".into());
        }
        let ratio = (t_end - t0) / self.step;
        let steps = (ratio - 1e-9 * ratio.max(1.0)).ceil();
        if steps > 1e12 {
            return invalid(format!("{steps:e} steps are too many"));
        }
        Ok(steps as usize)
    }

    /// Runs `system` from `x0`, recording into `recorder`.
    ///
    /// # Errors
    /// See [`SimulationError`]; the rows recorded before it stay recorded.
    pub fn run<S, R, const D: usize>(
        &self,
        system: &S,
        x0: [f64; D],
        recorder: &mut R,
    ) -> Result<Summary<D>, SimulationError>
    where
        S: Observed<D>,
        M: Advance<S, D>,
        R: Recorder,
    {
        self.run_with_progress(system, x0, recorder, |_| {})
    }

    /// [`Simulation::run`], calling `progress` with the fraction of the span
    /// done after every recorded row.
    ///
    /// # Errors
    /// As [`Simulation::run`].
    pub fn run_with_progress<S, R, const D: usize>(
        &self,
        system: &S,
        x0: [f64; D],
        recorder: &mut R,
        progress: impl FnMut(f64),
    ) -> Result<Summary<D>, SimulationError>
    where
        S: Observed<D>,
        M: Advance<S, D>,
        R: Recorder,
    {
        let steps = self.steps()?;
        let mut run = Run::start(self, system, x0, recorder)?;
        let outcome = run.advance_all(steps, progress);
        let finished = run
            .recorder
            .finish()
            .map_err(|source| SimulationError::Recording { t: run.t, source });
        outcome.and(finished).map(|()| run.summary)
    }
}

/// A run in progress.
struct Run<'a, M, S, R, const D: usize> {
    settings: &'a Simulation<M>,
    system: &'a S,
    recorder: &'a mut R,
    t: f64,
    x: [f64; D],
    energy0: f64,
    regularity: Regularity,
    row: Vec<f64>,
    inputs: usize,
    summary: Summary<D>,
}

impl<'a, M, S, R, const D: usize> Run<'a, M, S, R, D>
where
    S: Observed<D>,
    M: Advance<S, D>,
    R: Recorder,
{
    fn start(
        settings: &'a Simulation<M>,
        system: &'a S,
        x0: [f64; D],
        recorder: &'a mut R,
    ) -> Result<Self, SimulationError> {
        let t0 = settings.span.0;
        let x = integrate::finite(t0, x0)?;
        let columns = columns(system);
        let regularity = system.regularity(&x);
        let mut run = Self {
            settings,
            system,
            t: t0,
            x,
            energy0: system.energy(&x),
            regularity,
            row: Vec::with_capacity(columns.len()),
            inputs: system.input_names().len(),
            summary: Summary {
                steps: 0,
                t: t0,
                state: x,
                energy_drift: 0.0,
                max_constraint_residual: system.constraint_residual(&x),
                min_regularity: regularity.value.abs(),
            },
            recorder,
        };
        run.recorder
            .start(&columns)
            .map_err(|source| SimulationError::Recording { t: t0, source })?;
        run.check(run.regularity)?;
        run.record()?;
        Ok(run)
    }

    fn advance_all(
        &mut self,
        steps: usize,
        mut progress: impl FnMut(f64),
    ) -> Result<(), SimulationError> {
        let (t0, t_end) = self.settings.span;
        for i in 1..=steps {
            let t_next = if i == steps {
                t_end
            } else {
                t0 + i as f64 * self.settings.step
            };
            let x = self
                .settings
                .method
                .advance(self.system, self.t, &self.x, t_next)?;
            let regularity = self.system.regularity(&x);
            (self.t, self.x) = (t_next, x);
            self.check(regularity)?;
            self.regularity = regularity;
            self.update_summary(i);
            if i % self.settings.record_every == 0 || i == steps {
                self.record()?;
                progress((self.t - t0) / (t_end - t0));
            }
        }
        Ok(())
    }

    /// [`SimulationError::Singular`] when `regularity` at the current state
    /// is below the threshold or has changed sign since the last step.
    fn check(&self, regularity: Regularity) -> Result<(), SimulationError> {
        let crossed = regularity.signed
            && regularity.value.signum() != self.regularity.value.signum()
            && regularity.value != 0.0;
        let vanishes =
            regularity.value.is_nan() || regularity.value.abs() < self.settings.singular_below;
        if !(crossed || vanishes) {
            return Ok(());
        }
        Err(SimulationError::Singular {
            t: self.t,
            quantity: regularity.quantity,
            how: if vanishes {
                "vanishes"
            } else {
                "changed sign in the step to t"
            },
            value: regularity.value,
            threshold: self.settings.singular_below,
            state_names: self.system.state_names(),
            state: self.x.to_vec(),
        })
    }

    fn update_summary(&mut self, steps: usize) {
        let energy = self.system.energy(&self.x);
        let drift = (energy - self.energy0).abs()
            / if self.energy0 == 0.0 {
                1.0
            } else {
                self.energy0.abs()
            };
        let summary = &mut self.summary;
        summary.steps = steps;
        summary.t = self.t;
        summary.state = self.x;
        summary.energy_drift = summary.energy_drift.max(drift);
        summary.max_constraint_residual = summary
            .max_constraint_residual
            .max(self.system.constraint_residual(&self.x));
        summary.min_regularity = summary.min_regularity.min(self.regularity.value.abs());
    }

    fn record(&mut self) -> Result<(), SimulationError> {
        let (t, x) = (self.t, &self.x);
        self.row.clear();
        self.row.push(t);
        self.row.extend_from_slice(x);
        let start = self.row.len();
        self.row.resize(start + self.inputs, 0.0);
        self.system.inputs(t, x, &mut self.row[start..]);
        self.row.push(self.system.energy(x));
        self.row.push(self.system.constraint_residual(x));
        self.recorder
            .record(&self.row)
            .map_err(|source| SimulationError::Recording { t, source })
    }
}

/// `t`, the state's names, the inputs' names, `energy`,
/// `constraint_residual`.
fn columns<S: Observed<D>, const D: usize>(system: &S) -> Vec<String> {
    let mut columns = vec!["t".to_string()];
    columns.extend(system.state_names());
    columns.extend(system.input_names());
    columns.extend(["energy".to_string(), "constraint_residual".to_string()]);
    columns
}
