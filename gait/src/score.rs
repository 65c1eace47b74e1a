//! How a loop is scored: its displacement, its length and its distance from
//! the singular set, with their gradients in the loop's coefficients
//! (docs/MATH.md 4.4).
//!
//! The length is `L = int |rdot| dt`, `dL = int rdot . d(rdot) / |rdot| dt`.
//! The barrier keeps the loop off the singular set and inside the shape's
//! limits `|r_i| < l`: with the clearances `s_0 = |d(r)| / (margin d_ref)`
//! and `s_i = 1 + (l - |r_i|) / (margin l)`,
//!
//! ```text
//! B = (1/T) int sum_k psi(s_k - 1) dt,   psi(u) = (1/u - 1)^2 for 0 < u < 1, 0 above
//! ```
//!
//! (continuously differentiable at `u = 1`), infinite for `u <= 0`: a loop
//! must keep every `s_k > 1`, and the integral grows without bound as its
//! closest approach nears `s_k = 1`. The limits make the problem well posed
//! where the displacement per unit length grows with the loop's size (the
//! snakeboard's rotation does, through its momentum). Both integrals are
//! taken by Simpson's rule on the RK4 steps' points.

use super::fourier::FourierLoop;
use super::{Cost, Direction, GaitModel};

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
    /// The shape's limit `l`: a loop keeps `|r_i| < l`.
    pub limit: f64,
    /// `margin l`: the barrier acts within it of the limit.
    pub limit_band: f64,
    /// The barrier's weight.
    pub barrier_weight: f64,
}

impl Scoring {
    /// The steps per period, rounded up to even (Simpson's rule).
    pub fn even_steps(&self) -> usize {
        self.steps + self.steps % 2
    }
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

/// A loop's length and barrier with their gradients, and its least
/// clearance.
pub(super) struct PathCosts {
    pub length: f64,
    pub length_gradient: Vec<f64>,
    pub barrier: f64,
    pub barrier_gradient: Vec<f64>,
    pub clearance: f64,
}

impl PathCosts {
    /// The evaluation of a loop with these costs and its displacement.
    pub fn with_displacement(
        self,
        displacement: [f64; 3],
        displacement_gradient: Vec<[f64; 3]>,
    ) -> Evaluation {
        Evaluation {
            displacement,
            displacement_gradient,
            length: self.length,
            length_gradient: self.length_gradient,
            barrier: self.barrier,
            barrier_gradient: self.barrier_gradient,
            clearance: self.clearance,
        }
    }
}

/// The length and barrier of `shape_loop`, by Simpson's rule on the
/// `scoring`'s steps.
pub(super) fn path_costs(
    model: &dyn GaitModel,
    shape_loop: &FourierLoop,
    scoring: &Scoring,
) -> PathCosts {
    let steps = scoring.even_steps();
    let count = shape_loop.coefficients.len();
    let per = shape_loop.per_coordinate();
    let mut costs = PathCosts {
        length: 0.0,
        length_gradient: vec![0.0; count],
        barrier: 0.0,
        barrier_gradient: vec![0.0; count],
        clearance: f64::INFINITY,
    };
    for (k, weight) in simpson(steps, shape_loop.period).into_iter().enumerate() {
        let t = shape_loop.period * k as f64 / steps as f64;
        let (r, rdot) = shape_loop.shape(t);
        let (basis, basis_rate) = shape_loop.basis(t);
        let speed = rdot.iter().map(|v| v * v).sum::<f64>().sqrt();
        costs.length += weight * speed;
        let (divisor, divisor_gradient) = model.divisor(&r);
        let s = divisor.abs() / scoring.clearance;
        let (psi, dpsi) = barrier_of(s);
        let limits: Vec<f64> = r.iter().map(|&r| limit_clearance(r, scoring)).collect();
        costs.clearance = limits.iter().fold(costs.clearance.min(s), |a, &b| a.min(b));
        let limits: Vec<(f64, f64)> = limits.into_iter().map(barrier_of).collect();
        let psi = psi + limits.iter().map(|(psi, _)| psi).sum::<f64>();
        costs.barrier += weight * psi / shape_loop.period;
        for m in 0..count {
            let (i, b) = (m / per, m % per);
            if speed > 0.0 {
                costs.length_gradient[m] += weight * rdot[i] * basis_rate[b] / speed;
            }
            let ds = divisor.signum() * divisor_gradient[i] * basis[b] / scoring.clearance;
            let dlimit = -r[i].signum() * basis[b] / scoring.limit_band;
            let dpsi = dpsi * ds + limits[i].1 * dlimit;
            costs.barrier_gradient[m] += weight * dpsi / shape_loop.period;
        }
    }
    costs
}

/// The clearance `s_i = 1 + (l - |r_i|) / (margin l)` of a shape
/// coordinate from its limit.
fn limit_clearance(r: f64, scoring: &Scoring) -> f64 {
    1.0 + (scoring.limit - r.abs()) / scoring.limit_band
}

/// Simpson's weights on `steps + 1` points over a period `period` (steps
/// even).
pub(super) fn simpson(steps: usize, period: f64) -> Vec<f64> {
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

/// The least clearance, from the singular set (`s_0 = |d(r)| /
/// clearance`) and from the limits (`s_i`), at each of `samples` points of
/// the loop in turn, without integrating it: a cheap test of whether a loop
/// keeps off the singular set and inside the limits (`s > 1`). Each point
/// is computed as it is asked for, so a loop is rejected at its first point
/// below a bound (`clearances(..).any(|s| s < bound)`) without the rest
/// being evaluated.
pub fn clearances<'a>(
    model: &'a dyn GaitModel,
    shape_loop: &'a FourierLoop,
    scoring: &'a Scoring,
    samples: usize,
) -> impl Iterator<Item = f64> + 'a {
    (0..samples).map(move |k| {
        let r = shape_loop.position(shape_loop.period * k as f64 / samples as f64);
        let s = model.divisor(&r).0.abs() / scoring.clearance;
        (r.iter())
            .map(|&r| limit_clearance(r, scoring))
            .fold(s, f64::min)
    })
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

/// `xi(r, rdot, p)` of the `se2` factor in the body frame: the
/// reconstruction at the identity.
pub(super) fn body_velocity(model: &dyn GaitModel, r: &[f64], rdot: &[f64], p: &[f64]) -> [f64; 3] {
    let mut q = vec![0.0; model.coordinate_count()];
    for (&i, &value) in model.shape_indices().iter().zip(r) {
        q[i] = value;
    }
    let qdot = model.reconstructed_velocity(&q, rdot, p);
    model.group().map(|i| qdot[i])
}
