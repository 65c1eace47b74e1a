//! A step the integrator fails on is taken again in halves where shorter
//! steps pass, and ends the run where none does (`simulate`, "the
//! simulation loop"), on `xdot = -sqrt(x)`: from `x = 1`,
//! `sqrt(x) = 1 - t/2`, so `x` reaches 0 at `t = 2`, and the right-hand
//! side is NaN below 0.

use chaplygin_runtime::integrate::{Effort, Error, FixedStep, NonFiniteCause, Rk4};
use chaplygin_runtime::record::Table;
use chaplygin_runtime::simulate::{HALVINGS, Observed, Regularity, Simulation, SimulationError};
use chaplygin_runtime::system::{Energy, OdeSystem};

pub(crate) struct Draining;

impl OdeSystem<[f64; 1]> for Draining {
    fn rhs(&self, _t: f64, x: &[f64; 1]) -> [f64; 1] {
        [-x[0].sqrt()]
    }
}

impl Energy<[f64; 1]> for Draining {
    fn energy(&self, x: &[f64; 1]) -> f64 {
        x[0]
    }
}

impl Observed<[f64; 1]> for Draining {
    fn state_names(&self) -> Vec<String> {
        vec!["x".into()]
    }

    fn input_names(&self) -> Vec<String> {
        Vec::new()
    }

    fn inputs(&self, _t: f64, _x: &[f64; 1], _inputs: &mut [f64]) {}

    /// No inputs, no work.
    fn input_power(&self, _t: f64, _x: &[f64; 1]) -> f64 {
        0.0
    }

    fn configuration_velocity(&self, x: &[f64; 1], q: &mut [f64], qdot: &mut [f64]) {
        (q[0], qdot[0]) = (x[0], -x[0].sqrt());
    }

    fn constraint_residual(&self, _x: &[f64; 1]) -> f64 {
        0.0
    }

    fn regularity(&self, _x: &[f64; 1]) -> Regularity {
        Regularity {
            quantity: "none",
            value: 1.0,
            signed: false,
        }
    }
}

/// One RK4 step of 1.5 from `x = 1` puts its last stage at about
/// `1 - 1.5 * 0.79 < 0`; two steps of 0.75 stay inside. The run's one step
/// is those two steps exactly, near the solution `x(1.5) = 0.0625`.
#[test]
fn a_step_that_leaves_the_domain_is_taken_in_halves() {
    let whole = Rk4.step(&Draining, 0.0, &[1.0], 1.5);
    assert!(matches!(
        whole,
        Err(Error::NonFinite {
            cause: NonFiniteCause::RightHandSide,
            ..
        })
    ));
    let half = Rk4.step(&Draining, 0.0, &[1.0], 0.75).unwrap();
    let halves = Rk4.step(&Draining, 0.75, &half, 0.75).unwrap();
    let summary = Simulation::new(Rk4)
        .span(0.0, 1.5)
        .step(1.5)
        .run(&Draining, [1.0], &mut Table::new())
        .unwrap();
    assert_eq!((summary.steps, summary.split_steps), (1, 1));
    let effort = Effort {
        accepted: 2,
        rejected: 1,
        newton_iterations: 0,
    };
    assert_eq!(summary.effort, effort);
    assert_eq!(summary.state, halves);
    assert!(
        (summary.state[0] - 0.0625).abs() < 0.02,
        "{:?}",
        summary.state
    );
}

/// A step past the end fails however short its parts: the run ends with
/// the shortest failed part's error, a step of `2^-HALVINGS` of the run's
/// own, where the approximate solution reaches 0 (near `t = 2`).
#[test]
fn a_step_past_the_end_fails_at_its_shortest_part() {
    let error = Simulation::new(Rk4)
        .span(0.0, 3.0)
        .step(3.0)
        .run(&Draining, [1.0], &mut Table::new())
        .unwrap_err();
    let SimulationError::Integration(Error::NonFinite { t, h, .. }) = error else {
        panic!("{error:?}")
    };
    assert_eq!(h, 3.0 / f64::from(1 << HALVINGS));
    assert!(t > 1.9 && t < 2.1, "{t}");
}
