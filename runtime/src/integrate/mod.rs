//! Integrators over any [`OdeSystem`].
//!
//! | method | module | order | conserves |
//! |---|---|---|---|
//! | classical Runge-Kutta | [`rk4`] | 4 | linear invariants |
//! | Dormand-Prince 5(4), adaptive, dense output of order 4 | [`dormand_prince`] | 5 | linear invariants |
//! | implicit midpoint, Newton | [`midpoint`] | 2 | quadratic invariants; `H` of `xdot = J(x) dH/dx` for quadratic `H`, skew `J` |
//! | Gonzalez discrete gradient, Newton | [`discrete_gradient`] | 2 | `H` of `xdot = J(x) dH/dx` for any `H`, skew `J`; the power balance `H(X) - H(x) = h dH . F` with forcing |
//!
//! Fixed-step methods implement [`FixedStep`] and run with
//! [`integrate_fixed`], or with their step following tolerances by step
//! doubling ([`Controlled`]). Every method is written once over a
//! [`State`]: on fixed-size arrays a step stays on the stack and does not
//! allocate; only a returned [`Error`] allocates (a copy of the state).
//! An integration counts what it takes ([`Effort`]): its steps accepted
//! and rejected and the Newton iterations of its implicit steps.

mod controlled;
pub mod discrete_gradient;
pub mod dormand_prince;
pub mod midpoint;
mod newton;
pub mod rk4;

pub use controlled::Controlled;
pub use discrete_gradient::DiscreteGradient;
pub use dormand_prince::{DenseStep, DormandPrince};
pub use midpoint::Midpoint;
pub use rk4::Rk4;

use crate::state::State;
use crate::system::OdeSystem;

/// Why an integration stopped.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum Error {
    /// A value of the step became NaN or infinite: the new state, a stage
    /// of the right-hand side, or a Newton iterate's residual.
    #[error("non-finite {cause} in the step from t = {t} (h = {h}), state {state:?}")]
    NonFinite {
        /// Time at the start of the step (for a non-finite initial state,
        /// the initial time).
        t: f64,
        /// The step size (0 for the initial state).
        h: f64,
        /// What became non-finite.
        cause: NonFiniteCause,
        /// The state at the start of the step.
        state: Vec<f64>,
    },
    /// Newton's method of an implicit step did not converge.
    #[error(
        "Newton's method did not converge in the step from t = {t} (h = {h}): \
         last update {update:e} after {iterations} iterations, state {state:?}"
    )]
    NewtonFailure {
        /// Time at the start of the step.
        t: f64,
        /// The step size.
        h: f64,
        /// Iterations made.
        iterations: usize,
        /// Largest entry of the last Newton update.
        update: f64,
        /// The state at the start of the step.
        state: Vec<f64>,
    },
    /// The Jacobian of an implicit step's equation (`I - h/2 df/dx` at the
    /// iterate) had no nonzero pivot in an iteration of Newton's method.
    #[error(
        "singular Newton matrix I - h/2 df/dx in iteration {iteration} of the step from t = {t} \
         (h = {h}), state {state:?}"
    )]
    SingularJacobian {
        /// Time at the start of the step.
        t: f64,
        /// The step size.
        h: f64,
        /// The Newton iteration, from 1.
        iteration: usize,
        /// The state at the start of the step.
        state: Vec<f64>,
    },
    /// An adaptive method needed a step below its minimum to meet its tolerance.
    #[error("step size underflow at t = {t}: h = {h:e}, state {state:?}")]
    StepSizeUnderflow {
        /// Time at which the step failed.
        t: f64,
        /// The rejected step size.
        h: f64,
        /// The state at time `t`.
        state: Vec<f64>,
    },
    /// An adaptive method reached its maximum number of steps.
    #[error("{steps} steps taken by t = {t} without reaching the end, state {state:?}")]
    TooManySteps {
        /// Time reached.
        t: f64,
        /// Steps taken (accepted and rejected).
        steps: usize,
        /// The state at time `t`.
        state: Vec<f64>,
    },
}

impl Error {
    /// The time at which the integration stopped (the start of the failed
    /// step).
    pub fn time(&self) -> f64 {
        match self {
            Self::NonFinite { t, .. }
            | Self::NewtonFailure { t, .. }
            | Self::SingularJacobian { t, .. }
            | Self::StepSizeUnderflow { t, .. }
            | Self::TooManySteps { t, .. } => *t,
        }
    }

