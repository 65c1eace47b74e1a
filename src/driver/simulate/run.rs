//! A run: the simulation loop on the state's run-time size with the chosen
//! integrator and stop condition, recording every row, and its
//! [`Report`].

use super::request::{Integrator, Request};
use crate::driver::Failure;
use crate::driver::formulation::Formulation;
use crate::driver::setup::InputError;
use crate::driver::setup::stop::{Comparison, stop_condition};
use crate::runtime::integrate::{
    Controlled, DiscreteGradient, DormandPrince, Effort, Midpoint, Rk4,
};
use crate::runtime::record::{Recorder, Table};
use crate::runtime::simulate::{Simulation, SizedMethod, StopCondition};
use std::io;
use std::time::Instant;

/// What a run is made with: the integrator, the span, the largest step,
/// the tolerances (unless the steps are fixed), and the stop condition.
pub(super) struct Settings {
    integrator: Integrator,
    t_end: f64,
    dt: f64,
    tolerance: Tolerance,
    fixed_step: bool,
    stop: Option<Comparison>,
}

/// The tolerances of each step's local error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Relative.
    pub rtol: f64,
    /// Absolute.
    pub atol: f64,
}

impl Tolerance {
    /// `rtol` and `atol` when both are finite and not negative and one is
    /// positive.
    ///
    /// # Errors
    /// [`InputError::Unsupported`] naming the tolerance that is not.
    pub fn new(rtol: f64, atol: f64) -> Result<Self, InputError> {
        for (name, value) in [("rtol", rtol), ("atol", atol)] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(InputError::Unsupported(format!(
                    "--{name} {value}: a tolerance is a finite number, not negative"
                )));
            }
        }
        if rtol == 0.0 && atol == 0.0 {
            return Err(InputError::Unsupported(
                "--rtol and --atol are both 0: one of them must be positive".into(),
            ));
        }
        Ok(Self { rtol, atol })
    }

    /// `method` with its step following these tolerances.
    fn control<M>(self, method: M) -> Controlled<M> {
        Controlled::new(method, self.rtol, self.atol)
    }
}

/// What the energy drift and the power balance are relative to: the
/// largest kinetic energy `T` of the run plus the range of its potential
/// energy `V`, which a constant added to `V` does not change.
pub const RELATIVE: &str = "relative to max T + range V";

/// What a finished run reports.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// The integrator that ran.
    pub integrator: Integrator,
    /// What ran the model's functions (`jit`, `interpret`).
    pub engine: &'static str,
    /// The steps taken.
    pub steps: usize,
    /// The time reached.
    pub t: f64,
    /// The largest change of the energy, relative to
    /// [`Report::energy_scale`].
    pub energy_drift: f64,
    /// The largest energy gained less the inputs' work, relative to
    /// [`Report::energy_scale`] (see
    /// `chaplygin_runtime::simulate::Summary::power_balance`).
    pub power_balance: f64,
    /// The largest kinetic energy plus the range of the potential energy
    /// (see `chaplygin_runtime::simulate::Summary::energy_scale`).
    pub energy_scale: f64,
    /// Whether the inputs did work: the summary then reports the power
    /// balance instead of the energy drift.
    pub worked: bool,
    /// The largest `|A(q) qdot|` met.
    pub max_constraint_residual: f64,
    /// The largest `|f(q)|` met, with configuration constraints.
    pub max_holonomic_residual: Option<f64>,
    /// How many times the run changed chart.
    pub chart_switches: usize,
    /// How many times a fixed step failed and was taken again as two
    /// halves (see `chaplygin_runtime::simulate::Advanced`).
    pub split_steps: usize,
    /// The integrator's steps accepted and rejected and its Newton
    /// iterations (see `chaplygin_runtime::simulate::Summary::effort`).
    pub effort: Effort,
    /// The stop condition that ended the run, as given.
    pub stopped: Option<String>,
    /// The wall time of the run, in seconds.
    pub seconds: f64,
    /// The tolerances the steps followed, or judging the fixed steps.
    pub tolerance: Tolerance,
    /// Whether the steps were fixed (`--fixed-step`).
    pub fixed_step: bool,
    /// Whether every input was zero at every recorded state, so that the
    /// energy is conserved (see `chaplygin_runtime::simulate::Summary::forced`).
    pub conservative: bool,
    /// The largest absolute entry of the final state, the scale of the
    /// constraint residual.
    pub final_scale: f64,
}

impl Report {
    /// The report of a run with prescribed coordinates when `prescribed`:
    /// their forces do work, so it reports the power balance and is not
    /// judged as conservative.
    pub(super) fn driven(mut self, prescribed: bool) -> Report {
        self.worked |= prescribed;
        self.conservative &= !prescribed;
        self
    }
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "t = {}: {} steps of {} in {:.3} s, engine {}; ",
            self.t,
            self.steps,
            self.integrator.name(),
            self.seconds,
            self.engine,
        )?;
        let Effort {
            accepted,
            rejected,
            newton_iterations,
        } = self.effort;
        write!(
            f,
            "steps {accepted} accepted, {rejected} rejected, {newton_iterations} Newton iterations; "
        )?;
        match self.worked {
            true => write!(f, "power balance {:.3e} ({RELATIVE})", self.power_balance)?,
            false => write!(f, "energy drift {:.3e} ({RELATIVE})", self.energy_drift)?,
        }
        write!(
            f,
            "; max constraint residual {:.3e}",
            self.max_constraint_residual
        )?;
        if let Some(residual) = self.max_holonomic_residual {
            write!(f, "; max holonomic residual {residual:.3e}")?;
        }
        write!(f, "; chart switches {}", self.chart_switches)?;
        if self.split_steps > 0 {
            write!(f, "; steps split {}", self.split_steps)?;
        }
        if let Some(condition) = &self.stopped {
            write!(f, "; stopped at t = {}: {condition}", self.t)?;
        }
        Ok(())
    }
}

