//! Redundant contacts (docs/INTERFACE.md section 4): a `no_slip` row that
//! the rows before it imply is dropped with a note, not refused.
//!
//! **Everywhere.** A row in the span of the rows kept before it at every
//! configuration (the second rear wheel's lateral row on one axle) is found
//! as [`super::rows`] finds a dependent row: ranks modulo a prime at random
//! points prove the rows before it independent, and the exact rank confirms
//! the dependence.
//!
//! **On the holonomic surface.** Rows independent off the surface
//! `f(q) = 0` of the holonomic constraints may be dependent on it: an
//! Ackermann linkage ties the front wheels' angles so that both wheels'
//! axles meet the rear axle's line at one point, and one front wheel's
//! lateral row then follows from the other's and the rear axle's. The
//! motion stays on the surface, so such a row is redundant there. It is
//! found at points of the surface, reached from random configurations by
//! Gauss-Newton's least-norm steps
//!
//! ```text
//! q <- q - J^+ f(q),   J = df/dq   (the holonomic rows of A),
//! ```
//!
//! at the parameters' defaults. At each point the rows are scaled to unit
//! norm and a rank counts the singular values above [`RANK_TOLERANCE`]
//! times the largest: a contact row that adds rank at none of the points
//! is dropped. A declared row or a holonomic row that adds none is refused,
//! as off the surface.

use super::context::Context;
use super::rows::{dependent_row_error, first_dependent_row};
use crate::model::{Declared, Parameter, Redundancy, RedundantRow, Variable};
use crate::sym::modular::{self, PRIME};
use crate::sym::{ExprId, Matrix};
use chaplygin_runtime::nalgebra::{DMatrix, DVector};
use std::collections::HashMap;
use std::f64::consts::PI;
use std::ops::Range;

/// Singular values below this fraction of the largest count as zero in a
/// rank at a point of the surface.
const RANK_TOLERANCE: f64 = 1e-8;

/// How many points of the surface the ranks are taken at.
const SURFACE_POINTS: usize = 3;

/// How many random configurations Gauss-Newton may start from.
const SURFACE_STARTS: usize = 16;

/// Gauss-Newton's most steps from one start.
const PROJECTION_STEPS: usize = 60;

/// A residual `max |f|` below this is on the surface.
const SURFACE_RESIDUAL: f64 = 1e-13;

/// The constraint rows: names, normal forms and expressions, row by row.
pub(super) struct Rows {
    pub(super) names: Vec<Declared>,
    pub(super) matrix: Matrix,
    pub(super) expressions: Matrix<ExprId>,
    /// The rows dropped as redundant.
    pub(super) redundant: Vec<RedundantRow>,
}

/// Where the rows of each kind are, and where the holonomic surface is.
pub(super) struct Layout<'a> {
    /// The `no_slip` rows, which may be dropped.
    pub(super) contacts: Range<usize>,
    /// The holonomic rows `df/dq` (the last rows).
    pub(super) holonomic: Range<usize>,
    /// `f(q)`, one expression per holonomic constraint.
    pub(super) residuals: &'a [ExprId],
    pub(super) coordinates: &'a [Variable],
    pub(super) parameters: &'a [Parameter],
}

impl Rows {
    fn without(mut self, row: usize, redundancy: Redundancy) -> Rows {
        let kept: Vec<usize> = (0..self.matrix.rows()).filter(|&i| i != row).collect();
        let columns: Vec<usize> = (0..self.matrix.columns()).collect();
        self.matrix = self.matrix.submatrix(&kept, &columns);
        self.expressions = self.expressions.submatrix(&kept, &columns);
        let name = self.names.remove(row).name;
        self.redundant.push(RedundantRow { name, redundancy });
        self
    }
}

/// The rows with the redundant contact rows dropped, or `None` after
/// reporting a declared or holonomic row that depends on the others.
pub(super) fn without_redundant(
    cx: &mut Context,
    mut rows: Rows,
    mut layout: Layout<'_>,
) -> Option<Rows> {
    while let Some(row) = first_dependent_row(cx, &rows.matrix) {
        if !layout.contacts.contains(&row) {
            constraint_row_error(cx, &rows, row, "");
            return None;
        }
        rows = rows.without(row, Redundancy::Everywhere);
        layout.drop_contact();
    }
    if layout.holonomic.is_empty() {
        return Some(rows);
    }
    let points = surface_points(cx, &rows, &layout);
    while let Some(row) = first_dependent_at(cx, &rows, &layout, &points) {
        if !layout.contacts.contains(&row) {
            let on_surface = " on the surface of the holonomic constraints";
            constraint_row_error(cx, &rows, row, on_surface);
            return None;
        }
        rows = rows.without(row, Redundancy::OnHolonomicSurface);
        layout.drop_contact();
    }
    Some(rows)
}

