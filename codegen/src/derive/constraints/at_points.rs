//! The analysis at random points modulo a prime ([`crate::sym::modular`]),
//! for a basis of D too large for normal forms: Frobenius (`A [X_i, X_j]`
//! non-zero at a point proves D not integrable) and the growth vector
//! (each rank at a point is a proved lower bound of the generic rank;
//! equality holds with probability above `1 - 1e-15`, Schwartz-Zippel).

use super::{AnalysisError, DistributionBasis, STRUCTURED_GROWTH_NODES};
use crate::model::Model;
use crate::sym::modular::{self, ModularError, Point};
use crate::sym::residues::Values;
use crate::sym::{ExprId, Matrix};

/// Frobenius at random points: `A [X_i, X_j]` evaluated modulo a prime at
/// two points; a non-zero value proves D not integrable.
pub(super) fn is_involutive_at_points(
    model: &mut Model,
    basis: &DistributionBasis,
) -> Result<bool, AnalysisError> {
    let fields = expression_columns(&basis.field_expressions);
    let rows = model.constraint_expressions.clone();
    let mut products = Vec::new();
    for (i, x) in fields.iter().enumerate() {
        for y in &fields[i + 1..] {
            let bracket = Matrix::column(expression_bracket(model, x, y));
            products.extend_from_slice(rows.mul(&bracket, &mut model.store)?.entries());
        }
    }
    let store = &model.store;
    let values = modular::at_defined_points(modular::SEEDS.len(), |point| {
        Values::at(point).of(store, &products)
    })?;
    Ok(values.iter().flatten().all(|&v| v == 0))
}

/// Moore's test of one row at random points: `d a_i / d q_j - d a_j / d q_i`
/// non-zero at a point proves the row not exact.
pub(super) fn is_exact_row_at_points(
    model: &mut Model,
    entries: &[ExprId],
) -> Result<bool, AnalysisError> {
    let coordinates = model.coordinate_symbols();
    let mut asymmetries = Vec::new();
    for (i, &a_i) in entries.iter().enumerate() {
        for (j, &a_j) in entries.iter().enumerate().skip(i + 1) {
            let forward = model.store.derivative(a_i, coordinates[j]);
            let backward = model.store.derivative(a_j, coordinates[i]);
            asymmetries.push(model.store.sub(forward, backward));
        }
    }
    let store = &model.store;
    let values = modular::at_defined_points(modular::SEEDS.len(), |point| {
        Values::at(point).of(store, &asymmetries)
    })?;
    Ok(values.iter().flatten().all(|&v| v == 0))
}

/// The growth vector from ranks at a random point (the first where every
/// bracket is defined), with the brackets built as expressions;
/// `(growth, complete)`, incomplete when the brackets of the next level
/// would exceed [`STRUCTURED_GROWTH_NODES`] new nodes.
pub(super) fn growth_vector_at_point(
    model: &mut Model,
    basis: &DistributionBasis,
) -> Result<(Vec<usize>, bool), AnalysisError> {
    let start = model.store.len();
    let mut undefined = None;
    for point in modular::points() {
        match growth_at(model, basis, point, start) {
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
    model: &mut Model,
    basis: &DistributionBasis,
    point: Point,
    start: usize,
) -> Result<(Vec<usize>, bool), AnalysisError> {
    let fields = expression_columns(&basis.field_expressions);
    let mut span = SpanAtPoint::new(model.n(), point);
    let mut newest = span.additions(model, fields.clone())?;
    let mut growth = vec![span.rank()];
    while span.rank() < super::reachable_bound(model) && !newest.is_empty() {
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
    ) -> Result<Vec<Vec<ExprId>>, ModularError> {
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

fn expression_columns(matrix: &Matrix<ExprId>) -> Vec<Vec<ExprId>> {
    (0..matrix.columns())
        .map(|j| matrix.column_entries(j))
        .collect()
}
