//! A plan transcribed into an [`Nlp`] by direct collocation (Betts,
//! "Practical Methods for Optimal Control and Estimation Using Nonlinear
//! Programming", 2nd ed., SIAM 2010, sections 4.5 and 4.6).
//!
//! The state is the Lagrange-d'Alembert one, `x = (q, qdot)`, moving by
//! `f(x, u) = (qdot, qddot(q, qdot, u))`. The variables are each node's
//! state and inputs, `z = (x_0, u_0, ..., x_{N-1}, u_{N-1})`, at
//! `t_i = i h`, `h = T / (N - 1)`. Each interval's defect is a one-step
//! scheme written by its stages, a weight `w` at a point `a` of the way
//! from node `i` to node `i + 1` for the state, `b` for the inputs:
//!
//! ```text
//! x_{i+1} - x_i - h sum_k w_k f(X_k, U_k) = 0,
//! X_k = (1 - a_k) x_i + a_k x_{i+1},   U_k = (1 - b_k) u_i + b_k u_{i+1}.
//! ```
//!
//! Backward Euler is one stage `(w, a, b) = (1, 1, 1)`: first order, the
//! inputs held from the right, `u(t) = u_{i+1}` on `(t_i, t_{i+1}]`. The
//! implicit midpoint rule is one stage `(1, 1/2, 0)`: second order, the
//! inputs held from the left, `u(t) = u_i` on `[t_i, t_{i+1})`, each
//! approximating the optimal input at the interval's midpoint. (Averaging
//! the inputs instead leaves their mode `u_i + (-1)^i e` free.) The
//! running cost is integrated by the same stages, `J = sum_i h sum_k w_k
//! L(t_i + a_k h, X_k, U_k)`. A node's inputs the scheme does not read
//! (backward Euler's first, the midpoint rule's last) are reported as
//! their neighbour's.
//! The constraints' Jacobian is block-sparse: an interval's defect reads
//! its two nodes only, the `q` rows only `q` and `qdot` entrywise. Its
//! values are the model's exact Jacobian `acceleration_jacobian`, and the
//! cost's gradient the expression's exact derivatives.

use super::nlp::Nlp;
use crate::driver::expression::{Expression, Point};
use chaplygin_codegen::interpret::{InterpretedModel, evaluated};
use std::collections::BTreeSet;

/// A one-step collocation scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Scheme {
    /// `x_{i+1} = x_i + h f(x_{i+1}, u_{i+1})`: first order.
    BackwardEuler,
    /// `x_{i+1} = x_i + h f((x_i + x_{i+1})/2, (u_i + u_{i+1})/2)`: second
    /// order.
    Midpoint,
}

/// One stage of a scheme: its weight, and where between the nodes it
/// takes the state and the inputs.
pub(super) struct Stage {
    pub(super) weight: f64,
    pub(super) at: f64,
    pub(super) inputs_at: f64,
}

impl Scheme {
    /// Its name on the command line and in `plan.json`.
    pub fn name(self) -> &'static str {
        match self {
            Self::BackwardEuler => "backward-euler",
            Self::Midpoint => "midpoint",
        }
    }

    pub(super) fn stages(self) -> &'static [Stage] {
        match self {
            Self::BackwardEuler => &[Stage {
                weight: 1.0,
                at: 1.0,
                inputs_at: 1.0,
            }],
            Self::Midpoint => &[Stage {
                weight: 1.0,
                at: 0.5,
                inputs_at: 0.0,
            }],
        }
    }
}

/// The problem's data: the model, the grid, the cost and the bounds.
pub struct Transcription {
    model: InterpretedModel,
    pub(super) scheme: Scheme,
    pub(super) nodes: usize,
    duration: f64,
    pub(super) cost: Expression,
    lo: Vec<f64>,
    hi: Vec<f64>,
    guess: Vec<f64>,
    /// One interval's structure: (row of its defect, column among its two
    /// nodes' variables).
    local: Vec<(usize, usize)>,
    structure: Vec<(usize, usize)>,
}

/// A stage's time, state and inputs.
pub(super) struct StagePoint {
    t: f64,
    pub(super) x: Vec<f64>,
    pub(super) u: Vec<f64>,
}

