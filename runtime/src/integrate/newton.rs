//! Newton's method on a [`State`], shared by the implicit steps, in its
//! simplified form (Hairer & Wanner, *Solving Ordinary Differential
//! Equations II*, 2nd ed., 1996, section IV.8): the matrix `I - c A` of
//! the step's equation `g(y) = 0` is factored once, at the starting point,
//! by LU with partial pivoting ([`State::factor_shifted`], nalgebra's; on
//! the stack for fixed sizes), and each iteration
//!
//! ```text
//! y_{k+1} = y_k - (I - c A(y_j))^-1 g(y_k)
//! ```
//!
//! solves with the factors of the iterate `y_j` they were made at (first
//! `y_0`). From a predictor `y_0` at a distance `e` from the root, each
//! update is smaller than the last by a factor of about `c |dA/dy| e`, as
//! fast as the full method's quadratic rate for the short steps an
//! accurate run takes; where an update does not halve, `A` is evaluated
//! again at the new iterate and factored anew (`j = k + 1`), as the full
//! method would, so a poor predictor (a fast motion within the step) still
//! converges.

use super::max_norm;
use crate::state::State;

/// When Newton's method stops.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Settings {
    /// Stop when the update is at most `tolerance * max(1, |y|)` (max norms),
    /// or when it has stagnated below [`STAGNATION`] times that scale: it
    /// no longer halves from one iteration to the next after the matrix
    /// was refreshed, the iteration having reached the round-off of its
    /// residual (the discrete gradient's difference quotient of a large
    /// energy over a small step).
    pub(crate) tolerance: f64,
    /// Iterations allowed.
    pub(crate) max_iterations: usize,
}

/// An update that no longer halves is accepted below this fraction of
/// `max(1, |y|)` (see [`Settings::tolerance`]).
pub(crate) const STAGNATION: f64 = 1e-9;

/// Why Newton's method stopped without a root.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Failure {
    /// No convergence: iterations made and the largest entry of the last
    /// update.
    Diverged { iterations: usize, update: f64 },
    /// The matrix factored in this iteration (from 1) had no nonzero pivot.
    SingularJacobian { iteration: usize },
    /// The residual or the matrix at an iterate is not finite.
    NonFinite,
}

/// The equation `g(y) = 0` of an implicit step: `residual` returns `g(y)`
/// and `matrix` a matrix `a` whose shift `I - scale a` is (an
/// approximation of) the Jacobian `dg/dy`.
pub(crate) struct Equation<G, A> {
    pub(crate) scale: f64,
    pub(crate) residual: G,
    pub(crate) matrix: A,
}

/// The root of `equation` from `y`; each iteration made is added to
/// `iterations`.
pub(crate) fn solve_root<X: State>(
    mut y: X,
    settings: Settings,
    equation: Equation<impl Fn(&X) -> X, impl Fn(&X) -> X::Matrix>,
    iterations: &mut usize,
) -> Result<X, Failure> {
    let mut factors = factored(&equation, &y, 1)?;
    let (mut update, mut fresh) = (f64::INFINITY, true);
    for iteration in 1..=settings.max_iterations {
        *iterations += 1;
        let value = (equation.residual)(&y);
        if !finite(value.as_ref()) {
            return Err(Failure::NonFinite);
        }
        let delta = X::solve_factored(&factors, &value);
        let previous = core::mem::replace(&mut update, max_norm(delta.as_ref()));
        for (yi, di) in y.as_mut().iter_mut().zip(delta.as_ref()) {
            *yi -= di;
        }
        let scale = max_norm(y.as_ref()).max(1.0);
        let halved = update <= 0.5 * previous;
        let stagnated = fresh && !halved && update <= STAGNATION * scale;
        if update <= settings.tolerance * scale || stagnated {
            return Ok(y);
        }
        if !update.is_finite() {
            return Err(Failure::Diverged {
                iterations: iteration,
                update,
            });
        }
        fresh = !halved;
        if fresh {
            factors = factored(&equation, &y, iteration + 1)?;
        }
    }
    Err(Failure::Diverged {
        iterations: settings.max_iterations,
        update,
    })
}

/// The factors of `I - scale a` with `a` the equation's matrix at `y`, in
/// this `iteration`.
fn factored<X: State>(
    equation: &Equation<impl Fn(&X) -> X, impl Fn(&X) -> X::Matrix>,
    y: &X,
    iteration: usize,
) -> Result<X::Factors, Failure> {
    let a = (equation.matrix)(y);
    if !finite(X::entries(&a)) {
        return Err(Failure::NonFinite);
    }
    X::factor_shifted(equation.scale, &a).ok_or(Failure::SingularJacobian { iteration })
}

fn finite(values: &[f64]) -> bool {
    values.iter().all(|v| v.is_finite())
}
