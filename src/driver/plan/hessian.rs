//! The exact Hessian of a transcription's Lagrangian,
//!
//! ```text
//! H = sigma hess J + sum_i lambda_i hess c_i,
//! ```
//!
//! stage by stage (Betts 2010, section 4.6). A stage reads `y = (q, qdot,
//! u)`, each entry `c` a share `s_j(c)` of node `j`'s (`1 - a` of the
//! interval's first, `a` of its last, `a` the stage's `at` for the state
//! and `inputs_at` for the inputs), so its Hessian by the two nodes'
//! variables is `H_y` with entry `(c, c')` scaled by `s_j(c) s_j'(c')`. Of
//! an interval's defect `x_{i+1} - x_i - h sum_k w_k f(X_k, U_k)`, only the
//! `qddot` rows are not linear, so the stage's
//!
//! ```text
//! H_y = sigma h w_k hess L + hess (v^T qddot),   v = -h w_k lambda_qdot,
//! ```
//!
//! the running cost's Hessian from its expression's second derivatives
//! ([`crate::driver::expression::Expression::hessian`]), the model's from
//! `acceleration_hessian`, both exact. The final cost adds `sigma hess Phi`
//! to the last node's state.
//!
//! These are the Hessians of the one-stage schemes over a given duration.
//! Hermite-Simpson's midpoint state reads the nodes' slopes, and a free
//! duration scales every stage: for those [`Transcription::has_hessian`]
//! says no, and the solver approximates the Hessian.
//!
//! The structure is that of a Lagrangian coupling neighbouring nodes only:
//! each node's lower triangle, then the block of the next node's rows by
//! its columns, node by node (entries a scheme does not read stay zero).

use super::transcription::{Stage, StagePoint, Transcription, finite};
use chaplygin_codegen::interpret::evaluated;

impl Transcription {
    /// The number of entries of a node's lower triangle, `w (w + 1) / 2`.
    fn triangle(&self) -> usize {
        let w = self.width();
        w * (w + 1) / 2
    }

    /// Where node `i`'s entries start: each node before it holds its
    /// triangle and its block with the next.
    fn node_offset(&self, i: usize) -> usize {
        let w = self.width();
        i * (self.triangle() + w * w)
    }

    /// Whether the Lagrangian's exact Hessian is written out: for the
    /// one-stage schemes over a given duration (see the module
    /// documentation).
    pub(super) fn has_hessian(&self) -> bool {
        let linear = self.scheme.stages().iter().all(|stage| stage.slopes == 0.0);
        linear
            && self
                .global(super::transcription::Global::Duration)
                .is_none()
    }

    /// The lower triangle of the Lagrangian's Hessian: node by node, its
    /// triangle `(a, b)`, `a >= b`, then the next node's rows by its
    /// columns.
    pub(super) fn lagrangian_hessian_structure(&self) -> Vec<(usize, usize)> {
        let w = self.width();
        let mut structure = Vec::with_capacity(self.node_offset(self.nodes) - w * w);
        for i in 0..self.nodes {
            let first = i * w;
            structure.extend((0..w).flat_map(|a| (0..=a).map(move |b| (first + a, first + b))));
            if i + 1 < self.nodes {
                let next = first + w;
                structure.extend((0..w).flat_map(|a| (0..w).map(move |b| (next + a, first + b))));
            }
        }
        structure
    }

    /// The entries of `objective_factor hess J + sum lambda_i hess c_i` at
    /// `z`, in the order of [`Transcription::lagrangian_hessian_structure`];
    /// whether they are finite.
    pub(super) fn lagrangian_hessian(
        &self,
        z: &[f64],
        objective_factor: f64,
        multipliers: &[f64],
        values: &mut [f64],
    ) -> bool {
        values.fill(0.0);
        let h = self.step(z);
        for i in 0..self.nodes - 1 {
            for stage in self.scheme.stages() {
                let point = self.stage_point(z, i, stage);
                let defect = &multipliers[i * self.state()..(i + 1) * self.state()];
                let hessian =
                    self.stage_hessian(&point, h * stage.weight, objective_factor, defect);
                self.scatter(i, stage, &hessian, values);
            }
        }
        if let Some(phi) = &self.costs.terminal {
            let hessian = phi.hessian(&self.final_point(z));
            let (s, offset) = (self.state(), self.node_offset(self.nodes - 1));
            for a in 0..s {
                for b in 0..=a {
                    values[offset + a * (a + 1) / 2 + b] += objective_factor * hessian[a * s + b];
                }
            }
        }
        finite(values)
    }

    /// `H_y` of a stage weighing `scale = h w_k` (see the module
    /// documentation), `defect` the multipliers of its interval's defect.
    fn stage_hessian(
        &self,
        point: &StagePoint,
        scale: f64,
        objective_factor: f64,
        defect: &[f64],
    ) -> Vec<f64> {
        let n = self.model().sizes().n;
        let weights: Vec<f64> = defect[n..].iter().map(|lambda| -scale * lambda).collect();
        let (q, qdot) = point.x.split_at(n);
        let mut hessian = evaluated(
            self.model()
                .acceleration_hessian(q, qdot, &point.u, &weights),
        );
        if objective_factor != 0.0 {
            let cost = self.costs.running.hessian(&self.cost_point(point));
            for (h, l) in hessian.iter_mut().zip(cost) {
                *h += objective_factor * scale * l;
            }
        }
        hessian
    }

    /// Adds the stage Hessian `hessian` (by `y`) of interval `i` to the
    /// nodes' entries in `values`, each entry scaled by the two nodes'
    /// shares.
    fn scatter(&self, i: usize, stage: &Stage, hessian: &[f64], values: &mut [f64]) {
        let (s, w) = (self.state(), self.width());
        let share = |last: bool, c: usize| {
            let at = if c < s { stage.at } else { stage.inputs_at };
            if last { at } else { 1.0 - at }
        };
        for (node, last) in [(i, false), (i + 1, true)] {
            let offset = self.node_offset(node);
            for a in 0..w {
                for b in 0..=a {
                    let scale = share(last, a) * share(last, b);
                    values[offset + a * (a + 1) / 2 + b] += scale * hessian[a * w + b];
                }
            }
        }
        let offset = self.node_offset(i) + self.triangle();
        for a in 0..w {
            for b in 0..w {
                let scale = share(true, a) * share(false, b);
                values[offset + a * w + b] += scale * hessian[a * w + b];
            }
        }
    }
}