impl Transcription {
    /// The plan of `model` by `scheme` on `nodes` nodes over `duration`,
    /// minimizing the running cost `cost`, its variables bounded by `lo`
    /// and `hi` and started at `guess` (each `nodes` times a node's
    /// variables, `(q, qdot, u)`).
    pub(crate) fn new(
        model: InterpretedModel,
        scheme: Scheme,
        (nodes, duration): (usize, f64),
        cost: Expression,
        (lo, hi, guess): (Vec<f64>, Vec<f64>, Vec<f64>),
    ) -> Self {
        let mut transcription = Self {
            model,
            scheme,
            nodes,
            duration,
            cost,
            lo,
            hi,
            guess,
            local: Vec::new(),
            structure: Vec::new(),
        };
        transcription.local = transcription.local_structure();
        let (s, w) = (transcription.state(), transcription.width());
        transcription.structure = (0..nodes - 1)
            .flat_map(|i| {
                let local = &transcription.local;
                local.iter().map(move |&(k, c)| (i * s + k, i * w + c))
            })
            .collect();
        transcription
    }

    /// The model.
    pub fn model(&self) -> &InterpretedModel {
        &self.model
    }

    /// The time step `h`.
    pub fn step(&self) -> f64 {
        self.duration / (self.nodes - 1) as f64
    }

    /// The inputs at node `i` of `z` as the scheme applies them: with
    /// backward Euler, node 0's are node 1's (held from the right).
    pub fn held_inputs(&self, z: &[f64], i: usize) -> Vec<f64> {
        let (s, w) = (self.state(), self.width());
        let node = match self.scheme {
            Scheme::BackwardEuler => i.max(1),
            Scheme::Midpoint => i.min(self.nodes - 2),
        };
        z[node * w + s..(node + 1) * w].to_vec()
    }

    /// The state's size, `2n`.
    pub(super) fn state(&self) -> usize {
        2 * self.model.sizes().n
    }

    /// A node's variables, `2n + p`.
    pub fn width(&self) -> usize {
        self.state() + self.model.sizes().p
    }

    /// Whether a stage reads node `j`'s (0: the interval's first, 1: its
    /// last) state, and its inputs.
    fn reads(&self, j: usize) -> (bool, bool) {
        let read = |at: f64| if j == 0 { at != 1.0 } else { at != 0.0 };
        let stages = self.scheme.stages();
        (
            stages.iter().any(|stage| read(stage.at)),
            stages.iter().any(|stage| read(stage.inputs_at)),
        )
    }

    /// One interval's structure: each defect row reads its own entry at
    /// both nodes; a `q` row reads `qdot`'s same entry, a `qdot` row every
    /// state entry and input, of each node a stage reads.
    fn local_structure(&self) -> Vec<(usize, usize)> {
        let (n, s, w) = (self.model.sizes().n, self.state(), self.width());
        let mut entries = BTreeSet::new();
        for k in 0..s {
            entries.extend([(k, k), (k, w + k)]);
            for j in 0..2 {
                let (state, inputs) = self.reads(j);
                if k < n && state {
                    entries.insert((k, j * w + n + k));
                }
                if k >= n && state {
                    entries.extend((0..s).map(|c| (k, j * w + c)));
                }
                if k >= n && inputs {
                    entries.extend((s..w).map(|c| (k, j * w + c)));
                }
            }
        }
        entries.into_iter().collect()
    }

    /// The stage `stage` of interval `i` at `z`.
    pub(super) fn stage_point(&self, z: &[f64], i: usize, stage: &Stage) -> StagePoint {
        let (s, w) = (self.state(), self.width());
        let (first, last) = (&z[i * w..(i + 1) * w], &z[(i + 1) * w..(i + 2) * w]);
        let mix = |range: std::ops::Range<usize>, at: f64| -> Vec<f64> {
            first[range.clone()]
                .iter()
                .zip(&last[range])
                .map(|(a, b)| (1.0 - at) * a + at * b)
                .collect()
        };
        StagePoint {
            t: (i as f64 + stage.at) * self.step(),
            x: mix(0..s, stage.at),
            u: mix(s..w, stage.inputs_at),
        }
    }

