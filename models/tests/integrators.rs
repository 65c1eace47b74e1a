//! The runtime's integrators on generated models, through the formulation
//! traits the generated code implements: the implicit midpoint rule keeps the
//! energy of the snakeboard under the energy-based controller of MATH.md 3.2
//! where RK4 drifts, and the reduced and the Lagrange-d'Alembert formulations
//! give the same trajectory; the Chaplygin sleigh reaches its known
//! straight-line asymptotics.
//!
//! (With zero input the reduced snakeboard's momenta are constant, MATH.md
//! 3.1, so `Hbar` is kept exactly by every method: the closed loop is the
//! first case where conservation tells the methods apart.)

use chaplygin::energy_control::{
    CLOSED_LOOP_STATE, ClosedLoop, EnergyController, closed_loop_state, wheel_energy,
};
use chaplygin::runtime::integrate::{DormandPrince, FixedStep, Midpoint, Rk4, integrate_fixed};
use chaplygin::runtime::system::{Dalembert, Energy, Jacobian, OdeSystem, Reduced};
use chaplygin_models::{sleigh::Sleigh, snakeboard::Snakeboard};

const N: usize = Snakeboard::N;
const S: usize = Snakeboard::S;

/// The reduced state at `q = (0.1, -0.2, 0.3, 0, 0.3)` with momenta
/// `alpha = (1, 0.5, 0.025)` (the wheels turning at `phidot = 0.5`).
fn start() -> [f64; S] {
    [0.1, -0.2, 0.3, 0.0, 0.3, 1.0, 0.5, 0.025]
}

const D: usize = CLOSED_LOOP_STATE;

/// The closed loop of MATH.md 3.2 with the default board.
fn closed_loop() -> ClosedLoop<Snakeboard> {
    ClosedLoop {
        plant: Snakeboard {
            m: 1.0,
            r: 0.5,
            jt: 0.3,
            jw: 0.05,
        },
        controller: EnergyController::new(1.0, 2.0, 1.0, &Snakeboard::COORDINATES)
            .expect("the snakeboard steers by phi"),
    }
}
/// At rest at `phi = 0.2` with energy in both springs (`xt = 1`, `xw = 0.5`).
const AT_REST: [f64; D] = [0.0, 0.0, 0.0, 0.0, 0.2, 0.0, 0.0, 0.0, 1.0, 0.5];

#[test]
fn the_closed_loop_jacobian_matches_central_differences() {
    let z = [0.1, -0.2, 0.3, 0.4, 0.5, 0.7, -0.3, 0.1, 0.8, -0.4];
    let jac = closed_loop().jacobian(0.0, &z);
    let eps = 1e-6;
    for j in 0..D {
        let shifted = |s: f64| {
            let mut w = z;
            w[j] += s;
            closed_loop().rhs(0.0, &w)
        };
        let (plus, minus) = (shifted(eps), shifted(-eps));
        for i in 0..D {
            let difference = (plus[i] - minus[i]) / (2.0 * eps);
            assert!(
                (jac[i][j] - difference).abs() <= 1e-8,
                "({i}, {j}): {} vs {difference}",
                jac[i][j]
            );
        }
    }
}

/// The largest relative change of the closed loop's energy over `steps`
/// steps of `h` from [`AT_REST`], and the group momentum `alpha1` at `t = 10`.
fn energy_drift<M: FixedStep<ClosedLoop<Snakeboard>, [f64; D]>>(
    method: &M,
    h: f64,
    steps: usize,
) -> (f64, f64) {
    let h0 = closed_loop().energy(&AT_REST);
    let (mut worst, mut alpha1) = (0.0f64, f64::NAN);
    let observe = |t: f64, z: &[f64; D]| {
        worst = worst.max((closed_loop().energy(z) - h0).abs() / h0);
        if (t - 10.0).abs() < h / 2.0 {
            alpha1 = z[5];
        }
    };
    integrate_fixed(method, &closed_loop(), (0.0, AT_REST), h, steps, observe).unwrap();
    (worst, alpha1)
}

/// Over 200 s (20,000 steps) the midpoint rule's error stays at round-off
/// (3.9e-14) while RK4's grows with time (3.9e-7; 1.9e-6 over 1000 s).
#[test]
fn midpoint_keeps_the_closed_loop_energy_where_rk4_drifts() {
    assert_eq!(closed_loop().plant, Snakeboard::default());
    let (h, steps) = (0.01, 20_000);
    let (midpoint, alpha1) = energy_drift(&Midpoint::default(), h, steps);
    let (rk4, _) = energy_drift(&Rk4, h, steps);
    println!(
        "closed-loop snakeboard, h = {h}, {steps} steps: relative energy error \
         midpoint {midpoint:.3e}, RK4 {rk4:.3e}; alpha1(10) = {alpha1:.4}"
    );
    assert!(midpoint <= 1e-12, "{midpoint:e}");
    assert!(rk4 >= 1e4 * midpoint, "{rk4:e}");
    // the state builder places the springs after the board's state
    assert_eq!(
        closed_loop_state(&[0.0, 0.0, 0.0, 0.0, 0.2, 0.0, 0.0, 0.0], 1.0, 0.5),
        AT_REST
    );
    // alpha1dot = (a kt / r) sin(phi)^2 xt >= 0 while xt > 0 (MATH.md 3.2)
    assert!(
        alpha1 > 0.1,
        "energy flows into the group momentum: {alpha1}"
    );
}