    /// Whether the step may pass when taken in shorter steps: Newton's
    /// iteration diverging or meeting a singular matrix, or a stage, an
    /// iterate or the new state not finite (leaving the model's domain),
    /// all of which a step too long for the motion causes (a handlebar
    /// whipping through a turn within one step). A non-finite initial
    /// state, and the adaptive method's step size underflow and step count,
    /// are final.
    pub fn may_pass_in_shorter_steps(&self) -> bool {
        match self {
            Self::NewtonFailure { .. } | Self::SingularJacobian { .. } => true,
            Self::NonFinite { cause, .. } => *cause != NonFiniteCause::InitialState,
            Self::StepSizeUnderflow { .. } | Self::TooManySteps { .. } => false,
        }
    }

    /// The state at [`Error::time`].
    pub fn state(&self) -> &[f64] {
        match self {
            Self::NonFinite { state, .. }
            | Self::NewtonFailure { state, .. }
            | Self::SingularJacobian { state, .. }
            | Self::StepSizeUnderflow { state, .. }
            | Self::TooManySteps { state, .. } => state,
        }
    }
}

/// What became NaN or infinite in a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NonFiniteCause {
    /// The initial state.
    InitialState,
    /// The right-hand side `f(t, x)` at the state or at a stage.
    RightHandSide,
    /// The energy `H(x)` at the state (the discrete gradient's).
    Energy,
    /// The residual of an implicit step's equation at a Newton iterate
    /// (for the discrete gradient, the energy there).
    NewtonResidual,
    /// The new state.
    NewState,
}

impl std::fmt::Display for NonFiniteCause {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::InitialState => "initial state",
            Self::RightHandSide => "right-hand side f(t, x)",
            Self::Energy => "energy H(x)",
            Self::NewtonResidual => "residual of the implicit step's equation at a Newton iterate",
            Self::NewState => "new state",
        })
    }
}

/// A one-step method with a fixed step size, for systems of type `S` on
/// states of type `X`.
pub trait FixedStep<S, X> {
    /// The order `p` of the method: the local error of a step is
    /// `O(h^(p+1))`.
    const ORDER: u32;

    /// The state at `t + h` from the state `x` at `t`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] when the new state is not finite; the method's own
    /// failures (e.g. [`Error::NewtonFailure`], [`Error::SingularJacobian`]).
    fn step(&self, system: &S, t: f64, x: &X, h: f64) -> Result<X, Error> {
        self.step_counting(system, t, x, h, &mut 0)
    }

    /// [`FixedStep::step`], adding the Newton iterations it makes to
    /// `iterations` (those of a solve that fails too; none for an explicit
    /// method).
    ///
    /// # Errors
    /// As [`FixedStep::step`].
    fn step_counting(
        &self,
        system: &S,
        t: f64,
        x: &X,
        h: f64,
        iterations: &mut usize,
    ) -> Result<X, Error>;
}

/// Takes `steps` steps of size `h` from `x0` at `t0`, calling
/// `observe(t, x)` after each; returns the final state.
///
/// # Errors
/// The first error of a step.
pub fn integrate_fixed<S, M, X>(
    method: &M,
    system: &S,
    (t0, x0): (f64, X),
    h: f64,
    steps: usize,
    mut observe: impl FnMut(f64, &X),
) -> Result<X, Error>
where
    S: OdeSystem<X>,
    M: FixedStep<S, X>,
{
    let mut x = x0;
    for i in 0..steps {
        let t = t0 + i as f64 * h;
        x = method.step(system, t, &x, h)?;
        observe(t + h, &x);
    }
    Ok(x)
}

/// [`Error::NewtonFailure`], [`Error::SingularJacobian`] or
/// [`Error::NonFinite`] for the step of size `h` from `x` at `t`.
pub(crate) fn newton_failure(failure: newton::Failure, t: f64, h: f64, x: &[f64]) -> Error {
    let state = x.to_vec();
    match failure {
        newton::Failure::Diverged { iterations, update } => Error::NewtonFailure {
            t,
            h,
            iterations,
            update,
            state,
        },
        newton::Failure::SingularJacobian { iteration } => Error::SingularJacobian {
            t,
            h,
            iteration,
            state,
        },
        newton::Failure::NonFinite => Error::NonFinite {
            t,
            h,
            cause: NonFiniteCause::NewtonResidual,
            state,
        },
    }
}

/// Where a value is checked: the step of size `h` from the state `x` at `t`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StepAt<'a> {
    pub(crate) t: f64,
    pub(crate) h: f64,
    pub(crate) x: &'a [f64],
}

