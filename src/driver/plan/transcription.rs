//! A plan transcribed into an [`Nlp`] by direct collocation (Betts,
//! "Practical Methods for Optimal Control and Estimation Using Nonlinear
//! Programming", 2nd ed., SIAM 2010, sections 4.5 and 4.6).
//!
//! The state is the Lagrange-d'Alembert one, `x = (q, qdot)`, moving by
//! `f(x, u) = (qdot, qddot(q, qdot, u))`, the reduced one, `x = (q,
//! alpha)`, or the momentum equation's, `x = (q, rdot, p)` ([`super::form`]). The variables are each node's
//! state and inputs, then the plan's globals (with `--free-duration`, the
//! duration `T`): `z = (x_0, u_0, ..., x_{N-1}, u_{N-1}, T)`, at `t_i =
//! T s_i` for fractions `0 = s_0 < s_1 < ... < s_{N-1} = 1` of the
//! duration (evenly spaced, `s_i = i / (N - 1)`, unless the grid gives
//! them), interval `i` stepping `h = h_i = T (s_{i+1} - s_i)`. Each
//! interval's defect is a one-step scheme written by its stages, a weight
//! `w` at a point `a` of the way from node `i` to node `i + 1` for the
//! state, `b` for the inputs:
//!
//! ```text
//! x_{i+1} - x_i - h sum_k w_k f(X_k, U_k) = 0,
//! X_k = (1 - a_k) x_i + a_k x_{i+1} + c_k h (f_i - f_{i+1}),
//! U_k = (1 - b_k) u_i + b_k u_{i+1},        f_i = f(x_i, u_i).
//! ```
//!
//! Backward Euler is one stage `(w, a, b, c) = (1, 1, 1, 0)`: first order,
//! the inputs held from the right, `u(t) = u_{i+1}` on `(t_i, t_{i+1}]`.
//! The implicit midpoint rule is one stage `(1, 1/2, 0, 0)`: second order,
//! the inputs held from the left, `u(t) = u_i` on `[t_i, t_{i+1})`, each
//! approximating the optimal input at the interval's midpoint. (Averaging
//! the inputs instead leaves their mode `u_i + (-1)^i e` free.)
//!
//! Compressed Hermite-Simpson (Betts section 4.6.4; Drake's
//! `DirectCollocation`) is Simpson's rule, stages `(1/6, 0, 0, 0)`, `(4/6,
//! 1/2, 1/2, 1/8)` and `(1/6, 1, 1, 0)`:
//!
//! ```text
//! x_{i+1} - x_i - h/6 (f_i + 4 f_m + f_{i+1}) = 0,   f_m = f(x_m, u_m),
//! x_m = (x_i + x_{i+1})/2 + h/8 (f_i - f_{i+1}),     u_m = (u_i + u_{i+1})/2,
//! ```
//!
//! `x_m` being the cubic Hermite interpolant of the nodes' states and
//! slopes at the midpoint; fourth order, the inputs linear between nodes.
//!
//! The running cost is integrated by the same stages, `J = sum_i h_i sum_k
//! w_k L(t_i + a_k h_i, X_k, U_k)`, and the final cost `Phi(T, x_{N-1})`
//! added. A node's inputs the scheme does not read (backward Euler's
//! first, the midpoint rule's last) are reported as their neighbour's.
//!
//! The constraints' Jacobian is block-sparse: an interval's defect reads
//! its two nodes only (and `T`), the `q` rows of the one-stage schemes
//! only `q` and `qdot` entrywise. Its values are the model's exact
//! Jacobian `acceleration_jacobian` by the chain rule through the stages'
//! `X_k` (through `f_i` and `f_{i+1}` for Hermite-Simpson's midpoint), and
//! the costs' gradients the expressions' exact derivatives. By the
//! duration, every step and time scales with `T`: `dh_i/dT = h_i/T`, and a
//! stage's time `t` moves as `t/T`.

use super::form::Form;
use super::initial::{self, Held, InitialTerms};
use super::nlp::Nlp;
use crate::driver::expression::{Expression, Gradient, Point};
use chaplygin_codegen::interpret::{InterpretedModel, RowCurvatures};
use std::collections::{BTreeSet, HashMap};

/// A one-step collocation scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Scheme {
    /// `x_{i+1} = x_i + h f(x_{i+1}, u_{i+1})`: first order.
    BackwardEuler,
    /// `x_{i+1} = x_i + h f((x_i + x_{i+1})/2, u_i)`: second order.
    Midpoint,
    /// `x_{i+1} = x_i + h/6 (f_i + 4 f_m + f_{i+1})`, `x_m` the Hermite
    /// interpolant at the midpoint: fourth order.
    HermiteSimpson,
}

/// One stage of a scheme: its weight, where between the nodes it takes
/// the state and the inputs, and the weight `c` of the nodes' slopes in
/// its state, `c h (f_i - f_{i+1})`.
pub(super) struct Stage {
    pub(super) weight: f64,
    pub(super) at: f64,
    pub(super) inputs_at: f64,
    pub(super) slopes: f64,
}

