//! The exact Hessian of the estimation's Lagrangian,
//!
//! ```text
//! H = sigma hess RSS + sum_i lambda_i hess c_i,
//! ```
//!
//! by the nodes' states and the estimates `theta`. The residual sum of
//! squares adds `2 sigma` to the diagonal at each measured value. Interval
//! `i`'s defect reads `v = (x_i, x_{i+1}, theta)`; as for a plan
//! ([`crate::driver::plan`]'s `hessian`, Betts 2010, section 4.6), its
//! share of the Lagrangian is `lambda^T (x_{i+1} - x_i) + sum_k h w_k
//! g(X_k, theta)` with `g = -lambda^T f`, the inputs and `h` fixed, so
//! the second-order chain rule gives each stage's
//!
//! ```text
//! hess_v (h w g) = h w D^T G D
//!                + h w c h (E_i^T hess (mu^T f_i) E_i - E_{i+1}^T hess (mu^T f_{i+1}) E_{i+1}),
//! ```
//!
//! `D = d(X_k, theta)/dv`, `G` the Hessian of `g` by `(x, theta)`, `mu =
//! g_X`, `E_j` the selection of `(x_j, theta)` from `v`, and `hess (mu^T
//! f)` by `(x, theta)` at a node. The initial constraints add `sum_r
//! lambda_r hess c_{0,r}` by `(x_0, theta)` (`initial`). The blocks by the states are the plan's
//! ([`Transcription`]'s stage and slope terms); those by `theta` are the
//! model's `acceleration_parameter_hessian`, exact. Each point's second
//! derivatives, by the states and by the estimates, are computed once an
//! evaluation and weighted as often as the point is met (a node is a
//! stage of the intervals on both sides, and Hermite-Simpson's slopes
//! weigh an interval's nodes again).
//!
//! The structure: node by node, its lower triangle and the next node's
//! rows by its columns; then each estimate's row, by every state and the
//! estimates up to its own.

use super::Fit;
use crate::driver::plan::transcription::{PointCurvatures, StagePoint, Transcription};
use crate::runtime::nalgebra::DMatrix;
use chaplygin_codegen::interpret::{ParameterBlocks, ParameterCurvatures, evaluated};
use std::collections::HashMap;

/// The model's second derivatives at the points met in one evaluation of
/// the Hessian, each point's computed once and weighted as often as it is
/// met: by the states and inputs ([`PointCurvatures`]), and by the states
/// and the estimates, by the bits of the point's `(x, u)`.
#[derive(Default)]
struct Curvatures {
    rows: PointCurvatures,
    parameters: HashMap<Vec<u64>, ParameterCurvatures>,
}

impl Fit {
    /// A node's lower triangle's entries, `s (s + 1) / 2`.
    fn triangle(&self) -> usize {
        let s = self.state();
        s * (s + 1) / 2
    }

    /// Where node `i`'s entries start.
    fn node_offset(&self, i: usize) -> usize {
        let s = self.state();
        i * (self.triangle() + s * s)
    }

    /// Where estimate `l`'s row starts, after every node's entries.
    fn estimate_offset(&self, l: usize) -> usize {
        let (s, states) = (self.state(), self.states());
        self.node_offset(self.times.len()) - s * s + l * states + l * (l + 1) / 2
    }

    /// The lower triangle of the Lagrangian's Hessian (see the module
    /// documentation).
    pub(super) fn lagrangian_hessian_structure(&self) -> Vec<(usize, usize)> {
        let (s, nodes, states) = (self.state(), self.times.len(), self.states());
        let mut structure = Vec::with_capacity(self.estimate_offset(self.indices.len()));
        for i in 0..nodes {
            let first = i * s;
            structure.extend((0..s).flat_map(|a| (0..=a).map(move |b| (first + a, first + b))));
            if i + 1 < nodes {
                let next = first + s;
                structure.extend((0..s).flat_map(|a| (0..s).map(move |b| (next + a, first + b))));
            }
        }
        for l in 0..self.indices.len() {
            structure.extend((0..=states + l).map(|c| (states + l, c)));
        }
        structure
    }

    /// The entries of `objective_factor hess RSS + sum lambda_i hess c_i`
    /// at `y`, in the order of [`Fit::lagrangian_hessian_structure`];
    /// whether they are finite.
    pub(super) fn lagrangian_hessian(
        &self,
        y: &[f64],
        objective_factor: f64,
        multipliers: &[f64],
        values: &mut [f64],
    ) -> bool {
        values.fill(0.0);
        let s = self.state();
        for i in 0..self.times.len() {
            for &k in &self.measured {
                values[self.node_offset(i) + k * (k + 1) / 2 + k] += 2.0 * objective_factor;
            }
        }
        let z = self.transcribed(y);
        let transcription = self.transcription.borrow();
        let mut curvatures = Curvatures::default();
        for i in 0..self.times.len() - 1 {
            let defect = &multipliers[i * s..(i + 1) * s];
            let hessian = self.interval_hessian(&transcription, &mut curvatures, &z, i, defect);
            self.scatter(i, &hessian, values);
        }
        let initial = self.initial_terms(transcription.model(), &z[..s]);
        let mut hessian = DMatrix::zeros(2 * s + self.indices.len(), 2 * s + self.indices.len());
        for (lambda, second) in multipliers[self.defects()..].iter().zip(&initial.hessians) {
            add_at(&mut hessian, second, 0, s, *lambda);
        }
        self.scatter(0, &hessian, values);
        crate::driver::plan::transcription::finite(values)
    }

