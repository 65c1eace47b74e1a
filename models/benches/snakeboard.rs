//! The generated snakeboard against hand-written Rust of the same equations,
//! and the simulation throughput of two integrators on it.
//!
//! The hand-written references implement MATH.md 3.1 directly:
//! - `reduced_rhs`: the paper's "remarkably simple" reduced equations;
//! - `reduced_rhs_jacobian`: their Jacobian, differentiated by hand;
//! - `acceleration`: the Lagrange-d'Alembert saddle-point system
//!   `[[g, -A^T], [A, 0]] (qddot, lambda) = (B u, -Adot qdot)` (MATH.md 2;
//!   `g` is constant, so `C = 0`), assembled by hand and solved by LU with
//!   partial pivoting (`runtime::linalg::solve`, nalgebra's LU).
//!
//! Before timing, each reference is checked against the generated function
//! at the timed states. Each comparison is measured twice in the same run:
//! with criterion, and with a best-of-batches loop whose ratio is printed as
//! `RATIO name: generated / hand-written`. Throughput: steps per second of
//! RK4 and of the implicit midpoint rule on the reduced form
//! (`integrate_fixed`, `Reduced::constant`), printed as `THROUGHPUT`.
//!
//! Run with `cargo bench -p chaplygin-models --bench snakeboard`.

mod timing;

use chaplygin::runtime::integrate::{Midpoint, Rk4, integrate_fixed};
use chaplygin::runtime::linalg::solve;
use chaplygin::runtime::system::Reduced;
use chaplygin_models::snakeboard::Snakeboard;
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Instant;
use timing::{Random, best_nanoseconds, print_ratio};

/// Calls per timed batch.
const CALLS: usize = 200_000;
/// Distinct states the timed calls cycle through.
const STATES: usize = 64;

/// MATH.md 3.1: `xdot` of the reduced snakeboard, `x = (x, y, theta, psi, phi, alpha)`.
fn hand_reduced_rhs(b: &Snakeboard, x: &[f64; 8], u: &[f64; 2]) -> [f64; 8] {
    let (sin_theta, cos_theta) = x[2].sin_cos();
    let (sin_phi, cos_phi) = x[4].sin_cos();
    let forward = x[5] / b.m * cos_phi;
    let turning = x[5] * sin_phi / (b.m * b.r);
    [
        forward * cos_theta,
        forward * sin_theta,
        turning,
        x[6] / b.jt - turning,
        x[7] / b.jw,
        -sin_phi / b.r * u[0],
        u[0],
        u[1],
    ]
}

/// The Jacobian of [`hand_reduced_rhs`] with respect to `x`, by hand.
fn hand_reduced_rhs_jacobian(b: &Snakeboard, x: &[f64; 8], u: &[f64; 2]) -> [[f64; 8]; 8] {
    let (sin_theta, cos_theta) = x[2].sin_cos();
    let (sin_phi, cos_phi) = x[4].sin_cos();
    let (m, mr) = (b.m, b.m * b.r);
    let a1 = x[5];
    let mut j = [[0.0; 8]; 8];
    j[0][2] = -a1 / m * cos_phi * sin_theta;
    j[0][4] = -a1 / m * sin_phi * cos_theta;
    j[0][5] = cos_phi * cos_theta / m;
    j[1][2] = a1 / m * cos_phi * cos_theta;
    j[1][4] = -a1 / m * sin_phi * sin_theta;
    j[1][5] = cos_phi * sin_theta / m;
    j[2][4] = a1 * cos_phi / mr;
    j[2][5] = sin_phi / mr;
    j[3][4] = -a1 * cos_phi / mr;
    j[3][5] = -sin_phi / mr;
    j[3][6] = 1.0 / b.jt;
    j[4][7] = 1.0 / b.jw;
    j[5][4] = -cos_phi / b.r * u[0];
    j
}

