//! The exact Hessian of a transcription's Lagrangian,
//!
//! ```text
//! H = sigma hess J + sum_i lambda_i hess c_i,
//! ```
//!
//! interval by interval (Betts 2010, section 4.6). Interval `i` reads `v =
//! (z_i, z_{i+1}, T)`, `z_j = (x_j, u_j)`; its share of the Lagrangian is
//! `lambda^T (x_{i+1} - x_i) + sum_k h w_k g(t_k, Y_k)`, `lambda` its
//! defect's multipliers, with
//!
//! ```text
//! g(t, x, u) = sigma L(t, x, u) - lambda^T f(x, u),
//! Y_k = (X_k, U_k),   X_k = (1 - a_k) x_i + a_k x_{i+1} + c_k h (f_i - f_{i+1}),
//! h = T / (N - 1),    t_k = (i + a_k) h.
//! ```
//!
//! `h` and `t_k` are linear in `T`, `U_k` linear in the nodes, and of
//! `X_k` only the slopes' term curves, so the second-order chain rule
//! gives each stage's
//!
//! ```text
//! hess_v (h w g) = h w D^T G D + w (dh/dv)^T (dg/dv) + w (dg/dv)^T (dh/dv)
//!                + h w c sum_r (g_X)_r hess_v (h (f_i - f_{i+1}))_r,
//! ```
//!
//! `D = d(t, X, U)/dv` (the stage's motion, `dt/dT = t/T`), `G` the
//! Hessian of `g` by `(t, x, u)`, `dg/dv = (g_t, g_X, g_U) D` and `dh/dv =
//! (h/T) e_T`. With `mu = g_X`, the last term is `h w` times
//!
//! ```text
//! c h/T (e_T m^T + m e_T^T) + c h (hess_{z_i} (mu^T f_i) - hess_{z_{i+1}} (mu^T f_{i+1})),
//! m = (mu^T df_i/dz_i, -mu^T df_{i+1}/dz_{i+1}, 0).
//! ```
//!
//! `hess (mu^T f)` is the model's: in the Lagrange form `f = (qdot,
//! qddot)`, whose first rows are linear, so `hess (mu^T f) = hess
//! (mu_qdot^T qddot)`, its `acceleration_hessian`; in the reduced form
//! (`x = (q, alpha)`, [`super::form`]) `f = (X(q) alpha, alphadot)`,
//! whose every row curves, its `reduced_rhs_hessian` with all of `mu`;
//! in the momentum form (`x = (q, rdot, p)`) its `momentum_form_hessian`.
//!
//! The costs read `L(t, q, qdot, u)`, and `qdot = f_{1..n}(x)`, the first
//! `n` rows of `f`, in every form (the state itself in the Lagrange one).
//! With `E = d(t, q, qdot, u)/d(t, x, u)`, the identity but for the
//! velocities' rows `df_{1..n}/dx`, the second-order chain rule gives
//!
//! ```text
//! hess_(t, x, u) L = E^T (hess L) E + sum_r (L_qdot)_r hess f_r,
//! G = sigma E^T (hess L) E + hess (nu^T f),   nu = sigma (L_qdot, 0) - lambda,
//! ```
//!
//! the cost's curvature through the velocities joining the model's, one
//! `hess (nu^T f)` a stage (zero in the Lagrange form, where `qdot` is
//! the state). `hess L` comes from the running cost's expression
//! ([`crate::driver::expression::Expression::hessian`]), all exact. The
//! final cost adds `sigma (E^T (hess Phi) E + hess ((Phi_qdot, 0)^T f))`
//! by `(T, x_{N-1})`. Over a given duration the rows and columns of `T`
//! are dropped.
//!
//! The model's second derivatives at a point are computed once an
//! evaluation and weighted as often as the point is met
//! ([`PointCurvatures`]): Hermite-Simpson's five weightings an interval
//! fall on three points, two of them nodes shared with the neighbouring
//! intervals.
//!
//! The structure is that of a Lagrangian coupling neighbouring nodes
//! only: each node's lower triangle, then the block of the next node's
//! rows by its columns, node by node; with a free duration, then `T`'s row
//! by every node's columns and `T` (entries a scheme does not read stay
//! zero).

