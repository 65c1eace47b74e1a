//! One loop's displacement, length and distance from the singular set, each
//! with its exact gradient in the loop's coefficients (docs/MATH.md 4.4).
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
//! taken by Simpson's rule on the steps' points. The length is `L = int
//! |rdot| dt`, `dL = int rdot . d(rdot) / |rdot| dt`. The barrier keeps the
//! loop off the singular set: with the clearance `s = |d(r)| / (margin
//! d_ref)` and `u = s - 1`, `B = (1/T) int psi(u) dt`, `psi(u) = (1/u -
//! 1)^2` for `0 < u < 1`, 0 above (continuously differentiable at `u = 1`),
//! infinite for `u <= 0`: a loop must keep `s > 1`, and its integral grows
//! without bound as its closest approach nears `s = 1`.

use super::fourier::FourierLoop;
use super::{Cost, Direction, Kinematic};
use crate::runtime::gait::{self, GaitState, ShapeLoop};

/// A loop's displacement, length and barrier, with their gradients (one
/// entry per coefficient).
#[derive(Clone, Debug)]
pub struct Evaluation {
    /// `(x, y, theta)` of `g(T)`, from the identity.
    pub displacement: [f64; 3],
    /// `d(x, y, theta) / dc`.
    pub displacement_gradient: Vec<[f64; 3]>,
    /// `L`.
    pub length: f64,
    /// `dL / dc`.
    pub length_gradient: Vec<f64>,
    /// `B`.
    pub barrier: f64,
    /// `dB / dc`.
    pub barrier_gradient: Vec<f64>,
    /// The least clearance `s` along the loop (above 1 where the loop is
    /// allowed, above 2 outside the barrier).
    pub clearance: f64,
}

/// How a loop is scored.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scoring {
    /// The component maximized.
    pub direction: Direction,
    /// Per unit length, or not.
    pub cost: Cost,
    /// RK4 steps per period (even).
    pub steps: usize,
    /// `margin d_ref`: the least `|d(r)|` a loop may reach (clearance
    /// `s = 1`); the barrier acts up to twice it.
    pub clearance: f64,
    /// The barrier's weight.
    pub barrier_weight: f64,
}

impl Evaluation {
    /// The displacement per unit length (or the displacement) in the
    /// scored direction.
    pub fn efficiency(&self, scoring: &Scoring) -> f64 {
        let moved = self.displacement[scoring.direction.index()];
        match scoring.cost {
            Cost::Length => moved / self.length,
            Cost::None => moved,
        }
    }

    /// `d efficiency / dc`.
    pub fn efficiency_gradient(&self, scoring: &Scoring) -> Vec<f64> {
        let k = scoring.direction.index();
        let moved = self.displacement[k];
        (self.displacement_gradient.iter().zip(&self.length_gradient))
            .map(|(d, dl)| match scoring.cost {
                Cost::Length => (d[k] * self.length - moved * dl) / self.length.powi(2),
                Cost::None => d[k],
            })
            .collect()
    }

    /// What the optimizer minimizes: `-efficiency + weight B`; infinite
    /// where the loop meets the singular set or a value is not finite.
    pub fn cost(&self, scoring: &Scoring) -> f64 {
        let cost = -self.efficiency(scoring) + scoring.barrier_weight * self.barrier;
        match cost.is_finite() {
            true => cost,
            false => f64::INFINITY,
        }
    }

    /// `d cost / dc`.
    pub fn cost_gradient(&self, scoring: &Scoring) -> Vec<f64> {
        (self
            .efficiency_gradient(scoring)
            .iter()
            .zip(&self.barrier_gradient))
        .map(|(e, b)| -e + scoring.barrier_weight * b)
        .collect()
    }
}

