//! The long-run experiment: 10^6 steps (h = 0.01, 10^4 s) of the snakeboard
//! under the energy-based controller (MATH.md 3.2) with each integrator; the
//! relative energy error and the constraint residual at the end, and the
//! largest along the way. Ignored by default (it takes a minute in release):
//!
//! ```text
//! cargo test --release -p chaplygin-models --test integration long_run:: -- --ignored --nocapture
//! ```
//!
//! The numbers are recorded in BENCHMARKS.md.

use chaplygin::energy_control::{ClosedLoop, EnergyController, closed_loop_state};
use chaplygin::runtime::integrate::{DiscreteGradient, DormandPrince, Midpoint, Rk4};
use chaplygin::runtime::record::Recorder;
use chaplygin::runtime::simulate::{Advance, Simulation};
use chaplygin::runtime::system::{Constant, Dalembert};
use chaplygin_models::snakeboard::Snakeboard;
use std::io;
use std::time::Instant;

const STEPS: usize = 1_000_000;
const H: f64 = 0.01;

/// Keeps the last row and the largest energy error and residual of the rows.
struct Extremes {
    energy0: Option<f64>,
    worst_energy: f64,
    worst_residual: f64,
    last: Vec<f64>,
}

impl Recorder for Extremes {
    fn start(&mut self, _columns: &[String]) -> io::Result<()> {
        Ok(())
    }

    fn record(&mut self, row: &[f64]) -> io::Result<()> {
        let (energy, residual) = (row[row.len() - 2], row[row.len() - 1]);
        let energy0 = *self.energy0.get_or_insert(energy);
        self.worst_energy = self.worst_energy.max((energy - energy0).abs() / energy0);
        self.worst_residual = self.worst_residual.max(residual);
        self.last = row.to_vec();
        Ok(())
    }

    fn finish(&mut self) -> io::Result<()> {
        Ok(())
    }
}

fn long_run<M: for<'a> Advance<ClosedLoop<Snakeboard>, [f64; 10]>>(name: &str, method: M) {
    let closed_loop = ClosedLoop::<Snakeboard>::new(
        Snakeboard::default(),
        EnergyController::new(1.0, 2.0, 1.0, &Snakeboard::COORDINATES).expect("phi"),
    );
    let start = closed_loop_state(&[0.0; 8], 1.0, 0.5);
    let mut extremes = Extremes {
        energy0: None,
        worst_energy: 0.0,
        worst_residual: 0.0,
        last: Vec::new(),
    };
    let began = Instant::now();
    Simulation::new(method)
        .span(0.0, STEPS as f64 * H)
        .step(H)
        .record_every(100)
        .run(&closed_loop, start, &mut extremes)
        .unwrap();
    report(name, &extremes, began);
}

/// The uncontrolled snakeboard in the Lagrange-d'Alembert form, whose
/// equations keep the constraints only through `A qddot + Adot qdot = 0`:
/// the simulation projects the velocity back onto `ker A(q)` after each
/// step (`chaplygin::runtime::projection`), so the residual stays at
/// round-off and what is left is the integrator's energy error.
fn lagrange_dalembert_run<M>(name: &str, method: M)
where
    M: for<'a> Advance<Dalembert<'a, Snakeboard, Constant<2>, 5, 2, 2>, [f64; 10]>,
{
    let board = Snakeboard::default();
    let q = [0.0, 0.0, 0.0, 0.0, 0.3];
    // the wheels locked at phi = 0.3 (zero wheel momentum): the board circles
    let qdot = board.velocities(&q, &[1.0, 0.5, 0.0]);
    let mut start = [0.0; 10];
    start[..5].copy_from_slice(&q);
    start[5..].copy_from_slice(&qdot);
    let mut extremes = Extremes {
        energy0: None,
        worst_energy: 0.0,
        worst_residual: 0.0,
        last: Vec::new(),
    };
    let began = Instant::now();
    Simulation::new(method)
        .span(0.0, STEPS as f64 * H)
        .step(H)
        .record_every(100)
        .run(
            &Dalembert::constant(&board, [0.0, 0.0]),
            start,
            &mut extremes,
        )
        .unwrap();
    report(name, &extremes, began);
}

fn report(name: &str, extremes: &Extremes, began: Instant) {
    let energy0 = extremes.energy0.unwrap();
    let n = extremes.last.len();
    println!(
        "| {name} | {:.1e} | {:.1e} | {:.1e} | {:.1e} | {:.1} |",
        (extremes.last[n - 2] - energy0).abs() / energy0,
        extremes.worst_energy,
        extremes.last[n - 1],
        extremes.worst_residual,
        began.elapsed().as_secs_f64()
    );
}

#[test]
#[ignore = "10^6 steps per integrator: run in release, see the module documentation"]
fn a_million_steps_of_the_controlled_snakeboard() {
    println!(
        "| integrator | energy error at t = 10^4 | largest | constraint residual at t = 10^4 | largest | seconds |"
    );
    println!("|---|---|---|---|---|---|");
    long_run("RK4", Rk4);
    long_run("implicit midpoint", Midpoint::default());
    long_run("discrete gradient", DiscreteGradient::default());
    long_run(
        "Dormand-Prince (rtol = atol = 1e-10)",
        DormandPrince {
            rtol: 1e-10,
            atol: 1e-10,
            ..Default::default()
        },
    );
    lagrange_dalembert_run("RK4, Lagrange-d'Alembert form projected, no control", Rk4);
    lagrange_dalembert_run(
        "implicit midpoint, Lagrange-d'Alembert form projected, no control",
        Midpoint::default(),
    );
}
