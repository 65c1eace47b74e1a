//! A run in progress: the loop that advances, stops where the stop
//! condition comes to hold, checks the regularity, updates the summary and
//! records.

use super::drift::Drift;
use super::ends::Ends;
use super::work::Work;
use super::{
    Advance, CROSSING_TOLERANCE, Observed, Regularity, Simulation, SimulationError, StopCondition,
    Summary,
};
use crate::integrate::{self, Effort};
use crate::record::Recorder;
use crate::state::State;
use std::cell::Cell;

/// How many times a step is halved at most where the integrator fails on
/// it and shorter steps may pass (see [`super::Summary::split_steps`]):
/// down to `2^-10` of the step. Each part is checked as a step (projected,
/// inside the model's domain), so a split never carries a run past the
/// end of its model; where even the shortest parts fail, the error is the
/// shortest failed part's, at its own time and state.
pub const HALVINGS: u32 = 10;

/// A state a step reached, and how many times the step was split in two
/// to reach it.
pub(super) struct Stepped<X> {
    pub(super) x: X,
    pub(super) splits: usize,
}

/// A run in progress.
pub(super) struct Run<'a, M, C, S, R, X> {
    settings: &'a Simulation<M, C>,
    system: &'a S,
    pub(super) recorder: &'a mut R,
    pub(super) t: f64,
    x: X,
    drift: Drift,
    work: Work,
    ends: Ends<'a, S, X>,
    regularity: Regularity,
    row: Vec<f64>,
    inputs: usize,
    /// What the integrator took so far (kept apart from the summary,
    /// which the steps read while they count).
    effort: Cell<Effort>,
    pub(super) summary: Summary<X>,
}

