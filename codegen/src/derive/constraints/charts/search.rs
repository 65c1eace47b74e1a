//! Points of a chart's singular set, found on random lines through the
//! configuration space rather than at sample points.
//!
//! A chart with the dependent speeds `r` degenerates where its minor
//! `det A_r(q)` vanishes. Along a line `q(s) = o + s d` (origin `o` uniform
//! in `[-pi, pi]^m`, direction `d` uniform on the sphere, `s` across the
//! box) the signed pivot ratio `det A_r / prod_i |A_i|` is sampled at
//! [`SAMPLES`] points: between two samples of opposite sign it is bisected
//! to a zero, and at a local minimum of its magnitude below
//! [`NEAR_ZERO`] without a change of sign (a zero of even order) it is
//! minimized by golden-section search and kept when it reaches
//! [`ZERO`]. A hypersurface that meets the box is crossed by almost every
//! line through it, so the search reaches a singular set wherever it lies,
//! with a probability that grows with the number of lines ([`LINES`]).
//!
//! The rows are those the basis was eliminated on (the body rows of a
//! basis chosen in the body frame, which depend on the shape alone: only
//! the shape coordinates vary, the group's stay at the identity). With
//! configuration constraints `f(q) = 0`, one coordinate per constraint
//! (the one `f` depends on most at the defaults, by partial pivoting on
//! `df/dq`) is solved from them by Newton's method at each point of a
//! line through the others, starting from its default 0: the search runs
//! on the configurations the mechanism takes as assembled at its defaults
//! (the benchmark bicycle's pitch on its branch near 0, not a frame
//! pitched over); where `df/dq` vanishes at the defaults (a pendulum
//! declared by its Cartesian coordinates), every point is moved onto the
//! constraints by least-norm Newton steps instead. Points where Newton's
//! method has not converged after [`NEWTON_STEPS`] steps, or where an
//! expression is undefined (a square root of a negative number), are
//! skipped. The parameters are at their defaults.
//!
//! The rows are one program, run by the engine the caller's [`Backend`]
//! makes of it: the interpreter, or native code where the model is loaded
//! on the JIT.

use crate::ir::{self, Backend, Engine, IrError, Program};
use crate::model::Model;
use crate::sym::zero::SplitMix;
use crate::sym::{Context, ExprId, Matrix, SymbolId};
use chaplygin_runtime::monitor::{partial_pivots, signed_pivot_ratio};
use chaplygin_runtime::nalgebra::{DMatrix, DVector};
use std::cell::RefCell;
use std::f64::consts::PI;

/// Random lines searched per chart.
pub const LINES: usize = 24;
/// Samples along each line.
pub const SAMPLES: usize = 160;
/// A local minimum of `|ratio|` below this is searched for a zero of even
/// order.
pub const NEAR_ZERO: f64 = 1e-2;
/// A pivot ratio below this counts as zero: the point lies on the set.
pub const ZERO: f64 = 1e-8;

/// The Newton steps onto the configuration constraints after which a
/// point is given up: from the defaults, Newton's method converges
/// quadratically or not at all (on the benchmark bicycle's 10,433 points it
/// took at most 8 steps or never converged: a pitch with no root near the
/// default branch), so more steps are spent on points it never reaches.
pub const NEWTON_STEPS: usize = 16;

/// The seed of the lines: the search is deterministic.
const SEED: u64 = 0x5eed_c4a7_5eed_c4a7;

/// The rows a basis was eliminated on, compiled for evaluation at many
/// points, with the configuration constraints to project onto.
pub struct FrameRows {
    program: Program,
    engine: Box<dyn Engine>,
    n: usize,
    c: usize,
    h: usize,
    /// The coordinates the lines move (the others stay at 0).
    varying: Vec<usize>,
    /// The coordinates solved from the configuration constraints.
    solved: Vec<usize>,
    parameters: Vec<f64>,
    /// The program's inputs and outputs, kept from one evaluation to the
    /// next.
    buffers: RefCell<Buffers>,
}

#[derive(Default)]
struct Buffers {
    inputs: Vec<f64>,
    outputs: Vec<f64>,
}

/// The rows at a configuration on the constraints.
pub struct RowsAt {
    /// The configuration, moved onto `f(q) = 0`.
    pub q: Vec<f64>,
    /// The rows, `c x n`.
    pub rows: DMatrix<f64>,
}