impl Stage {
    /// A stage whose state lies on the segment between the nodes'.
    const fn linear(weight: f64, at: f64, inputs_at: f64) -> Self {
        Self {
            weight,
            at,
            inputs_at,
            slopes: 0.0,
        }
    }
}

/// The share of node `j` (0: the interval's first, 1: its last) in a
/// point `at` of the way between them.
pub(super) fn share(j: usize, at: f64) -> f64 {
    if j == 0 { 1.0 - at } else { at }
}

impl Scheme {
    /// Every scheme, for a lookup by [`Scheme::name`].
    pub const ALL: &'static [Self] = &[Self::BackwardEuler, Self::Midpoint, Self::HermiteSimpson];

    /// Its name on the command line and in `plan.json`.
    pub fn name(self) -> &'static str {
        match self {
            Self::BackwardEuler => "backward-euler",
            Self::Midpoint => "midpoint",
            Self::HermiteSimpson => "hermite-simpson",
        }
    }

    pub(super) fn stages(self) -> &'static [Stage] {
        const BACKWARD_EULER: [Stage; 1] = [Stage::linear(1.0, 1.0, 1.0)];
        const MIDPOINT: [Stage; 1] = [Stage::linear(1.0, 0.5, 0.0)];
        const HERMITE_SIMPSON: [Stage; 3] = [
            Stage::linear(1.0 / 6.0, 0.0, 0.0),
            Stage {
                weight: 4.0 / 6.0,
                at: 0.5,
                inputs_at: 0.5,
                slopes: 1.0 / 8.0,
            },
            Stage::linear(1.0 / 6.0, 1.0, 1.0),
        ];
        match self {
            Self::BackwardEuler => &BACKWARD_EULER,
            Self::Midpoint => &MIDPOINT,
            Self::HermiteSimpson => &HERMITE_SIMPSON,
        }
    }
}

/// A variable of the whole plan, after the nodes' variables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Global {
    /// The duration `T`.
    Duration,
}

/// The grid: the number of nodes, the duration (its first guess where it
/// is free), whether it is free, and the nodes' times as fractions of the
/// duration, increasing from 0 to 1 (`None`: evenly spaced).
#[derive(Clone, Debug)]
pub(crate) struct Grid {
    pub nodes: usize,
    pub duration: f64,
    pub free_duration: bool,
    pub fractions: Option<Vec<f64>>,
}

/// The objective's terms: the running cost `L(t, q, qdot, u)` and the
/// final cost `Phi(T, q(T), qdot(T))`.
pub(crate) struct Costs {
    pub running: Expression,
    pub terminal: Option<Expression>,
}

/// The problem's data: the model, the grid, the costs and the bounds.
pub struct Transcription {
    model: InterpretedModel,
    /// The formulation whose state the nodes hold.
    form: Form,
    pub(super) scheme: Scheme,
    pub(super) nodes: usize,
    /// `T`, or its first guess where it is a variable.
    duration: f64,
    /// Each node's time as a fraction of `T`, `s_i`.
    fractions: Vec<f64>,
    /// The variables after the nodes', in order.
    globals: Vec<Global>,
    pub(super) costs: Costs,
    lo: Vec<f64>,
    hi: Vec<f64>,
    guess: Vec<f64>,
    /// The model's constraints held at the first node by rows after the
    /// defects ([`super::initial`]): those the start leaves free to break.
    start: Vec<Held>,
    /// One interval's structure: (row of its defect, column among its two
    /// nodes' variables).
    local: Vec<(usize, usize)>,
    structure: Vec<(usize, usize)>,
}

/// A stage's time, state, inputs and velocities `qdot`.
pub(super) struct StagePoint {
    pub(super) t: f64,
    pub(super) x: Vec<f64>,
    pub(super) u: Vec<f64>,
    pub(super) qdot: Vec<f64>,
}

impl StagePoint {
    /// The bits of the point's `(x, u)`: what the model's derivatives at
    /// the point depend on, as a key of the points met.
    pub(super) fn bits(&self) -> Vec<u64> {
        (self.x.iter().chain(&self.u))
            .map(|value| value.to_bits())
            .collect()
    }
}

/// The model's second derivatives ([`Form::rhs_curvatures`]) at the points
/// met in one evaluation of a Lagrangian's Hessian, by the bits of the
/// point's `(x, u)`: each point's are computed once and weighted as often
/// as it is met. A node is a stage of the intervals on both sides of it,
/// and Hermite-Simpson's slopes weigh both nodes of an interval again, so
/// that its five weightings an interval fall on three points.
#[derive(Default)]
pub(super) struct PointCurvatures {
    at: HashMap<Vec<u64>, RowCurvatures>,
}

#[cfg(test)]
impl PointCurvatures {
    /// The number of points whose curvatures were computed.
    pub(super) fn points(&self) -> usize {
        self.at.len()
    }
}

/// How a stage's state moves with the interval's variables: `dX/dz_j`
/// for its first and last node (2n x (2n + p) each, row-major) and
/// `dX/dT`.
pub(super) struct Motion {
    pub(super) by_node: [Vec<f64>; 2],
    pub(super) by_duration: Vec<f64>,
}

