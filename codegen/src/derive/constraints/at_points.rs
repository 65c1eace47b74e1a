//! The analysis at random points modulo a prime ([`crate::sym::modular`]),
//! for a basis of D too large for normal forms: Frobenius (`A [X_i, X_j]`
//! non-zero at a point proves D not integrable) and the growth vector
//! (each rank at a point is a proved lower bound of the generic rank;
//! equality holds with probability above `1 - 1e-15`, Schwartz-Zippel).

use super::{AnalysisError, DistributionBasis, STRUCTURED_GROWTH_NODES};
use crate::model::Model;
use crate::sym::modular::{self, Outside, Point, Values};
use crate::sym::{ExprId, ExprMatrix};

/// Frobenius at random points: `A [X_i, X_j]` evaluated modulo a prime at
/// two points; a non-zero value proves D not integrable.
pub(super) fn is_involutive_at_points(
    model: &mut Model,
    basis: &DistributionBasis,
) -> Result<bool, AnalysisError> {
    let fields = expression_columns(&basis.field_expressions);
    let rows = ExprMatrix::of(&model.constraint_matrix, &mut model.store);
    let mut products = Vec::new();
    for (i, x) in fields.iter().enumerate() {
        for y in &fields[i + 1..] {
            let bracket = ExprMatrix::column(expression_bracket(model, x, y));
            products.extend_from_slice(rows.mul(&bracket, &mut model.store)?.entries());
        }
    }
    for seed in modular::SEEDS {
        let values = Values::at(Point::new(seed)).of(&model.store, &products)?;
        if values.iter().any(|&v| v != 0) {
            return Ok(false);
        }
    }
    Ok(true)
}

/// The growth vector from ranks at a random point, with the brackets built
/// as expressions; `(growth, complete)`, incomplete when the brackets of
/// the next level would exceed [`STRUCTURED_GROWTH_NODES`] new nodes.
pub(super) fn growth_vector_at_point(
    model: &mut Model,
    basis: &DistributionBasis,
) -> Result<(Vec<usize>, bool), AnalysisError> {
    let start = model.store.len();
    let fields = expression_columns(&basis.field_expressions);
    let mut span = SpanAtPoint::new(model.n(), Point::new(modular::SEEDS[0]));
    let mut newest = span.additions(model, fields.clone())?;
    let mut growth = vec![span.rank()];
    while span.rank() < model.n() && !newest.is_empty() {
        let mut brackets = Vec::with_capacity(fields.len() * newest.len());
        for x in &fields {
            for y in &newest {
                if model.store.len() - start > STRUCTURED_GROWTH_NODES {
                    return Ok((growth, false));
                }
                brackets.push(expression_bracket(model, x, y));
            }
        }
        newest = span.additions(model, brackets)?;
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
        model: &Model,
        candidates: Vec<Vec<ExprId>>,
    ) -> Result<Vec<Vec<ExprId>>, Outside> {
        let mut added = Vec::new();
        for candidate in candidates {
            let values = self.at_point.of(&model.store, &candidate)?;
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

fn expression_bracket(model: &mut Model, x: &[ExprId], y: &[ExprId]) -> Vec<ExprId> {
    let coordinates = model.coordinate_symbols();
    model.store.lie_bracket_of_expressions(x, y, &coordinates)
}

fn expression_columns(matrix: &ExprMatrix) -> Vec<Vec<ExprId>> {
    (0..matrix.columns())
        .map(|j| matrix.column_entries(j))
        .collect()
}