    /// `f(x, u) = (qdot, qddot)`.
    fn rhs(&self, point: &StagePoint) -> Vec<f64> {
        let n = self.model.sizes().n;
        let (q, qdot) = point.x.split_at(n);
        let (qddot, _) = evaluated(self.model.acceleration(q, qdot, &point.u));
        qdot.iter().chain(&qddot).copied().collect()
    }

    /// `df/dx` (2n x 2n) and `df/du` (2n x p), row-major.
    fn rhs_jacobian(&self, point: &StagePoint) -> (Vec<f64>, Vec<f64>) {
        let (n, p) = (self.model.sizes().n, self.model.sizes().p);
        let s = 2 * n;
        let (q, qdot) = point.x.split_at(n);
        let (by_q, by_qdot, by_u) = evaluated(self.model.acceleration_jacobian(q, qdot, &point.u));
        let mut fx = vec![0.0; s * s];
        let mut fu = vec![0.0; s * p];
        for k in 0..n {
            fx[k * s + n + k] = 1.0;
            let row = (n + k) * s;
            fx[row..row + n].copy_from_slice(&by_q[k * n..(k + 1) * n]);
            fx[row + n..row + s].copy_from_slice(&by_qdot[k * n..(k + 1) * n]);
            fu[(n + k) * p..(n + k + 1) * p].copy_from_slice(&by_u[k * p..(k + 1) * p]);
        }
        (fx, fu)
    }

    /// Where the cost is evaluated at a stage.
    pub(super) fn cost_point<'a>(&self, point: &'a StagePoint) -> Point<'a> {
        let (q, qdot) = point.x.split_at(self.model.sizes().n);
        Point {
            t: point.t,
            q,
            qdot,
            u: &point.u,
            ..Point::default()
        }
    }

    /// The running cost's gradient by `(q, qdot, u)` at a stage.
    fn cost_gradient(&self, point: &StagePoint) -> Vec<f64> {
        let (_, gradient) = self.cost.gradient(&self.cost_point(point));
        [gradient.q, gradient.qdot, gradient.u].concat()
    }

    /// One interval's defect Jacobian, dense over its two nodes' variables
    /// (2n x 2(2n + p)), row-major.
    fn interval_jacobian(&self, z: &[f64], i: usize) -> Vec<f64> {
        let (s, w, h) = (self.state(), self.width(), self.step());
        let columns = 2 * w;
        let mut block = vec![0.0; s * columns];
        for k in 0..s {
            block[k * columns + k] = -1.0;
            block[k * columns + w + k] = 1.0;
        }
        let p = w - s;
        for stage in self.scheme.stages() {
            let (fx, fu) = self.rhs_jacobian(&self.stage_point(z, i, stage));
            for j in 0..2 {
                let [state, inputs] = [stage.at, stage.inputs_at].map(|at| {
                    let share = if j == 0 { 1.0 - at } else { at };
                    h * stage.weight * share
                });
                for k in 0..s {
                    let row = &mut block[k * columns + j * w..k * columns + (j + 1) * w];
                    for c in 0..s {
                        row[c] -= state * fx[k * s + c];
                    }
                    for l in 0..p {
                        row[s + l] -= inputs * fu[k * p + l];
                    }
                }
            }
        }
        block
    }
}

/// Whether every value is finite.
pub(super) fn finite(values: &[f64]) -> bool {
    values.iter().all(|v| v.is_finite())
}

impl Nlp for Transcription {
    fn variables(&self) -> usize {
        self.nodes * self.width()
    }

    fn constraints(&self) -> usize {
        (self.nodes - 1) * self.state()
    }

    fn bounds(&self) -> (&[f64], &[f64]) {
        (&self.lo, &self.hi)
    }

    fn guess(&self) -> Vec<f64> {
        self.guess.clone()
    }

