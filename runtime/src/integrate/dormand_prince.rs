//! The Dormand-Prince 5(4) embedded Runge-Kutta pair with step size control
//! (Dormand & Prince, "A family of embedded Runge-Kutta formulae", J. Comput.
//! Appl. Math. 6, 1980; coefficients and controller as in Hairer, Nørsett &
//! Wanner, *Solving Ordinary Differential Equations I*, 2nd ed., 1993,
//! section II.4, table 4.6 and the code DOPRI5).
//!
//! Order 5, propagated with local extrapolation; the embedded order-4
//! solution estimates the local error. A step is accepted when the error,
//! scaled per component by `atol + rtol max(|x_i|, |X_i|)`, has RMS norm at
//! most 1; the next step is `h min(5, max(0.2, 0.9 err^(-1/5)))` (no growth
//! right after a rejection). Seven stages, the last reused as the first of
//! the next step (FSAL). Each accepted step has a continuous extension of
//! order 4 ([`DenseStep`], Hairer, Nørsett & Wanner, section II.6), for
//! output between steps. It conserves linear invariants; the global error of
//! other quantities is roughly proportional to the tolerance.

use super::{
    Effort, Error, Limits, NonFiniteCause, StepAt, Tolerance, combine, finite_start, step_factor,
};
use crate::state::State;
use crate::system::OdeSystem;

/// Dormand-Prince 5(4) with its tolerances and limits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DormandPrince {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// Smallest step size allowed (absolute value).
    pub min_step: f64,
    /// Steps allowed per call of [`DormandPrince::integrate`], accepted and
    /// rejected.
    pub max_steps: usize,
}

impl Default for DormandPrince {
    /// `rtol = atol = 1e-8`, `min_step = 1e-14`, `max_steps = 10^6`.
    fn default() -> Self {
        Self {
            rtol: 1e-8,
            atol: 1e-8,
            min_step: 1e-14,
            max_steps: 1_000_000,
        }
    }
}

pub use super::Solution;

const C: [f64; 6] = [1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const A2: [f64; 1] = [1.0 / 5.0];
const A3: [f64; 2] = [3.0 / 40.0, 9.0 / 40.0];
const A4: [f64; 3] = [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0];
const A5: [f64; 4] = [
    19372.0 / 6561.0,
    -25360.0 / 2187.0,
    64448.0 / 6561.0,
    -212.0 / 729.0,
];
const A6: [f64; 5] = [
    9017.0 / 3168.0,
    -355.0 / 33.0,
    46732.0 / 5247.0,
    49.0 / 176.0,
    -5103.0 / 18656.0,
];
/// The order-5 weights (also the seventh stage's row).
const B: [f64; 6] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
];
/// Order-5 minus order-4 weights, for the seven stages.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

/// Weights of the stages in the dense output's last coefficient (Hairer,
/// Nørsett & Wanner, section II.6; the code DOPRI5). `k2` has weight 0.
const DENSE: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// One trial step: the seven stages, the order-5 state and the scaled error
/// estimate.
struct Trial<X> {
    stages: [X; 7],
    x: X,
    error: f64,
}

/// An accepted step with its continuous extension of order 4 (Dormand &
/// Prince 1986 via Hairer, Nørsett & Wanner, section II.6): a quartic in
/// `theta = (t - start)/h` through both end states, exact in `f` at both ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DenseStep<X> {
    start: f64,
    h: f64,
    coefficients: [X; 5],
}

impl<X: State> DenseStep<X> {
    fn new(start: f64, h: f64, x: &X, trial: &Trial<X>) -> Self {
        let k = &trial.stages;
        let difference = x.with_entries(|i| trial.x[i] - x[i]);
        let at_start = x.with_entries(|i| h * k[0][i] - difference[i]);
        let fourth = x.with_entries(|i| difference[i] - h * k[6][i] - at_start[i]);
        let fifth = x.with_entries(|i| h * (0..7).map(|s| DENSE[s] * k[s][i]).sum::<f64>());
        let coefficients = [x.clone(), difference, at_start, fourth, fifth];
        Self {
            start,
            h,
            coefficients,
        }
    }

