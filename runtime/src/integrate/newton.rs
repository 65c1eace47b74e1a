//! Newton's method on a fixed-size system, shared by the implicit steps:
//! each iteration solves `J delta = r` by LU with partial pivoting
//! (nalgebra's, on the stack, for the sizes of [`Square`]).

use super::max_norm;
use crate::linalg::Square;
use nalgebra::{Const, SMatrix, SVector};

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
/// and (an approximation of) its Jacobian.
pub(crate) fn solve_root<const D: usize>(
    mut y: [f64; D],
    settings: Settings,
    residual: impl Fn(&[f64; D]) -> ([f64; D], SMatrix<f64, D, D>),
) -> Result<[f64; D], Failure>
where
    Const<D>: Square,
{
    let mut update = f64::INFINITY;
    for iteration in 1..=settings.max_iterations {
        let previous = update;
        let (value, jacobian) = residual(&y);
        if !(value.iter().all(|v| v.is_finite()) && jacobian.iter().all(|v| v.is_finite())) {
            return Err(Failure::NonFinite);
        }
        let delta: [f64; D] = jacobian
            .lu()
            .solve(&SVector::from(value))
            .ok_or(Failure::SingularJacobian { iteration })?
            .into();
        update = max_norm(&delta);
        for (yi, di) in y.iter_mut().zip(delta) {
            *yi -= di;
        }
        let scale = max_norm(&y).max(1.0);
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

/// `I - scale * a`, `a` row-major.
pub(crate) fn identity_minus<const D: usize>(scale: f64, a: &[[f64; D]; D]) -> SMatrix<f64, D, D> {
    SMatrix::from_fn(|i, j| f64::from(u8::from(i == j)) - scale * a[i][j])
}