/// `u(t) = (0.2 cos t, -0.05 sin 2t)`: with `jw = 0.05` the wheels obey
/// `phi'' = -sin 2t`, so from `phi = 0.3`, `phidot = 0.5` they follow
/// `phi = 0.3 + sin(2t)/4`, away from the singular `phi = +-pi/2`.
fn input(t: f64) -> [f64; 2] {
    [0.2 * t.cos(), -0.05 * (2.0 * t).sin()]
}

#[test]
fn reduced_and_lagrange_dalembert_trajectories_agree() {
    let board = Snakeboard::default();
    let reduced = Reduced::new(&board, input);
    let dalembert = Dalembert::new(&board, input);
    let method = DormandPrince {
        rtol: 1e-12,
        atol: 1e-12,
        ..Default::default()
    };
    let mut x = start();
    let q0: [f64; N] = core::array::from_fn(|i| x[i]);
    let v0 = board.velocities(&q0, &[x[5], x[6], x[7]]);
    let mut y: [f64; 2 * N] = core::array::from_fn(|i| if i < N { q0[i] } else { v0[i - N] });
    let mut worst = 0.0f64;
    for i in 0..20 {
        let (t0, t1) = (0.5 * i as f64, 0.5 * (i + 1) as f64);
        x = method.integrate(&reduced, (t0, x), t1).unwrap().x;
        y = method.integrate(&dalembert, (t0, y), t1).unwrap().x;
        let phi = 0.3 + (2.0 * t1).sin() / 4.0;
        assert!(
            (x[4] - phi).abs() <= 1e-9 && (y[4] - phi).abs() <= 1e-9,
            "{x:?} {y:?}"
        );
        for k in 0..N {
            worst = worst.max((x[k] - y[k]).abs());
        }
    }
    println!(
        "snakeboard over 10 s: largest |q_reduced - q_lagrange_dalembert| {worst:.3e}; q(10) = {:?}",
        &x[..N]
    );
    assert!(worst <= 1e-8, "{worst:e}");
    assert!(
        x[..2].iter().any(|v| v.abs() > 0.5),
        "the board moves: {x:?}"
    );
}

/// The Chaplygin sleigh (blade speed `v` along the heading, angular velocity
/// `w`, centre of mass `a` ahead of the blade) obeys `vdot = a w^2`,
/// `wdot = -m a v w / (I + m a^2)` (Bloch, *Nonholonomic Mechanics and
/// Control*, 2003, chapter 1): the energy `m v^2/2 + (I + m a^2) w^2/2` is
/// conserved, `w` decays to 0 and `v` grows to `sqrt(2 E / m)`, a straight
/// line.
#[test]
fn the_sleigh_tends_to_a_straight_line_at_the_speed_its_energy_allows() {
    let sleigh = Sleigh::default();
    let system = Dalembert::constant(&sleigh, []);
    let (theta, v, w) = (0.3f64, 0.5, 2.0);
    let start = [0.0, 0.0, theta, v * theta.cos(), v * theta.sin(), w];
    let energy = system.energy(&start);
    let expected =
        (sleigh.m * v * v + (sleigh.inertia + sleigh.m * sleigh.a.powi(2)) * w * w) / 2.0;
    assert!((energy - expected).abs() <= 1e-14, "{energy} vs {expected}");
    let tight = DormandPrince {
        rtol: 1e-11,
        atol: 1e-11,
        ..Default::default()
    };
    let end = tight.integrate(&system, (0.0, start), 40.0).unwrap().x;
    let speed = end[3] * end[2].cos() + end[4] * end[2].sin();
    let limit = (2.0 * energy / sleigh.m).sqrt();
    println!(
        "sleigh at t = 40: w = {:.3e}, v = {speed:.12} (limit {limit:.12}), energy error {:.3e}",
        end[5],
        (system.energy(&end) - energy).abs() / energy
    );
    assert!(end[5].abs() <= 1e-9, "{end:?}");
    assert!((speed - limit).abs() <= 1e-8, "{speed} vs {limit}");
    assert!((system.energy(&end) - energy).abs() <= 1e-9 * energy);
    assert!(
        sleigh.constraint_residual(&[end[0], end[1], end[2]], &[end[3], end[4], end[5]])[0].abs()
            <= 1e-8
    );
}

/// MATH.md 3.2: the wheel pair `(alpha3, xw)` exchanges no energy with the
/// rest, so `alpha3^2/(2 Jw) + kw xw^2/2` is constant along the closed loop
/// (the midpoint rule keeps this quadratic invariant too), while the
/// torso spring's energy `kt xt^2/2` does flow into `alpha1`.
#[test]
fn the_wheel_pair_keeps_its_own_energy() {
    let wheels0 = wheel_energy(
        closed_loop().plant.jw,
        closed_loop().controller.kw,
        &AT_REST,
    );
    let (mut worst, mut torso_spring_change) = (0.0f64, 0.0f64);
    let torso0 = 2.0 * AT_REST[S] * AT_REST[S] / 2.0;
    let observe = |_t: f64, z: &[f64; D]| {
        worst = worst.max(
            (wheel_energy(closed_loop().plant.jw, closed_loop().controller.kw, z) - wheels0).abs()
                / wheels0,
        );
        torso_spring_change = torso_spring_change.max((2.0 * z[S] * z[S] / 2.0 - torso0).abs());
    };
    integrate_fixed(
        &Midpoint::default(),
        &closed_loop(),
        (0.0, AT_REST),
        0.01,
        2000,
        observe,
    )
    .unwrap();
    assert!(worst <= 1e-12, "wheel-pair energy changed by {worst:e}");
    assert!(
        torso_spring_change > 0.1,
        "the torso spring exchanges energy: {torso_spring_change}"
    );
}
