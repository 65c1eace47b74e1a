//! Newton's method on a fixed-size system, shared by the implicit steps.

use super::max_norm;
use crate::linalg::solve;

/// When Newton's method stops.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Settings {
    /// Stop when the update is at most `tolerance * max(1, |y|)` (max norms).
    pub(crate) tolerance: f64,
    /// Iterations allowed.
    pub(crate) max_iterations: usize,
}

/// Newton's method did not converge: iterations made and the largest entry
/// of the last update.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Diverged {
    pub(crate) iterations: usize,
    pub(crate) update: f64,
}

/// The root of `residual(y)` from `y`, where `residual` returns the value
/// and (an approximation of) its Jacobian.
pub(crate) fn solve_root<const D: usize>(
    mut y: [f64; D],
    settings: Settings,
    residual: impl Fn(&[f64; D]) -> ([f64; D], [[f64; D]; D]),
) -> Result<[f64; D], Diverged> {
    let mut update = f64::INFINITY;
    for iteration in 1..=settings.max_iterations {
        let (value, jacobian) = residual(&y);
        let delta = solve(jacobian, value);
        update = max_norm(&delta);
        for (yi, di) in y.iter_mut().zip(delta) {
            *yi -= di;
        }
        if update <= settings.tolerance * max_norm(&y).max(1.0) {
            return Ok(y);
        }
        if !update.is_finite() {
            return Err(Diverged {
                iterations: iteration,
                update,
            });
        }
    }
    Err(Diverged {
        iterations: settings.max_iterations,
        update,
    })
}

/// `I - scale * a`.
pub(crate) fn identity_minus<const D: usize>(scale: f64, mut a: [[f64; D]; D]) -> [[f64; D]; D] {
    for (i, row) in a.iter_mut().enumerate() {
        for (j, entry) in row.iter_mut().enumerate() {
            *entry = f64::from(u8::from(i == j)) - scale * *entry;
        }
    }
    a
}
