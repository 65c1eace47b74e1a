//! Newton's method on a [`State`], shared by the implicit steps: each
//! iteration solves `(I - c A) delta = r` by LU with partial pivoting
//! ([`State::solve_shifted`], nalgebra's; on the stack for fixed sizes).

use super::max_norm;
use crate::state::State;

/// When Newton's method stops.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Settings {
    /// Stop when the update is at most `tolerance * max(1, |y|)` (max norms),
    /// or when it has stagnated below [`STAGNATION`] times that scale: it
    /// no longer halves from one iteration to the next, the iteration
    /// having reached the round-off of its residual (the discrete
    /// gradient's difference quotient of a large energy over a small step).
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
    /// The Jacobian had no nonzero pivot in this iteration (from 1).
    SingularJacobian { iteration: usize },
    /// The residual or its Jacobian at an iterate is not finite.
    NonFinite,
}

/// The root of `residual(y)` from `y`, where `residual` returns the value
/// `g(y)` and a matrix `a` whose shift `I - scale a` is (an approximation of)
/// the Jacobian `dg/dy`; each iteration made is added to `iterations`.
pub(crate) fn solve_root<X: State>(
    mut y: X,
    settings: Settings,
    scale: f64,
    iterations: &mut usize,
    residual: impl Fn(&X) -> (X, X::Matrix),
) -> Result<X, Failure> {
    let mut update = f64::INFINITY;
    for iteration in 1..=settings.max_iterations {
        *iterations += 1;
        let previous = update;
        let (value, a) = residual(&y);
        let finite = |values: &[f64]| values.iter().all(|v| v.is_finite());
        if !(finite(value.as_ref()) && finite(X::entries(&a))) {
            return Err(Failure::NonFinite);
        }
        let delta =
            X::solve_shifted(scale, &a, &value).ok_or(Failure::SingularJacobian { iteration })?;
        update = max_norm(delta.as_ref());
        for (yi, di) in y.as_mut().iter_mut().zip(delta.as_ref()) {
            *yi -= di;
        }
        let scale = max_norm(y.as_ref()).max(1.0);
        let stagnated = update > 0.5 * previous && update <= STAGNATION * scale;
        if update <= settings.tolerance * scale || stagnated {
            return Ok(y);
        }
        if !update.is_finite() {
            return Err(Failure::Diverged {
                iterations: iteration,
                update,
            });
        }
    }
    Err(Failure::Diverged {
        iterations: settings.max_iterations,
        update,
    })
}
