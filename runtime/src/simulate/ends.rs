//! Where a run ends because the mechanics does (docs/guide/simulating.md, "Where a run
//! ends"): a step that fails, or that comes to the edge of the model's own
//! domain, is stopped with the cause named where it is known.
//!
//! - The model's guarded expressions ([`crate::system::Domain`]: square
//!   roots, logarithms, divisors, tangents) are checked after every step:
//!   the run stops where one fails (a positive value turned non-positive, a
//!   divisor through zero) or falls below [`REACHED`] times its value at the
//!   start, the edge where its derivatives grow without bound (the benchmark
//!   bicycle's front contact divides by a square root that reaches zero as
//!   a double root where the front wheel lies flat, so it never turns
//!   negative).
//! - Where a step fails (its integrator, the projection onto the
//!   constraints, or the regularity measure), the step's explicit predictor
//!   `x + theta h f(t, x)` ([`PREDICTED`]) is searched for what it crossed:
//!   a guard that fails, constraint rows that turn dependent
//!   ([`crate::monitor::dependent_rows`]), or a guard below
//!   [`NEAR_BOUNDARY`] times its value at the start. Failing that, the
//!   step's own error stands.

use super::{GuardedValue, Observed, SimulationError};
use crate::state::State;

/// The fractions `theta` of a failed step at which its explicit predictor
/// `x + theta h f(t, x)` is searched (0: the state the step starts from).
pub const PREDICTED: [f64; 7] = [0.0, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0];

/// Where a step fails, a guarded expression below this fraction of its
/// value at the start of the run names the cause.
pub const NEAR_BOUNDARY: f64 = 1e-2;

/// After any step, a guarded expression below this fraction of its value
/// at the start of the run ends it: the edge of the model's domain.
pub const REACHED: f64 = 1e-5;

/// What a run knows of where its model ends.
pub(crate) struct Ends<'a, S, X> {
    system: &'a S,
    state: core::marker::PhantomData<fn(&X)>,
    /// The guarded expressions at the start.
    start: Vec<GuardedValue<'a>>,
    singular_below: f64,
}

impl<'a, S: Observed<X>, X: State> Ends<'a, S, X> {
    pub(super) fn new(system: &'a S, x0: &X, singular_below: f64) -> Self {
        Self {
            system,
            state: core::marker::PhantomData,
            start: system.domain(x0),
            singular_below,
        }
    }

    /// [`SimulationError::Undefined`] when a guarded expression fails at
    /// the initial state `x0` (time `t0`).
    pub(super) fn at_start(&self, t0: f64, x0: &X) -> Result<(), SimulationError> {
        match self.start.iter().find(|guard| guard.fails()) {
            Some(failed) => Err(self.undefined(t0, true, failed.clone(), x0)),
            None => Ok(()),
        }
    }

    /// After the step from `x` at `t` to `next`: the guarded expression
    /// that fails at `next`, or falls below [`REACHED`] times its value at
    /// the start there, if any.
    pub(super) fn reached(&self, t: f64, x: &X, next: &X) -> Result<(), SimulationError> {
        match self
            .failed(x, next)
            .or_else(|| self.smallest_below(next, REACHED))
        {
            Some(guard) => Err(self.undefined(t, false, guard, next)),
            None => Ok(()),
        }
    }

    /// The cause of the failure `error` of the step of size `h` from `x`
    /// at `t`, where it is known (see the module documentation); `error`
    /// otherwise.
    pub(super) fn explain(&self, t: f64, x: &X, h: f64, error: SimulationError) -> SimulationError {
        let rate = self.system.rhs(t, x);
        let predicted: Vec<X> = match rate.as_ref().iter().all(|v| v.is_finite()) {
            true => PREDICTED
                .iter()
                .map(|theta| x.with_entries(|i| x[i] + theta * h * rate[i]))
                .collect(),
            false => vec![x.clone()],
        };
        let undefined = predicted.iter().find_map(|next| {
            self.failed(x, next)
                .map(|guard| self.undefined(t, false, guard, next))
        });
        let rows = || {
            predicted.iter().find_map(|next| {
                let rows = self.system.dependent_rows(next);
                (!rows.is_empty()).then(|| self.dependent(t, rows, next))
            })
        };
        let near = || {
            predicted.iter().find_map(|next| {
                self.smallest_below(next, NEAR_BOUNDARY)
                    .map(|guard| self.undefined(t, false, guard, next))
            })
        };
        let singular = matches!(error, SimulationError::Singular { .. });
        undefined
            .or_else(|| if singular { None } else { rows() })
            .or_else(near)
            .unwrap_or_else(|| self.rows_crossed(x, error))
    }

    /// A regularity measure that changed sign in the step from `x` names
    /// the constraint rows dependent where it crossed zero, found by
    /// bisection on the segment from `x` to the step's end (a point within
    /// the step's own error of the path, where the rows are far closer to
    /// dependent than at either end); any other error is returned as it is.
    fn rows_crossed(&self, x: &X, mut error: SimulationError) -> SimulationError {
        if let SimulationError::Singular {
            rows,
            crossed: true,
            state,
            ..
        } = &mut error
            && rows.is_empty()
        {
            let next = x.with_entries(|i| state[i]);
            let at = |s: f64| x.with_entries(|i| x[i] + s * (next[i] - x[i]));
            let sign = self.system.regularity(x).value.signum();
            let (mut low, mut high) = (0.0, 1.0);
            for _ in 0..60 {
                let middle = 0.5 * (low + high);
                match self.system.regularity(&at(middle)).value.signum() == sign {
                    true => low = middle,
                    false => high = middle,
                }
            }
            *rows = self.system.dependent_rows(&at(0.5 * (low + high)));
        }
        error
    }

    /// The first guarded expression that fails at `next` where it held at `x`.
    fn failed(&self, x: &X, next: &X) -> Option<GuardedValue<'a>> {
        let before = self.system.domain(x);
        self.system
            .domain(next)
            .into_iter()
            .zip(before)
            .find(|(guard, before)| guard.fails_from(before.value))
            .map(|(guard, _)| guard)
    }

    /// The guarded expression smallest relative to its value at the start,
    /// at `x`, if below `fraction` of it.
    fn smallest_below(&self, x: &X, fraction: f64) -> Option<GuardedValue<'a>> {
        let relative = |(guard, start): &(GuardedValue<'_>, &GuardedValue<'_>)| {
            (guard.value / start.value).abs()
        };
        self.system
            .domain(x)
            .into_iter()
            .zip(&self.start)
            .filter(|pair| relative(pair) < fraction)
            .min_by(|a, b| relative(a).total_cmp(&relative(b)))
            .map(|(guard, _)| guard)
    }

    fn undefined(&self, t: f64, initial: bool, guard: GuardedValue<'_>, x: &X) -> SimulationError {
        let at_start = self
            .start
            .iter()
            .find(|start| start.description == guard.description)
            .map_or(f64::NAN, |start| start.value);
        SimulationError::Undefined {
            t,
            initial,
            expression: guard.description.into_owned(),
            value: guard.value,
            at_start,
            state_names: self.system.state_names(),
            state: x.as_ref().to_vec(),
        }
    }

    fn dependent(&self, t: f64, rows: Vec<String>, x: &X) -> SimulationError {
        let regularity = self.system.regularity(x);
        SimulationError::Singular {
            t,
            rows,
            quantity: regularity.quantity,
            crossed: false,
            value: regularity.value,
            threshold: self.singular_below,
            state_names: self.system.state_names(),
            state: x.as_ref().to_vec(),
        }
    }
}
