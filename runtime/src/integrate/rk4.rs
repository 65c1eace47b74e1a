//! The classical fourth-order Runge-Kutta method (Kutta 1901; Hairer, Nørsett
//! & Wanner, *Solving Ordinary Differential Equations I*, 2nd ed., 1993,
//! section II.1, table 1.2).
//!
//! Order 4: the global error after a fixed time is `O(h^4)`. Explicit, four
//! evaluations of `f` per step. It conserves linear invariants exactly, but
//! not quadratic ones: the energy of a conservative system drifts, by
//! `O(h^4)` per unit time.

use super::{Error, FixedStep, NonFiniteCause, StepAt, combine};
use crate::state::State;
use crate::system::OdeSystem;

/// The classical Runge-Kutta method of order 4.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rk4;

impl<S: OdeSystem<X>, X: State> FixedStep<S, X> for Rk4 {
    const ORDER: u32 = 4;

    fn step_counting(
        &self,
        system: &S,
        t: f64,
        x: &X,
        h: f64,
        _iterations: &mut usize,
    ) -> Result<X, Error> {
        let half = h / 2.0;
        let at = StepAt {
            t,
            h,
            x: x.as_ref(),
        };
        let rhs = |t, x: &X| at.finite(system.rhs(t, x), NonFiniteCause::RightHandSide);
        let k1 = rhs(t, x)?;
        let k2 = rhs(t + half, &combine(x, half, &[(1.0, &k1)]))?;
        let k3 = rhs(t + half, &combine(x, half, &[(1.0, &k2)]))?;
        let k4 = rhs(t + h, &combine(x, h, &[(1.0, &k3)]))?;
        let sixth = 1.0 / 6.0;
        let terms = [
            (sixth, &k1),
            (2.0 * sixth, &k2),
            (2.0 * sixth, &k3),
            (sixth, &k4),
        ];
        at.finite(combine(x, h, &terms), NonFiniteCause::NewState)
    }
}
