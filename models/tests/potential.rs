//! A model with potential energy: the Chaplygin sleigh on an inclined plane,
//! its centre of mass `a` ahead of the blade at height
//! `y + a sin(theta)` along the slope. Its reduced energy
//! `Hbar = 1/2 alpha^T gbar^-1 alpha + m g sin(beta) (y + a sin(theta))` is
//! not quadratic, so the implicit midpoint rule keeps it only to `O(h^2)`;
//! Gonzalez's discrete gradient keeps it to round-off.

use chaplygin::runtime::integrate::{DiscreteGradient, FixedStep, Midpoint, integrate_fixed};
use chaplygin::runtime::system::{Constant, Dalembert, Energy, Reduced};

chaplygin::model! {
    /// Chaplygin sleigh on a plane inclined by `beta`, `y` pointing uphill.
    pub struct InclinedSleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5, g = 9.81, beta = 0.3],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        potential_energy: m*g*sin(beta)*(y + a*sin(theta)),
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
        momentum_basis: [
            forward = [cos(theta), sin(theta), 0],
            turning = [-m*a*sin(theta), m*a*cos(theta), inertia + m*a^2],
        ],
    }
}

/// Heading across the slope, moving forward and turning.
fn start(sleigh: &InclinedSleigh) -> [f64; 5] {
    let q = [0.0, 0.0, 0.2];
    let alpha = sleigh.momenta(&q, &[2.0 * 0.2f64.cos(), 2.0 * 0.2f64.sin(), 1.5]);
    [q[0], q[1], q[2], alpha[0], alpha[1]]
}

/// The potential `m g sin(beta) (y + a sin(theta))` by hand.
fn potential(sleigh: &InclinedSleigh, x: &[f64; 5]) -> f64 {
    sleigh.m * sleigh.g * sleigh.beta.sin() * (x[1] + sleigh.a * x[2].sin())
}

/// The largest change of `Hbar` in one step, relative to the energy's scale
/// `|T| + |V|` there (the sleigh slides downhill, so `T` and `V` grow
/// together while their sum stays), and the total drift relative to that
/// scale at the end.
fn energy_errors<M>(method: &M, h: f64, steps: usize) -> (f64, f64)
where
    M: for<'a> FixedStep<Reduced<'a, InclinedSleigh, Constant<0>, 0>, [f64; 5]>,
{
    let sleigh = InclinedSleigh::default();
    let system = Reduced::constant(&sleigh, []);
    let x0 = start(&sleigh);
    let (h0, mut previous, mut worst_step, mut scale) =
        (system.energy(&x0), system.energy(&x0), 0.0f64, 0.0);
    let end = integrate_fixed(method, &system, (0.0, x0), h, steps, |_, x| {
        let energy = system.energy(x);
        let v = potential(&sleigh, x);
        scale = (energy - v).abs() + v.abs();
        worst_step = worst_step.max((energy - previous).abs() / scale);
        previous = energy;
    })
    .unwrap();
    (worst_step, (system.energy(&end) - h0).abs() / scale)
}

#[test]
fn the_discrete_gradient_keeps_the_energy_with_a_potential() {
    let (h, steps) = (0.01, 10_000);
    let (gradient_step, gradient) = energy_errors(&DiscreteGradient::default(), h, steps);
    let (midpoint_step, midpoint) = energy_errors(&Midpoint::default(), h, steps);
    println!(
        "inclined sleigh, h = {h}, {steps} steps, energy error relative to |T| + |V|: \
         discrete gradient {gradient_step:.3e} per step, {gradient:.3e} in all; \
         midpoint {midpoint_step:.3e} per step, {midpoint:.3e} in all"
    );
    assert!(gradient_step <= 1e-14, "{gradient_step:e}");
    assert!(gradient <= 1e-12, "{gradient:e}");
    assert!(
        midpoint_step >= 1e3 * gradient_step.max(1e-17),
        "{midpoint_step:e}"
    );
}

#[test]
fn the_potential_enters_both_formulations_alike() {
    let sleigh = InclinedSleigh::default();
    let x = start(&sleigh);
    let (q, alpha) = ([x[0], x[1], x[2]], [x[3], x[4]]);
    let qdot = sleigh.velocities(&q, &alpha);
    // energy: T + V of the Lagrange-d'Alembert form equals Hbar
    let dalembert = Dalembert::constant(&sleigh, []);
    let state = [q[0], q[1], q[2], qdot[0], qdot[1], qdot[2]];
    assert!((dalembert.energy(&state) - sleigh.hamiltonian(&x)).abs() <= 1e-13);
    // sliding straight downhill from rest heading down the slope: the blade
    // allows it, and the acceleration is g sin(beta) along the heading
    let down = [0.0, 0.0, -std::f64::consts::FRAC_PI_2];
    let (qddot, _) = sleigh.acceleration(&down, &[0.0; 3], &[]);
    let expected = 9.81 * 0.3f64.sin() * sleigh.m / sleigh.m;
    assert!(
        qddot[0].abs() <= 1e-12 && qddot[2].abs() <= 1e-12,
        "{qddot:?}"
    );
    assert!(
        (qddot[1] + expected).abs() <= 1e-12,
        "{qddot:?} vs -{expected}"
    );
}