use super::transcription::{
    Global, Motion, PointCurvatures, StagePoint, Transcription, finite, share,
};

/// A dense symmetric matrix, row-major: over one interval's variables
/// `(z_i, z_{i+1}, T)`, or a stage's `(t, x, u)`.
struct Dense {
    size: usize,
    values: Vec<f64>,
}

impl Dense {
    fn new(size: usize) -> Self {
        Self {
            size,
            values: vec![0.0; size * size],
        }
    }

    fn at(&self, a: usize, b: usize) -> f64 {
        self.values[a * self.size + b]
    }

    /// Adds `scale (e_T r^T + r e_T^T)` for a row `r` over the variables.
    fn add_duration_outer(&mut self, row: &[f64], scale: f64) {
        let last = self.size - 1;
        for (c, r) in row.iter().enumerate() {
            self.values[last * self.size + c] += scale * r;
            self.values[c * self.size + last] += scale * r;
        }
    }

    /// Adds `scale block` (width x width, row-major) to the variables
    /// from `first` on.
    fn add_block(&mut self, first: usize, width: usize, block: &[f64], scale: f64) {
        for a in 0..width {
            for b in 0..width {
                self.values[(first + a) * self.size + first + b] += scale * block[a * width + b];
            }
        }
    }

    /// Adds `scale D^T G D`, `D` (m x size) and `G` (m x m) row-major.
    fn add_congruent(&mut self, motion: &[f64], curvature: &[f64], scale: f64) {
        let (m, size) = (motion.len() / self.size, self.size);
        let mut product = vec![0.0; m * size];
        for r in 0..m {
            for (k, g) in curvature[r * m..(r + 1) * m].iter().enumerate() {
                if *g != 0.0 {
                    let (out, row) = (&mut product[r * size..(r + 1) * size], &motion[k * size..]);
                    for (o, d) in out.iter_mut().zip(row) {
                        *o += g * d;
                    }
                }
            }
        }
        for k in 0..m {
            for a in 0..size {
                let d = motion[k * size + a];
                if d != 0.0 {
                    let out = &mut self.values[a * size..(a + 1) * size];
                    for (o, p) in out.iter_mut().zip(&product[k * size..(k + 1) * size]) {
                        *o += scale * d * p;
                    }
                }
            }
        }
    }
}

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

    /// Where the duration's row starts, after every node's entries.
    fn duration_offset(&self) -> usize {
        let w = self.width();
        self.node_offset(self.nodes) - w * w
    }

    /// The lower triangle of the Lagrangian's Hessian: node by node, its
    /// triangle `(a, b)`, `a >= b`, then the next node's rows by its
    /// columns; with a free duration, its row.
    pub(super) fn lagrangian_hessian_structure(&self) -> Vec<(usize, usize)> {
        let w = self.width();
        let mut structure = Vec::with_capacity(self.node_offset(self.nodes));
        for i in 0..self.nodes {
            let first = i * w;
            structure.extend((0..w).flat_map(|a| (0..=a).map(move |b| (first + a, first + b))));
            if i + 1 < self.nodes {
                let next = first + w;
                structure.extend((0..w).flat_map(|a| (0..w).map(move |b| (next + a, first + b))));
            }
        }
        if let Some(duration) = self.global(Global::Duration) {
            structure.extend((0..self.nodes * w).map(|c| (duration, c)));
            structure.push((duration, duration));
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
        let s = self.state();
        let mut curvatures = PointCurvatures::default();
        for i in 0..self.nodes - 1 {
            let defect = &multipliers[i * s..(i + 1) * s];
            let hessian = self.interval_hessian(&mut curvatures, z, i, objective_factor, defect);
            self.scatter(i, &hessian, values);
        }
        self.add_final_cost(&mut curvatures, z, objective_factor, values);
        self.add_start(z, &multipliers[self.defects()..], values);
        finite(values)
    }

    /// `sum_r lambda_r hess c_0r` of the start's rows, `lambda` their
    /// multipliers, added to the first node's triangle.
    fn add_start(&self, z: &[f64], lambda: &[f64], values: &mut [f64]) {
        if lambda.is_empty() {
            return;
        }
        let terms = self.start_terms(z);
        let first = self.node_offset(0);
        for (l, hessian) in lambda.iter().zip(&terms.hessians) {
            for a in 0..hessian.nrows() {
                for b in 0..=a {
                    values[first + a * (a + 1) / 2 + b] += l * hessian[(a, b)];
                }
            }
        }
    }

    /// `objective_factor hess Phi(T, x_{N-1})` added to the last node's
    /// state and, with a free duration, to `T`'s row: `E^T hess Phi E +
    /// hess (Phi_qdot^T qdot)` by `(T, x)`.
    fn add_final_cost(
        &self,
        curvatures: &mut PointCurvatures,
        z: &[f64],
        objective_factor: f64,
        values: &mut [f64],
    ) {
        let Some(phi) = &self.costs.terminal else {
            return;
        };
        let (n, s, w) = (self.model().sizes().n, self.state(), self.width());
        let last = self.final_stage(z);
        let point = self.cost_point(&last);
        let (_, by) = phi.gradient(&point);
        let (fx, _) = self.rhs_jacobian(&last);
        let mut hessian = Dense::new(1 + w);
        hessian.values = self.cost_curvature(&phi.hessian(&point), &fx[..n * s]);
        let mut weights = by.qdot;
        weights.resize(s, 0.0);
        let model = self.rhs_hessian(curvatures, &last, &weights);
        hessian.add_block(1, w, &model, 1.0);
        let offset = self.node_offset(self.nodes - 1);
        for a in 0..s {
            for b in 0..=a {
                values[offset + a * (a + 1) / 2 + b] += objective_factor * hessian.at(1 + a, 1 + b);
            }
        }
        if self.global(Global::Duration).is_some() {
            let row = self.duration_offset();
            let first = (self.nodes - 1) * w;
            for a in 0..s {
                values[row + first + a] += objective_factor * hessian.at(0, 1 + a);
            }
            values[row + self.nodes * w] += objective_factor * hessian.at(0, 0);
        }
    }

    /// Interval `i`'s Hessian by `(z_i, z_{i+1}, T)` (see the module
    /// documentation), `defect` the multipliers of its defect.
    fn interval_hessian(
        &self,
        curvatures: &mut PointCurvatures,
        z: &[f64],
        i: usize,
        objective_factor: f64,
        defect: &[f64],
    ) -> Dense {
        let (s, w) = (self.state(), self.width());
        let (h, duration) = (self.step(z, i), self.duration(z));
        let mut hessian = Dense::new(2 * w + 1);
        for stage in self.scheme.stages() {
            let point = self.stage_point(z, i, stage);
            let motion = self.stage_motion(z, i, stage);
            let along = self.stage_derivative(&point, &motion, stage.inputs_at, duration);
            let (slope, curvature) = self.stage_terms(curvatures, &point, objective_factor, defect);
            let scale = h * stage.weight;
            hessian.add_congruent(&along, &curvature, scale);
            let by_v = row_times(&slope, &along);
            hessian.add_duration_outer(&by_v, stage.weight * h / duration);
            if stage.slopes != 0.0 {
                let mu = &slope[1..1 + s];
                let c = scale * stage.slopes * h;
                let (by_nodes, blocks) = self.slopes_terms(curvatures, z, i, mu);
                hessian.add_duration_outer(&by_nodes, c / duration);
                hessian.add_block(0, w, &blocks[0], c);
                hessian.add_block(w, w, &blocks[1], -c);
            }
        }
        hessian
    }

    /// `D = d(t, X, U)/dv` of a stage ((1 + w) x (2w + 1), row-major).
    fn stage_derivative(
        &self,
        point: &StagePoint,
        motion: &Motion,
        inputs_at: f64,
        duration: f64,
    ) -> Vec<f64> {
        let (s, w) = (self.state(), self.width());
        let size = 2 * w + 1;
        let mut along = vec![0.0; (1 + w) * size];
        along[size - 1] = point.t / duration;
        for k in 0..s {
            let row = &mut along[(1 + k) * size..(2 + k) * size];
            for j in 0..2 {
                row[j * w..(j + 1) * w].copy_from_slice(&motion.by_node[j][k * w..(k + 1) * w]);
            }
            row[size - 1] = motion.by_duration[k];
        }
        for l in 0..w - s {
            let row = &mut along[(1 + s + l) * size..(2 + s + l) * size];
            for j in 0..2 {
                row[j * w + s + l] = share(j, inputs_at);
            }
        }
        along
    }

    /// The gradient (1 + w) and Hessian ((1 + w)^2) of `g = sigma L -
    /// lambda^T f` by `(t, x, u)` at a stage: `sigma E^T hess L E` and
    /// `hess (nu^T f)`, `nu = sigma (L_qdot, 0) - lambda` (see the module
    /// documentation).
    pub(super) fn stage_terms(
        &self,
        curvatures: &mut PointCurvatures,
        point: &StagePoint,
        objective_factor: f64,
        defect: &[f64],
    ) -> (Vec<f64>, Vec<f64>) {
        let (n, s, w) = (self.model().sizes().n, self.state(), self.width());
        let m = 1 + w;
        let (fx, fu) = self.rhs_jacobian(point);
        let mut slope = vec![0.0; m];
        for (r, lambda) in defect.iter().enumerate() {
            for (c, d) in fx[r * s..(r + 1) * s].iter().enumerate() {
                slope[1 + c] -= lambda * d;
            }
            for (c, d) in fu[r * (w - s)..(r + 1) * (w - s)].iter().enumerate() {
                slope[1 + s + c] -= lambda * d;
            }
        }
        let mut weights: Vec<f64> = defect.iter().map(|lambda| -lambda).collect();
        let mut curvature = vec![0.0; m * m];
        if objective_factor != 0.0 {
            let (gradient, by) = self.cost_gradient(point);
            slope[0] += objective_factor * by.t;
            for (g, l) in slope[1..].iter_mut().zip(gradient) {
                *g += objective_factor * l;
            }
            for (nu, l) in weights.iter_mut().zip(&by.qdot) {
                *nu += objective_factor * l;
            }
            let cost = self.costs.running.hessian(&self.cost_point(point));
            let by_state = self.cost_curvature(&cost, &fx[..n * s]);
            for (g, l) in curvature.iter_mut().zip(by_state) {
                *g += objective_factor * l;
            }
        }
        let model = self.rhs_hessian(curvatures, point, &weights);
        for a in 0..w {
            for (g, d) in curvature[(1 + a) * m + 1..(2 + a) * m]
                .iter_mut()
                .zip(&model[a * w..(a + 1) * w])
            {
                *g += d;
            }
        }
        (slope, curvature)
    }

    /// `E^T G E` ((1 + w)^2, row-major) for `G` a cost's Hessian by `(t,
    /// q, qdot, u)`, `E = d(t, q, qdot, u)/d(t, x, u)`: the identity but
    /// for the velocities' rows, `velocities` (`d qdot/dx`, n x s, the
    /// first `n` rows of `df/dx`).
    fn cost_curvature(&self, cost: &[f64], velocities: &[f64]) -> Vec<f64> {
        let (n, s, w) = (self.model().sizes().n, self.state(), self.width());
        let (rows, columns) = (1 + 2 * n + w - s, 1 + w);
        let mut motion = vec![0.0; rows * columns];
        for r in 0..rows {
            let row = &mut motion[r * columns..(r + 1) * columns];
            match r {
                r if r <= n => row[r] = 1.0,
                r if r <= 2 * n => {
                    row[1..=s].copy_from_slice(&velocities[(r - 1 - n) * s..(r - n) * s]);
                }
                r => row[r - 2 * n + s] = 1.0,
            }
        }
        let mut congruent = Dense::new(columns);
        congruent.add_congruent(&motion, cost, 1.0);
        congruent.values
    }

    /// For `mu` by the state (s), the row `(mu^T df_i/dz_i, -mu^T
    /// df_{i+1}/dz_{i+1}, 0)` and the nodes' `hess (mu^T f)` (w x w each).
    pub(super) fn slopes_terms(
        &self,
        curvatures: &mut PointCurvatures,
        z: &[f64],
        i: usize,
        mu: &[f64],
    ) -> (Vec<f64>, [Vec<f64>; 2]) {
        let (s, w) = (self.state(), self.width());
        let mut row = vec![0.0; 2 * w + 1];
        let blocks = [0, 1].map(|j| {
            let node = self.node_point(z, i + j);
            let sign = if j == 0 { 1.0 } else { -1.0 };
            let (fx, fu) = self.rhs_jacobian(&node);
            for (r, m) in mu.iter().enumerate() {
                for (c, d) in fx[r * s..(r + 1) * s].iter().enumerate() {
                    row[j * w + c] += sign * m * d;
                }
                for (c, d) in fu[r * (w - s)..(r + 1) * (w - s)].iter().enumerate() {
                    row[j * w + s + c] += sign * m * d;
                }
            }
            self.rhs_hessian(curvatures, &node, mu)
        });
        (row, blocks)
    }

    /// Adds interval `i`'s Hessian to the nodes' entries in `values`, and
    /// to the duration's row where it is free.
    fn scatter(&self, i: usize, hessian: &Dense, values: &mut [f64]) {
        let w = self.width();
        for (node, first) in [(i, 0), (i + 1, w)] {
            let offset = self.node_offset(node);
            for a in 0..w {
                for b in 0..=a {
                    values[offset + a * (a + 1) / 2 + b] += hessian.at(first + a, first + b);
                }
            }
        }
        let offset = self.node_offset(i) + self.triangle();
        for a in 0..w {
            for b in 0..w {
                values[offset + a * w + b] += hessian.at(w + a, b);
            }
        }
        if self.global(Global::Duration).is_some() {
            let (row, last) = (self.duration_offset(), 2 * w);
            for c in 0..2 * w {
                values[row + i * w + c] += hessian.at(last, c);
            }
            values[row + self.nodes * w] += hessian.at(last, last);
        }
    }
}