impl Transcription {
    /// The plan of `model` by `scheme` on `grid`, minimizing `costs`, its
    /// variables bounded by `lo` and `hi` and started at `guess` (each
    /// `nodes` times a node's variables, `(q, qdot, u)`, then the globals:
    /// `T` where it is free).
    pub(crate) fn new(
        model: InterpretedModel,
        scheme: Scheme,
        grid: Grid,
        costs: Costs,
        (lo, hi, guess): (Vec<f64>, Vec<f64>, Vec<f64>),
    ) -> Self {
        let globals = if grid.free_duration {
            vec![Global::Duration]
        } else {
            Vec::new()
        };
        let last = (grid.nodes - 1) as f64;
        let fractions = grid
            .fractions
            .unwrap_or_else(|| (0..grid.nodes).map(|i| i as f64 / last).collect());
        let mut transcription = Self {
            model,
            form: Form::Lagrange,
            scheme,
            nodes: grid.nodes,
            duration: grid.duration,
            fractions,
            globals,
            costs,
            lo,
            hi,
            guess,
            start: Vec::new(),
            local: Vec::new(),
            structure: Vec::new(),
        };
        transcription.local = transcription.local_structure();
        transcription.structure = transcription.global_structure();
        transcription
    }

    /// The same plan with its nodes' states in `form` (its bounds and
    /// guess already in that form's variables).
    pub(crate) fn in_form(mut self, form: Form) -> Self {
        self.form = form;
        self.local = self.local_structure();
        self.structure = self.global_structure();
        self
    }

    /// The same plan with the constraints `held` held at its first node.
    pub(super) fn holding_start(mut self, held: Vec<Held>) -> Self {
        self.start = held;
        self.structure = self.global_structure();
        self
    }

    /// The formulation whose state the nodes hold.
    pub fn form(&self) -> Form {
        self.form
    }

    /// The intervals' structure, then the duration's column, then the
    /// start's rows, each dense over the first node's state entries its
    /// program reads.
    fn global_structure(&self) -> Vec<(usize, usize)> {
        let (s, w) = (self.state(), self.width());
        let intervals = (0..self.nodes - 1)
            .flat_map(|i| self.local.iter().map(move |&(k, c)| (i * s + k, i * w + c)));
        let duration = self.global(Global::Duration);
        let by_duration = duration
            .into_iter()
            .flat_map(|column| (0..self.defects()).map(move |row| (row, column)));
        let start = self.start_reads().enumerate().flat_map(|(r, read)| {
            let row = self.defects() + r;
            (0..read).map(move |c| (row, c))
        });
        intervals.chain(by_duration).chain(start).collect()
    }

    /// The same program, the inputs of its guess moved by `amplitude
    /// sin(pi s_i)` at each node `i` (`s_i` its time as a fraction of `T`),
    /// inside the bounds.
    pub(super) fn nudging_inputs(mut self, amplitude: f64) -> Self {
        let (state, width) = (self.state(), self.width());
        for (node, &s) in self.fractions.iter().enumerate() {
            for j in node * width + state..(node + 1) * width {
                let nudged = self.guess[j] + amplitude * (std::f64::consts::PI * s).sin();
                self.guess[j] = nudged.clamp(self.lo[j], self.hi[j]);
            }
        }
        self
    }

    /// The number of defect rows, `(N - 1) s`; the start's rows follow.
    pub(super) fn defects(&self) -> usize {
        (self.nodes - 1) * self.state()
    }