    /// The time at the start of the step.
    pub fn start(&self) -> f64 {
        self.start
    }

    /// The time at the end of the step.
    pub fn end(&self) -> f64 {
        self.start + self.h
    }

    /// The interpolated state at time `t`, meant for `t` within the step.
    pub fn at(&self, t: f64) -> X {
        let theta = (t - self.start) / self.h;
        let rest = 1.0 - theta;
        let [r1, r2, r3, r4, r5] = &self.coefficients;
        r1.with_entries(|i| {
            r1[i] + theta * (r2[i] + rest * (r3[i] + theta * (r4[i] + rest * r5[i])))
        })
    }
}

impl DormandPrince {
    /// Integrates from `x0` at `t0` to `t1` (forward or backward).
    ///
    /// # Errors
    /// [`Error::NonFinite`] when the right-hand side at the start is not
    /// finite, or when the step fell below `min_step` rejected for stages
    /// that were not finite (a step into where `f` is undefined is retried
    /// shorter first); [`Error::StepSizeUnderflow`] when the step needed to
    /// meet the tolerance falls below `min_step` (or below round-off of
    /// `t`); [`Error::TooManySteps`].
    pub fn integrate<S: OdeSystem<X>, X: State>(
        &self,
        system: &S,
        start: (f64, X),
        t1: f64,
    ) -> Result<Solution<X>, Error> {
        self.integrate_with(system, start, t1, |_| {})
    }

    /// [`DormandPrince::integrate`], calling `observe` with every accepted
    /// step and its continuous extension, in order.
    ///
    /// # Errors
    /// As [`DormandPrince::integrate`].
    pub fn integrate_with<S: OdeSystem<X>, X: State>(
        &self,
        system: &S,
        start: (f64, X),
        t1: f64,
        observe: impl FnMut(&DenseStep<X>),
    ) -> Result<Solution<X>, Error> {
        let mut effort = Effort::default();
        let x = self.steps(system, start, t1, observe, &mut effort)?;
        Ok(Solution { x, effort })
    }

    /// [`DormandPrince::integrate`], adding its steps to `effort` (those
    /// before a failure too).
    ///
    /// # Errors
    /// As [`DormandPrince::integrate`].
    pub fn integrate_counting<S: OdeSystem<X>, X: State>(
        &self,
        system: &S,
        start: (f64, X),
        t1: f64,
        effort: &mut Effort,
    ) -> Result<X, Error> {
        self.steps(system, start, t1, |_| {}, effort)
    }

