//! How a run ends: the [`Summary`] of a finished run (at the end of its
//! span, or where its stop condition came to hold), or the
//! [`SimulationError`] that stopped it.

use crate::integrate::{self, Effort};
use crate::projection::ProjectionError;

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
        "singular configuration at t = {t}: {}the {quantity} {} ({value:.3e}, threshold {threshold:.0e}) at {}",
        dependency(rows),
        if *crossed { "changed sign in the step to t" } else { "vanishes" },
        named(state_names, state)
    )]
    Singular {
        /// Time of the first state found singular.
        t: f64,
        /// The constraint rows that are dependent there (a singularity of
        /// the mechanics), none when they are independent.
        rows: Vec<String>,
        /// What degenerates.
        quantity: &'static str,
        /// Whether the measure changed sign in the step to `t` (a crossing)
        /// rather than fell below the threshold.
        crossed: bool,
        /// The regularity measure there.
        value: f64,
        /// The threshold it fell below.
        threshold: f64,
        /// The state's names.
        state_names: Vec<String>,
        /// The state.
        state: Vec<f64>,
    },
    /// A step left the domain of the model's own expressions, or came to
    /// its end: a square root or logarithm of a non-positive value, a
    /// divisor through zero, or one of them near zero where the step failed
    /// (`crate::system::Domain`, [`super::ends`]).
    #[error(
        "the model's domain ends {}: {expression} (it is {value:.3e}, {at_start:.3e} at the start) at {}",
        if *initial { format!("at the initial state, t = {t}") } else { format!("in the step from t = {t}") },
        named(state_names, state)
    )]
    Undefined {
        /// Time at the start of the step (the initial time for an initial
        /// state outside the domain).
        t: f64,
        /// Whether the initial state is outside the domain.
        initial: bool,
        /// The guarded expression, where it is and what must hold.
        expression: String,
        /// Its value at `state`.
        value: f64,
        /// Its value at the start of the run.
        at_start: f64,
        /// The state's names.
        state_names: Vec<String>,
        /// The state at which it fails: on the step's explicit predictor.
        state: Vec<f64>,
    },
    /// The state could not be kept on the constraint manifold.
    #[error("projection onto the constraints failed after the step to t = {t}: {source}")]
    Projection {
        /// Time of the state that could not be projected.
        t: f64,
        /// Which constraint, and why.
        source: ProjectionError,
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

impl SimulationError {
    /// The time at which the run stopped, if it started.
    pub fn time(&self) -> Option<f64> {
        match self {
            Self::Settings { .. } => None,
            Self::Integration(error) => Some(error.time()),
            Self::Singular { t, .. }
            | Self::Undefined { t, .. }
            | Self::Projection { t, .. }
            | Self::Recording { t, .. } => Some(*t),
        }
    }

    /// The state that caused the stop, where the error has it.
    pub fn state(&self) -> Option<&[f64]> {
        match self {
            Self::Integration(error) => Some(error.state()),
            Self::Singular { state, .. } | Self::Undefined { state, .. } => Some(state),
            Self::Settings { .. } | Self::Projection { .. } | Self::Recording { .. } => None,
        }
    }
}

/// `the constraint rows a, b are dependent: ` when some are.
fn dependency(rows: &[String]) -> String {
    match rows {
        [] => String::new(),
        rows => format!("the constraint rows {} are dependent: ", rows.join(", ")),
    }
}

/// `name = value, ...`, a value that is not finite as `name not finite`.
fn named(names: &[String], values: &[f64]) -> String {
    let pairs: Vec<String> = names
        .iter()
        .zip(values)
        .map(|(name, value)| match value.is_finite() {
            true => format!("{name} = {value:.6}"),
            false => format!("{name} not finite"),
        })
        .collect();
    pairs.join(", ")
}

/// What a finished run measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary<X> {
    /// Steps taken.
    pub steps: usize,
    /// The final time.
    pub t: f64,
    /// The final state.
    pub state: X,
    /// The largest `|E(t) - E(0)|` over the steps, relative to
    /// [`Summary::energy_scale`] (absolute where that is 0).
    pub energy_drift: f64,
    /// The largest `|E(t) - E(0) - W(t)|` over the steps, relative as
    /// [`Summary::energy_drift`]: the energy gained less the work `W` the
    /// inputs did ([`super::Observed::input_power`]), integrated step by
    /// step by the three-point rule (the quadratic through the last three
    /// states), a third-order quadrature.
    pub power_balance: f64,
    /// The scale of [`Summary::energy_drift`]: the largest kinetic energy
    /// `T = E - V` over the steps plus the range of the energy at rest `V`
    /// ([`super::Observed::energy_at_rest`]), which a constant added to the
    /// potential does not change.
    pub energy_scale: f64,
    /// Whether the inputs delivered power at some state: the run's
    /// energy then changes by their work, and [`Summary::power_balance`]
    /// is the check.
    pub worked: bool,
    /// The largest constraint residual over the steps.
    pub max_constraint_residual: f64,
    /// The largest `|f(q)|` of the configuration constraints over the steps
    /// (0 when the system keeps none).
    pub max_holonomic_residual: f64,
    /// The smallest `|regularity|` over the steps.
    pub min_regularity: f64,
    /// How often the run changed the chart of D
    /// ([`super::Observed::change_chart`]).
    pub chart_switches: usize,
    /// How many times a step failed and was taken again as two halves
    /// ([`super::HALVINGS`]): 0 where every step passed whole.
    pub split_steps: usize,
    /// The integrator's steps accepted and rejected and its Newton
    /// iterations, over the whole run (a crossing's search included): for
    /// a fixed-step method one accepted step per step of the run and one
    /// rejected per split; for an adaptive one as many as its tolerance
    /// needs.
    pub effort: Effort,
    /// Whether an input was not zero at a recorded state: a run without
    /// inputs, or whose inputs stayed zero, conserves its energy (the
    /// model language declares no dissipation), so that
    /// [`Summary::energy_drift`] is the integrator's error.
    pub forced: bool,
    /// Why the run ended before the end of its span: the description of
    /// the stop condition that came to hold at [`Summary::t`]
    /// ([`super::Simulation::stop_when`]); `None` for a run to the end.
    pub stopped: Option<String>,
}

#[cfg(test)]
mod tests {
    use super::SimulationError;
    use crate::integrate;

    /// Each error with a time and a state gives them; the others say what
    /// they lack.
    #[test]
    fn an_error_names_the_time_and_the_state_that_stopped_the_run() {
        let singular = SimulationError::Singular {
            t: 0.5,
            rows: vec!["front".into(), "back".into()],
            quantity: "det",
            crossed: true,
            value: 1e-9,
            threshold: 1e-8,
            state_names: vec!["x".into(), "phi".into()],
            state: vec![0.25, 1.57],
        };
        assert_eq!(singular.time(), Some(0.5));
        assert_eq!(singular.state(), Some(&[0.25, 1.57][..]));
        let underflow = SimulationError::from(integrate::Error::StepSizeUnderflow {
            t: 2.0,
            h: 1e-15,
            state: vec![3.0],
        });
        assert_eq!(underflow.time(), Some(2.0));
        assert_eq!(underflow.state(), Some(&[3.0][..]));
        let settings = SimulationError::Settings {
            reason: "negative span".into(),
        };
        assert_eq!((settings.time(), settings.state()), (None, None));
    }
}
