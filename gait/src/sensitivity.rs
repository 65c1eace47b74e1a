//! A loop's displacement with its exact gradient in the loop's
//! coefficients for a model that carries momentum, by forward
//! sensitivities (docs/MATH.md 4.4).
//!
//! Along the prescribed shape `r(t; c)` the group and the momenta obey
//!
//! ```text
//! gdot = g xi(r, rdot, p)      (x, y)' = R(theta) (xi_1, xi_2),  theta' = xi_3
//! pdot = f(r, rdot, p)
//! ```
//!
//! from `g(0) = e`, `p(0) = p0`. Their derivatives in a coefficient `c_m`,
//! `(dg, dp)`, obey the variational equations
//!
//! ```text
//! dxi = xi_r dr + xi_rdot drdot + xi_p dp,   dp' = f_r dr + f_rdot drdot + f_p dp
//! d(x, y)' = R(theta) (dxi_1, dxi_2) + R'(theta) (xi_1, xi_2) dtheta,   dtheta' = dxi_3
//! ```
//!
//! from zero, with `dr = dr/dc_m` the loop's basis function and the
//! Jacobians the model's exact `body_velocity_jacobian` and
//! `momentum_rhs_jacobian`. Both are integrated together by the gaits' RK4
//! step (`runtime::gait::rk4_step`), so the gradient is the exact
//! derivative of the discrete displacement (an explicit Runge-Kutta step
//! commutes with differentiation). It serves principally kinematic models
//! too (no momenta), where it must agree with the curvature's route.

use super::GaitModel;
use super::fourier::FourierLoop;
use super::score::{Evaluation, Scoring, body_velocity, path_costs};
use chaplygin_runtime::gait;

/// Evaluates `shape_loop` on `model` from zero momentum; where the loop
/// meets the singular set the values are not finite, and
/// [`Evaluation::cost`] infinite.
pub fn by_sensitivities(
    model: &dyn GaitModel,
    shape_loop: &FourierLoop,
    scoring: &Scoring,
) -> Evaluation {
    let steps = scoring.even_steps();
    let h = shape_loop.period / steps as f64;
    let block = 3 + model.momentum_count();
    let count = shape_loop.coefficients.len();
    let mut state = vec![0.0; block * (1 + count)];
    let rate = |t: f64, state: &[f64]| variational_rate(model, shape_loop, t, state);
    for k in 0..steps {
        state = gait::rk4_step(&rate, k as f64 * h, &state, h);
    }
    let displacement = [state[0], state[1], state[2]];
    let displacement_gradient = (0..count)
        .map(|m| std::array::from_fn(|c| state[block * (1 + m) + c]))
        .collect();
    path_costs(model, shape_loop, scoring).with_displacement(displacement, displacement_gradient)
}

/// The rate of `(g, p)` and of each coefficient's `(dg, dp)`, stacked as
/// blocks of `3 + mp`.
fn variational_rate(
    model: &dyn GaitModel,
    shape_loop: &FourierLoop,
    t: f64,
    state: &[f64],
) -> Vec<f64> {
    let momenta = model.momentum_count();
    let block = 3 + momenta;
    let (r, rdot) = shape_loop.shape(t);
    let (basis, basis_rate) = shape_loop.basis(t);
    let nr = r.len();
    let per = shape_loop.per_coordinate();
    let (theta, p) = (state[2], &state[3..block]);
    let xi = body_velocity(model, &r, &rdot, p);
    let jacobians = model.jacobians(&r, &rdot, p);
    let (sin, cos) = theta.sin_cos();
    let mut rate = Vec::with_capacity(state.len());
    rate.extend([cos * xi[0] - sin * xi[1], sin * xi[0] + cos * xi[1], xi[2]]);
    rate.extend(model.momentum_rhs(&r, &rdot, p));
    for (m, variation) in state.chunks_exact(block).skip(1).enumerate() {
        let (i, b) = (m / per, m % per);
        let (dtheta, dp) = (variation[2], &variation[3..]);
        let along = |row: &[f64]| -> f64 {
            let momentum: f64 = row[2 * nr..].iter().zip(dp).map(|(j, v)| j * v).sum();
            row[i] * basis[b] + row[nr + i] * basis_rate[b] + momentum
        };
        let dxi = jacobians.body_velocity.each_ref().map(|row| along(row));
        rate.extend([
            cos * dxi[0] - sin * dxi[1] - (sin * xi[0] + cos * xi[1]) * dtheta,
            sin * dxi[0] + cos * dxi[1] + (cos * xi[0] - sin * xi[1]) * dtheta,
            dxi[2],
        ]);
        rate.extend(jacobians.momentum.iter().map(|row| along(row)));
    }
    rate
}
