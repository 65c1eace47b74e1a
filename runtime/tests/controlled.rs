//! Step-size control by step doubling ([`Controlled`]) on the pendulum
//! from `q = 2`: the error at `t = 10` against a Dormand-Prince run at
//! `1e-13` follows the tolerance for every method, the discrete
//! gradient's energy stays to the square of its error estimate (local
//! extrapolation of two energy-conserving steps), no step is longer than
//! the span, and a stage leaving the domain only shortens the step.

use crate::discrete_gradient::{Pendulum, X0};
use crate::split_steps::Draining;
use chaplygin_runtime::integrate::{
    Controlled, DiscreteGradient, DormandPrince, Error, FixedStep, Midpoint, Rk4, Solution,
};
use chaplygin_runtime::system::Energy;

const T_END: f64 = 10.0;

fn reference() -> [f64; 2] {
    let tight = DormandPrince {
        rtol: 1e-13,
        atol: 1e-13,
        ..DormandPrince::default()
    };
    tight.integrate(&Pendulum, (0.0, X0), T_END).unwrap().x
}

/// The largest error of `method` controlled to `tolerance` at `T_END`,
/// and its accepted steps, in one call over the span (steps at most
/// `T_END`) after ten calls of one unit each.
fn error_and_steps<M: FixedStep<Pendulum, [f64; 2]>>(method: M, tolerance: f64) -> (f64, usize) {
    let controlled = Controlled::new(method, tolerance, tolerance);
    let (mut x, mut accepted) = (X0, 0);
    for i in 0..10 {
        let solution = controlled
            .integrate(&Pendulum, (f64::from(i), x), f64::from(i + 1))
            .unwrap();
        (x, accepted) = (solution.x, accepted + solution.effort.accepted);
    }
    let exact = reference();
    let error = (x[0] - exact[0]).abs().max((x[1] - exact[1]).abs());
    (error, accepted)
}

/// The error at `T_END` is within the sum of the local errors allowed
/// (steps times tolerance), and a thousand times tighter tolerance cuts it
/// at least a hundredfold.
#[test]
fn the_error_follows_the_tolerance_for_every_method() {
    let runs = |tolerance| {
        [
            ("rk4", error_and_steps(Rk4, tolerance)),
            ("midpoint", error_and_steps(Midpoint::default(), tolerance)),
            (
                "discrete gradient",
                error_and_steps(DiscreteGradient::default(), tolerance),
            ),
        ]
    };
    let (loose, tight) = (runs(1e-6), runs(1e-9));
    for ((name, (error, steps)), (_, (tight_error, tight_steps))) in loose.into_iter().zip(tight) {
        println!(
            "{name}: error {error:.2e} in {steps} steps at 1e-6, \
             {tight_error:.2e} in {tight_steps} at 1e-9"
        );
        assert!(error < steps as f64 * 1e-6, "{name}: {error:e}");
        assert!(
            tight_error < tight_steps as f64 * 1e-9,
            "{name}: {tight_error:e}"
        );
        assert!(
            tight_error < error / 100.0,
            "{name}: {error:e} -> {tight_error:e}"
        );
    }
}

/// Both the whole step and the two halves keep the energy exactly; their
/// extrapolation changes it by the order of the square of their
/// difference, at most `3 tol (1 + |x|)`, per step: over 100 s at 1e-6,
/// within the steps times that square.
#[test]
fn the_controlled_discrete_gradient_keeps_the_energy() {
    let tolerance = 1e-6;
    let drift = |solution: &Solution<[f64; 2]>| {
        let start = Pendulum.energy(&X0);
        ((Pendulum.energy(&solution.x) - start) / start).abs()
    };
    let gradient = Controlled::new(DiscreteGradient::default(), tolerance, tolerance)
        .integrate(&Pendulum, (0.0, X0), 100.0)
        .unwrap();
    let per_step = (3.0 * tolerance * (1.0 + X0[0])).powi(2);
    let drift = drift(&gradient);
    assert!(
        drift < gradient.effort.accepted as f64 * per_step,
        "{drift:e} in {} steps",
        gradient.effort.accepted
    );
}

/// One RK4 step of 1.5 from `x = 1` leaves the domain of
/// `xdot = -sqrt(x)` (see `split_steps`); the controlled method shortens
/// it and reaches `x(1.5) = (1 - 0.75)^2` to its tolerance.
#[test]
fn a_step_leaving_the_domain_is_shortened() {
    assert!(matches!(
        Rk4.step(&Draining, 0.0, &[1.0], 1.5),
        Err(Error::NonFinite { .. })
    ));
    let solution = Controlled::new(Rk4, 1e-10, 1e-10)
        .integrate(&Draining, (0.0, [1.0]), 1.5)
        .unwrap();
    assert!((solution.x[0] - 0.0625).abs() < 1e-9, "{:?}", solution.x);
    assert!(solution.effort.rejected > 0);
}

/// Tolerances no step above the smallest allowed can meet end in a step
/// size underflow naming the time reached, not in a hang.
#[test]
fn unreachable_tolerances_underflow() {
    let mut controlled = Controlled::new(Rk4, 0.0, 1e-300);
    controlled.min_step = 1e-6;
    let error = controlled.integrate(&Pendulum, (0.0, X0), 1.0).unwrap_err();
    assert!(
        matches!(error, Error::StepSizeUnderflow { h, .. } if h < 1e-6),
        "{error}"
    );
}