    /// The steps from `x0` at `t0` to `t1`, each accepted one observed,
    /// counted in `effort`.
    fn steps<S: OdeSystem<X>, X: State>(
        &self,
        system: &S,
        (t0, x0): (f64, X),
        t1: f64,
        mut observe: impl FnMut(&DenseStep<X>),
        effort: &mut Effort,
    ) -> Result<X, Error> {
        let (mut t, mut x) = (t0, finite_start(t0, x0)?);
        let start = StepAt {
            t,
            h: 0.0,
            x: x.as_ref(),
        };
        let mut f = start.finite(system.rhs(t, &x), NonFiniteCause::RightHandSide)?;
        let mut h = self.initial_step(x.as_ref(), f.as_ref(), t1 - t0);
        let (steps, mut just_rejected) = (effort.accepted + effort.rejected, false);
        let mut non_finite_trial = false;
        while (t1 - t) * (t1 - t0).signum() > 0.0 {
            let limits = Limits {
                min_step: self.min_step,
                max_steps: self.max_steps,
            };
            limits
                .check(t, h, x.as_ref(), effort.accepted + effort.rejected - steps)
                .map_err(|error| match error {
                    // the step shrank to nothing because its stages were not finite
                    Error::StepSizeUnderflow { t, h, state } if non_finite_trial => {
                        Error::NonFinite {
                            t,
                            h,
                            cause: NonFiniteCause::RightHandSide,
                            state,
                        }
                    }
                    other => other,
                })?;
            let last = (t + h - t1) * h.signum() >= 0.0;
            let step = if last { t1 - t } else { h };
            let trial = self.trial(system, t, &x, &f, step);
            non_finite_trial = !trial
                .stages
                .iter()
                .all(|stage| stage.as_ref().iter().all(|v| v.is_finite()));
            let error = if trial.error.is_nan() {
                f64::INFINITY
            } else {
                trial.error
            };
            if error <= 1.0 {
                observe(&DenseStep::new(t, step, &x, &trial));
                let at = StepAt {
                    t,
                    h: step,
                    x: x.as_ref(),
                };
                let next = at.finite(trial.x, NonFiniteCause::NewState)?;
                let [.., last_stage] = trial.stages;
                (x, f) = (next, last_stage);
                t = if last { t1 } else { t + step };
                effort.accepted += 1;
            } else {
                effort.rejected += 1;
            }
            // the embedded estimate is of order 4
            h = step * step_factor(error, 4, just_rejected);
            just_rejected = error > 1.0;
        }
        Ok(x)
    }

    fn tolerance(&self) -> Tolerance {
        Tolerance {
            rtol: self.rtol,
            atol: self.atol,
        }
    }

    /// A first step `0.01 |x| / |f|` (RMS norms scaled by the tolerances;
    /// Hairer, Nørsett & Wanner, section II.4), at most the whole span.
    fn initial_step(&self, x: &[f64], f: &[f64], span: f64) -> f64 {
        let (dx, df) = (
            self.tolerance().scaled_norm(x, x, x),
            self.tolerance().scaled_norm(f, x, x),
        );
        let h = if dx < 1e-5 || df < 1e-5 {
            1e-6
        } else {
            0.01 * dx / df
        };
        h.min(span.abs()) * span.signum()
    }

    /// The six new stages of a step of size `h`, the order-5 state and its
    /// scaled error estimate.
    fn trial<S: OdeSystem<X>, X: State>(
        &self,
        system: &S,
        t: f64,
        x: &X,
        k1: &X,
        h: f64,
    ) -> Trial<X> {
        let k2 = system.rhs(t + C[0] * h, &combine(x, h, &[(A2[0], k1)]));
        let k3 = system.rhs(t + C[1] * h, &combine(x, h, &[(A3[0], k1), (A3[1], &k2)]));
        let y4 = combine(x, h, &[(A4[0], k1), (A4[1], &k2), (A4[2], &k3)]);
        let k4 = system.rhs(t + C[2] * h, &y4);
        let y5 = combine(
            x,
            h,
            &[(A5[0], k1), (A5[1], &k2), (A5[2], &k3), (A5[3], &k4)],
        );
        let k5 = system.rhs(t + C[3] * h, &y5);
        let six = [
            (A6[0], k1),
            (A6[1], &k2),
            (A6[2], &k3),
            (A6[3], &k4),
            (A6[4], &k5),
        ];
        let k6 = system.rhs(t + C[4] * h, &combine(x, h, &six));
        let stages = [
            (B[0], k1),
            (B[2], &k3),
            (B[3], &k4),
            (B[4], &k5),
            (B[5], &k6),
        ];
        let next = combine(x, h, &stages);
        let k7 = system.rhs(t + C[5] * h, &next);
        let all = [k1, &k2, &k3, &k4, &k5, &k6, &k7];
        let difference = x.with_entries(|i| h * (0..7).map(|s| E[s] * all[s][i]).sum::<f64>());
        Trial {
            error: self
                .tolerance()
                .scaled_norm(difference.as_ref(), x.as_ref(), next.as_ref()),
            stages: [k1.clone(), k2, k3, k4, k5, k6, k7],
            x: next,
        }
    }
}