/// The error on constraint row `row`, which depends on the ones before it
/// (`where_` says where, if not everywhere). A row that is identically
/// zero is said to constrain nothing: a configuration constraint's row is
/// `df/dq`, zero where `f` reads no coordinate.
fn constraint_row_error(cx: &mut Context, rows: &Rows, row: usize, where_: &str) {
    let name = &rows.names[row];
    let matrix = &rows.matrix;
    if (0..matrix.columns()).all(|j| matrix.get(row, j).is_zero()) {
        let message = format!(
            "constraint `{}` constrains nothing: its row is zero in the velocities (a \
             configuration constraint must read a coordinate)",
            name.name
        );
        cx.diagnostics.error(name.span, message);
    } else {
        dependent_row_error(cx, name, "constraint", where_);
    }
}

impl Layout<'_> {
    /// One contact row fewer: the later rows move up by one.
    fn drop_contact(&mut self) {
        self.contacts.end -= 1;
        self.holonomic = self.holonomic.start - 1..self.holonomic.end - 1;
    }

    /// The value of every coordinate and parameter symbol at `q`.
    fn values_at(&self, q: &[f64]) -> HashMap<crate::sym::SymbolId, f64> {
        let coordinates = self
            .coordinates
            .iter()
            .map(|c| c.symbol)
            .zip(q.iter().copied());
        let parameters = (self.parameters.iter()).map(|p| (p.variable.symbol, p.default.to_f64()));
        coordinates.chain(parameters).collect()
    }
}

/// Up to [`SURFACE_POINTS`] points of the holonomic surface.
fn surface_points(cx: &mut Context, rows: &Rows, layout: &Layout<'_>) -> Vec<Vec<f64>> {
    let jacobian: Vec<ExprId> = layout
        .holonomic
        .clone()
        .flat_map(|i| rows.expressions.row_entries(i))
        .collect();
    let n = layout.coordinates.len();
    modular::points()
        .take(SURFACE_STARTS)
        .filter_map(|point| {
            let start = (0..n).map(|i| point.value(i) as f64 / PRIME as f64 * 2.0 * PI - PI);
            project(cx, layout, &jacobian, start.collect())
        })
        .take(SURFACE_POINTS)
        .collect()
}

/// Gauss-Newton from `q` onto `f = 0`, or `None` where it does not converge.
fn project(
    cx: &mut Context,
    layout: &Layout<'_>,
    jacobian: &[ExprId],
    mut q: Vec<f64>,
) -> Option<Vec<f64>> {
    let (h, n) = (layout.residuals.len(), q.len());
    for _ in 0..PROJECTION_STEPS {
        let values = layout.values_at(&q);
        let value_of = |symbol| values.get(&symbol).copied().unwrap_or(f64::NAN);
        let f = DVector::from_vec(cx.sym.evaluate_many(layout.residuals, &value_of));
        if !f.iter().all(|v| v.is_finite()) {
            return None;
        }
        if f.amax() < SURFACE_RESIDUAL {
            return Some(q);
        }
        let j = DMatrix::from_row_slice(h, n, &cx.sym.evaluate_many(jacobian, &value_of));
        let step = j.svd(true, true).solve(&f, RANK_TOLERANCE).ok()?;
        q.iter_mut().zip(step.iter()).for_each(|(q, s)| *q -= s);
    }
    None
}

/// The first row that adds rank at none of `points`, each row scaled to
/// unit norm.
fn first_dependent_at(
    cx: &mut Context,
    rows: &Rows,
    layout: &Layout<'_>,
    points: &[Vec<f64>],
) -> Option<usize> {
    let (c, n) = (rows.matrix.rows(), rows.matrix.columns());
    let values: Vec<DMatrix<f64>> = points
        .iter()
        .map(|q| {
            let values = layout.values_at(q);
            let value_of = |symbol| values.get(&symbol).copied().unwrap_or(f64::NAN);
            let entries = cx.sym.evaluate_many(rows.expressions.entries(), &value_of);
            let mut a = DMatrix::from_row_slice(c, n, &entries);
            a.row_iter_mut().for_each(|mut row| {
                let norm = row.norm();
                if norm > 0.0 {
                    row /= norm;
                }
            });
            a
        })
        .collect();
    (1..c).find(|&i| {
        !points.is_empty()
            && values
                .iter()
                .all(|a| rank(&a.rows(0, i).into_owned()) == rank(&a.rows(0, i + 1).into_owned()))
    })
}

/// The numeric rank: singular values above [`RANK_TOLERANCE`] times the largest.
fn rank(a: &DMatrix<f64>) -> usize {
    let singular = a.singular_values();
    let largest = singular.max();
    singular
        .iter()
        .filter(|&&s| s > RANK_TOLERANCE * largest)
        .count()
}