    /// For each of the start's rows, how many of the first state's entries
    /// it reads.
    fn start_reads(&self) -> impl Iterator<Item = usize> + '_ {
        self.start.iter().flat_map(|held| {
            let read = held.reads(&self.model);
            std::iter::repeat_n(read, held.rows(&self.model))
        })
    }

    /// Defect row `row` (below [`Transcription::defects`]) in words: the
    /// state entry and the interval at `z`.
    pub(super) fn describe_defect(&self, z: &[f64], row: usize) -> String {
        let (s, i) = (self.state(), row / self.state());
        let name = &self.form.state_names(&self.model)[row % s];
        let [from, to] = [i, i + 1].map(|j| self.node_time(z, j));
        format!("the defect of `{name}` from t = {from:.4} to {to:.4}")
    }

    /// The start's rows and their derivatives by the first state.
    pub(super) fn start_terms(&self, z: &[f64]) -> InitialTerms {
        let s = self.state();
        initial::initial_terms(&self.model, &self.start, (&z[..s], s), &[])
    }

    /// The model.
    pub fn model(&self) -> &InterpretedModel {
        &self.model
    }

    /// The model, to set its parameters.
    pub(super) fn model_mut(&mut self) -> &mut InterpretedModel {
        &mut self.model
    }

    /// The number of nodes `N`.
    pub fn nodes(&self) -> usize {
        self.nodes
    }

    /// Where `global` is among the variables, if it is one.
    pub fn global(&self, global: Global) -> Option<usize> {
        let first = self.nodes * self.width();
        self.globals
            .iter()
            .position(|g| *g == global)
            .map(|k| first + k)
    }

    /// The duration `T` at `z`.
    pub fn duration(&self, z: &[f64]) -> f64 {
        self.global(Global::Duration)
            .map_or(self.duration, |j| z[j])
    }

    /// Interval `i`'s time step at `z`, `h_i = T (s_{i+1} - s_i)`.
    pub fn step(&self, z: &[f64], i: usize) -> f64 {
        self.duration(z) * (self.fractions[i + 1] - self.fractions[i])
    }

    /// Node `i`'s time at `z`, `t_i = T s_i`.
    pub fn node_time(&self, z: &[f64], i: usize) -> f64 {
        self.duration(z) * self.fractions[i]
    }

    /// The inputs at node `i` of `z` as the scheme applies them: with
    /// backward Euler, node 0's are node 1's (held from the right); with
    /// the midpoint rule, the last node's are the one before's (held from
    /// the left); with Hermite-Simpson, each node's own.
    pub fn held_inputs(&self, z: &[f64], i: usize) -> Vec<f64> {
        let (s, w) = (self.state(), self.width());
        let node = match self.scheme {
            Scheme::BackwardEuler => i.max(1),
            Scheme::Midpoint => i.min(self.nodes - 2),
            Scheme::HermiteSimpson => i,
        };
        z[node * w + s..(node + 1) * w].to_vec()
    }

    /// The state's size, `2n` (`n + k` in the reduced form, `n + R + K` in
    /// the momentum form).
    pub(super) fn state(&self) -> usize {
        self.form.state(&self.model)
    }

    /// A node's variables, `2n + p` (`n + k + p`).
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
    /// state entry and input, of each node a stage reads. A stage that
    /// reads the nodes' slopes, or a form other than Lagrange's, makes every row read
    /// every variable.
    fn local_structure(&self) -> Vec<(usize, usize)> {
        let (n, s, w) = (self.model.sizes().n, self.state(), self.width());
        let slopes = self.scheme.stages().iter().any(|stage| stage.slopes != 0.0);
        if slopes || self.form != Form::Lagrange {
            return (0..s)
                .flat_map(|k| (0..2 * w).map(move |c| (k, c)))
                .collect();
        }
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

    /// Node `i` of `z` as a point.
    pub(super) fn node_point(&self, z: &[f64], i: usize) -> StagePoint {
        let (s, w) = (self.state(), self.width());
        let x = z[i * w..i * w + s].to_vec();
        self.point(self.node_time(z, i), x, z[i * w + s..(i + 1) * w].to_vec())
    }

    /// The point of time `t`, state `x` and inputs `u`, its velocities
    /// read from `x`.
    fn point(&self, t: f64, x: Vec<f64>, u: Vec<f64>) -> StagePoint {
        let qdot = self.form.velocities(&self.model, &x);
        StagePoint { t, x, u, qdot }
    }

    /// The stage `stage` of interval `i` at `z`.
    pub(super) fn stage_point(&self, z: &[f64], i: usize, stage: &Stage) -> StagePoint {
        let (s, w, h) = (self.state(), self.width(), self.step(z, i));
        let (first, last) = (&z[i * w..(i + 1) * w], &z[(i + 1) * w..(i + 2) * w]);
        let mix = |range: std::ops::Range<usize>, at: f64| -> Vec<f64> {
            first[range.clone()]
                .iter()
                .zip(&last[range])
                .map(|(a, b)| (1.0 - at) * a + at * b)
                .collect()
        };
        let mut x = mix(0..s, stage.at);
        if stage.slopes != 0.0 {
            let [f_first, f_last] = [i, i + 1].map(|j| self.rhs(&self.node_point(z, j)));
            for (k, x) in x.iter_mut().enumerate() {
                *x += stage.slopes * h * (f_first[k] - f_last[k]);
            }
        }
        self.point(
            self.node_time(z, i) + stage.at * h,
            x,
            mix(s..w, stage.inputs_at),
        )
    }

    /// How the stage `stage` of interval `i` moves with the interval's
    /// variables and `T`: `dX/dz_j = share_j I + (+-) c h df_j/dz_j`,
    /// `dX/dT = c (h/T) (f_i - f_{i+1})`.
    pub(super) fn stage_motion(&self, z: &[f64], i: usize, stage: &Stage) -> Motion {
        let (s, w, h) = (self.state(), self.width(), self.step(z, i));
        let p = w - s;
        let mut by_node = [0, 1].map(|j| {
            let mut block = vec![0.0; s * w];
            for k in 0..s {
                block[k * w + k] = share(j, stage.at);
            }
            block
        });
        let mut by_duration = vec![0.0; s];
        if stage.slopes != 0.0 {
            let c = stage.slopes * h;
            for (j, sign) in [(0, 1.0), (1, -1.0)] {
                let node = self.node_point(z, i + j);
                let ((fx, fu), f) = (self.rhs_jacobian(&node), self.rhs(&node));
                for k in 0..s {
                    let row = &mut by_node[j][k * w..(k + 1) * w];
                    for (r, d) in row[..s].iter_mut().zip(&fx[k * s..(k + 1) * s]) {
                        *r += sign * c * d;
                    }
                    for (r, d) in row[s..].iter_mut().zip(&fu[k * p..(k + 1) * p]) {
                        *r += sign * c * d;
                    }
                    by_duration[k] += sign * c / self.duration(z) * f[k];
                }
            }
        }
        Motion {
            by_node,
            by_duration,
        }
    }

    /// `f(x, u)` of the plan's form.
    fn rhs(&self, point: &StagePoint) -> Vec<f64> {
        self.form.rhs(&self.model, &point.x, &point.u)
    }

    /// The Hessian of `weights^T f` by `(x, u)` (w x w, row-major) at
    /// `point` ([`Form::rhs_hessian`]), from the point's curvatures in
    /// `curvatures`, computed there when it has none yet.
    pub(super) fn rhs_hessian(
        &self,
        curvatures: &mut PointCurvatures,
        point: &StagePoint,
        weights: &[f64],
    ) -> Vec<f64> {
        let at = (curvatures.at.entry(point.bits()))
            .or_insert_with(|| self.form.rhs_curvatures(&self.model, (&point.x, &point.u)));
        self.form.rhs_hessian(&self.model, at, weights)
    }

    /// `df/dx` (s x s) and `df/du` (s x p), row-major, at `point`.
    pub(super) fn rhs_jacobian(&self, point: &StagePoint) -> (Vec<f64>, Vec<f64>) {
        self.form.rhs_jacobian(&self.model, &point.x, &point.u)
    }

    /// Where a cost is evaluated at a stage.
    pub(super) fn cost_point<'a>(&self, point: &'a StagePoint) -> Point<'a> {
        Point {
            t: point.t,
            q: &point.x[..self.model.sizes().n],
            qdot: &point.qdot,
            u: &point.u,
            ..Point::default()
        }
    }

    /// The running cost's gradient by the state and `u` at a stage, and
    /// by `(t, q, qdot, u)`.
    pub(super) fn cost_gradient(&self, point: &StagePoint) -> (Vec<f64>, Gradient) {
        let (_, gradient) = self.costs.running.gradient(&self.cost_point(point));
        let mut by_variables = self.state_gradient(point, (&gradient.q, &gradient.qdot));
        by_variables.extend(&gradient.u);
        (by_variables, gradient)
    }

    /// A function's gradient by the state at `point` from its gradients
    /// by `q` and `qdot`.
    fn state_gradient(&self, point: &StagePoint, (by_q, by_qdot): (&[f64], &[f64])) -> Vec<f64> {
        self.form
            .state_gradient(&self.model, (&point.x, &point.u), (by_q, by_qdot))
    }

    /// Where the final cost is evaluated, as a stage: `t = T`, the last
    /// node's state.
    pub(super) fn final_stage(&self, z: &[f64]) -> StagePoint {
        let mut last = self.node_point(z, self.nodes - 1);
        last.t = self.duration(z);
        last
    }

    /// Adds `scale (G_x dX/dz_j + G_u dU/dz_j)` to node `j`'s columns of
    /// `block` (rows x 2(2n + p), row-major) for both nodes, and returns
    /// `scale G_x dX/dT` (rows), for `G_x` (rows x 2n) and `G_u` (rows x
    /// p) a function's derivatives by a stage's state and inputs.
    fn chain(
        &self,
        (stage, motion): (&Stage, &Motion),
        (gx, gu): (&[f64], &[f64]),
        scale: f64,
        block: &mut [f64],
    ) -> Vec<f64> {
        let (s, w) = (self.state(), self.width());
        let p = w - s;
        let rows = gx.len() / s;
        let mut by_duration = vec![0.0; rows];
        for r in 0..rows {
            let gx_row = &gx[r * s..(r + 1) * s];
            for j in 0..2 {
                let out = &mut block[r * 2 * w + j * w..r * 2 * w + (j + 1) * w];
                for (k, g) in gx_row.iter().enumerate() {
                    let moved = &motion.by_node[j][k * w..(k + 1) * w];
                    for (o, m) in out.iter_mut().zip(moved) {
                        *o += scale * g * m;
                    }
                }
                let inputs = scale * share(j, stage.inputs_at);
                for (o, g) in out[s..].iter_mut().zip(&gu[r * p..(r + 1) * p]) {
                    *o += inputs * g;
                }
            }
            let moved: f64 = gx_row
                .iter()
                .zip(&motion.by_duration)
                .map(|(g, m)| g * m)
                .sum();
            by_duration[r] = scale * moved;
        }
        by_duration
    }

    /// Interval `i`'s defect.
    fn defect(&self, z: &[f64], i: usize) -> Vec<f64> {
        let (s, w, h) = (self.state(), self.width(), self.step(z, i));
        let mut defect: Vec<f64> = (0..s).map(|k| z[(i + 1) * w + k] - z[i * w + k]).collect();
        for stage in self.scheme.stages() {
            let f = self.rhs(&self.stage_point(z, i, stage));
            for (d, fk) in defect.iter_mut().zip(&f) {
                *d -= h * stage.weight * fk;
            }
        }
        defect
    }

    /// One interval's defect Jacobian, dense over its two nodes' variables
    /// (2n x 2(2n + p), row-major), and its derivative by `T` (2n).
    fn interval_jacobian(&self, z: &[f64], i: usize) -> (Vec<f64>, Vec<f64>) {
        let (s, w, h) = (self.state(), self.width(), self.step(z, i));
        let columns = 2 * w;
        let mut block = vec![0.0; s * columns];
        for k in 0..s {
            block[k * columns + k] = -1.0;
            block[k * columns + w + k] = 1.0;
        }
        let mut by_duration = vec![0.0; s];
        for stage in self.scheme.stages() {
            let point = self.stage_point(z, i, stage);
            let ((fx, fu), f) = (self.rhs_jacobian(&point), self.rhs(&point));
            let motion = self.stage_motion(z, i, stage);
            let scale = -h * stage.weight;
            let through = self.chain((stage, &motion), (&fx, &fu), scale, &mut block);
            for (k, d) in by_duration.iter_mut().enumerate() {
                *d += through[k] + scale / self.duration(z) * f[k];
            }
        }
        (block, by_duration)
    }

    /// Interval `i`'s running cost.
    fn interval_cost(&self, z: &[f64], i: usize) -> f64 {
        let h = self.step(z, i);
        self.scheme
            .stages()
            .iter()
            .map(|stage| {
                let point = self.stage_point(z, i, stage);
                h * stage.weight * self.costs.running.at(&self.cost_point(&point))
            })
            .sum()
    }

    /// Interval `i`'s running cost's gradient by its two nodes' variables
    /// (2(2n + p)), and its derivative by `T`.
    fn interval_cost_gradient(&self, z: &[f64], i: usize) -> (Vec<f64>, f64) {
        let (s, w, h) = (self.state(), self.width(), self.step(z, i));
        let duration = self.duration(z);
        let mut block = vec![0.0; 2 * w];
        let mut by_duration = 0.0;
        for stage in self.scheme.stages() {
            let point = self.stage_point(z, i, stage);
            let value = self.costs.running.at(&self.cost_point(&point));
            let (gradient, by) = self.cost_gradient(&point);
            let motion = self.stage_motion(z, i, stage);
            let scale = h * stage.weight;
            let (gx, gu) = gradient.split_at(s);
            let through = self.chain((stage, &motion), (gx, gu), scale, &mut block);
            by_duration += through[0] + scale * (value + by.t * point.t) / duration;
        }
        (block, by_duration)
    }
}