impl Settings {
    /// The settings of `request` for `formulation`, with its `stop`
    /// condition: the integrator chosen, or the formulation's default (see
    /// [`Integrator::chosen_or_default`]).
    ///
    /// # Errors
    /// Tolerances that are not, or the discrete gradient on a formulation
    /// without structure.
    pub(super) fn new(
        request: &Request,
        formulation: &dyn Formulation,
        stop: Option<&Comparison>,
    ) -> Result<Self, Failure> {
        let stop = stop.cloned();
        let structured = formulation.is_structured();
        let integrator = Integrator::chosen_or_default(request.integrator, structured);
        if integrator == Integrator::DiscreteGradient && !structured {
            return Err(InputError::Unsupported(
                "the discrete-gradient integrator needs the structured (reduced) form: use --formulation reduced".into(),
            )
            .into());
        }
        if request.fixed_step && integrator == Integrator::Dopri5 {
            return Err(InputError::Unsupported(
                "dopri5 always follows the tolerance: --fixed-step takes rk4, midpoint or discrete-gradient".into(),
            )
            .into());
        }
        Ok(Self {
            integrator,
            t_end: request.t_end,
            dt: request.dt,
            tolerance: Tolerance::new(request.rtol, request.atol)?,
            fixed_step: request.fixed_step,
            stop,
        })
    }

    /// Runs `formulation` from `x0` into `recorder`, on states of the size
    /// `x0` has.
    ///
    /// # Errors
    /// The run's failure.
    pub(super) fn run(
        &self,
        formulation: &dyn Formulation,
        x0: &[f64],
        recorder: &mut Both<'_>,
        progress: &mut dyn FnMut(f64),
    ) -> Result<Report, Failure> {
        let x0 = x0.to_vec();
        let stop = self
            .stop
            .as_ref()
            .map(|comparison| stop_condition(formulation, comparison));
        let holonomic = formulation.holonomic_residual(&x0).is_some();
        let started = Instant::now();
        let summary = Simulation::new(self.method())
            .span(0.0, self.t_end)
            .step(self.dt)
            .stop_when(
                stop.as_ref()
                    .map(|stop| stop as &dyn StopCondition<Vec<f64>>),
            )
            .run_sized(formulation, x0, recorder, progress)?;
        Ok(Report {
            integrator: self.integrator,
            engine: formulation.engine(),
            steps: summary.steps,
            t: summary.t,
            energy_drift: summary.energy_drift,
            power_balance: summary.power_balance,
            energy_scale: summary.energy_scale,
            worked: summary.worked,
            max_constraint_residual: summary.max_constraint_residual,
            max_holonomic_residual: holonomic.then_some(summary.max_holonomic_residual),
            chart_switches: summary.chart_switches,
            split_steps: summary.split_steps,
            effort: summary.effort,
            stopped: summary.stopped,
            seconds: started.elapsed().as_secs_f64(),
            tolerance: self.tolerance,
            fixed_step: self.fixed_step,
            conservative: !summary.forced,
            final_scale: summary.state.iter().fold(0.0, |m: f64, v| m.max(v.abs())),
        })
    }

    /// The integrator, its step fixed or following the tolerances.
    fn method(&self) -> SizedMethod {
        match (self.integrator, self.fixed_step) {
            (Integrator::Rk4, true) => SizedMethod::Rk4(Rk4),
            (Integrator::Rk4, false) => SizedMethod::ControlledRk4(self.tolerance.control(Rk4)),
            (Integrator::Midpoint, true) => SizedMethod::Midpoint(Midpoint::default()),
            (Integrator::Midpoint, false) => {
                SizedMethod::ControlledMidpoint(self.tolerance.control(Midpoint::default()))
            }
            (Integrator::DiscreteGradient, true) => {
                SizedMethod::DiscreteGradient(DiscreteGradient::default())
            }
            (Integrator::DiscreteGradient, false) => SizedMethod::ControlledDiscreteGradient(
                self.tolerance.control(DiscreteGradient::default()),
            ),
            (Integrator::Dopri5, _) => SizedMethod::DormandPrince(DormandPrince {
                rtol: self.tolerance.rtol,
                atol: self.tolerance.atol,
                ..DormandPrince::default()
            }),
        }
    }
}

/// A recorder writing into a table and another recorder.
pub(super) struct Both<'a>(pub &'a mut Table, pub &'a mut dyn Recorder);

impl Recorder for Both<'_> {
    fn start(&mut self, columns: &[String]) -> io::Result<()> {
        self.0.start(columns)?;
        self.1.start(columns)
    }

    fn record(&mut self, row: &[f64]) -> io::Result<()> {
        self.0.record(row)?;
        self.1.record(row)
    }

    fn finish(&mut self) -> io::Result<()> {
        self.0.finish()?;
        self.1.finish()
    }
}