/// The row `r^T D` for `r` (m) and `D` (m x size, row-major).
fn row_times(row: &[f64], matrix: &[f64]) -> Vec<f64> {
    let size = matrix.len() / row.len();
    let mut product = vec![0.0; size];
    for (k, r) in row.iter().enumerate() {
        for (p, d) in product.iter_mut().zip(&matrix[k * size..(k + 1) * size]) {
            *p += r * d;
        }
    }
    product
}

#[cfg(test)]
mod tests {
    use super::super::transcription::tests::transcription;
    use super::PointCurvatures;
    use crate::driver::plan::Scheme;

    /// Hermite-Simpson weighs the model's curvatures five times an interval
    /// (its three stages, and its slopes' terms at both nodes) at three
    /// points, its nodes shared with the neighbouring intervals. The
    /// stages at the nodes and the slopes' nodes are the same points to the
    /// bit, so that over the two intervals of 3 nodes the curvatures are
    /// computed at 5 points, not 10.
    #[test]
    fn hermite_simpson_computes_each_points_curvatures_once() {
        let (nlp, z) = transcription(Scheme::HermiteSimpson, true);
        let s = nlp.state();
        let mut curvatures = PointCurvatures::default();
        for i in 0..2 {
            let defect: Vec<f64> = (0..s).map(|k| 0.4 - 0.1 * (k + i) as f64).collect();
            nlp.interval_hessian(&mut curvatures, &z, i, 1.0, &defect);
        }
        assert_eq!(curvatures.points(), 5);
    }
}
