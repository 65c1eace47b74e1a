//! The analysis at random points modulo a prime ([`crate::sym::modular`]),
//! for a basis of D too large for normal forms: Frobenius (`A [X_i, X_j]`
//! non-zero at a point proves D not integrable) and the growth vector
//! (each rank at a point is a proved lower bound of the generic rank;
//! equality holds with probability above `1 - 1e-15`, Schwartz-Zippel).

use super::{AnalysisError, DistributionBasis, STRUCTURED_GROWTH_NODES};
use crate::model::Model;
use crate::sym::Context;
use crate::sym::modular::{self, ModularError, Point};
use crate::sym::residues::Values;
use crate::sym::{ExprId, Matrix};

/// Frobenius at random points: `A [X_i, X_j]` evaluated modulo a prime at
/// two points; a non-zero value proves D not integrable.
pub(super) fn is_involutive_at_points(
    model: &Model,
    cx: &mut Context,
    basis: &DistributionBasis,
) -> Result<bool, AnalysisError> {
    let fields = expression_columns(&basis.field_expressions);
    let rows = &model.constraint_expressions;
    let mut products = Vec::new();
    for (i, x) in fields.iter().enumerate() {
        for y in &fields[i + 1..] {
            let bracket = Matrix::column(expression_bracket(model, cx, x, y));
            products.extend_from_slice(rows.mul(&bracket, cx)?.entries());
        }
    }
    let values = modular::at_defined_points(modular::SEEDS.len(), |point| {
        Values::at(point).of(cx, &products)
    })?;
    Ok(values.iter().flatten().all(|&v| v == 0))
}

/// Moore's test of one row at random points: `d a_i / d q_j - d a_j / d q_i`
/// non-zero at a point proves the row not exact.
pub(super) fn is_exact_row_at_points(
    model: &Model,
    cx: &mut Context,
    entries: &[ExprId],
) -> Result<bool, AnalysisError> {
    let asymmetries = curl(model, cx, entries);
    let values = modular::at_defined_points(modular::SEEDS.len(), |point| {
        Values::at(point).of(cx, &asymmetries)
    })?;
    Ok(values.iter().flatten().all(|&v| v == 0))
}

/// The curl of a row: `d a_i / d q_j - d a_j / d q_i` for `i < j`.
pub(super) fn curl(model: &Model, cx: &mut Context, entries: &[ExprId]) -> Vec<ExprId> {
    let coordinates = model.coordinate_symbols();
    let mut curl = Vec::new();
    for (i, &a_i) in entries.iter().enumerate() {
        for (j, &a_j) in entries.iter().enumerate().skip(i + 1) {
            let forward = cx.derivative(a_i, coordinates[j]);
            let backward = cx.derivative(a_j, coordinates[i]);
            curl.push(cx.sub(forward, backward));
        }
    }
    curl
}

/// The growth vector from ranks at a random point (the first where every
/// bracket is defined), with the brackets built as expressions;
/// `(growth, complete)`, incomplete when the brackets of the next level
/// would exceed [`STRUCTURED_GROWTH_NODES`] new nodes.
pub(super) fn growth_vector_at_point(
    model: &Model,
    cx: &mut Context,
    basis: &DistributionBasis,
) -> Result<(Vec<usize>, bool), AnalysisError> {
    let start = cx.len();
    let mut undefined = None;
    for point in modular::points() {
        match growth_at(model, cx, basis, point, start) {
            Err(AnalysisError::Undecided(outside @ ModularError::Undefined { .. })) => {
                undefined = Some(outside);
            }
            decided => return decided,
        }
    }
    Err(AnalysisError::Undecided(undefined.unwrap_or(
        ModularError::Undefined {
            expr: "every point drawn".to_string(),
        },
    )))
}

fn growth_at(
    model: &Model,
    cx: &mut Context,
    basis: &DistributionBasis,
    point: Point,
    start: usize,
) -> Result<(Vec<usize>, bool), AnalysisError> {
    let fields = expression_columns(&basis.field_expressions);
    let mut span = SpanAtPoint::new(model.n(), point);
    let mut newest = span.additions(cx, fields.clone())?;
    let mut growth = vec![span.rank()];
    while span.rank() < super::reachable_bound(model) && !newest.is_empty() {
        let mut brackets = Vec::with_capacity(fields.len() * newest.len());
        for x in &fields {
            for y in &newest {
                if cx.len() - start > STRUCTURED_GROWTH_NODES {
                    return Ok((growth, false));
                }
                brackets.push(expression_bracket(model, cx, x, y));
            }
        }
        newest = span.additions(cx, brackets)?;
        if newest.is_empty() {
            break;
        }
        growth.push(span.rank());
    }
    Ok((growth, true))
}

/// Fields kept for their values at a point, which are independent there.
struct SpanAtPoint {
    n: usize,
    /// The kept fields' values, row after row.
    values: Vec<u64>,
    /// The values of every node evaluated at the point.
    at_point: Values,
}

impl SpanAtPoint {
    fn new(n: usize, point: Point) -> SpanAtPoint {
        SpanAtPoint {
            n,
            values: Vec::new(),
            at_point: Values::at(point),
        }
    }

    fn rank(&self) -> usize {
        self.values.len() / self.n.max(1)
    }

    /// Keeps each candidate whose value at `point` raises the rank; returns those.
    fn additions(
        &mut self,
        cx: &Context,
        candidates: Vec<Vec<ExprId>>,
    ) -> Result<Vec<Vec<ExprId>>, ModularError> {
        let mut added = Vec::new();
        for candidate in candidates {
            let values = self.at_point.of(cx, &candidate)?;
            let before = self.values.len();
            self.values.extend_from_slice(&values);
            let fields = self.rank();
            if modular::rank(self.values.clone(), fields, self.n) == fields {
                added.push(candidate);
            } else {
                self.values.truncate(before);
            }
        }
        Ok(added)
    }
}

fn expression_bracket(model: &Model, cx: &mut Context, x: &[ExprId], y: &[ExprId]) -> Vec<ExprId> {
    let coordinates = model.coordinate_symbols();
    cx.lie_bracket_of_expressions(x, y, &coordinates)
}

fn expression_columns(matrix: &Matrix<ExprId>) -> Vec<Vec<ExprId>> {
    (0..matrix.columns())
        .map(|j| matrix.column_entries(j))
        .collect()
}
