//! The first guess of the states the data do not measure: the model's
//! own motion from the first row. With `x_0 = (d_0, v)`, the first row's
//! measured values `d_0` held and the unmeasured entries `v` free,
//!
//! ```text
//! minimize over v   sum over measured (i, k) of (x_k(t_i; P(x_0)) - d_{i,k})^2,
//! ```
//!
//! `x(t; x_0)` the motion from `x_0` under the data's inputs as the scheme
//! applies them (the replay's integration, [`replayed_states_by`], with
//! [`GUESS_SUBSTEPS`] steps an interval) and `P`
//! the projection onto the initial constraints `c_0 = 0`
//! ([`super::initial`]) that moves the unmeasured entries only, by
//! Gauss-Newton steps `v <- v - (dc_0/dv)^+ c_0`. It is solved by
//! Levenberg-Marquardt (Marquardt, "An algorithm for least-squares
//! estimation of nonlinear parameters", SIAM J. Appl. Math. 11, 1963), the
//! Jacobian by forward differences. `v` starts at 0, but for a measured
//! coordinate's unmeasured rate, which starts at the data's slope between
//! the first two rows; then each unmeasured velocity in turn takes the
//! best of [`SCAN`], where the cost is lower: rest is often a stationary
//! point of the cost (a bicycle falls over the same way forwards and
//! backwards), which the scan steps off. Every node then starts at that
//! motion, its measured entries at the data.
//!
//! A motion that the data's first row and inputs already fix (a bicycle's
//! forward speed, read from how its lean and steer move) thus starts near
//! the truth instead of at 0, where the collocation's solver may not find
//! it.

use super::Fit;
use crate::driver::plan::replay::replayed_states_by;
use crate::runtime::nalgebra::{DMatrix, DVector};
use crate::runtime::record::Table;

/// RK4 steps an interval of the guess's motions. A start needs no more:
/// their error, `O((h / 4)^4)`, lies 256 times below Hermite-Simpson's own
/// `O(h^4)` and far below the other schemes' `O(h)` and `O(h^2)`, while
/// the descent integrates the motion some hundred times. (With the plan's
/// replay's 40 steps, the test of the constraints' derivatives against
/// central differences, nine estimates' starts, took 5.0 s in the test
/// build; with 4, 2.3 s.)
const GUESS_SUBSTEPS: usize = 4;

/// The values each unmeasured velocity is tried at before the descent.
const SCAN: [f64; 6] = [-30.0, -3.0, -0.3, 0.3, 3.0, 30.0];

/// The most projection steps, and the constraints' residual they stop at.
const PROJECTION_STEPS: usize = 10;
const PROJECTED: f64 = 1e-12;

/// The most Levenberg-Marquardt iterations.
const ITERATIONS: usize = 30;

/// The least relative fall of the cost that continues the iterations.
const PROGRESS: f64 = 1e-10;

/// The most times a step's damping is raised (by 4) before the descent
/// stops.
const DAMPING_TRIES: usize = 12;

/// Where the descent stands: the start `v`, its residuals and cost, and
/// the damping that made the last step.
struct Descent {
    v: Vec<f64>,
    residuals: DVector<f64>,
    cost: f64,
    damping: Option<f64>,
}

impl Fit {
    /// Each node's state as the first guess: the fitted motion, the
    /// measured entries the data's; `None` where no motion is finite.
    pub(super) fn simulated_states(&self) -> Option<Vec<f64>> {
        let free = self.unmeasured();
        if free.is_empty() {
            return None;
        }
        let v = self.scanned(&free, self.first_unmeasured(&free));
        let residuals = self.motion_residuals(&free, &v)?;
        let mut at = Descent {
            cost: residuals.norm_squared(),
            v,
            residuals,
            damping: None,
        };
        for _ in 0..ITERATIONS {
            let Some(next) = self.descended(&free, &at) else {
                break;
            };
            let fall = (at.cost - next.cost) / at.cost.max(f64::MIN_POSITIVE);
            at = next;
            if fall <= PROGRESS {
                break;
            }
        }
        self.nodes_along(&free, &at.v)
    }

    /// One Levenberg-Marquardt step from `at`, `(J^T J + mu I) dv = -J^T
    /// r`, its damping `mu` raised until the cost falls; `None` where it
    /// does not.
    fn descended(&self, free: &[usize], at: &Descent) -> Option<Descent> {
        let jacobian = self.motion_jacobian(free, &at.v, &at.residuals);
        let normal = jacobian.transpose() * &jacobian;
        let gradient = jacobian.transpose() * &at.residuals;
        let largest = normal.diagonal().max().max(f64::MIN_POSITIVE);
        let mut mu = at.damping.unwrap_or(1e-3 * largest);
        for _ in 0..DAMPING_TRIES {
            let damped = &normal + DMatrix::identity(free.len(), free.len()) * mu;
            if let Some(step) = damped.cholesky().map(|c| c.solve(&(-&gradient))) {
                let v: Vec<f64> = at.v.iter().zip(step.iter()).map(|(a, b)| a + b).collect();
                if let Some(residuals) = self.motion_residuals(free, &v) {
                    let cost = residuals.norm_squared();
                    if cost < at.cost {
                        let damping = Some(mu / 3.0);
                        return Some(Descent {
                            v,
                            residuals,
                            cost,
                            damping,
                        });
                    }
                }
            }
            mu *= 4.0;
        }
        None
    }

