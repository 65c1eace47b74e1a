//! The integrators as the simulation loop drives them ([`Advance`]): one
//! step for the fixed-step methods, steps following the tolerances for
//! Dormand-Prince and the controlled methods.

use crate::integrate::{
    self, Controlled, DiscreteGradient, DormandPrince, FixedStep, Midpoint, Rk4,
};
use crate::state::State;
use crate::system::OdeSystem;

/// An integrator as the simulation loop uses it: from `x` at `t` to the
/// state at `t_next`.
pub trait Advance<S, X> {
    /// The state at `t_next`.
    ///
    /// # Errors
    /// The integrator's [`integrate::Error`].
    fn advance(&self, system: &S, t: f64, x: &X, t_next: f64) -> Result<X, integrate::Error>;
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
                t: f64,
                x: &X,
                t_next: f64,
            ) -> Result<X, integrate::Error> {
                self.step(system, t, x, t_next - t)
            }
        }
    )*};
}

one_step_advances!(Rk4, Midpoint, DiscreteGradient);

/// Adaptive steps to `t_next` within the tolerances.
impl<S: OdeSystem<X>, X: State> Advance<S, X> for DormandPrince {
    fn advance(&self, system: &S, t: f64, x: &X, t_next: f64) -> Result<X, integrate::Error> {
        Ok(self.integrate(system, (t, x.clone()), t_next)?.x)
    }
}

/// Steps within the tolerances to `t_next`, none longer than
/// `t_next - t`.
impl<M: FixedStep<S, X>, S, X: State> Advance<S, X> for Controlled<M> {
    fn advance(&self, system: &S, t: f64, x: &X, t_next: f64) -> Result<X, integrate::Error> {
        Ok(self.integrate(system, (t, x.clone()), t_next)?.x)
    }
}
