//! The compiled benchmark bicycle: per-call times of `acceleration` and
//! `acceleration_jacobian`, of the reduced form's right-hand side and its
//! Jacobian (in charts 0 and 1, at `x_k = 0.3 (k + 1) / 2`), and of a
//! linearization about upright running,
//! for comparison with CasADi's C of the same equations
//! (`bench/peers/casadi_bicycle.py`, timed by `bench/peers/timing.c`).
//!
//! It first prints `BICYCLE_STATE` and `(qddot, lambda)` at the timing
//! harness's state (`q_k = 0.3 (k + 1) / 2`, `qdot_k = 0.3 (k + 1) / 3`,
//! `u_k = 0.3 (k + 1) / 4`), which the CasADi script prints too: the two
//! compute the same equations. Times are the best of several batches
//! (`timing::best_nanoseconds`) at that state, as the harness times
//! CasADi's function.
//!
//! Run with `cargo bench -p chaplygin-models --bench bicycle`.

// The timing loop shared with the snakeboard benchmark, whose ratios and
// random states this benchmark does not use.
#[allow(dead_code)]
mod timing;

use chaplygin::runtime::linearize::{Compiled, OperatingPoint, linearize};
use chaplygin_models::bicycle::Bicycle;
use timing::best_nanoseconds;

/// Calls per timed batch.
const CALLS: usize = 100_000;

fn main() {
    let bicycle = Bicycle::default();
    let q: [f64; 8] = std::array::from_fn(|k| 0.3 * (k + 1) as f64 / 2.0);
    let qdot: [f64; 8] = std::array::from_fn(|k| 0.3 * (k + 1) as f64 / 3.0);
    let u: [f64; 2] = std::array::from_fn(|k| 0.3 * (k + 1) as f64 / 4.0);
    let (qddot, lambda) = bicycle.acceleration(&q, &qdot, &u);
    let values: Vec<String> = qddot
        .iter()
        .chain(&lambda)
        .map(|x| format!("{x:.15e}"))
        .collect();
    println!("BICYCLE_STATE {}", values.join(" "));
    let state = [(q, qdot, u)];
    let acceleration = best_nanoseconds(&state, CALLS, |(q, qdot, u)| {
        bicycle.acceleration(q, qdot, u)
    });
    println!("BICYCLE acceleration: {acceleration:.1} ns/call");
    let jacobian = best_nanoseconds(&state, CALLS / 10, |(q, qdot, u)| {
        bicycle.acceleration_jacobian(q, qdot, u)
    });
    println!("BICYCLE acceleration_jacobian: {jacobian:.1} ns/call");
    let x: [f64; 11] = std::array::from_fn(|k| 0.3 * (k + 1) as f64 / 2.0);
    let reduced = [(x, u)];
    let rhs = best_nanoseconds(&reduced, CALLS, |(x, u)| bicycle.reduced_rhs(x, u));
    println!("BICYCLE reduced_rhs: {rhs:.1} ns/call");
    let rhs_jacobian = best_nanoseconds(&reduced, CALLS / 10, |(x, u)| {
        bicycle.reduced_rhs_jacobian(x, u)
    });
    println!("BICYCLE reduced_rhs_jacobian: {rhs_jacobian:.1} ns/call");
    let in_chart1 = best_nanoseconds(&reduced, CALLS / 10, |(x, u)| {
        bicycle.reduced_rhs_jacobian_chart1(x, u)
    });
    println!("BICYCLE reduced_rhs_jacobian_chart1: {in_chart1:.1} ns/call");
    let model = Compiled::holonomic(&bicycle);
    let upright = |v: f64| {
        let mut velocities = [None; 8];
        velocities[3] = Some(0.0);
        velocities[5] = Some(0.0);
        velocities[6] = Some(-v / bicycle.rR);
        let coordinates = [None, None, None, Some(0.0), None, Some(0.0), None, None];
        let point = OperatingPoint::solve(&model, &coordinates, &velocities).expect("upright");
        linearize(&model, &point, &[0.0, 0.0], &[]).expect("a relative equilibrium")
    };
    let speeds = [5.0];
    let one_speed = best_nanoseconds(&speeds, 100, |&v| upright(v));
    println!(
        "BICYCLE linearize at one speed (operating point, Jacobians, eigenvalues): {:.1} us",
        one_speed / 1e3
    );
}
