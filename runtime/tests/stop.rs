//! Stop conditions against closed forms: a run ends where its condition
//! first holds, the crossing located within its step to 1e-9 in t by every
//! integrator, the last row recorded there, and a condition that holds at
//! the start stops the run there.

use chaplygin_runtime::integrate::{DiscreteGradient, DormandPrince, Midpoint, Rk4};
use chaplygin_runtime::record::Table;
use chaplygin_runtime::simulate::{
    Advance, Observed, Regularity, Simulation, Stop, StopCondition, Summary,
};
use chaplygin_runtime::system::{Energy, Jacobian, OdeSystem, Structured};

/// A body thrown up against gravity: `qdot = p`, `pdot = -G`, in the
/// structure `J = [[0, 1], [-1, 0]]` of `H = p^2/2 + G q`. Its motion
/// `q = q0 + p0 t - G t^2/2` is a polynomial of degree 2, which every
/// integrator here follows exactly (RK4 and Dormand-Prince by their order;
/// the midpoint rule and the discrete gradient, which equal each other for
/// this quadratic `H`, by `q1 = q0 + h (p0 + p1)/2`).
pub(crate) struct Thrown;

const G: f64 = 1.0;

impl OdeSystem<[f64; 2]> for Thrown {
    fn rhs(&self, _t: f64, x: &[f64; 2]) -> [f64; 2] {
        [x[1], -G]
    }
}

impl Jacobian<[f64; 2]> for Thrown {
    fn jacobian(&self, _t: f64, _x: &[f64; 2]) -> [[f64; 2]; 2] {
        [[0.0, 1.0], [0.0, 0.0]]
    }
}

impl Energy<[f64; 2]> for Thrown {
    fn energy(&self, x: &[f64; 2]) -> f64 {
        x[1] * x[1] / 2.0 + G * x[0]
    }
}

impl Structured<[f64; 2]> for Thrown {
    fn structure_matrix(&self, _x: &[f64; 2]) -> [[f64; 2]; 2] {
        [[0.0, 1.0], [-1.0, 0.0]]
    }

    fn energy_gradient(&self, x: &[f64; 2]) -> [f64; 2] {
        [G, x[1]]
    }

    fn forcing(&self, _t: f64, _x: &[f64; 2]) -> [f64; 2] {
        [0.0; 2]
    }
}

impl Observed<[f64; 2]> for Thrown {
    fn state_names(&self) -> Vec<String> {
        vec!["q".into(), "dot(q)".into()]
    }

    fn input_names(&self) -> Vec<String> {
        Vec::new()
    }

    fn inputs(&self, _t: f64, _x: &[f64; 2], _inputs: &mut [f64]) {}

    /// No inputs, no work.
    fn input_power(&self, _t: f64, _x: &[f64; 2]) -> f64 {
        0.0
    }

    fn configuration_velocity(&self, x: &[f64; 2], q: &mut [f64], qdot: &mut [f64]) {
        (q[0], qdot[0]) = (x[0], x[1]);
    }

    /// The height's `G q`.
    fn energy_at_rest(&self, x: &[f64; 2]) -> f64 {
        G * x[0]
    }

    fn constraint_residual(&self, _x: &[f64; 2]) -> f64 {
        0.0
    }

    fn regularity(&self, _x: &[f64; 2]) -> Regularity {
        Regularity {
            quantity: "none",
            value: 1.0,
            signed: false,
        }
    }
}

/// Thrown from `q = 0` at `p = 2`, the body rises above `q = 1` where
/// `2 t - t^2/2 = 1`: at `t = 2 - sqrt(2)`.
const X0: [f64; 2] = [0.0, 2.0];
const CROSSING: f64 = 2.0 - std::f64::consts::SQRT_2;

