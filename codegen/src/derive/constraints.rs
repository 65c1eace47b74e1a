//! Constraint analysis (Moore, "Nonholonomic Constraints"; MATH.md section 1).
//!
//! **Basis of D.** With `A(q) qdot = 0` (c rows), choose c dependent speeds
//! `u_r` (pivot columns of A) and write the independent ones `u_s`; then
//! `u_r = A_n u_s` with `A_n = -A_r^-1 A_s`, and the columns of `[I; A_n]`
//! (rows permuted back to the coordinates' order) are k = n - c vector fields
//! `X_1..X_k` spanning `D = ker A`. The pivots are chosen at the model's
//! default configuration (every coordinate 0, parameters at their defaults):
//! row by row, the column with the largest value there, so the pivots do not
//! vanish at the defaults and the basis is regular near them.

use crate::model::Model;
use crate::sym::{Matrix, MatrixError, RationalFunction, SymbolId};

/// A basis of the constraint distribution D and how it was chosen.
#[derive(Clone, Debug)]
pub struct DistributionBasis {
    /// `X`, n x k: column j is the vector field `X_j`.
    pub fields: Matrix,
    /// The coordinates whose speeds are dependent (pivot columns), in row order.
    pub dependent: Vec<usize>,
    /// The coordinates whose speeds are independent, in order: `X_j` has a 1
    /// at `independent[j]` and 0 at the other independent speeds.
    pub independent: Vec<usize>,
}

/// Chooses the dependent speeds at the defaults and solves for a basis of D.
pub fn distribution_basis(model: &mut Model) -> Result<DistributionBasis, MatrixError> {
    let (n, c) = (model.n(), model.c());
    let dependent = pivot_columns(model);
    let independent: Vec<usize> = (0..n).filter(|j| !dependent.contains(j)).collect();
    let atoms = model.store.atoms().clone();
    let a = &model.constraint_matrix;
    let columns = |indices: &[usize]| {
        let mut m = Matrix::zeros(c, indices.len());
        for i in 0..c {
            for (k, &j) in indices.iter().enumerate() {
                m.set(i, k, a.get(i, j).clone());
            }
        }
        m
    };
    let a_n = columns(&dependent)
        .solve(&columns(&independent), &atoms)?
        .neg();
    let mut fields = Matrix::zeros(n, independent.len());
    for (k, &j) in independent.iter().enumerate() {
        fields.set(j, k, RationalFunction::one());
    }
    for (row, &j) in dependent.iter().enumerate() {
        for k in 0..independent.len() {
            fields.set(j, k, a_n.get(row, k).clone());
        }
    }
    Ok(DistributionBasis {
        fields,
        dependent,
        independent,
    })
}

/// Gaussian elimination with partial pivoting on A at the defaults: the
/// pivot column of each row is the one of largest magnitude there.
fn pivot_columns(model: &mut Model) -> Vec<usize> {
    let (n, c) = (model.n(), model.c());
    let defaults = default_point(model);
    let mut values = model
        .constraint_matrix
        .evaluate(&mut model.store, &|s| defaults(s));
    let mut pivots: Vec<usize> = Vec::with_capacity(c);
    for row in 0..c {
        let best = (0..n).filter(|j| !pivots.contains(j)).max_by(|&a, &b| {
            values[row * n + a]
                .abs()
                .total_cmp(&values[row * n + b].abs())
        });
        let Some(column) = best else { break };
        let pivot = values[row * n + column];
        if pivot != 0.0 {
            for below in row + 1..c {
                let factor = values[below * n + column] / pivot;
                for j in 0..n {
                    values[below * n + j] -= factor * values[row * n + j];
                }
            }
        }
        pivots.push(column);
    }
    pivots
}

/// The default configuration: coordinates 0, parameters at their defaults.
pub fn default_point(model: &Model) -> impl Fn(SymbolId) -> f64 + use<> {
    let parameters: Vec<(SymbolId, f64)> = model
        .parameters
        .iter()
        .map(|p| (p.variable.symbol, p.default.to_f64()))
        .collect();
    move |s| {
        parameters
            .iter()
            .find(|(p, _)| *p == s)
            .map_or(0.0, |(_, v)| *v)
    }
}

#[cfg(test)]
mod tests {
    use super::distribution_basis;
    use crate::model::{Model, check};
    use crate::syntax::parse_str;

    fn model(source: &str) -> Model {
        check(&parse_str(source).expect("parses")).expect("checks")
    }

    #[test]
    fn the_basis_spans_the_kernel_of_the_constraints() {
        let mut snakeboard = model(crate::fixtures::SNAKEBOARD);
        let basis = distribution_basis(&mut snakeboard).expect("regular at the defaults");
        assert_eq!(basis.fields.columns(), 3);
        let atoms = snakeboard.store.atoms().clone();
        let product = snakeboard
            .constraint_matrix
            .mul(&basis.fields, &atoms)
            .expect("fits");
        assert!(product.is_zero(), "A X must vanish exactly");
        assert_eq!(basis.fields.rank(&atoms), 3);
        // at q = 0 the front and back rows are (0, 1, r, 0, 0) and (0, 1, -r, 0, 0):
        // x has a zero column there, so y and theta are the dependent speeds.
        assert_eq!(basis.dependent, [1, 2]);
        assert_eq!(basis.independent, [0, 3, 4]);
    }
}
