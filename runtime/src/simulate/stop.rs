//! Stop conditions: a run ends cleanly where a condition first holds
//! ([`Simulation::stop_when`](super::Simulation::stop_when)).
//!
//! A condition is an event function `g(t, x)` that holds where `g > 0`.
//! The run stops at the first step whose end has `g > 0`; within that step
//! the crossing is located by bisection on the step's length, each trial
//! state re-advanced from the step's start by the integrator itself
//! ([`super::Advance`]), so that the located state is the integrator's own
//! (for any integrator, adaptive ones included) to [`CROSSING_TOLERANCE`]
//! in `t`. A condition that holds at the start stops the run there, before
//! any step.

/// The bisection of a step where a stop condition starts to hold ends when
/// its bracket is at most this long: the located time is at most this much
/// after the first time the integrated condition holds.
pub const CROSSING_TOLERANCE: f64 = 1e-9;

/// A stop condition on states of type `X`.
pub trait StopCondition<X> {
    /// The event function `g(t, x)`: the condition holds where `g > 0`
    /// (a NaN never holds).
    fn value(&self, t: f64, x: &X) -> f64;
    /// What the condition says, reported in
    /// [`Summary::stopped`](super::Summary::stopped).
    fn description(&self) -> &str;
}

/// The condition that never holds: a run without a stop condition.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Never;

impl<X> StopCondition<X> for Never {
    fn value(&self, _t: f64, _x: &X) -> f64 {
        -1.0
    }

    fn description(&self) -> &str {
        "never"
    }
}

/// A stop condition given by its description and its event function, any
/// `Fn(f64, &X) -> f64`:
///
/// ```text
/// Stop::new("abs(phi) > 1", |_t, x: &[f64; 11]| x[3].abs() - 1.0)
/// ```
#[derive(Clone, Copy)]
pub struct Stop<S, F> {
    description: S,
    event: F,
}

impl<S: AsRef<str>, F> Stop<S, F> {
    /// The condition `event(t, x) > 0`, reported as `description`.
    pub fn new(description: S, event: F) -> Self {
        Self { description, event }
    }
}

impl<S: AsRef<str>, F> core::fmt::Debug for Stop<S, F> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_tuple("Stop")
            .field(&self.description.as_ref())
            .finish()
    }
}

impl<S, F, X> StopCondition<X> for Stop<S, F>
where
    S: AsRef<str>,
    F: Fn(f64, &X) -> f64,
{
    fn value(&self, t: f64, x: &X) -> f64 {
        (self.event)(t, x)
    }

    fn description(&self) -> &str {
        self.description.as_ref()
    }
}

/// A condition behind a reference (a `&dyn StopCondition<X>` among them).
impl<C: StopCondition<X> + ?Sized, X> StopCondition<X> for &C {
    fn value(&self, t: f64, x: &X) -> f64 {
        (**self).value(t, x)
    }

    fn description(&self) -> &str {
        (**self).description()
    }
}

/// An optional condition: `None` never holds.
impl<C: StopCondition<X>, X> StopCondition<X> for Option<C> {
    fn value(&self, t: f64, x: &X) -> f64 {
        self.as_ref()
            .map_or(-1.0, |condition| condition.value(t, x))
    }

    fn description(&self) -> &str {
        self.as_ref()
            .map_or("never", |condition| condition.description())
    }
}