impl<'a, M, C, S, R, X: State> Run<'a, M, C, S, R, X>
where
    S: Observed<X>,
    M: Advance<S, X>,
    C: StopCondition<X>,
    R: Recorder,
{
    /// The run at its first state, recorded; stopped already where the
    /// stop condition holds there.
    pub(super) fn start(
        settings: &'a Simulation<M, C>,
        system: &'a S,
        x0: X,
        recorder: &'a mut R,
    ) -> Result<Self, SimulationError> {
        let t0 = settings.span.0;
        let ends = Ends::new(system, &x0, settings.singular_below);
        ends.at_start(t0, &x0)?;
        let x = integrate::finite_start(t0, x0)?;
        let columns = columns(system, &x);
        let regularity = system.regularity(&x);
        let mut run = Self {
            settings,
            system,
            t: t0,
            drift: Drift::start(system.energy(&x), system.energy_at_rest(&x)),
            work: Work::start(t0, system.input_power(t0, &x)),
            ends,
            regularity,
            row: Vec::with_capacity(columns.len()),
            inputs: system.input_names().len(),
            effort: Cell::default(),
            summary: Summary {
                steps: 0,
                t: t0,
                state: x.clone(),
                energy_drift: 0.0,
                power_balance: 0.0,
                energy_scale: 0.0,
                worked: false,
                max_constraint_residual: system.constraint_residual(&x),
                max_holonomic_residual: system.holonomic_residual(&x).unwrap_or(0.0),
                min_regularity: regularity.value.abs(),
                chart_switches: 0,
                split_steps: 0,
                effort: Effort::default(),
                forced: false,
                stopped: None,
            },
            x,
            recorder,
        };
        run.recorder
            .start(&columns)
            .map_err(|source| SimulationError::Recording { t: t0, source })?;
        run.check(run.regularity)?;
        run.record()?;
        if run.holds(t0, &run.x) {
            run.stop();
        }
        Ok(run)
    }

    /// The steps to the end of the span, or to where the stop condition
    /// comes to hold.
    pub(super) fn advance_all(
        &mut self,
        steps: usize,
        mut progress: impl FnMut(f64),
    ) -> Result<(), SimulationError> {
        let (t0, t_end) = self.settings.span;
        for i in 1..=steps {
            if self.summary.stopped.is_some() {
                break;
            }
            let t_next = if i == steps {
                t_end
            } else {
                t0 + i as f64 * self.settings.step
            };
            let t = self.t;
            let stepped = self.step_or_fall_back(t_next)?;
            self.summary.split_steps += stepped.splits;
            let mut end = (t_next, stepped.x);
            let stops = self.holds(end.0, &end.1);
            if stops {
                end = self.crossing(t_next, end.1)?;
            }
            let regularity = self.system.regularity(&end.1);
            let previous = core::mem::replace(&mut self.x, end.1);
            self.t = end.0;
            self.check(regularity)
                .map_err(|singular| self.ends.explain(t, &previous, end.0 - t, singular))?;
            self.regularity = regularity;
            self.change_chart();
            self.update_summary(i);
            if stops || i % self.settings.record_every == 0 || i == steps {
                self.record()?;
                progress((self.t - t0) / (t_end - t0));
            }
            if stops {
                self.stop();
            }
        }
        Ok(())
    }

    /// The state at `t_next` advanced from the current one (see
    /// [`Run::step_from`]).
    fn step_to(&self, t_next: f64) -> Result<Stepped<X>, SimulationError> {
        self.step_from(self.t, &self.x, t_next, HALVINGS)
    }

    /// The method's advance from `x` at `t` to `t_next`, its steps and
    /// Newton iterations counted in the summary.
    fn advance(&self, t: f64, x: &X, t_next: f64) -> Result<X, integrate::Error> {
        let mut effort = self.effort.get();
        let advanced = (self.settings.method).advance(self.system, (t, x), t_next, &mut effort);
        self.effort.set(effort);
        advanced
    }

    /// The state at `t_next` advanced from `x` at `t` and projected onto
    /// the constraints ([`Observed::project`]), inside the model's domain;
    /// where the integrator fails and shorter steps may pass
    /// ([`integrate::Error::may_pass_in_shorter_steps`]), taken as two
    /// halves, each split the same way, at most `halvings` deep, and each
    /// checked as a step; a failure explained where its cause is known
    /// ([`Ends`]).
    fn step_from(
        &self,
        t: f64,
        x: &X,
        t_next: f64,
        halvings: u32,
    ) -> Result<Stepped<X>, SimulationError> {
        let h = t_next - t;
        let advanced = match self.advance(t, x, t_next) {
            Ok(advanced) => advanced,
            Err(error) if halvings > 0 && error.may_pass_in_shorter_steps() => {
                let middle = 0.5 * (t + t_next);
                let first = self.step_from(t, x, middle, halvings - 1)?;
                let second = self.step_from(middle, &first.x, t_next, halvings - 1)?;
                return Ok(Stepped {
                    x: second.x,
                    splits: 1 + first.splits + second.splits,
                });
            }
            Err(error) => return Err(self.ends.explain(t, x, h, error.into())),
        };
        let next = self.system.project(advanced).map_err(|source| {
            let projection = SimulationError::Projection { t: t_next, source };
            self.ends.explain(t, x, h, projection)
        })?;
        self.ends.reached(t, x, &next)?;
        Ok(Stepped { x: next, splits: 0 })
    }

    /// [`Run::step_to`], taken again in the run-time chart partial
    /// pivoting picks where it fails in another chart for a reason not
    /// named ([`Observed::change_to_pivoted_chart`]; the change counts as a
    /// switch).
    fn step_or_fall_back(&mut self, t_next: f64) -> Result<Stepped<X>, SimulationError> {
        match self.step_to(t_next) {
            Err(SimulationError::Integration(_) | SimulationError::Projection { .. })
                if self.system.change_to_pivoted_chart(&mut self.x) =>
            {
                self.summary.chart_switches += 1;
                self.regularity = self.system.regularity(&self.x);
                self.step_to(t_next)
            }
            step => step,
        }
    }

    /// Whether the stop condition holds at `(t, x)`.
    fn holds(&self, t: f64, x: &X) -> bool {
        self.settings.condition.value(t, x) > 0.0
    }

    /// Where the stop condition comes to hold in the step from the current
    /// state to `(t_next, x_next)`, where it holds: the step's length
    /// bisected to [`CROSSING_TOLERANCE`], each trial state advanced from
    /// the step's start; the first time found to hold and its state.
    fn crossing(&self, t_next: f64, x_next: X) -> Result<(f64, X), SimulationError> {
        let (mut below, mut above) = (0.0, t_next - self.t);
        let mut found = (t_next, x_next);
        while above - below > CROSSING_TOLERANCE {
            let length = 0.5 * (below + above);
            let t = self.t + length;
            let x = self.step_to(t)?.x;
            if self.holds(t, &x) {
                (above, found) = (length, (t, x));
            } else {
                below = length;
            }
        }
        Ok(found)
    }

    /// Ends the run where it is, saying why in the summary.
    fn stop(&mut self) {
        let description = self.settings.condition.description();
        self.summary.stopped = Some(description.to_string());
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
            rows: self.system.dependent_rows(&self.x),
            quantity: regularity.quantity,
            crossed: !vanishes,
            value: regularity.value,
            threshold: self.settings.singular_below,
            state_names: self.system.state_names(),
            state: self.x.as_ref().to_vec(),
        })
    }

    /// Changes the chart where the active one degenerates
    /// ([`Observed::change_chart`]), counting the switch; the sign of the
    /// regularity measure is compared in the new chart from then on.
    fn change_chart(&mut self) {
        if self.system.change_chart(&mut self.x) {
            self.summary.chart_switches += 1;
            self.regularity = self.system.regularity(&self.x);
        }
    }

    fn update_summary(&mut self, steps: usize) {
        let energy = self.system.energy(&self.x);
        let power = self.system.input_power(self.t, &self.x);
        self.work.advance(self.t, power);
        let at_rest = self.system.energy_at_rest(&self.x);
        self.drift.observe(energy, at_rest, self.work.total());
        let summary = &mut self.summary;
        summary.energy_drift = self.drift.energy_drift();
        summary.power_balance = self.drift.power_balance();
        summary.energy_scale = self.drift.scale();
        summary.worked |= power != 0.0;
        summary.steps = steps;
        summary.t = self.t;
        summary.state.clone_from(&self.x);
        summary.max_constraint_residual = summary
            .max_constraint_residual
            .max(self.system.constraint_residual(&self.x));
        if let Some(residual) = self.system.holonomic_residual(&self.x) {
            summary.max_holonomic_residual = summary.max_holonomic_residual.max(residual);
        }
        summary.min_regularity = summary.min_regularity.min(self.regularity.value.abs());
        summary.effort = self.effort.get();
    }

    fn record(&mut self) -> Result<(), SimulationError> {
        let (t, x) = (self.t, &self.x);
        self.row.clear();
        self.row.push(t);
        self.row.extend_from_slice(x.as_ref());
        let start = self.row.len();
        self.row.resize(start + self.inputs, 0.0);
        self.system.inputs(t, x, &mut self.row[start..]);
        self.summary.forced |= self.row[start..].iter().any(|u| *u != 0.0);
        self.row.push(self.system.energy(x));
        self.row.push(self.system.constraint_residual(x));
        self.row.extend(self.system.holonomic_residual(x));
        self.row
            .extend(self.system.chart().map(|chart| chart as f64));
        self.recorder
            .record(&self.row)
            .map_err(|source| SimulationError::Recording { t, source })
    }
}

/// `t`, the state's names, the inputs' names, `energy`,
/// `constraint_residual`, `holonomic_residual` when the system keeps
/// configuration constraints, and `chart` when it has several charts.
fn columns<S: Observed<X>, X: State>(system: &S, x: &X) -> Vec<String> {
    let mut columns = vec!["t".to_string()];
    columns.extend(system.state_names());
    columns.extend(system.input_names());
    columns.extend(["energy".to_string(), "constraint_residual".to_string()]);
    if system.holonomic_residual(x).is_some() {
        columns.push("holonomic_residual".to_string());
    }
    if system.chart().is_some() {
        columns.push("chart".to_string());
    }
    columns
}
