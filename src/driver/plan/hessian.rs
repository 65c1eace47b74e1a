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
//! Since `f = (qdot, qddot)`, `hess (mu^T f) = hess (mu_qdot^T qddot)`,
//! the model's `acceleration_hessian`; `sigma hess L` comes from the running cost's
//! expression ([`crate::driver::expression::Expression::hessian`]), both
//! exact. The final cost adds `sigma hess Phi(T, x_{N-1})`. Over a given
//! duration the rows and columns of `T` are dropped.
//!
//! The structure is that of a Lagrangian coupling neighbouring nodes
//! only: each node's lower triangle, then the block of the next node's
//! rows by its columns, node by node; with a free duration, then `T`'s row
//! by every node's columns and `T` (entries a scheme does not read stay
//! zero).

use super::transcription::{Global, Motion, StagePoint, Transcription, finite, share};
use chaplygin_codegen::interpret::evaluated;

/// A dense symmetric matrix over one interval's variables `(z_i,
/// z_{i+1}, T)`, row-major.
struct IntervalHessian {
    size: usize,
    values: Vec<f64>,
}

impl IntervalHessian {
    fn new(width: usize) -> Self {
        let size = 2 * width + 1;
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

    /// Adds `scale block` (w x w, row-major) to the variables from
    /// `first` on.
    fn add_block(&mut self, first: usize, block: &[f64], scale: f64) {
        let width = (self.size - 1) / 2;
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
        for i in 0..self.nodes - 1 {
            let defect = &multipliers[i * s..(i + 1) * s];
            let hessian = self.interval_hessian(z, i, objective_factor, defect);
            self.scatter(i, &hessian, values);
        }
        self.add_final_cost(z, objective_factor, values);
        finite(values)
    }

    /// `objective_factor hess Phi(T, x_{N-1})` added to the last node's
    /// state and, with a free duration, to `T`'s row.
    fn add_final_cost(&self, z: &[f64], objective_factor: f64, values: &mut [f64]) {
        let Some(phi) = &self.costs.terminal else {
            return;
        };
        let hessian = phi.hessian(&self.final_point(z));
        let (s, w) = (self.state(), self.width());
        let m = 1 + s;
        let offset = self.node_offset(self.nodes - 1);
        for a in 0..s {
            for b in 0..=a {
                values[offset + a * (a + 1) / 2 + b] +=
                    objective_factor * hessian[(1 + a) * m + 1 + b];
            }
        }
        if self.global(Global::Duration).is_some() {
            let row = self.duration_offset();
            let last = (self.nodes - 1) * w;
            for a in 0..s {
                values[row + last + a] += objective_factor * hessian[1 + a];
            }
            values[row + self.nodes * w] += objective_factor * hessian[0];
        }
    }

    /// Interval `i`'s Hessian by `(z_i, z_{i+1}, T)` (see the module
    /// documentation), `defect` the multipliers of its defect.
    fn interval_hessian(
        &self,
        z: &[f64],
        i: usize,
        objective_factor: f64,
        defect: &[f64],
    ) -> IntervalHessian {
        let (n, w) = (self.model().sizes().n, self.width());
        let (h, duration) = (self.step(z, i), self.duration(z));
        let mut hessian = IntervalHessian::new(w);
        for stage in self.scheme.stages() {
            let point = self.stage_point(z, i, stage);
            let motion = self.stage_motion(z, i, stage);
            let along = self.stage_derivative(&point, &motion, stage.inputs_at, duration);
            let (slope, curvature) = self.stage_terms(&point, objective_factor, defect);
            let scale = h * stage.weight;
            hessian.add_congruent(&along, &curvature, scale);
            let by_v = row_times(&slope, &along);
            hessian.add_duration_outer(&by_v, stage.weight * h / duration);
            if stage.slopes != 0.0 {
                let mu = &slope[1..1 + 2 * n];
                let c = scale * stage.slopes * h;
                let (by_nodes, blocks) = self.slopes_terms(z, i, mu);
                hessian.add_duration_outer(&by_nodes, c / duration);
                hessian.add_block(0, &blocks[0], c);
                hessian.add_block(w, &blocks[1], -c);
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
    /// lambda^T f` by `(t, x, u)` at a stage.
    pub(super) fn stage_terms(
        &self,
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
        let weights: Vec<f64> = defect[n..].iter().map(|lambda| -lambda).collect();
        let (q, qdot) = point.x.split_at(n);
        let model = evaluated(
            self.model()
                .acceleration_hessian(q, qdot, &point.u, &weights),
        );
        let mut curvature = vec![0.0; m * m];
        for a in 0..w {
            curvature[(1 + a) * m + 1..(2 + a) * m].copy_from_slice(&model[a * w..(a + 1) * w]);
        }
        if objective_factor != 0.0 {
            let cost = self.costs.running.hessian(&self.cost_point(point));
            for (g, l) in curvature.iter_mut().zip(cost) {
                *g += objective_factor * l;
            }
            let (gradient, by_t) = self.cost_gradient(point);
            slope[0] += objective_factor * by_t;
            for (g, l) in slope[1..].iter_mut().zip(gradient) {
                *g += objective_factor * l;
            }
        }
        (slope, curvature)
    }

    /// For `mu` by the state, the row `(mu^T df_i/dz_i, -mu^T
    /// df_{i+1}/dz_{i+1}, 0)` and the nodes' `hess (mu^T f)` (w x w each).
    pub(super) fn slopes_terms(
        &self,
        z: &[f64],
        i: usize,
        mu: &[f64],
    ) -> (Vec<f64>, [Vec<f64>; 2]) {
        let (n, s, w) = (self.model().sizes().n, self.state(), self.width());
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
            let (q, qdot) = node.x.split_at(n);
            evaluated(
                self.model()
                    .acceleration_hessian(q, qdot, &node.u, &mu[n..]),
            )
        });
        (row, blocks)
    }

    /// Adds interval `i`'s Hessian to the nodes' entries in `values`, and
    /// to the duration's row where it is free.
    fn scatter(&self, i: usize, hessian: &IntervalHessian, values: &mut [f64]) {
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
