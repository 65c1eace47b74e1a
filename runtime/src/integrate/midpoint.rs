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

use super::{Error, FixedStep, finite, max_norm};
use crate::linalg::solve;
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

impl<S: Jacobian<D>, const D: usize> FixedStep<S, D> for Midpoint {
    fn step(&self, system: &S, t: f64, x: &[f64; D], h: f64) -> Result<[f64; D], Error> {
        let (tm, half) = (t + h / 2.0, h / 2.0);
        let euler = system.rhs(t, x);
        let mut m: [f64; D] = core::array::from_fn(|i| x[i] + half * euler[i]);
        let (mut update, mut iterations) = (f64::INFINITY, 0);
        while iterations < self.max_iterations {
            iterations += 1;
            let delta = newton_update(system, tm, half, x, &m);
            update = max_norm(&delta);
            for (mi, di) in m.iter_mut().zip(delta) {
                *mi -= di;
            }
            if update <= self.tolerance * max_norm(&m).max(1.0) {
                return finite(t + h, core::array::from_fn(|i| 2.0 * m[i] - x[i]));
            }
            if !update.is_finite() {
                break;
            }
        }
        Err(Error::NewtonFailure {
            t,
            h,
            iterations,
            update,
            state: x.to_vec(),
        })
    }
}

/// The Newton update `(I - half df/dx)^-1 g(m)`, `g(m) = m - x - half f(tm, m)`.
fn newton_update<S: Jacobian<D>, const D: usize>(
    system: &S,
    tm: f64,
    half: f64,
    x: &[f64; D],
    m: &[f64; D],
) -> [f64; D] {
    let f = system.rhs(tm, m);
    let g = core::array::from_fn(|i| m[i] - x[i] - half * f[i]);
    let mut dg = system.jacobian(tm, m);
    for (i, row) in dg.iter_mut().enumerate() {
        for (j, entry) in row.iter_mut().enumerate() {
            *entry = f64::from(u8::from(i == j)) - half * *entry;
        }
    }
    solve(dg, g)
}