impl StepAt<'_> {
    /// `value` itself when all its entries are finite, else
    /// [`Error::NonFinite`] with `cause`, this step and its start state.
    pub(crate) fn finite<V: AsRef<[f64]>>(
        &self,
        value: V,
        cause: NonFiniteCause,
    ) -> Result<V, Error> {
        if value.as_ref().iter().all(|v| v.is_finite()) {
            Ok(value)
        } else {
            Err(Error::NonFinite {
                t: self.t,
                h: self.h,
                cause,
                state: self.x.to_vec(),
            })
        }
    }
}

/// The initial state `x0` at `t0` when it is finite, else
/// [`Error::NonFinite`].
pub(crate) fn finite_start<X: AsRef<[f64]>>(t0: f64, x0: X) -> Result<X, Error> {
    if x0.as_ref().iter().all(|v| v.is_finite()) {
        return Ok(x0);
    }
    Err(Error::NonFinite {
        t: t0,
        h: 0.0,
        cause: NonFiniteCause::InitialState,
        state: x0.as_ref().to_vec(),
    })
}

/// What an integration took: its steps and the Newton iterations of its
/// implicit steps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Effort {
    /// Accepted steps.
    pub accepted: usize,
    /// Rejected steps: the error estimate too large, or the method failing
    /// on the step (Newton's iteration diverging, a stage leaving the
    /// model's domain), the step then taken again shorter.
    pub rejected: usize,
    /// Newton iterations, in accepted and rejected steps alike (each one
    /// evaluation of `f` and its Jacobian and one LU solve).
    pub newton_iterations: usize,
}

/// The end of an adaptive integration ([`DormandPrince::integrate`],
/// [`Controlled::integrate`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution<X> {
    /// The state at the final time.
    pub x: X,
    /// The steps accepted and rejected, and the Newton iterations.
    pub effort: Effort,
}

/// The tolerances of an adaptive method's local error.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tolerance {
    pub(crate) rtol: f64,
    pub(crate) atol: f64,
}

impl Tolerance {
    /// The RMS norm of the error estimate `v` scaled per component by
    /// `atol + rtol max(|x_i|, |y_i|)`, at the step's two ends `x` and `y`.
    pub(crate) fn scaled_norm(&self, v: &[f64], x: &[f64], y: &[f64]) -> f64 {
        let sum: f64 = (0..v.len())
            .map(|i| (v[i] / (self.atol + self.rtol * x[i].abs().max(y[i].abs()))).powi(2))
            .sum();
        (sum / v.len().max(1) as f64).sqrt()
    }
}

/// The factor of the next step after one with the scaled error estimate
/// `error` of a method whose error estimate is of order `order`:
/// `0.9 error^(-1/(order + 1))`, between 0.2 and 5, at most 1 right after
/// a rejection (Hairer, Nørsett & Wanner I, section II.4).
pub(crate) fn step_factor(error: f64, order: u32, just_rejected: bool) -> f64 {
    let growth = if just_rejected { 1.0 } else { 5.0 };
    (0.9 * error.powf(-1.0 / f64::from(order + 1))).clamp(0.2, growth)
}

/// The limits of an adaptive method's steps.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Limits {
    pub(crate) min_step: f64,
    pub(crate) max_steps: usize,
}

impl Limits {
    /// Whether another step of size `h` at `t` is allowed after `steps`
    /// steps, from the state `x` (a NaN step, e.g. from zero tolerances, is
    /// an underflow).
    pub(crate) fn check(&self, t: f64, h: f64, x: &[f64], steps: usize) -> Result<(), Error> {
        if steps >= self.max_steps {
            return Err(Error::TooManySteps {
                t,
                steps,
                state: x.to_vec(),
            });
        }
        if h.is_nan() || h.abs() < self.min_step.max(16.0 * f64::EPSILON * t.abs()) {
            return Err(Error::StepSizeUnderflow {
                t,
                h,
                state: x.to_vec(),
            });
        }
        Ok(())
    }
}

/// `x + h sum_i b_i k_i`.
pub(crate) fn combine<X: State>(x: &X, h: f64, terms: &[(f64, &X)]) -> X {
    x.with_entries(|i| x[i] + h * terms.iter().map(|(b, k)| b * k[i]).sum::<f64>())
}

/// The largest absolute entry; NaN when an entry is NaN (`f64::max` would
/// drop it, and a NaN update would pass for a converged one).
pub(crate) fn max_norm(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| {
        if v.is_nan() || m.is_nan() {
            f64::NAN
        } else {
            m.max(v.abs())
        }
    })
}