impl FrameRows {
    /// `rows` (`c x n` expressions), with `varying` the coordinates that
    /// move; the configuration constraints are the model's, each solved for
    /// one of `varying`; run by the engine `backend` makes.
    pub fn new(
        model: &Model,
        cx: &Context,
        rows: &Matrix<ExprId>,
        varying: Vec<usize>,
        backend: &dyn Backend,
    ) -> Result<Self, IrError> {
        let (n, c) = (model.n(), model.c());
        let h = model.mechanism.holonomic.len();
        let coordinate_rows = &model.constraint_expressions;
        let mut outputs = rows.entries().to_vec();
        for i in c - h..c {
            outputs.extend((0..n).map(|j| coordinate_rows.get(i, j)));
        }
        outputs.extend(model.mechanism.expressions.holonomic_residual.entries());
        let mut inputs: Vec<SymbolId> = model.coordinate_symbols();
        inputs.extend(model.parameter_symbols());
        let program = ir::lower(cx, &inputs, &outputs)?;
        let mut frame = FrameRows {
            engine: backend.engine(&[&program]),
            program,
            n,
            c,
            h,
            varying,
            solved: Vec::new(),
            parameters: model.parameter_defaults(),
            buffers: RefCell::default(),
        };
        frame.solved = frame.solved_coordinates();
        frame.varying.retain(|i| !frame.solved.contains(i));
        Ok(frame)
    }

    /// One of the varying coordinates per configuration constraint, the
    /// pivots of `df/dq` on them at the defaults (none where that fails).
    fn solved_coordinates(&self) -> Vec<usize> {
        if self.h == 0 {
            return Vec::new();
        }
        let Some((_, jacobian, _)) = self.evaluate(&vec![0.0; self.n]) else {
            return Vec::new();
        };
        let mut pivots = vec![0; self.h];
        match self.varying.len() > self.h
            && partial_pivots(&jacobian.select_columns(&self.varying), &mut pivots)
        {
            true => pivots.iter().map(|&k| self.varying[k]).collect(),
            false => Vec::new(),
        }
    }

    /// The number of coordinates the search moves.
    pub fn dimension(&self) -> usize {
        self.varying.len()
    }

    /// `(rows, df/dq, f)` at `q`; `None` where a value is not finite.
    fn evaluate(&self, q: &[f64]) -> Option<(DMatrix<f64>, DMatrix<f64>, DVector<f64>)> {
        let mut buffers = self.buffers.borrow_mut();
        let Buffers {
            inputs,
            outputs: values,
        } = &mut *buffers;
        inputs.clear();
        inputs.extend(q);
        inputs.extend(&self.parameters);
        values.resize(self.program.outputs().len(), 0.0);
        (self.engine.evaluate(0, &self.program, inputs, values)).ok()?;
        if !values.iter().all(|v| v.is_finite()) {
            return None;
        }
        let (n, c, h) = (self.n, self.c, self.h);
        let rows = DMatrix::from_row_slice(c, n, &values[..c * n]);
        let jacobian = DMatrix::from_row_slice(h, n, &values[c * n..(c + h) * n]);
        let residual = DVector::from_row_slice(&values[(c + h) * n..]);
        Some((rows, jacobian, residual))
    }

    /// The rows at the point `point` of the varying coordinates, moved
    /// onto the configuration constraints; `None` where that fails or a
    /// value is not finite.
    pub fn at(&self, point: &[f64]) -> Option<RowsAt> {
        let mut q = vec![0.0; self.n];
        for (&i, &value) in self.varying.iter().zip(point) {
            q[i] = value;
        }
        // Newton's method on the solved coordinates, or the least-norm step
        // along all varying ones when none could be chosen at the defaults.
        let moving = match self.solved.len() == self.h {
            true => &self.solved,
            false => &self.varying,
        };
        for _ in 0..NEWTON_STEPS {
            let (rows, jacobian, residual) = self.evaluate(&q)?;
            let scale = jacobian.amax().max(1.0);
            if residual.amax() <= 1e-13 * scale {
                return Some(RowsAt { q, rows });
            }
            let jacobian = jacobian.select_columns(moving);
            let step =
                jacobian.transpose() * (&jacobian * jacobian.transpose()).lu().solve(&residual)?;
            for (&i, delta) in moving.iter().zip(step.iter()) {
                q[i] -= delta;
            }
        }
        None
    }
}

/// A line `o + s d` through the box `[-pi, pi]^m`.
struct Line {
    origin: Vec<f64>,
    direction: Vec<f64>,
}

