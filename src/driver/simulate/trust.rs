//! Whether a finished run can be trusted (docs/INTERFACE.md section 12):
//! the tolerance that bounds each step's local error also bounds what the
//! whole run may lose. A conservative run (every input zero: the model
//! language declares no dissipation) keeps its energy, so its relative
//! energy drift is the integrators' error; the constraint residual
//! `|A(q) qdot|` is zero on an exact motion. Either beyond [`ALLOWANCE`]
//! times the tolerance is a [`Warning`]: the command line prints it on
//! stderr (an error with `--strict`), Python raises a `RuntimeWarning`.

use super::request::Integrator;
use super::run::{RELATIVE, Report};

/// How many times the tolerance the energy drift and the constraint
/// residual of a run may reach: each step's local error is within the
/// tolerance, and a run of many steps accumulates a few of them (the
/// benchmark bicycle's fall to a lean of 1.2 at the default tolerance
/// 1e-8: a drift of 2e-8 with dopri5, 8e-8 with rk4).
pub const ALLOWANCE: f64 = 100.0;

/// What makes a finished run untrustworthy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Warning {
    /// A conservative run's relative energy drift beyond what the tolerance
    /// allows.
    EnergyDrift {
        /// The drift.
        drift: f64,
        /// What the tolerance allows.
        allowed: f64,
    },
    /// A constraint residual, of the velocity constraints or of the
    /// configuration constraints, beyond what the tolerance allows.
    ConstraintResidual {
        /// The largest residual met.
        residual: f64,
        /// What the tolerance allows.
        allowed: f64,
    },
}

impl Report {
    /// What the tolerance does not allow in this run: the energy drift of a
    /// conservative run above [`ALLOWANCE`] `max(rtol, atol)`, the
    /// constraint residuals (`|A(q) qdot|`, and `|f(q)|` with configuration
    /// constraints) above [`ALLOWANCE`] `max(rtol, atol)` times the
    /// final state's scale (at least 1).
    pub fn warnings(&self) -> Vec<Warning> {
        let allowed = ALLOWANCE * self.tolerance.rtol.max(self.tolerance.atol);
        let mut warnings = Vec::new();
        if self.conservative && beyond(self.energy_drift, allowed) {
            warnings.push(Warning::EnergyDrift {
                drift: self.energy_drift,
                allowed,
            });
        }
        let residual_allowed = allowed * self.final_scale.max(1.0);
        let residuals = [
            Some(self.max_constraint_residual),
            self.max_holonomic_residual,
        ];
        for residual in residuals.into_iter().flatten() {
            if beyond(residual, residual_allowed) {
                warnings.push(Warning::ConstraintResidual {
                    residual,
                    allowed: residual_allowed,
                });
            }
        }
        warnings
    }

    /// The warning's line, with what to change: a smaller step or
    /// tolerance, another integrator.
    pub fn explain(&self, warning: &Warning) -> String {
        let change = if self.fixed_step {
            "a smaller --dt, or steps following the tolerance (without --fixed-step)"
        } else {
            "a smaller --rtol and --atol"
        };
        let other = match self.integrator {
            Integrator::DiscreteGradient => "another integrator",
            _ => "another integrator (discrete-gradient keeps the energy of the reduced form)",
        };
        let (what, value, allowed) = match *warning {
            Warning::EnergyDrift { drift, allowed } => {
                ("energy drift of a run without inputs", drift, allowed)
            }
            Warning::ConstraintResidual { residual, allowed } => {
                ("constraint residual", residual, allowed)
            }
        };
        let relative = match warning {
            Warning::EnergyDrift { .. } => format!(" ({RELATIVE})"),
            Warning::ConstraintResidual { .. } => String::new(),
        };
        format!(
            "warning: {what} {value:.3e}{relative} exceeds {allowed:.1e}, {ALLOWANCE} times the tolerance \
             (--rtol {:e}, --atol {:e}): the run is not accurate to its tolerance; try {change}, \
             or {other}",
            self.tolerance.rtol, self.tolerance.atol
        )
    }
}

/// Whether `value` exceeds `allowed` or is not a number.
fn beyond(value: f64, allowed: f64) -> bool {
    value > allowed || value.is_nan()
}

#[cfg(test)]
mod tests {
    use super::{ALLOWANCE, Warning};
    use crate::driver::simulate::{Integrator, Report, Tolerance};
    use crate::runtime::integrate::Effort;

    /// A finished run at the default tolerance with the given drift and
    /// residuals.
    fn report(conservative: bool, drift: f64, residual: f64, holonomic: Option<f64>) -> Report {
        Report {
            integrator: Integrator::Rk4,
            engine: "jit",
            steps: 10,
            t: 0.1,
            energy_drift: drift,
            power_balance: drift,
            energy_scale: 1.0,
            worked: !conservative,
            max_constraint_residual: residual,
            max_holonomic_residual: holonomic,
            chart_switches: 0,
            split_steps: 0,
            effort: Effort::default(),
            stopped: None,
            seconds: 0.0,
            tolerance: Tolerance::new(1e-8, 1e-9).expect("tolerances"),
            fixed_step: false,
            conservative,
            final_scale: 10.0,
        }
    }

    /// The energy drift counts only where the run is conservative; the
    /// residuals are judged against the tolerance times the state's scale
    /// (here 10); NaN is beyond any bound.
    #[test]
    fn each_quantity_is_judged_against_its_bound() {
        let allowed = ALLOWANCE * 1e-8;
        assert_eq!(report(true, 0.5 * allowed, 0.0, None).warnings(), []);
        assert_eq!(
            report(true, 2.0 * allowed, 0.0, None).warnings(),
            [Warning::EnergyDrift {
                drift: 2.0 * allowed,
                allowed
            }]
        );
        assert_eq!(report(false, 1.0, 0.0, None).warnings(), []);
        assert_eq!(report(true, 0.0, 5.0 * allowed, Some(0.0)).warnings(), []);
        assert_eq!(
            report(false, 0.0, 0.0, Some(20.0 * allowed)).warnings(),
            [Warning::ConstraintResidual {
                residual: 20.0 * allowed,
                allowed: 10.0 * allowed
            }]
        );
        assert_eq!(report(true, f64::NAN, f64::NAN, None).warnings().len(), 2);
        let line = report(true, 1.0, 0.0, None);
        let warning = line.warnings()[0];
        let text = line.explain(&warning);
        assert!(
            text.starts_with(
                "warning: energy drift of a run without inputs 1.000e0 (relative to max T + range V) exceeds 1.0e-6"
            ),
            "{text}"
        );
        assert!(text.contains("a smaller --rtol and --atol"), "{text}");
    }
}