    fn objective(&self, z: &[f64]) -> Option<f64> {
        let h = self.step();
        let total: f64 = (0..self.nodes - 1)
            .flat_map(|i| {
                self.scheme.stages().iter().map(move |stage| {
                    let point = self.stage_point(z, i, stage);
                    h * stage.weight * self.cost.at(&self.cost_point(&point))
                })
            })
            .sum();
        total.is_finite().then_some(total)
    }

    fn gradient(&self, z: &[f64], gradient: &mut [f64]) -> bool {
        let (w, h) = (self.width(), self.step());
        gradient.fill(0.0);
        for i in 0..self.nodes - 1 {
            for stage in self.scheme.stages() {
                let by = self.cost_gradient(&self.stage_point(z, i, stage));
                let s = self.state();
                for (j, first) in [(i, true), (i + 1, false)] {
                    let share = |at: f64| h * stage.weight * if first { 1.0 - at } else { at };
                    let (state, inputs) = (share(stage.at), share(stage.inputs_at));
                    let node = &mut gradient[j * w..(j + 1) * w];
                    for (c, (g, d)) in node.iter_mut().zip(&by).enumerate() {
                        *g += if c < s { state } else { inputs } * d;
                    }
                }
            }
        }
        finite(gradient)
    }

    fn residuals(&self, z: &[f64], residuals: &mut [f64]) -> bool {
        let (s, w, h) = (self.state(), self.width(), self.step());
        for i in 0..self.nodes - 1 {
            let defect = &mut residuals[i * s..(i + 1) * s];
            for (k, d) in defect.iter_mut().enumerate() {
                *d = z[(i + 1) * w + k] - z[i * w + k];
            }
            for stage in self.scheme.stages() {
                let f = self.rhs(&self.stage_point(z, i, stage));
                for (d, fk) in defect.iter_mut().zip(&f) {
                    *d -= h * stage.weight * fk;
                }
            }
        }
        finite(residuals)
    }

    fn jacobian_structure(&self) -> &[(usize, usize)] {
        &self.structure
    }

    fn jacobian_values(&self, z: &[f64], values: &mut [f64]) -> bool {
        let columns = 2 * self.width();
        let per_interval = self.local.len();
        for i in 0..self.nodes - 1 {
            let block = self.interval_jacobian(z, i);
            let out = &mut values[i * per_interval..(i + 1) * per_interval];
            for (value, &(k, c)) in out.iter_mut().zip(&self.local) {
                *value = block[k * columns + c];
            }
        }
        finite(values)
    }

    fn hessian_structure(&self) -> Vec<(usize, usize)> {
        self.lagrangian_hessian_structure()
    }

    fn hessian_values(
        &self,
        z: &[f64],
        objective_factor: f64,
        multipliers: &[f64],
        values: &mut [f64],
    ) -> bool {
        self.lagrangian_hessian(z, objective_factor, multipliers, values)
    }
}

#[cfg(test)]
mod tests {
    use super::{Nlp, Scheme, Transcription};
    use crate::driver::expression::{Expression, Scope};
    use chaplygin_codegen::interpret::InterpretedModel;

    /// The differential drive on 3 nodes at a point with every variable
    /// nonzero, its cost reading coordinates, velocities and inputs.
    fn transcription(scheme: Scheme) -> (Transcription, Vec<f64>) {
        let model =
            InterpretedModel::from_source(include_str!("../catalog/differential_drive.model"))
                .expect("the model derives");
        let scope = Scope {
            coordinates: &["x", "y", "theta", "phi_r", "phi_l"],
            inputs: &["u_right", "u_left"],
            ..Scope::default()
        };
        let cost = Expression::parse("u_right^2 + x*dot(theta)^2 + sin(theta)*u_left + t", &scope)
            .expect("parses");
        let size = 3 * 12;
        let z: Vec<f64> = (0..size)
            .map(|j| 0.3 * ((j as f64) * 0.77).sin() + 0.1)
            .collect();
        let free = vec![f64::NEG_INFINITY; size];
        let bounds = (free.clone(), free.iter().map(|v| -v).collect(), z.clone());
        let transcription = Transcription::new(model, scheme, (3, 0.8), cost, bounds);
        (transcription, z)
    }