    /// Interval `i`'s Hessian by `(x_i, x_{i+1}, theta)`, `defect` its
    /// defect's multipliers, at the transcription's variables `z`.
    fn interval_hessian(
        &self,
        transcription: &Transcription,
        curvatures: &mut Curvatures,
        z: &[f64],
        i: usize,
        defect: &[f64],
    ) -> DMatrix<f64> {
        let (n, s, w) = (self.state() / 2, self.state(), transcription.width());
        let estimated = self.indices.len();
        let h = transcription.step(z, i);
        let mut hessian = DMatrix::zeros(2 * s + estimated, 2 * s + estimated);
        for stage in transcription.scheme.stages() {
            let point = transcription.stage_point(z, i, stage);
            let motion = transcription.stage_motion(z, i, stage);
            let mut along = DMatrix::zeros(s + estimated, 2 * s + estimated);
            for k in 0..s {
                for j in 0..2 {
                    for c in 0..s {
                        along[(k, j * s + c)] = motion.by_node[j][k * w + c];
                    }
                }
            }
            let by_parameters = self.stage_motion_by_parameters(transcription, z, i, stage.slopes);
            for (k, value) in by_parameters.iter().enumerate() {
                along[(k / estimated, 2 * s + k % estimated)] = *value;
            }
            for l in 0..estimated {
                along[(s + l, 2 * s + l)] = 1.0;
            }
            let (slope, curvature) =
                transcription.stage_terms(&mut curvatures.rows, &point, 0.0, defect);
            let weights: Vec<f64> = defect[n..].iter().map(|lambda| -lambda).collect();
            let g = self.curvature_by_state_and_parameters(
                transcription,
                &mut curvatures.parameters,
                &point,
                |a, b| curvature[(1 + a) * (1 + w) + 1 + b],
                &weights,
            );
            hessian += (along.transpose() * g * &along) * (h * stage.weight);
            if stage.slopes != 0.0 {
                let mu = &slope[1..1 + s];
                let (_, blocks) = transcription.slopes_terms(&mut curvatures.rows, z, i, mu);
                for (j, sign) in [(0, 1.0), (1, -1.0)] {
                    let node = transcription.node_point(z, i + j);
                    let block = &blocks[j];
                    let k_j = self.curvature_by_state_and_parameters(
                        transcription,
                        &mut curvatures.parameters,
                        &node,
                        |a, b| block[a * w + b],
                        &mu[n..],
                    );
                    let scale = sign * h * stage.weight * stage.slopes * h;
                    add_at(&mut hessian, &k_j, j * s, s, scale);
                }
            }
        }
        hessian
    }

    /// The Hessian of `weights^T qddot` by `(x, theta)` at `point`, its
    /// block by the state `by_state(a, b)`, from the point's curvatures by
    /// the estimates in `at_points`, computed there when it has none yet.
    fn curvature_by_state_and_parameters(
        &self,
        transcription: &Transcription,
        at_points: &mut HashMap<Vec<u64>, ParameterCurvatures>,
        point: &StagePoint,
        by_state: impl Fn(usize, usize) -> f64,
        weights: &[f64],
    ) -> DMatrix<f64> {
        let (n, s, estimated) = (self.state() / 2, self.state(), self.indices.len());
        let at = at_points.entry(point.bits()).or_insert_with(|| {
            let (q, qdot) = point.x.split_at(n);
            evaluated(transcription.model().acceleration_parameter_curvatures(
                q,
                qdot,
                &point.u,
                &self.indices,
            ))
        });
        let ParameterBlocks {
            mixed,
            by_parameters,
        } = evaluated(at.hessian(weights));
        DMatrix::from_fn(s + estimated, s + estimated, |a, b| match (a < s, b < s) {
            (true, true) => by_state(a, b),
            (true, false) => mixed[a * estimated + b - s],
            (false, true) => mixed[b * estimated + a - s],
            (false, false) => by_parameters[(a - s) * estimated + b - s],
        })
    }

    /// Adds interval `i`'s Hessian to the nodes' and the estimates' entries.
    fn scatter(&self, i: usize, hessian: &DMatrix<f64>, values: &mut [f64]) {
        let (s, states) = (self.state(), self.states());
        for (node, first) in [(i, 0), (i + 1, s)] {
            let offset = self.node_offset(node);
            for a in 0..s {
                for b in 0..=a {
                    values[offset + a * (a + 1) / 2 + b] += hessian[(first + a, first + b)];
                }
            }
        }
        let offset = self.node_offset(i) + self.triangle();
        for a in 0..s {
            for b in 0..s {
                values[offset + a * s + b] += hessian[(s + a, b)];
            }
        }
        for l in 0..self.indices.len() {
            let (row, theta) = (self.estimate_offset(l), 2 * s + l);
            for c in 0..2 * s {
                values[row + i * s + c] += hessian[(theta, c)];
            }
            for m in 0..=l {
                values[row + states + m] += hessian[(theta, 2 * s + m)];
            }
        }
    }
}

/// Adds `scale block` over `(x_j, theta)` to the interval's Hessian, `x_j`
/// starting at `first`.
fn add_at(hessian: &mut DMatrix<f64>, block: &DMatrix<f64>, first: usize, s: usize, scale: f64) {
    let theta = hessian.nrows() - (block.nrows() - s);
    let place = |a: usize| if a < s { first + a } else { theta + a - s };
    for a in 0..block.nrows() {
        for b in 0..block.ncols() {
            hessian[(place(a), place(b))] += scale * block[(a, b)];
        }
    }
}