/// MATH.md 2 for the snakeboard: the saddle-point system assembled from the
/// hand-written `g`, `A`, `Adot qdot` and `B`, solved at run time.
fn hand_acceleration(
    b: &Snakeboard,
    q: &[f64; 5],
    qdot: &[f64; 5],
    u: &[f64; 2],
) -> ([f64; 5], [f64; 2]) {
    let j = b.jt + b.m * b.r * b.r;
    let metric = [
        [b.m, 0.0, 0.0, 0.0, 0.0],
        [0.0, b.m, 0.0, 0.0, 0.0],
        [0.0, 0.0, j, b.jt, 0.0],
        [0.0, 0.0, b.jt, b.jt, 0.0],
        [0.0, 0.0, 0.0, 0.0, b.jw],
    ];
    let (sin_phi, cos_phi) = q[4].sin_cos();
    let (sin_front, cos_front) = (q[2] + q[4]).sin_cos();
    let (sin_back, cos_back) = (q[2] - q[4]).sin_cos();
    let rows = [
        [-sin_front, cos_front, b.r * cos_phi, 0.0, 0.0],
        [-sin_back, cos_back, -b.r * cos_phi, 0.0, 0.0],
    ];
    let spin = b.r * sin_phi * qdot[4] * qdot[2];
    let rows_rate = [
        -(qdot[2] + qdot[4]) * (cos_front * qdot[0] + sin_front * qdot[1]) - spin,
        -(qdot[2] - qdot[4]) * (cos_back * qdot[0] + sin_back * qdot[1]) + spin,
    ];
    let mut system = [[0.0; 7]; 7];
    let mut right = [0.0, 0.0, 0.0, u[0], u[1], -rows_rate[0], -rows_rate[1]];
    for i in 0..5 {
        system[i][..5].copy_from_slice(&metric[i]);
        for c in 0..2 {
            system[i][5 + c] = -rows[c][i];
            system[5 + c][i] = rows[c][i];
        }
    }
    right = solve(&system, &right).expect("the saddle-point system is regular off phi = +-pi/2");
    (
        [right[0], right[1], right[2], right[3], right[4]],
        [right[5], right[6]],
    )
}

/// A state `(q, qdot)` with `qdot` allowed: `qdot = velocities(q, alpha)`.
struct State {
    q: [f64; 5],
    qdot: [f64; 5],
    x: [f64; 8],
    u: [f64; 2],
}

fn states(board: &Snakeboard) -> Vec<State> {
    let mut random = Random::new(7);
    (0..STATES)
        .map(|_| {
            let mut q: [f64; 5] = random.array(-3.0, 3.0);
            q[4] = random.uniform(-1.2, 1.2);
            let alpha: [f64; 3] = random.array(-1.0, 1.0);
            let x = std::array::from_fn(|i| if i < 5 { q[i] } else { alpha[i - 5] });
            State {
                q,
                qdot: board.velocities(&q, &alpha),
                x,
                u: random.array(-1.0, 1.0),
            }
        })
        .collect()
}

fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / x.abs().max(1.0))
        .fold(0.0, f64::max)
}

/// The references compute what the generated functions compute.
fn check_references(board: &Snakeboard, states: &[State]) {
    for s in states {
        let rhs = largest_difference(
            &board.reduced_rhs(&s.x, &s.u),
            &hand_reduced_rhs(board, &s.x, &s.u),
        );
        let jacobian = largest_difference(
            board.reduced_rhs_jacobian(&s.x, &s.u).as_flattened(),
            hand_reduced_rhs_jacobian(board, &s.x, &s.u).as_flattened(),
        );
        let (qddot, lambda) = board.acceleration(&s.q, &s.qdot, &s.u);
        let (hand_qddot, hand_lambda) = hand_acceleration(board, &s.q, &s.qdot, &s.u);
        let acceleration =
            largest_difference(&qddot, &hand_qddot).max(largest_difference(&lambda, &hand_lambda));
        assert!(
            rhs.max(jacobian).max(acceleration) < 1e-10,
            "reference differs: rhs {rhs:e}, jacobian {jacobian:e}, acceleration {acceleration:e}"
        );
    }
}

