//! The body frame of a symmetric model (MATH.md 1.1 and 4; Koon & Marsden,
//! "The geometric structure of nonholonomic mechanics", section 2).
//!
//! The declared group acts on the left and carries the constraint
//! distribution to itself (checked exactly when the model is checked), so D
//! at `q = g . (e, r)` is the left translate of D at the group identity `e`
//! (every group coordinate 0):
//!
//! ```text
//! qdot = L(q) (xi, rdot),   L = R(theta) on each se2 factor's (x, y), 1 elsewhere
//! A(q) qdot = 0   <=>   A(e, r) (xi, rdot) = 0
//! ```
//!
//! with `xi` the body velocity (`(cos th xdot + sin th ydot,
//! -sin th xdot + cos th ydot, thdot)` for `se2`, `qdot` for an abelian factor).
//! The body rows `A(e, r)` depend on the shape and the parameters only, so a
//! basis of their kernel has no group coordinate in a denominator, and
//! `X = L X_body` is a basis of D whose only dependence on the group is the
//! rotation `L`, regular at every heading.

use crate::model::{GroupFactor, Model};
use crate::sym::{Context, ExprId, Function, Matrix, MatrixError};
use std::collections::HashMap;

/// The body rows and the map from body to coordinate velocities, as
/// expressions.
pub(super) struct BodyFrame {
    /// `A(e, r)`, c x n: the constraint rows at the group identity.
    pub(super) constraints: Matrix<ExprId>,
    /// `L(q)`, n x n: `qdot = L (xi, rdot)`.
    pub(super) to_coordinates: Matrix<ExprId>,
}

impl BodyFrame {
    /// The body frame of `model`'s declared symmetry; `None` without one.
    pub(super) fn of(model: &Model, cx: &mut Context) -> Result<Option<BodyFrame>, MatrixError> {
        let Some(symmetry) = model.symmetry.clone() else {
            return Ok(None);
        };
        let zero = cx.integer(0);
        let identity: HashMap<_, _> = symmetry
            .factors
            .iter()
            .flat_map(|factor| match *factor {
                GroupFactor::Se2 { x, y, theta } => vec![x, y, theta],
                GroupFactor::Translation(q) | GroupFactor::Rotation(q) => vec![q],
            })
            .map(|i| (model.coordinates[i].symbol, zero))
            .collect();
        let a = &model.constraint_expressions;
        let mut constraints = cx.zero_matrix(a.rows(), a.columns());
        for i in 0..a.rows() {
            for j in 0..a.columns() {
                constraints.set(i, j, cx.substitute(*a.get(i, j), &identity)?);
            }
        }
        let mut to_coordinates = cx.identity_matrix(model.coordinates.len());
        for factor in &symmetry.factors {
            if let GroupFactor::Se2 { x, y, theta } = *factor {
                let heading = cx.symbol(model.coordinates[theta].symbol);
                let cos = cx.apply(Function::Cos, heading)?;
                let sin = cx.apply(Function::Sin, heading)?;
                let minus_sin = cx.neg(sin);
                to_coordinates.set(x, x, cos);
                to_coordinates.set(x, y, minus_sin);
                to_coordinates.set(y, x, sin);
                to_coordinates.set(y, y, cos);
            }
        }
        Ok(Some(BodyFrame {
            constraints,
            to_coordinates,
        }))
    }

    /// `A(e, r)` in normal form.
    pub(super) fn exact_constraints(&self, cx: &mut Context) -> Result<Matrix, MatrixError> {
        exact(&self.constraints, cx)
    }

    /// `L(q)` in normal form.
    pub(super) fn exact_to_coordinates(&self, cx: &mut Context) -> Result<Matrix, MatrixError> {
        exact(&self.to_coordinates, cx)
    }
}

/// `matrix` in normal form.
fn exact(matrix: &Matrix<ExprId>, cx: &mut Context) -> Result<Matrix, MatrixError> {
    Matrix::from_expressions(cx, matrix.rows(), matrix.columns(), matrix.entries())
}