/// Whether every value is finite.
pub(super) fn finite(values: &[f64]) -> bool {
    values.iter().all(|v| v.is_finite())
}

impl Nlp for Transcription {
    fn variables(&self) -> usize {
        self.nodes * self.width() + self.globals.len()
    }

    fn constraints(&self) -> usize {
        self.defects() + initial::rows(&self.model, &self.start)
    }

    fn bounds(&self) -> (&[f64], &[f64]) {
        (&self.lo, &self.hi)
    }

    fn guess(&self) -> Vec<f64> {
        self.guess.clone()
    }

    fn objective(&self, z: &[f64]) -> Option<f64> {
        let running: f64 = (0..self.nodes - 1).map(|i| self.interval_cost(z, i)).sum();
        let terminal = self
            .costs
            .terminal
            .as_ref()
            .map_or(0.0, |phi| phi.at(&self.cost_point(&self.final_stage(z))));
        let total = running + terminal;
        total.is_finite().then_some(total)
    }

    fn gradient(&self, z: &[f64], gradient: &mut [f64]) -> bool {
        let (s, w) = (self.state(), self.width());
        let duration = self.global(Global::Duration);
        gradient.fill(0.0);
        for i in 0..self.nodes - 1 {
            let (block, by_duration) = self.interval_cost_gradient(z, i);
            for (g, d) in gradient[i * w..(i + 2) * w].iter_mut().zip(&block) {
                *g += d;
            }
            if let Some(j) = duration {
                gradient[j] += by_duration;
            }
        }
        if let Some(phi) = &self.costs.terminal {
            let stage = self.final_stage(z);
            let (_, by) = phi.gradient(&self.cost_point(&stage));
            let last = (self.nodes - 1) * w;
            let by_state = self.state_gradient(&stage, (&by.q, &by.qdot));
            for (g, d) in gradient[last..last + s].iter_mut().zip(&by_state) {
                *g += d;
            }
            if let Some(j) = duration {
                gradient[j] += by.t;
            }
        }
        finite(gradient)
    }