    /// Central differences of `f` at `z` by variable `j`.
    fn central(z: &[f64], j: usize, f: &dyn Fn(&[f64]) -> Vec<f64>) -> Vec<f64> {
        let step = 1e-6;
        let (mut plus, mut minus) = (z.to_vec(), z.to_vec());
        plus[j] += step;
        minus[j] -= step;
        let (a, b) = (f(&plus), f(&minus));
        a.iter()
            .zip(&b)
            .map(|(a, b)| (a - b) / (2.0 * step))
            .collect()
    }

    #[test]
    fn the_exact_derivatives_agree_with_central_differences() {
        for scheme in [Scheme::BackwardEuler, Scheme::Midpoint] {
            let (nlp, z) = transcription(scheme);
            let mut dense = vec![0.0; nlp.constraints() * nlp.variables()];
            let mut values = vec![0.0; nlp.jacobian_structure().len()];
            assert!(nlp.jacobian_values(&z, &mut values));
            for (&(row, column), value) in nlp.jacobian_structure().iter().zip(&values) {
                dense[row * nlp.variables() + column] = *value;
            }
            let mut gradient = vec![0.0; nlp.variables()];
            assert!(nlp.gradient(&z, &mut gradient));
            let residuals = |z: &[f64]| {
                let mut c = vec![0.0; nlp.constraints()];
                assert!(nlp.residuals(z, &mut c));
                c
            };
            let objective = |z: &[f64]| vec![nlp.objective(z).expect("finite")];
            for j in 0..nlp.variables() {
                let by_j = central(&z, j, &residuals);
                for (row, numeric) in by_j.iter().enumerate() {
                    let exact = dense[row * nlp.variables() + j];
                    assert!(
                        (exact - numeric).abs() < 1e-6,
                        "{scheme:?} ({row}, {j}): {exact} vs {numeric}"
                    );
                }
                let numeric = central(&z, j, &objective)[0];
                assert!(
                    (gradient[j] - numeric).abs() < 1e-6,
                    "{scheme:?} {j}: {} vs {numeric}",
                    gradient[j]
                );
            }
        }
    }

    /// `sigma grad J + Jc^T lambda` at `z`, from the exact gradient and
    /// Jacobian.
    fn lagrangian_gradient(nlp: &Transcription, z: &[f64], sigma: f64, lambda: &[f64]) -> Vec<f64> {
        let mut gradient = vec![0.0; nlp.variables()];
        assert!(nlp.gradient(z, &mut gradient));
        let mut values = vec![0.0; nlp.jacobian_structure().len()];
        assert!(nlp.jacobian_values(z, &mut values));
        for g in &mut gradient {
            *g *= sigma;
        }
        for (&(row, column), value) in nlp.jacobian_structure().iter().zip(&values) {
            gradient[column] += lambda[row] * value;
        }
        gradient
    }

    #[test]
    fn the_lagrangians_hessian_agrees_with_central_differences_of_its_gradient() {
        for scheme in [Scheme::BackwardEuler, Scheme::Midpoint] {
            let (nlp, z) = transcription(scheme);
            let sigma = 0.7;
            let lambda: Vec<f64> = (0..nlp.constraints())
                .map(|i| (1.3 * i as f64).cos() - 0.2)
                .collect();
            let structure = nlp.hessian_structure();
            let mut values = vec![0.0; structure.len()];
            assert!(nlp.hessian_values(&z, sigma, &lambda, &mut values));
            let size = nlp.variables();
            let mut dense = vec![0.0; size * size];
            for (&(row, column), value) in structure.iter().zip(&values) {
                assert!(row >= column, "({row}, {column}) is above the diagonal");
                dense[row * size + column] += value;
                if row != column {
                    dense[column * size + row] += value;
                }
            }
            let gradient = |z: &[f64]| lagrangian_gradient(&nlp, z, sigma, &lambda);
            for j in 0..size {
                let by_j = central(&z, j, &gradient);
                for (row, numeric) in by_j.iter().enumerate() {
                    let exact = dense[row * size + j];
                    assert!(
                        (exact - numeric).abs() < 1e-6,
                        "{scheme:?} ({row}, {j}): {exact} vs {numeric}"
                    );
                }
            }
        }
    }
}