/// The run of `method` from [`X0`] with steps of 0.1, every fourth
/// recorded, until `condition`; its summary and rows.
fn thrown<M, C>(method: M, condition: C) -> (Summary<[f64; 2]>, Vec<Vec<f64>>)
where
    M: Advance<Thrown, [f64; 2]>,
    C: StopCondition<[f64; 2]>,
{
    let mut table = Table::new();
    let summary = Simulation::new(method)
        .span(0.0, 3.0)
        .step(0.1)
        .record_every(4)
        .stop_when(condition)
        .run(&Thrown, X0, &mut table)
        .expect("the run ends cleanly");
    (summary, table.rows)
}

fn above_one() -> Stop<&'static str, impl Fn(f64, &[f64; 2]) -> f64> {
    Stop::new("q > 1", |_t, x: &[f64; 2]| x[0] - 1.0)
}

fn assert_stopped_at_the_crossing(
    (summary, rows): (Summary<[f64; 2]>, Vec<Vec<f64>>),
    method: &str,
) {
    assert_eq!(summary.stopped.as_deref(), Some("q > 1"), "{method}");
    assert!(
        (summary.t - CROSSING).abs() < 1e-9,
        "{method}: {}",
        summary.t
    );
    assert!(summary.t >= CROSSING, "{method}: the condition holds there");
    assert_eq!(
        summary.steps, 6,
        "{method}: the crossing is in the sixth step"
    );
    let last = rows.last().unwrap();
    assert_eq!(
        (last[0], last[1]),
        (summary.t, summary.state[0]),
        "{method}"
    );
    let exact = X0[0] + X0[1] * last[0] - G * last[0] * last[0] / 2.0;
    assert!((last[1] - exact).abs() < 1e-12, "{method}: q = {}", last[1]);
    assert!((last[1] - 1.0).abs() < 2e-9, "{method}: q = {}", last[1]);
    let times: Vec<f64> = rows.iter().map(|row| row[0]).collect();
    assert_eq!(times.len(), 3, "{method}: t = 0, 0.4 and the crossing");
}

#[test]
fn every_integrator_stops_at_the_crossing() {
    assert_stopped_at_the_crossing(thrown(Rk4, above_one()), "rk4");
    assert_stopped_at_the_crossing(thrown(Midpoint::default(), above_one()), "midpoint");
    assert_stopped_at_the_crossing(
        thrown(DiscreteGradient::default(), above_one()),
        "discrete gradient",
    );
    assert_stopped_at_the_crossing(thrown(DormandPrince::default(), above_one()), "dopri5");
}

/// A condition of time alone, `t > 0.123456789`, within the second step.
#[test]
fn a_condition_of_time_stops_at_that_time() {
    let (summary, _) = thrown(
        Rk4,
        Stop::new("t > 0.123456789", |t, _x: &[f64; 2]| t - 0.123456789),
    );
    assert!((summary.t - 0.123456789).abs() < 1e-9, "{}", summary.t);
    assert_eq!(summary.steps, 2);
}

/// A condition that holds at the start stops the run there, before any
/// step, with the first row recorded.
#[test]
fn a_condition_true_at_the_start_stops_there() {
    let (summary, rows) = thrown(Rk4, Stop::new("q < 1", |_t, x: &[f64; 2]| 1.0 - x[0]));
    assert_eq!(summary.stopped.as_deref(), Some("q < 1"));
    assert_eq!((summary.t, summary.steps, summary.state), (0.0, 0, X0));
    assert_eq!(rows, vec![vec![0.0, X0[0], X0[1], Thrown.energy(&X0), 0.0]]);
}

/// Without a condition, or with one that never holds, the run goes to the
/// end of its span and says it did not stop.
#[test]
fn a_run_without_a_stop_goes_to_the_end() {
    let mut table = Table::new();
    let summary = Simulation::new(Rk4)
        .span(0.0, 3.0)
        .step(0.1)
        .run(&Thrown, X0, &mut table)
        .unwrap();
    assert_eq!((summary.t, summary.steps, summary.stopped), (3.0, 30, None));
    let (summary, _) = thrown(Rk4, Stop::new("q > 3", |_t, x: &[f64; 2]| x[0] - 3.0));
    assert_eq!((summary.t, summary.stopped), (3.0, None));
}