    fn residuals(&self, z: &[f64], residuals: &mut [f64]) -> bool {
        let s = self.state();
        for i in 0..self.nodes - 1 {
            residuals[i * s..(i + 1) * s].copy_from_slice(&self.defect(z, i));
        }
        let start = self.start_terms(z).values;
        residuals[self.defects()..].copy_from_slice(&start);
        finite(residuals)
    }

    fn jacobian_structure(&self) -> &[(usize, usize)] {
        &self.structure
    }

    fn describe_row(&self, z: &[f64], row: usize) -> String {
        match row.checked_sub(self.defects()) {
            None => self.describe_defect(z, row),
            Some(r) => {
                let name = initial::row_name(&self.model, &self.start, r);
                format!("the start's {name}")
            }
        }
    }

    fn jacobian_values(&self, z: &[f64], values: &mut [f64]) -> bool {
        let columns = 2 * self.width();
        let per_interval = self.local.len();
        let intervals = (self.nodes - 1) * per_interval;
        let mut by_duration = Vec::with_capacity(self.defects());
        for i in 0..self.nodes - 1 {
            let (block, by_t) = self.interval_jacobian(z, i);
            let out = &mut values[i * per_interval..(i + 1) * per_interval];
            for (value, &(k, c)) in out.iter_mut().zip(&self.local) {
                *value = block[k * columns + c];
            }
            by_duration.extend(by_t);
        }
        let mut at = intervals;
        if self.global(Global::Duration).is_some() {
            values[at..at + by_duration.len()].copy_from_slice(&by_duration);
            at += by_duration.len();
        }
        let start = self.start_terms(z).jacobian;
        for (r, read) in self.start_reads().enumerate() {
            for c in 0..read {
                values[at] = start[(r, c)];
                at += 1;
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
pub(super) mod tests {
    use super::{Costs, Grid, Nlp, Scheme, Transcription};
    use crate::driver::expression::{Expression, Scope};
    use crate::driver::plan::kkt::lagrangian_gradient;
    use chaplygin_codegen::interpret::InterpretedModel;

    /// The differential drive on 3 unevenly spaced nodes (at 0, 0.3 and 1
    /// of the duration) at a point with every variable nonzero, its
    /// running cost reading the time, coordinates, velocities and inputs,
    /// its final cost the time and the state; with `free_duration`, `T =
    /// 0.8` a variable.
    pub(in crate::driver::plan) fn transcription(
        scheme: Scheme,
        free_duration: bool,
    ) -> (Transcription, Vec<f64>) {
        let model =
            InterpretedModel::from_source(include_str!("../catalog/differential_drive.model"))
                .expect("the model derives");
        let names = (
            &["x", "y", "theta", "phi_r", "phi_l"][..],
            &["u_right", "u_left"][..],
        );
        let costs = (
            "u_right^2 + x*dot(theta)^2 + sin(theta)*u_left + t*dot(x)",
            "x^2*dot(y) + t^2*theta",
        );
        let fractions = Some(vec![0.0, 0.3, 1.0]);
        three_nodes(
            model,
            names,
            costs,
            (12, fractions),
            (scheme, free_duration),
        )
    }

    /// `model`'s plan on 3 nodes at `fractions` of the duration (evenly
    /// spaced for `None`), each node `width` variables, at a point with
    /// every variable nonzero: the running and final `costs` read the
    /// coordinates and inputs `names`; with `free_duration`, `T = 0.8` a
    /// variable.
    pub(in crate::driver::plan) fn three_nodes(
        model: InterpretedModel,
        (coordinates, inputs): (&[&str], &[&str]),
        (running, terminal): (&str, &str),
        (width, fractions): (usize, Option<Vec<f64>>),
        (scheme, free_duration): (Scheme, bool),
    ) -> (Transcription, Vec<f64>) {
        let scope = Scope {
            coordinates,
            inputs,
            ..Scope::default()
        };
        let running = Expression::parse(running, &scope).expect("parses");
        let final_scope = Scope {
            coordinates,
            ..Scope::default()
        };
        let terminal = Expression::parse(terminal, &final_scope).expect("parses");
        let size = 3 * width + usize::from(free_duration);
        let mut z: Vec<f64> = (0..size)
            .map(|j| 0.3 * ((j as f64) * 0.77).sin() + 0.1)
            .collect();
        if free_duration {
            z[size - 1] = 0.8;
        }
        let free = vec![f64::NEG_INFINITY; size];
        let bounds = (free.clone(), free.iter().map(|v| -v).collect(), z.clone());
        let grid = Grid {
            nodes: 3,
            duration: 0.8,
            free_duration,
            fractions,
        };
        let costs = Costs {
            running,
            terminal: Some(terminal),
        };
        let transcription = Transcription::new(model, scheme, grid, costs, bounds);
        (transcription, z)
    }

    /// Central differences of `f` at `z` by variable `j`.
    pub(in crate::driver::plan) fn central(
        z: &[f64],
        j: usize,
        f: &dyn Fn(&[f64]) -> Vec<f64>,
    ) -> Vec<f64> {
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

    /// The constraints' Jacobian of `nlp` at `z`, dense and row-major.
    pub(in crate::driver::plan) fn dense_jacobian(nlp: &dyn Nlp, z: &[f64]) -> Vec<f64> {
        let mut dense = vec![0.0; nlp.constraints() * nlp.variables()];
        let mut values = vec![0.0; nlp.jacobian_structure().len()];
        assert!(nlp.jacobian_values(z, &mut values));
        for (&(row, column), value) in nlp.jacobian_structure().iter().zip(&values) {
            dense[row * nlp.variables() + column] = *value;
        }
        dense
    }

    /// Asserts that the exact Jacobian and gradient of `nlp` at `z` agree
    /// with central differences to 1e-6; `label` names the case.
    pub(in crate::driver::plan) fn assert_derivatives_agree(
        nlp: &Transcription,
        z: &[f64],
        label: &str,
    ) {
        let dense = dense_jacobian(nlp, z);
        let mut gradient = vec![0.0; nlp.variables()];
        assert!(nlp.gradient(z, &mut gradient));
        let residuals = |z: &[f64]| {
            let mut c = vec![0.0; nlp.constraints()];
            assert!(nlp.residuals(z, &mut c));
            c
        };
        let objective = |z: &[f64]| vec![nlp.objective(z).expect("finite")];
        for j in 0..nlp.variables() {
            let by_j = central(z, j, &residuals);
            for (row, numeric) in by_j.iter().enumerate() {
                let exact = dense[row * nlp.variables() + j];
                assert!(
                    (exact - numeric).abs() < 1e-6,
                    "{label} ({row}, {j}): {exact} vs {numeric}"
                );
            }
            let numeric = central(z, j, &objective)[0];
            assert!(
                (gradient[j] - numeric).abs() < 1e-6,
                "{label} {j}: {} vs {numeric}",
                gradient[j]
            );
        }
    }

    #[test]
    fn the_exact_derivatives_agree_with_central_differences() {
        for (scheme, free_duration) in Scheme::ALL.iter().flat_map(|&s| [(s, false), (s, true)]) {
            let (nlp, z) = transcription(scheme, free_duration);
            assert_derivatives_agree(&nlp, &z, &format!("{scheme:?} free {free_duration}"));
        }
    }

    /// The Hessian of the Lagrangian of `nlp` at `z` (objective factor
    /// `sigma`, multipliers `lambda`), dense and row-major, from its lower
    /// triangle (asserted to hold every entry).
    pub(in crate::driver::plan) fn dense_hessian(
        nlp: &dyn Nlp,
        z: &[f64],
        sigma: f64,
        lambda: &[f64],
    ) -> Vec<f64> {
        let structure = nlp.hessian_structure();
        let mut values = vec![0.0; structure.len()];
        assert!(nlp.hessian_values(z, sigma, lambda, &mut values));
        let size = nlp.variables();
        let mut dense = vec![0.0; size * size];
        for (&(row, column), value) in structure.iter().zip(&values) {
            assert!(row >= column, "({row}, {column}) is above the diagonal");
            dense[row * size + column] += value;
            if row != column {
                dense[column * size + row] += value;
            }
        }
        dense
    }

    /// Asserts that the exact Hessian of the Lagrangian of `nlp` at `z`
    /// (objective factor 0.7, multipliers every one different) agrees
    /// with central differences of its exact gradient to 1e-6; `label`
    /// names the case.
    pub(in crate::driver::plan) fn assert_hessian_agrees(
        nlp: &Transcription,
        z: &[f64],
        label: &str,
    ) {
        let sigma = 0.7;
        let lambda: Vec<f64> = (0..nlp.constraints())
            .map(|i| (1.3 * i as f64).cos() - 0.2)
            .collect();
        let size = nlp.variables();
        let dense = dense_hessian(nlp, z, sigma, &lambda);
        let gradient = |z: &[f64]| lagrangian_gradient(nlp, z, sigma, &lambda).expect("finite");
        for j in 0..size {
            let by_j = central(z, j, &gradient);
            for (row, numeric) in by_j.iter().enumerate() {
                let exact = dense[row * size + j];
                assert!(
                    (exact - numeric).abs() < 1e-6,
                    "{label} ({row}, {j}): {exact} vs {numeric}"
                );
            }
        }
    }

    /// A plan's coordinates and inputs, and its running and final costs.
    pub(in crate::driver::plan) type Named<'a> =
        ((&'a [&'a str], &'a [&'a str]), (&'a str, &'a str));

    /// Asserts that the exact Jacobian, gradient and Hessian of the
    /// Lagrangian agree with central differences on `model`'s plan on 3
    /// nodes ([`three_nodes`], then `made` of it, whose nodes hold
    /// `state` entries), for every scheme with a fixed and a free
    /// duration; `label` names the case.
    pub(in crate::driver::plan) fn assert_every_scheme_agrees(
        model: &InterpretedModel,
        (names, costs): Named<'_>,
        (state, made): (usize, &dyn Fn(Transcription) -> Transcription),
        label: &str,
    ) {
        let width = state + model.sizes().p;
        for (scheme, free_duration) in Scheme::ALL.iter().flat_map(|&s| [(s, false), (s, true)]) {
            let (nlp, z) = three_nodes(
                model.clone(),
                names,
                costs,
                (width, None),
                (scheme, free_duration),
            );
            let nlp = made(nlp);
            let label = format!("{label} {scheme:?} free {free_duration}");
            assert_derivatives_agree(&nlp, &z, &label);
            assert_hessian_agrees(&nlp, &z, &label);
        }
    }

    #[test]
    fn the_lagrangians_hessian_agrees_with_central_differences_of_its_gradient() {
        for (scheme, free_duration) in Scheme::ALL.iter().flat_map(|&s| [(s, false), (s, true)]) {
            let (nlp, z) = transcription(scheme, free_duration);
            assert_hessian_agrees(&nlp, &z, &format!("{scheme:?} free {free_duration}"));
        }
    }
}
