//! A principally kinematic loop's displacement with its exact gradient in
//! the loop's coefficients, from the connection's curvature (docs/MATH.md
//! 4.4).
//!
//! The displacement `g(T)` is integrated by RK4 (`runtime::gait::run`) at
//! the loop's `steps`; its variation along a deformation `dr` of the loop
//! is, with `h(t) = g(T)^-1 g(t)` and `xi0 = xi(r(0), dr(0))`,
//!
//! ```text
//! eta = g(T)^-1 dg(T) = xi0 - Ad_{g(T)^-1} xi0 + int_0^T Ad_{h(t)} sum_{i<j} F_ij(r) (dr_i rdot_j - dr_j rdot_i) dt
//! d(x, y) = R(theta(T)) (eta_1, eta_2),   dtheta = eta_3
//! Ad_{(p, phi)} (v, omega) = (R(phi) v + omega (p_y, -p_x), omega)
//! ```
//!
//! taken by Simpson's rule on the steps' points: one pass along the loop
//! and a quadrature, whatever the number of coefficients.

use super::GaitModel;
use super::fourier::FourierLoop;
use super::score::{Evaluation, Scoring, body_velocity, path_costs, simpson};
use chaplygin_runtime::gait::{self, GaitState, ShapeLoop};

/// Evaluates `shape_loop` on the principally kinematic `model`; where the
/// loop meets the singular set, or `model` has no curvature, the values
/// are not finite and [`Evaluation::cost`] infinite.
pub fn by_curvature(
    model: &dyn GaitModel,
    shape_loop: &FourierLoop,
    scoring: &Scoring,
) -> Evaluation {
    let path = group_path(model, shape_loop, scoring.even_steps());
    let steps = path.len() - 1;
    let end = path[steps];
    let weights = simpson(steps, shape_loop.period);
    let count = shape_loop.coefficients.len();
    let per = shape_loop.per_coordinate();
    let planes = planes(model.shape_indices().len());
    let mut eta = vec![[0.0; 3]; count];
    for (k, (&g, &weight)) in path.iter().zip(&weights).enumerate() {
        let t = shape_loop.period * k as f64 / steps as f64;
        let (r, rdot) = shape_loop.shape(t);
        let (basis, _) = shape_loop.basis(t);
        let h = gait::relative(&end, &g);
        let curvature = (model.curvature(&r)).unwrap_or_else(|| vec![[f64::NAN; 3]; planes.len()]);
        for (m, eta) in eta.iter_mut().enumerate() {
            let (i, b) = (m / per, m % per);
            let twist = swept_twist(&planes, &curvature, (i, basis[b]), &rdot);
            let moved = adjoint(h, twist);
            for c in 0..3 {
                eta[c] += weight * moved[c];
            }
        }
    }
    let (r0, _) = shape_loop.shape(0.0);
    let (basis0, _) = shape_loop.basis(0.0);
    let to_end = inverse(end);
    let displacement_gradient = (0..count)
        .map(|m| {
            let (i, b) = (m / per, m % per);
            let mut dr0 = vec![0.0; r0.len()];
            dr0[i] = basis0[b];
            let xi0 = body_velocity(model, &r0, &dr0, &[]);
            let moved = adjoint(to_end, xi0);
            let e: [f64; 3] = std::array::from_fn(|c| eta[m][c] + xi0[c] - moved[c]);
            let (sin, cos) = end[2].sin_cos();
            [cos * e[0] - sin * e[1], sin * e[0] + cos * e[1], e[2]]
        })
        .collect();
    path_costs(model, shape_loop, scoring).with_displacement(end, displacement_gradient)
}

/// `(x, y, theta)` at every step of one period from the identity.
fn group_path(model: &dyn GaitModel, shape_loop: &FourierLoop, steps: usize) -> Vec<[f64; 3]> {
    let law = |t: f64| shape_loop.shape(t);
    let run_loop = ShapeLoop {
        shape: &law,
        period: shape_loop.period,
    };
    let group = model.group();
    let mut path: Vec<[f64; 3]> = Vec::with_capacity(steps + 1);
    let q0 = vec![0.0; model.coordinate_count()];
    gait::run(
        model,
        &run_loop,
        (&q0, &[]),
        (1, steps),
        &mut |_, state: &GaitState| path.push(group.map(|i| state.q[i])),
    );
    path
}

/// `sum_{i<j} F_ij (dr_i rdot_j - dr_j rdot_i)` for a deformation `dr` of
/// the coordinate `i` alone: only the planes through `i` contribute.
fn swept_twist(
    planes: &[(usize, usize)],
    curvature: &[[f64; 3]],
    (i, dr): (usize, f64),
    rdot: &[f64],
) -> [f64; 3] {
    let mut twist = [0.0; 3];
    for (&(p, q), f) in planes.iter().zip(curvature) {
        let area = match (p == i, q == i) {
            (true, _) => dr * rdot[q],
            (_, true) => -dr * rdot[p],
            _ => 0.0,
        };
        for c in 0..3 {
            twist[c] += f[c] * area;
        }
    }
    twist
}

/// `Ad_{(p, phi)} (v, omega)` on se(2).
fn adjoint(h: [f64; 3], xi: [f64; 3]) -> [f64; 3] {
    let (sin, cos) = h[2].sin_cos();
    [
        cos * xi[0] - sin * xi[1] + xi[2] * h[1],
        sin * xi[0] + cos * xi[1] - xi[2] * h[0],
        xi[2],
    ]
}

/// `(p, phi)^-1`.
fn inverse(g: [f64; 3]) -> [f64; 3] {
    gait::relative(&g, &[0.0; 3])
}

/// The shape planes `(i, j)`, `i < j`, in order.
fn planes(count: usize) -> Vec<(usize, usize)> {
    (0..count)
        .flat_map(|i| (i + 1..count).map(move |j| (i, j)))
        .collect()
}