impl Line {
    fn point(&self, s: f64) -> Vec<f64> {
        self.origin
            .iter()
            .zip(&self.direction)
            .map(|(o, d)| o + s * d)
            .collect()
    }
}

/// [`LINES`] lines through `[-pi, pi]^m`, the same for every search.
fn lines(m: usize) -> Vec<Line> {
    let mut random = SplitMix::new(SEED);
    (0..LINES)
        .map(|_| {
            let origin = (0..m).map(|_| random.uniform(-PI, PI)).collect();
            let direction: Vec<f64> = loop {
                let d: Vec<f64> = (0..m).map(|_| random.uniform(-1.0, 1.0)).collect();
                let norm = d.iter().map(|v| v * v).sum::<f64>().sqrt();
                if norm > 1e-3 && norm <= 1.0 {
                    break d.iter().map(|v| v / norm).collect();
                }
            };
            Line { origin, direction }
        })
        .collect()
}

/// Points where the chart with the dependent speeds `dependent`
/// degenerates, each moved onto the configuration constraints.
pub fn singular_points(rows: &FrameRows, dependent: &[usize]) -> Vec<RowsAt> {
    let m = rows.dimension();
    if m == 0 {
        return Vec::new();
    }
    let half = PI * (m as f64).sqrt();
    let ratio = |line: &Line, s: f64| {
        rows.at(&line.point(s))
            .map(|at| signed_pivot_ratio(&at.rows, dependent))
    };
    let mut found = Vec::new();
    for line in lines(m) {
        let s: Vec<f64> = (0..SAMPLES)
            .map(|i| -half + 2.0 * half * i as f64 / (SAMPLES - 1) as f64)
            .collect();
        let values: Vec<Option<f64>> = s.iter().map(|&s| ratio(&line, s)).collect();
        for i in 0..SAMPLES - 1 {
            let (Some(a), Some(b)) = (values[i], values[i + 1]) else {
                continue;
            };
            let zero = if a * b < 0.0 {
                bisect(|s| ratio(&line, s), (s[i], a), s[i + 1])
            } else if i > 0 && is_small_minimum(values[i - 1], a, b) {
                minimize(|s| ratio(&line, s).map(f64::abs), s[i - 1], s[i + 1])
            } else {
                None
            };
            if let Some(at) = zero.and_then(|s| rows.at(&line.point(s))) {
                found.push(at);
            }
        }
    }
    found
}

/// Whether `b` (between `a` and `c`) is a local minimum of the magnitude
/// below [`NEAR_ZERO`] without a change of sign around it.
fn is_small_minimum(a: Option<f64>, b: f64, c: f64) -> bool {
    let Some(a) = a else {
        return false;
    };
    b.abs() < NEAR_ZERO && b.abs() <= a.abs() && b.abs() <= c.abs() && a * b > 0.0 && b * c > 0.0
}

/// The zero of `f` between `low` (where it is `f_low`) and `high`, where
/// it has the other sign, by bisection; `None` when the bracket closes on
/// a jump (the value there is not near zero) or a value is undefined.
fn bisect(
    f: impl Fn(f64) -> Option<f64>,
    (mut low, f_low): (f64, f64),
    mut high: f64,
) -> Option<f64> {
    let sign = f_low.signum();
    for _ in 0..80 {
        let middle = (low + high) / 2.0;
        if middle == low || middle == high {
            break;
        }
        match f(middle)? {
            value if value.signum() == sign => low = middle,
            _ => high = middle,
        }
    }
    let middle = (low + high) / 2.0;
    (f(middle)?.abs() < ZERO).then_some(middle)
}

/// The minimum of `f` on `[low, high]` by golden-section search, where it
/// reaches [`ZERO`].
fn minimize(f: impl Fn(f64) -> Option<f64>, mut low: f64, mut high: f64) -> Option<f64> {
    let golden = (5f64.sqrt() - 1.0) / 2.0;
    let (mut left, mut right) = (high - golden * (high - low), low + golden * (high - low));
    let (mut f_left, mut f_right) = (f(left)?, f(right)?);
    for _ in 0..100 {
        if f_left < f_right {
            (high, right, f_right) = (right, left, f_left);
            left = high - golden * (high - low);
            f_left = f(left)?;
        } else {
            (low, left, f_left) = (left, right, f_right);
            right = low + golden * (high - low);
            f_right = f(right)?;
        }
    }
    let middle = (low + high) / 2.0;
    (f(middle)? < ZERO).then_some(middle)
}
