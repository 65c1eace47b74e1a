//! The implicit midpoint rule (Hairer, Lubich & Wanner, *Geometric Numerical
//! Integration*, 2nd ed., 2006, sections I.1.2 and IV.2), solved by Newton's
//! method with the system's [`Jacobian`].
//!
//! One step `x -> X` solves `X = x + h f(t + h/2, m)` with the midpoint
//! `m = (x + X)/2`: Newton's method finds `m` from
//! `g(m) = m - x - h/2 f(t + h/2, m) = 0`, whose Jacobian is
//! `I - h/2 df/dx`, starting from the explicit Euler half step; then
//! `X = 2 m - x`.
//!
//! Order 2, symmetric, symplectic. It conserves every quadratic invariant
//! exactly (Hairer, Lubich & Wanner, theorem IV.2.1). For a structured system
//! `xdot = J(x) dH/dx` with `H` quadratic (constant Hessian) and `J(x)` skew
//! at every `x`: `H(X) - H(x) = dH/dx(m) . (X - x)` exactly because `H` is
//! quadratic, and `X - x = h J(m) dH/dx(m)` is orthogonal to `dH/dx(m)`
//! because `J(m)` is skew; so `H` is conserved up to the Newton tolerance and
//! round-off, whether or not `J` depends on `x`. (This is the case of the
//! reduced port-Hamiltonian form with zero input and a constant metric, e.g.
//! the snakeboard in the paper's momentum basis.)

use super::newton::{Equation, Settings, solve_root};
use super::{Error, FixedStep, NonFiniteCause, StepAt, newton_failure};
use crate::state::State;
use crate::system::Jacobian;

/// The implicit midpoint rule with its Newton iteration's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Midpoint {
    /// Newton stops when its update is at most `tolerance * max(1, |m|)`
    /// (max norms). Convergence is quadratic, so the error left is of the
    /// order of `tolerance^2`, above round-off.
    pub tolerance: f64,
    /// Newton iterations allowed per step.
    pub max_iterations: usize,
}

impl Default for Midpoint {
    /// `tolerance = 1e-13`, `max_iterations = 50`.
    fn default() -> Self {
        Self {
            tolerance: 1e-13,
            max_iterations: 50,
        }
    }
}

impl<S: Jacobian<X>, X: State> FixedStep<S, X> for Midpoint {
    const ORDER: u32 = 2;

    fn step_counting(
        &self,
        system: &S,
        t: f64,
        x: &X,
        h: f64,
        iterations: &mut usize,
    ) -> Result<X, Error> {
        let (tm, half) = (t + h / 2.0, h / 2.0);
        let at = StepAt {
            t,
            h,
            x: x.as_ref(),
        };
        let euler = at.finite(system.rhs(t, x), NonFiniteCause::RightHandSide)?;
        let start = x.with_entries(|i| x[i] + half * euler[i]);
        let settings = Settings {
            tolerance: self.tolerance,
            max_iterations: self.max_iterations,
        };
        let equation = Equation {
            scale: half,
            residual: |m: &X| {
                let f = system.rhs(tm, m);
                m.with_entries(|i| m[i] - x[i] - half * f[i])
            },
            matrix: |m: &X| system.jacobian(tm, m),
        };
        let midpoint = solve_root(start, settings, equation, iterations)
            .map_err(|failure| newton_failure(failure, t, h, x.as_ref()))?;
        at.finite(
            x.with_entries(|i| 2.0 * midpoint[i] - x[i]),
            NonFiniteCause::NewState,
        )
    }
}
