//! The momentum formulation (`system::Momentum`, MATH.md section 4) against
//! the Lagrange-d'Alembert equations (`system::Dalembert`, MATH.md section 2)
//! for every built-in model with a symmetry: from the same `(q, qdot)` (a
//! velocity of the reduced form's `velocities`, so allowed by the
//! constraints), with the same open-loop inputs, the configurations and
//! velocities agree over 10 s under tight Dormand-Prince; without inputs the
//! energy is conserved; the reconstructed velocity satisfies the constraints
//! to round-off throughout.

use chaplygin::runtime::control::Controller;
use chaplygin::runtime::integrate::DormandPrince;
use chaplygin::runtime::linalg::Square;
use chaplygin::runtime::nalgebra::Const;
use chaplygin::runtime::simulate::Observed;
use chaplygin::runtime::system::{
    Dalembert, Domain, Energy, LagrangeDalembert, ModelNames, Momenta, Momentum, MomentumEquations,
};
use chaplygin_models::{
    differential_drive::DifferentialDrive, rolling_disk::RollingDisk, sleigh::Sleigh,
    snakeboard::Snakeboard,
};

const TIGHT: DormandPrince = DormandPrince {
    rtol: 1e-12,
    atol: 1e-12,
    min_step: 1e-14,
    max_steps: 1_000_000,
};

/// Largest `|a_i - b_i|`.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0, |worst, (a, b)| worst.max((a - b).abs()))
}

/// What a 10 s run of both formulations measured.
struct Comparison {
    /// Largest distance of `(q, qdot)` between the formulations, second by second.
    state_gap: f64,
    /// Largest `|E(t) - E(0)|` of the momentum formulation.
    energy_drift: f64,
    /// Largest constraint residual of the momentum formulation.
    residual: f64,
    /// The configurations at every second, of the momentum formulation.
    configurations: Vec<Vec<f64>>,
}

/// Runs both formulations of `model` from `q0` with reduced momenta `alpha0`
/// under `input(t)`, and compares them every second for 10 s.
fn compare<
    M,
    U,
    const N: usize,
    const R: usize,
    const K: usize,
    const C: usize,
    const P: usize,
    const S: usize,
    const D: usize,
    const TWO_N: usize,
>(
    model: &M,
    input: U,
    q0: [f64; N],
    alpha0: &[f64; S],
) -> Comparison
where
    M: MomentumEquations<N, R, K, P>
        + LagrangeDalembert<N, C, P>
        + Momenta<N, S>
        + ModelNames
        + Domain,
    U: Controller<D, P> + Controller<TWO_N, P> + Copy,
    Const<N>: Square,
    Const<D>: Square,
    Const<TWO_N>: Square,
{
    let qdot0 = model.velocities(&q0, alpha0);
    let dalembert = Dalembert::new(model, input);
    let momentum = Momentum::new(model, input);
    let mut lagrange_state: [f64; TWO_N] =
        core::array::from_fn(|i| if i < N { q0[i] } else { qdot0[i - N] });
    let mut momentum_state: [f64; D] = momentum.initial_state(&q0, &qdot0);
    let energy0 = momentum.energy(&momentum_state);
    let mut comparison = Comparison {
        state_gap: 0.0,
        energy_drift: 0.0,
        residual: momentum.constraint_residual(&momentum_state),
        configurations: Vec::new(),
    };
    for second in 0..10 {
        let (t0, t1) = (f64::from(second), f64::from(second + 1));
        lagrange_state = TIGHT
            .integrate(&dalembert, (t0, lagrange_state), t1)
            .expect("d'Alembert run")
            .x;
        momentum_state = TIGHT
            .integrate(&momentum, (t0, momentum_state), t1)
            .expect("momentum run")
            .x;
        let (q, qdot) = momentum.configuration_velocity(&momentum_state);
        comparison.state_gap = comparison
            .state_gap
            .max(distance(&q, &lagrange_state[..N]))
            .max(distance(&qdot, &lagrange_state[N..]));
        comparison.energy_drift = comparison
            .energy_drift
            .max((momentum.energy(&momentum_state) - energy0).abs());
        comparison.residual = comparison
            .residual
            .max(momentum.constraint_residual(&momentum_state));
        comparison.configurations.push(q.to_vec());
    }
    comparison
}

