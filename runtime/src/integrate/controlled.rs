//! Step-size control for the one-step methods by step doubling (Hairer,
//! Nørsett & Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.,
//! 1993, section II.4, "Richardson extrapolation").
//!
//! From the state `x` at `t`, a method of order `p` takes one step of size
//! `h` to `X1` and two of size `h/2` to `X2`. Their local errors are
//! `C h^(p+1)` and about `2 C (h/2)^(p+1)`, so
//!
//! ```text
//! err = (X2 - X1) / (2^p - 1)
//! ```
//!
//! estimates the error of `X2`. The step is accepted when `err`, scaled per
//! component by `atol + rtol max(|x_i|, |X2_i|)`, has RMS norm at most 1,
//! and the run goes on from the local extrapolation `X2 + err`, of order
//! `p + 1`, and `p + 2` for a symmetric method (the midpoint rule, the
//! discrete gradient), whose error expansion holds only even powers of `h`
//! (Hairer, Nørsett & Wanner, section II.8). Where `X1` and `X2` both
//! keep an invariant `I` of the method (the discrete gradient's energy, the
//! midpoint rule's quadratic invariants), `I(X2 + err) - I(x)` is
//! `dI(X2) . err + O(|err|^2)` with `dI(X2) . (X2 - X1) = O(|X2 - X1|^2)`:
//! the extrapolation moves the invariant by the square of the estimate
//! only. The next step is
//! `h min(5, max(0.2, 0.9 err^(-1/(p+1))))`, no larger than the interval
//! asked for (the command line's `--dt`), and not growing right after a
//! rejection. A step on which the method fails where shorter steps may
//! pass ([`Error::may_pass_in_shorter_steps`]: Newton's iteration
//! diverging, a stage leaving the model's domain) is rejected and taken
//! again four times shorter, so the implicit solve's convergence feeds the
//! same control.

use super::{Effort, Error, FixedStep, Limits, Solution, Tolerance, step_factor};
use crate::state::State;
use std::cell::Cell;

/// A one-step method `M` whose step follows the tolerances.
#[derive(Clone, Debug, PartialEq)]
pub struct Controlled<M> {
    /// The method stepped.
    pub method: M,
    /// Relative tolerance of the local error.
    pub rtol: f64,
    /// Absolute tolerance of the local error.
    pub atol: f64,
    /// Smallest step size allowed.
    pub min_step: f64,
    /// Steps allowed per call of [`Controlled::integrate`], accepted and
    /// rejected.
    pub max_steps: usize,
    /// The step the last accepted step proposed, where the next call
    /// starts (0 before the first).
    proposed: Cell<f64>,
}

impl<M> Controlled<M> {
    /// `method` controlled to the tolerances `rtol` and `atol`, with
    /// `min_step = 1e-14` and `max_steps = 10^6`.
    pub fn new(method: M, rtol: f64, atol: f64) -> Self {
        Self {
            method,
            rtol,
            atol,
            min_step: 1e-14,
            max_steps: 1_000_000,
            proposed: Cell::new(0.0),
        }
    }

    /// Integrates from `x0` at `t0` forward to `t1`, in steps of at most
    /// `t1 - t0`.
    ///
    /// # Errors
    /// The method's errors that shorter steps do not cure; where they do,
    /// the failure of a step shorter than `min_step`;
    /// [`Error::StepSizeUnderflow`] when the tolerances need a step below
    /// `min_step` (or below round-off of `t`); [`Error::TooManySteps`].
    pub fn integrate<S, X>(
        &self,
        system: &S,
        start: (f64, X),
        t1: f64,
    ) -> Result<Solution<X>, Error>
    where
        M: FixedStep<S, X>,
        X: State,
    {
        let mut effort = Effort::default();
        let x = self.integrate_counting(system, start, t1, &mut effort)?;
        Ok(Solution { x, effort })
    }

    /// [`Controlled::integrate`], adding its steps and Newton iterations
    /// to `effort` (those before a failure too).
    ///
    /// # Errors
    /// As [`Controlled::integrate`].
    pub fn integrate_counting<S, X>(
        &self,
        system: &S,
        (t0, x0): (f64, X),
        t1: f64,
        effort: &mut Effort,
    ) -> Result<X, Error>
    where
        M: FixedStep<S, X>,
        X: State,
    {
        let span = t1 - t0;
        let mut h = match self.proposed.get() {
            proposed if proposed > 0.0 => proposed.min(span),
            _ => span,
        };
        let (mut t, mut x) = (t0, x0);
        let (steps, mut just_rejected) = (effort.accepted + effort.rejected, false);
        while t < t1 {
            let last = t + h >= t1 - 16.0 * f64::EPSILON * t1.abs();
            let step = if last { t1 - t } else { h };
            let taken = effort.accepted + effort.rejected - steps;
            self.limits().check(t, step, x.as_ref(), taken)?;
            let error = match self.trial(system, t, &x, step, &mut effort.newton_iterations) {
                Ok((next, error)) if error <= 1.0 => {
                    (t, x) = (if last { t1 } else { t + step }, next);
                    effort.accepted += 1;
                    error
                }
                Ok((_, error)) => {
                    effort.rejected += 1;
                    error
                }
                Err(failure)
                    if failure.may_pass_in_shorter_steps() && step / 4.0 >= self.min_step =>
                {
                    effort.rejected += 1;
                    h = step / 4.0;
                    just_rejected = true;
                    continue;
                }
                Err(failure) => return Err(failure),
            };
            let next = (step * step_factor(error, M::ORDER, just_rejected)).min(span);
            just_rejected = error > 1.0;
            h = if last && !just_rejected {
                next.max(h)
            } else {
                next
            };
        }
        self.proposed.set(h);
        Ok(x)
    }

    fn tolerance(&self) -> Tolerance {
        Tolerance {
            rtol: self.rtol,
            atol: self.atol,
        }
    }

    fn limits(&self) -> Limits {
        Limits {
            min_step: self.min_step,
            max_steps: self.max_steps,
        }
    }

    /// One step of size `h` and two of `h/2` from `x` at `t`: the state
    /// the two reach and their scaled error estimate (infinite where it is
    /// not a number); their Newton iterations added to `iterations`.
    fn trial<S, X>(
        &self,
        system: &S,
        t: f64,
        x: &X,
        h: f64,
        iterations: &mut usize,
    ) -> Result<(X, f64), Error>
    where
        M: FixedStep<S, X>,
        X: State,
    {
        let method = &self.method;
        let whole = method.step_counting(system, t, x, h, iterations)?;
        let half = method.step_counting(system, t, x, h / 2.0, iterations)?;
        let two_halves = method.step_counting(system, t + h / 2.0, &half, h / 2.0, iterations)?;
        let denominator = f64::from((1_u32 << M::ORDER) - 1);
        let difference = x.with_entries(|i| (two_halves[i] - whole[i]) / denominator);
        let error =
            self.tolerance()
                .scaled_norm(difference.as_ref(), x.as_ref(), two_halves.as_ref());
        let extrapolated = x.with_entries(|i| two_halves[i] + difference[i]);
        Ok((
            extrapolated,
            if error.is_nan() { f64::INFINITY } else { error },
        ))
    }
}