/// Simpson's weights on `steps + 1` points over a period `period` (steps
/// even).
fn simpson(steps: usize, period: f64) -> Vec<f64> {
    let h = period / steps as f64;
    (0..=steps)
        .map(|k| {
            let weight = match k {
                0 => 1.0,
                k if k == steps => 1.0,
                k if k % 2 == 1 => 4.0,
                _ => 2.0,
            };
            weight * h / 3.0
        })
        .collect()
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

/// Evaluates `shape_loop` on `model`; where the loop meets the singular
/// set the values are not finite, and [`Evaluation::cost`] infinite.
pub fn evaluate(model: &dyn Kinematic, shape_loop: &FourierLoop, scoring: &Scoring) -> Evaluation {
    let steps = scoring.steps + scoring.steps % 2;
    let group = model.group();
    let shape_indices = model.shape_indices();
    let law = |t: f64| shape_loop.shape(t);
    let run_loop = ShapeLoop {
        shape: &law,
        period: shape_loop.period,
    };
    let mut path: Vec<[f64; 3]> = Vec::with_capacity(steps + 1);
    let q0 = vec![0.0; model.coordinate_count()];
    gait::run(
        model,
        &run_loop,
        (&q0, &[]),
        (1, steps),
        &mut |_, state: &GaitState| {
            path.push(group.map(|i| state.q[i]));
        },
    );
    let end = path[steps];
    let to_end = inverse(end);
    let weights = simpson(steps, shape_loop.period);
    let count = shape_loop.coefficients.len();
    let per = shape_loop.per_coordinate();
    let mut eta = vec![[0.0; 3]; count];
    let (mut length, mut length_gradient) = (0.0, vec![0.0; count]);
    let (mut barrier, mut barrier_gradient) = (0.0, vec![0.0; count]);
    let mut clearance = f64::INFINITY;
    let planes = planes(shape_indices.len());
    for (k, (&g, &weight)) in path.iter().zip(&weights).enumerate() {
        let t = shape_loop.period * k as f64 / steps as f64;
        let (r, rdot) = shape_loop.shape(t);
        let (basis, basis_rate) = shape_loop.basis(t);
        let h = gait::relative(&end, &g);
        let curvature = model.curvature(&r);
        let speed = rdot.iter().map(|v| v * v).sum::<f64>().sqrt();
        length += weight * speed;
        let (divisor, divisor_gradient) = model.divisor(&r);
        let s = divisor.abs() / scoring.clearance;
        clearance = clearance.min(s);
        let (psi, dpsi) = barrier_of(s);
        barrier += weight * psi / shape_loop.period;
        for m in 0..count {
            let (i, b) = (m / per, m % per);
            let (dr, drdot) = (basis[b], basis_rate[b]);
            let mut twist = [0.0; 3];
            for (&(p, q), f) in planes.iter().zip(&curvature) {
                // dr is e_i basis[b]: only the planes through i contribute.
                let area = match (p == i, q == i) {
                    (true, _) => dr * rdot[q],
                    (_, true) => -dr * rdot[p],
                    _ => 0.0,
                };
                for c in 0..3 {
                    twist[c] += f[c] * area;
                }
            }
            let moved = adjoint(h, twist);
            for c in 0..3 {
                eta[m][c] += weight * moved[c];
            }
            if speed > 0.0 {
                length_gradient[m] += weight * rdot[i] * drdot / speed;
            }
            let ds = divisor.signum() * divisor_gradient[i] * dr / scoring.clearance;
            barrier_gradient[m] += weight * dpsi * ds / shape_loop.period;
        }
    }
    let (r0, _) = shape_loop.shape(0.0);
    let (basis0, _) = shape_loop.basis(0.0);
    let displacement_gradient = (0..count)
        .map(|m| {
            let (i, b) = (m / per, m % per);
            let mut dr0 = vec![0.0; r0.len()];
            dr0[i] = basis0[b];
            let xi0 = body_velocity(model, &shape_indices, &r0, &dr0);
            let moved = adjoint(to_end, xi0);
            let e: [f64; 3] = std::array::from_fn(|c| eta[m][c] + xi0[c] - moved[c]);
            let (sin, cos) = end[2].sin_cos();
            [cos * e[0] - sin * e[1], sin * e[0] + cos * e[1], e[2]]
        })
        .collect();
    Evaluation {
        displacement: end,
        displacement_gradient,
        length,
        length_gradient,
        barrier,
        barrier_gradient,
        clearance,
    }
}

/// The least clearance `s = |d(r)| / clearance` at `samples` points of
/// the loop, without integrating it: a cheap test of whether a loop keeps
/// off the singular set.
pub fn clearance(
    model: &dyn Kinematic,
    shape_loop: &FourierLoop,
    scoring: &Scoring,
    samples: usize,
) -> f64 {
    (0..samples)
        .map(|k| {
            let t = shape_loop.period * k as f64 / samples as f64;
            model.divisor(&shape_loop.shape(t).0).0.abs() / scoring.clearance
        })
        .fold(f64::INFINITY, f64::min)
}

/// The shape planes `(i, j)`, `i < j`, in order.
fn planes(count: usize) -> Vec<(usize, usize)> {
    (0..count)
        .flat_map(|i| (i + 1..count).map(move |j| (i, j)))
        .collect()
}

/// `psi(s - 1)` and its derivative in `s`.
fn barrier_of(s: f64) -> (f64, f64) {
    let u = s - 1.0;
    if u <= 0.0 {
        (f64::INFINITY, 0.0)
    } else if u < 1.0 {
        ((1.0 / u - 1.0).powi(2), -2.0 * (1.0 / u - 1.0) / (u * u))
    } else {
        (0.0, 0.0)
    }
}

/// `xi(r, rdot)` in the body frame: the reconstruction at the identity.
fn body_velocity(model: &dyn Kinematic, shape: &[usize], r: &[f64], rdot: &[f64]) -> [f64; 3] {
    let mut q = vec![0.0; model.coordinate_count()];
    for (&i, &value) in shape.iter().zip(r) {
        q[i] = value;
    }
    let qdot = model.reconstructed_velocity(&q, rdot, &[]);
    model.group().map(|i| qdot[i])
}