fn print_ratios(board: &Snakeboard, states: &[State]) {
    let pairs: [(&str, f64, f64); 3] = [
        (
            "reduced_rhs",
            best_nanoseconds(states, CALLS, |s| board.reduced_rhs(&s.x, &s.u)),
            best_nanoseconds(states, CALLS, |s| hand_reduced_rhs(board, &s.x, &s.u)),
        ),
        (
            "reduced_rhs_jacobian",
            best_nanoseconds(states, CALLS, |s| board.reduced_rhs_jacobian(&s.x, &s.u)),
            best_nanoseconds(states, CALLS, |s| {
                hand_reduced_rhs_jacobian(board, &s.x, &s.u)
            }),
        ),
        (
            "acceleration",
            best_nanoseconds(states, CALLS, |s| board.acceleration(&s.q, &s.qdot, &s.u)),
            best_nanoseconds(states, CALLS, |s| {
                hand_acceleration(board, &s.q, &s.qdot, &s.u)
            }),
        ),
    ];
    for (name, generated, hand_written) in pairs {
        print_ratio(name, generated, hand_written);
    }
}

/// Steps of the throughput runs (h = 1e-3, constant input).
const STEPS: usize = 100_000;

/// Steps per second of RK4 and the implicit midpoint rule, best of three runs.
fn print_throughput(board: &Snakeboard, start: [f64; 8]) {
    let system = Reduced::constant(board, [0.1, -0.2]);
    let rk4 = best_seconds(|| integrate_fixed(&Rk4, &system, (0.0, start), 1e-3, STEPS, |_, _| {}));
    let midpoint = best_seconds(|| {
        integrate_fixed(
            &Midpoint::default(),
            &system,
            (0.0, start),
            1e-3,
            STEPS,
            |_, _| {},
        )
    });
    for (name, seconds) in [("rk4", rk4), ("midpoint", midpoint)] {
        println!(
            "THROUGHPUT {name}: {:.3e} steps/s ({:.1} ns/step)",
            STEPS as f64 / seconds,
            seconds / STEPS as f64 * 1e9
        );
    }
}

fn best_seconds<T, E: std::fmt::Debug>(run: impl Fn() -> Result<T, E>) -> f64 {
    (0..3)
        .map(|_| {
            let begin = Instant::now();
            black_box(run().expect("the integration runs"));
            begin.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

fn bench(c: &mut Criterion) {
    let board = Snakeboard::default();
    let states = states(&board);
    check_references(&board, &states);
    print_ratios(&board, &states);
    print_throughput(&board, states[0].x);
    let s = &states[0];
    let mut group = c.benchmark_group("snakeboard");
    group.bench_function("reduced_rhs/generated", |b| {
        b.iter(|| board.reduced_rhs(black_box(&s.x), black_box(&s.u)))
    });
    group.bench_function("reduced_rhs/hand-written", |b| {
        b.iter(|| hand_reduced_rhs(&board, black_box(&s.x), black_box(&s.u)))
    });
    group.bench_function("reduced_rhs_jacobian/generated", |b| {
        b.iter(|| board.reduced_rhs_jacobian(black_box(&s.x), black_box(&s.u)))
    });
    group.bench_function("reduced_rhs_jacobian/hand-written", |b| {
        b.iter(|| hand_reduced_rhs_jacobian(&board, black_box(&s.x), black_box(&s.u)))
    });
    group.bench_function("acceleration/generated", |b| {
        b.iter(|| board.acceleration(black_box(&s.q), black_box(&s.qdot), black_box(&s.u)))
    });
    group.bench_function("acceleration/hand-written", |b| {
        b.iter(|| hand_acceleration(&board, black_box(&s.q), black_box(&s.qdot), black_box(&s.u)))
    });
    let system = Reduced::constant(&board, [0.1, -0.2]);
    group.bench_function("rk4_1000_steps", |b| {
        b.iter(|| integrate_fixed(&Rk4, &system, (0.0, black_box(s.x)), 1e-3, 1000, |_, _| {}))
    });
    group.bench_function("midpoint_1000_steps", |b| {
        b.iter(|| {
            integrate_fixed(
                &Midpoint::default(),
                &system,
                (0.0, black_box(s.x)),
                1e-3,
                1000,
                |_, _| {},
            )
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