    /// The state's entries no column measures.
    fn unmeasured(&self) -> Vec<usize> {
        (0..self.state())
            .filter(|k| !self.measured.contains(k))
            .collect()
    }

    /// `v`'s start: 0, or a measured coordinate's slope for its rate.
    fn first_unmeasured(&self, free: &[usize]) -> Vec<f64> {
        let n = self.state() / 2;
        let step = self.times[1] - self.times[0];
        free.iter()
            .map(|&k| {
                let coordinate = k.checked_sub(n);
                let column = coordinate.and_then(|c| self.measured.iter().position(|&m| m == c));
                column.map_or(0.0, |j| (self.data[1][j] - self.data[0][j]) / step)
            })
            .collect()
    }

    /// `v` with each unmeasured velocity in turn moved to the value of
    /// [`SCAN`] with the least cost, where that is less than its own.
    fn scanned(&self, free: &[usize], mut v: Vec<f64>) -> Vec<f64> {
        let cost = |v: &[f64]| {
            self.motion_residuals(free, v)
                .map_or(f64::INFINITY, |r| r.norm_squared())
        };
        let n = self.state() / 2;
        for j in (0..free.len()).filter(|&j| free[j] >= n) {
            let mut best = (cost(&v), v[j]);
            for value in SCAN {
                let mut trial = v.clone();
                trial[j] = value;
                let tried = cost(&trial);
                if tried < best.0 {
                    best = (tried, value);
                }
            }
            v[j] = best.1;
        }
        v
    }

    /// The first state with the first row's measured values and `v`,
    /// projected onto the initial constraints.
    fn first_state(&self, free: &[usize], v: &[f64]) -> Vec<f64> {
        let mut x0 = vec![0.0; self.state()];
        for (&k, value) in self.measured.iter().zip(&self.data[0]) {
            x0[k] = *value;
        }
        for (&k, value) in free.iter().zip(v) {
            x0[k] = *value;
        }
        let transcription = self.transcription.borrow();
        for _ in 0..PROJECTION_STEPS {
            let terms = self.initial_terms(transcription.model(), &x0);
            let values = DVector::from_vec(terms.values);
            if values.amax() <= PROJECTED {
                break;
            }
            let by_free = terms.jacobian.select_columns(free);
            let Ok(inverse) = by_free.pseudo_inverse(1e-12) else {
                break;
            };
            for (&k, step) in free.iter().zip((inverse * values).iter()) {
                x0[k] -= step;
            }
        }
        x0
    }

    /// The motion from the start `v` gives, at every node.
    fn motion(&self, free: &[usize], v: &[f64]) -> Vec<Vec<f64>> {
        let transcription = self.transcription.borrow();
        let x0 = self.first_state(free, v);
        let mut columns = vec!["t".to_string()];
        columns.extend(self.columns.iter().cloned());
        let rows = self
            .times
            .iter()
            .zip(&self.inputs)
            .map(|(t, u)| [&[*t][..], &x0, u].concat())
            .collect();
        let table = Table { columns, rows };
        replayed_states_by(
            (transcription.model(), transcription.form()),
            transcription.scheme,
            &table,
            GUESS_SUBSTEPS,
        )
    }

    /// The residuals of the start `v`: the motion's measured entries
    /// against the data; `None` where any is not finite.
    fn motion_residuals(&self, free: &[usize], v: &[f64]) -> Option<DVector<f64>> {
        let states = self.motion(free, v);
        let residuals: Vec<f64> = states
            .iter()
            .zip(&self.data)
            .flat_map(|(x, d)| self.measured.iter().zip(d).map(|(&k, d)| x[k] - d))
            .collect();
        super::super::transcription::finite(&residuals).then(|| DVector::from_vec(residuals))
    }

    /// The residuals' Jacobian by `v`, by forward differences; a column
    /// whose step leaves the motion infinite is 0.
    fn motion_jacobian(&self, free: &[usize], v: &[f64], at: &DVector<f64>) -> DMatrix<f64> {
        let mut jacobian = DMatrix::zeros(at.len(), free.len());
        for j in 0..free.len() {
            let step = 1e-6 * (1.0 + v[j].abs());
            let mut moved = v.to_vec();
            moved[j] += step;
            if let Some(r) = self.motion_residuals(free, &moved) {
                jacobian.set_column(j, &((r - at) / step));
            }
        }
        jacobian
    }

    /// Every node's state along the motion from `v`, the measured entries
    /// the data's; `None` where the motion is not finite.
    fn nodes_along(&self, free: &[usize], v: &[f64]) -> Option<Vec<f64>> {
        let mut states = self.motion(free, v);
        for (x, d) in states.iter_mut().zip(&self.data) {
            for (&k, value) in self.measured.iter().zip(d) {
                x[k] = *value;
            }
        }
        let states = states.concat();
        super::super::transcription::finite(&states).then_some(states)
    }
}
