//! The integrators as the simulation loop drives them ([`Advance`]): one
//! step for the fixed-step methods, steps following the tolerances for
//! Dormand-Prince and the controlled methods, each counting what it took
//! ([`Effort`]).

use crate::integrate::{
    self, Controlled, DiscreteGradient, DormandPrince, Effort, FixedStep, Midpoint, Rk4,
};
use crate::state::State;
use crate::system::OdeSystem;

/// An integrator as the simulation loop uses it: from `x` at `t` to the
/// state at `t_next`.
pub trait Advance<S, X> {
    /// The state at `t_next`, the steps and Newton iterations taken added
    /// to `effort` (a step that fails counts as rejected).
    ///
    /// # Errors
    /// The integrator's [`integrate::Error`].
    fn advance(
        &self,
        system: &S,
        start: (f64, &X),
        t_next: f64,
        effort: &mut Effort,
    ) -> Result<X, integrate::Error>;
}

macro_rules! one_step_advances {
    ($($method:ty),*) => {$(
        /// One step of size `t_next - t`.
        impl<S, X: State> Advance<S, X> for $method
        where
            $method: FixedStep<S, X>,
        {
            fn advance(
                &self,
                system: &S,
                (t, x): (f64, &X),
                t_next: f64,
                effort: &mut Effort,
            ) -> Result<X, integrate::Error> {
                let iterations = &mut effort.newton_iterations;
                let stepped = self.step_counting(system, t, x, t_next - t, iterations);
                match stepped {
                    Ok(_) => effort.accepted += 1,
                    Err(_) => effort.rejected += 1,
                }
                stepped
            }
        }
    )*};
}

one_step_advances!(Rk4, Midpoint, DiscreteGradient);

/// Adaptive steps to `t_next` within the tolerances.
impl<S: OdeSystem<X>, X: State> Advance<S, X> for DormandPrince {
    fn advance(
        &self,
        system: &S,
        (t, x): (f64, &X),
        t_next: f64,
        effort: &mut Effort,
    ) -> Result<X, integrate::Error> {
        self.integrate_counting(system, (t, x.clone()), t_next, effort)
    }
}

/// Steps within the tolerances to `t_next`, none longer than
/// `t_next - t`.
impl<M: FixedStep<S, X>, S, X: State> Advance<S, X> for Controlled<M> {
    fn advance(
        &self,
        system: &S,
        (t, x): (f64, &X),
        t_next: f64,
        effort: &mut Effort,
    ) -> Result<X, integrate::Error> {
        self.integrate_counting(system, (t, x.clone()), t_next, effort)
    }
}
