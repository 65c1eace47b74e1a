//! The simulation loop: a formulation closed by its controller (an
//! [`Observed`] system), an integrator ([`Advance`]), a time span and step,
//! an optional stop condition ([`StopCondition`]), and a [`Recorder`].
//!
//! ```text
//! Simulation::new(Midpoint::default()).span(0.0, 30.0).step(0.01)
//!     .run(&Reduced::new(&board, controller), x0, &mut CsvRecorder::create("trajectory.csv")?)
//! ```
//!
//! With [`Simulation::stop_when`] the run ends cleanly where a condition
//! `g(t, x) > 0` first holds, the crossing located within its step to
//! [`CROSSING_TOLERANCE`] in `t` ([`stop`]); the last row
//! recorded is the state there and [`Summary::stopped`] says why.
//!
//! At every step the loop checks the state is finite, the model's own
//! expressions inside their domain, and the formulation's regularity
//! measure ([`crate::monitor`]): the run stops with
//! [`SimulationError::Singular`], naming the time, the configuration, the
//! quantity and the constraint rows that turned dependent, when the measure
//! falls below the threshold or changes sign within a step (a signed
//! measure crossing zero between two steps), and with
//! [`SimulationError::Undefined`] where a guarded expression of the model
//! fails; a failed step is searched for what it crossed ([`ends`]). A
//! step on which the integrator fails where shorter steps may pass
//! (Newton's iteration diverging, a stage leaving the model's domain, on a
//! step too long for a fast motion) is first taken again as two halves,
//! each checked as a step and split the same way, at most [`HALVINGS`]
//! deep; the run goes on at its own step, and [`Summary::split_steps`]
//! counts the splits. The
//! rows recorded until then stay recorded and the recorder is finished
//! (flushed) on every exit.
//!
//! The summary counts what the integrator took ([`Summary::effort`]: steps
//! accepted and rejected, Newton iterations) and measures the energy drift
//! against the run's kinetic energy and the range of its potential
//! ([`Summary::energy_drift`], [`Summary::energy_scale`]), which a constant
//! added to the potential does not change.
//!
//! A system whose state's size is known only at run time runs through
//! [`Simulation::run_sized`] ([`sized`]), compiled here once for every such
//! system and integrator.
//!
//! A formulation with several charts (the reduced form of a model with
//! constraints: the charts derived at build time and the run-time charts
//! of [`crate::partition`]) is then asked to change its chart
//! ([`Observed::change_chart`], [`crate::system::next_chart`]): where the active chart's
//! pivot ratio is below [`crate::system::CHART_SWITCH`] times the best one's, the state
//! moves into the best chart through its velocity and the run goes on
//! there, in the run-time chart of partial pivoting where no derived chart
//! fits (the re-selection of independent coordinates of Wehage & Haug,
//! "Generalized coordinate partitioning for dimension reduction in analysis
//! of constrained dynamic systems", J. Mech. Design 104, 1982); a step that
//! fails for a reason not named is taken again in that chart. The switches
//! are counted in [`Summary::chart_switches`] and each row records its
//! chart.

mod advance;
mod drift;
pub mod ends;
mod observed;
mod outcome;
mod run;
pub mod sized;
pub mod stop;
mod work;

pub use advance::Advance;
pub use observed::{GuardedValue, MULTIPLIERS, Observed, RECONSTRUCTION, REDUCED, Regularity};
pub use outcome::{SimulationError, Summary};
pub use run::HALVINGS;
pub use sized::{RunTimeSized, SizedMethod, SizedStop, SliceSystem};
pub use stop::{CROSSING_TOLERANCE, Never, Stop, StopCondition};

use crate::record::Recorder;
use crate::state::State;
use run::Run;

/// A simulation's settings: the integrator, the time span, the step, how
/// often to record, the regularity threshold, and the stop condition `C`
/// ([`Never`] unless [`Simulation::stop_when`] sets one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Simulation<M, C = Never> {
    method: M,
    span: (f64, f64),
    step: f64,
    record_every: usize,
    singular_below: f64,
    condition: C,
}

impl<M> Simulation<M> {
    /// A run with `method` over `[0, 10]` with steps of `0.01`, recording
    /// every step, stopping where the regularity measure falls below `1e-6`,
    /// without a stop condition.
    pub fn new(method: M) -> Self {
        Self {
            method,
            span: (0.0, 10.0),
            step: 0.01,
            record_every: 1,
            singular_below: 1e-6,
            condition: Never,
        }
    }
}

impl<M, C> Simulation<M, C> {
    /// End the run cleanly where `condition` first holds (see [`stop`]):
    /// the crossing is located within its step, the last row recorded is
    /// the state there, and [`Summary::stopped`] is the condition's
    /// description.
    pub fn stop_when<E>(self, condition: E) -> Simulation<M, E> {
        Simulation {
            method: self.method,
            span: self.span,
            step: self.step,
            record_every: self.record_every,
            singular_below: self.singular_below,
            condition,
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

    /// Runs `system` from `x0` to the end of the span, or to where the stop
    /// condition first holds, recording into `recorder`.
    ///
    /// # Errors
    /// See [`SimulationError`]; the rows recorded before it stay recorded.
    pub fn run<S, R, X: State>(
        &self,
        system: &S,
        x0: X,
        recorder: &mut R,
    ) -> Result<Summary<X>, SimulationError>
    where
        S: Observed<X>,
        M: Advance<S, X>,
        C: StopCondition<X>,
        R: Recorder,
    {
        self.run_with_progress(system, x0, recorder, |_| {})
    }

    /// [`Simulation::run`], calling `progress` with the fraction of the span
    /// done after every recorded row.
    ///
    /// # Errors
    /// As [`Simulation::run`].
    pub fn run_with_progress<S, R, X: State>(
        &self,
        system: &S,
        x0: X,
        recorder: &mut R,
        progress: impl FnMut(f64),
    ) -> Result<Summary<X>, SimulationError>
    where
        S: Observed<X>,
        M: Advance<S, X>,
        C: StopCondition<X>,
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