/// Dormand-Prince at `rtol = atol = 1e-12` keeps each formulation within
/// about 1e-10 of its exact flow over 10 s; the two exact flows coincide.
const AGREEMENT: f64 = 1e-8;
/// The reconstructed velocity satisfies `A(q) qdot = 0` by construction:
/// only round-off remains.
const ROUND_OFF: f64 = 1e-12;
/// The energy's drift under the integrator's local errors of ~1e-12 per step.
const ENERGY_DRIFT: f64 = 1e-9;

fn assert_agrees(comparison: &Comparison, energy_conserved: bool) {
    assert!(
        comparison.state_gap < AGREEMENT,
        "state gap {}",
        comparison.state_gap
    );
    assert!(
        comparison.residual < ROUND_OFF,
        "constraint residual {}",
        comparison.residual
    );
    if energy_conserved {
        assert!(
            comparison.energy_drift < ENERGY_DRIFT,
            "energy drift {}",
            comparison.energy_drift
        );
    }
}

/// The steering angle `phi` stays away from +-pi/2, where the snakeboard's
/// constraints degenerate.
fn assert_steering_regular(comparison: &Comparison) {
    for q in &comparison.configurations {
        assert!(q[4].abs() < 1.2, "phi = {}", q[4]);
    }
}

#[test]
fn snakeboard_momentum_matches_dalembert() {
    let board = Snakeboard::default();
    let q0 = [0.1, -0.2, 0.3, 0.2, 0.4];
    let alpha0 = [0.5, 0.01, -0.005];
    let driven = compare::<_, _, 5, 2, 1, 2, 2, 3, 8, 10>(
        &board,
        |t: f64| [0.05 * t.sin(), 0.03 * (2.0 * t).cos()],
        q0,
        &alpha0,
    );
    assert_steering_regular(&driven);
    assert_agrees(&driven, false);
    let free = compare::<_, _, 5, 2, 1, 2, 2, 3, 8, 10>(&board, |_: f64| [0.0; 2], q0, &alpha0);
    assert_steering_regular(&free);
    assert_agrees(&free, true);
}

#[test]
fn rolling_disk_momentum_matches_dalembert() {
    let disk = RollingDisk::default();
    let q0 = [0.3, -0.1, 0.7, 0.2];
    let alpha0 = [0.4, -0.6];
    let driven = compare::<_, _, 4, 1, 1, 2, 2, 2, 6, 8>(
        &disk,
        |t: f64| [0.02 * (1.5 * t).sin(), 0.04 * t.cos()],
        q0,
        &alpha0,
    );
    assert_agrees(&driven, false);
    let free = compare::<_, _, 4, 1, 1, 2, 2, 2, 6, 8>(&disk, |_: f64| [0.0; 2], q0, &alpha0);
    assert_agrees(&free, true);
}

#[test]
fn differential_drive_momentum_matches_dalembert() {
    let drive = DifferentialDrive::default();
    let q0 = [0.2, 0.5, -0.4, 0.0, 1.0];
    let alpha0 = [0.3, 0.1];
    let driven = compare::<_, _, 5, 2, 0, 3, 2, 2, 7, 10>(
        &drive,
        |t: f64| [0.001 * t.sin(), 0.002 * (0.5 * t).cos()],
        q0,
        &alpha0,
    );
    assert_agrees(&driven, false);
    let free = compare::<_, _, 5, 2, 0, 3, 2, 2, 7, 10>(&drive, |_: f64| [0.0; 2], q0, &alpha0);
    assert_agrees(&free, true);
}

/// The sleigh has no inputs: its run is the free one.
#[test]
fn sleigh_momentum_matches_dalembert() {
    let sleigh = Sleigh::default();
    let free = compare::<_, _, 3, 0, 2, 1, 0, 2, 5, 6>(
        &sleigh,
        |_: f64| [],
        [0.1, 0.2, 0.3],
        &[0.8, -0.5],
    );
    assert_agrees(&free, true);
}

/// The state is named as documented: coordinates, `dot(r)`, `p1..`.
#[test]
fn momentum_state_names() {
    let board = Snakeboard::default();
    let system = Momentum::constant(&board, [0.0; 2]);
    let names = Observed::<[f64; 8]>::state_names(&system);
    assert_eq!(
        names,
        [
            "x", "y", "theta", "psi", "phi", "dot(psi)", "dot(phi)", "p1"
        ]
    );
}
