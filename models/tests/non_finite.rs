//! A step that meets a non-finite value stops with a structured error saying
//! where (the step's start `t`, its size `h`, the finite state it started
//! from) and why (which value went non-finite), instead of returning a NaN
//! state.
//!
//! The system: `xdot = J dH/dx`, `J = [[0, 1], [-1, 0]]`, with the energy
//! `H(x) = (x0^2 + x1^2)/2 + sqrt(x1 + 0.95)`, not defined below
//! `x1 = -0.95`, where long steps from `x = (1, 0)` land.

use chaplygin::runtime::Error;
use chaplygin::runtime::integrate::{
    DiscreteGradient, DormandPrince, FixedStep, NonFiniteCause, Rk4,
};
use chaplygin::runtime::system::{Energy, Jacobian, OdeSystem, Structured};

struct Walled;

impl Walled {
    fn gradient(x: &[f64; 2]) -> [f64; 2] {
        [x[0], x[1] + 0.5 / (x[1] + 0.95).sqrt()]
    }
}

impl OdeSystem<[f64; 2]> for Walled {
    fn rhs(&self, _t: f64, x: &[f64; 2]) -> [f64; 2] {
        let gradient = Self::gradient(x);
        [gradient[1], -gradient[0]]
    }
}

impl Jacobian<[f64; 2]> for Walled {
    fn jacobian(&self, _t: f64, x: &[f64; 2]) -> [[f64; 2]; 2] {
        [[0.0, 1.0 - 0.25 * (x[1] + 0.95).powf(-1.5)], [-1.0, 0.0]]
    }
}

impl Energy<[f64; 2]> for Walled {
    fn energy(&self, x: &[f64; 2]) -> f64 {
        (x[0] * x[0] + x[1] * x[1]) / 2.0 + (x[1] + 0.95).sqrt()
    }
}

impl Structured<[f64; 2]> for Walled {
    fn structure_matrix(&self, _x: &[f64; 2]) -> [[f64; 2]; 2] {
        [[0.0, 1.0], [-1.0, 0.0]]
    }

    fn energy_gradient(&self, x: &[f64; 2]) -> [f64; 2] {
        Self::gradient(x)
    }

    fn forcing(&self, _t: f64, _x: &[f64; 2]) -> [f64; 2] {
        [0.0; 2]
    }
}

/// Asserts `error` is [`Error::NonFinite`] for the step of size `h` from
/// `(1, 0)` at `t = 0`, with `cause`.
fn assert_non_finite(error: Error, h: f64, cause: NonFiniteCause) {
    assert_eq!(
        error,
        Error::NonFinite {
            t: 0.0,
            h,
            cause,
            state: vec![1.0, 0.0],
        },
        "{error}"
    );
}

/// The discrete gradient's Newton iteration starts (explicit midpoint, from
/// finite stages) at `x1 = -1.57`, where `H` is NaN: its residual there is
/// NaN. (Newton's update used to be measured with `f64::max`, which drops
/// NaN entries, so the NaN iterate passed for converged and the step
/// returned a NaN state.)
#[test]
fn the_discrete_gradient_stops_at_a_non_finite_newton_residual() {
    let error = DiscreteGradient::default()
        .step(&Walled, 0.0, &[1.0, 0.0], 1.2)
        .unwrap_err();
    let message = error.to_string();
    assert!(
        message.starts_with("non-finite residual of the implicit step's equation"),
        "{message}"
    );
    assert_non_finite(error, 1.2, NonFiniteCause::NewtonResidual);
    // a short step stays where H is defined and conserves it
    let x = DiscreteGradient::default()
        .step(&Walled, 0.0, &[1.0, 0.0], 0.1)
        .unwrap();
    let drift = (Walled.energy(&x) - Walled.energy(&[1.0, 0.0])).abs();
    assert!(drift <= 1e-13, "{drift}");
}

/// RK4's second stage `x + h/2 k1` lies at `x1 = -1`: the right-hand side
/// there is NaN.
#[test]
fn rk4_stops_at_a_non_finite_stage() {
    let error = Rk4.step(&Walled, 0.0, &[1.0, 0.0], 2.0).unwrap_err();
    assert_non_finite(error, 2.0, NonFiniteCause::RightHandSide);
}

/// Dormand-Prince retries a step whose stages are not finite with a shorter
/// one; running into the wall (the flow reaches `x1 = -0.95`, where `H` ends,
/// at a finite time), its steps shrink to nothing on non-finite stages, and
/// the error says so, from the last finite state, instead of reporting an
/// underflow.
#[test]
fn dormand_prince_into_the_wall_says_the_stages_were_not_finite() {
    let error = DormandPrince::default()
        .integrate(&Walled, (0.0, [1.0, 0.0]), 10.0)
        .unwrap_err();
    match &error {
        Error::NonFinite {
            t, cause, state, ..
        } => {
            assert_eq!(*cause, NonFiniteCause::RightHandSide);
            assert!(*t > 0.0 && state.iter().all(|v| v.is_finite()), "{error}");
            assert!(state[1] > -0.95 && state[1] < -0.9, "{error}");
        }
        other => panic!("{other}"),
    }
}
