//! The exact Jacobian of `acceleration`'s `qddot(q, qdot, u)` (MATH.md
//! section 6), of the solution the derivation's strategy computes.
//!
//! The solve by blocks is differentiated implicitly. `(qddot, lambda)` solve
//! `g qddot = f + A^T lambda`, `A qddot = d` (`f = B u - C - dV/dq`,
//! `d = -Adot qdot`), so their derivatives by any one variable `theta` (a
//! `q_j`, `qdot_j` or `u_j`, written `'`) solve the same system with
//! another right-hand side:
//!
//! ```text
//! g qddot' = (f' - g' qddot + A'^T lambda) + A^T lambda'
//! A qddot' = d' - A' qddot
//! ```
//!
//! (`g` and `A` depend on `q` alone, so for `qdot` and `u` only `f'` and
//! `d'` remain). Every variable's column is solved with the factors the
//! solve by blocks took once ([`BlockFactors`](super::BlockFactors)), over
//! the `qddot` and `lambda` that `acceleration` computes: the factorization
//! itself is not differentiated, which for the twelve-link snake makes the
//! Jacobian several times smaller. It is the derivative of the solution,
//! the same rational function, exact wherever the solve is defined.
//!
//! The closed form is differentiated as an expression
//! ([`Context::derivatives`]): it is small, and its derivatives weigh less
//! than a solve of the differentiated system (the sleigh's and the
//! rolling disk's less than half).

use super::{LagrangeDalembert, Strategy};
use crate::model::Model;
use crate::sym::{Context, ExprId, Matrix, MatrixError, SymbolId};

/// `d qddot_i / d variables_j`, n x `variables.len()`, of `solution`
/// (`qddot` then `lambda`, as `acceleration` computes them with the
/// derivation's strategy): the closed form differentiated, the solve by
/// blocks differentiated implicitly ([`implicit_jacobian`]).
pub fn acceleration_jacobian(
    model: &Model,
    cx: &mut Context,
    derivation: &LagrangeDalembert,
    solution: &[ExprId],
    variables: &[SymbolId],
) -> Result<Matrix<ExprId>, MatrixError> {
    match derivation.strategy {
        Strategy::Symbolic => differentiated(cx, &solution[..model.n()], variables),
        Strategy::Numeric => implicit_jacobian(model, cx, derivation, solution, variables),
    }
}

/// `d functions_i / d variables_j`, each differentiated as an expression.
fn differentiated(
    cx: &mut Context,
    functions: &[ExprId],
    variables: &[SymbolId],
) -> Result<Matrix<ExprId>, MatrixError> {
    let columns: Vec<Matrix<ExprId>> = variables
        .iter()
        .map(|&v| Matrix::column(cx.derivatives(functions, v)))
        .collect();
    side_by_side(&columns, functions.len())
}

/// `d qddot_i / d variables_j`, n x `variables.len()`, by implicit
/// differentiation about `solution` (`qddot` then `lambda`).
pub fn implicit_jacobian(
    model: &Model,
    cx: &mut Context,
    derivation: &LagrangeDalembert,
    solution: &[ExprId],
    variables: &[SymbolId],
) -> Result<Matrix<ExprId>, MatrixError> {
    let solved = Solved::of(model, cx, derivation, solution);
    let mut force_columns = Vec::with_capacity(variables.len());
    let mut drift_columns = Vec::with_capacity(variables.len());
    for &variable in variables {
        let (force, drift) = solved.differentiated_by(cx, variable)?;
        force_columns.push(force);
        drift_columns.push(drift);
    }
    let force = side_by_side(&force_columns, model.n())?;
    let drift = side_by_side(&drift_columns, model.c())?;
    let (rates, _) = derivation.block_factors.solve(cx, &force, &drift)?;
    Ok(rates)
}

/// The saddle-point system as expressions, and its solution.
struct Solved {
    /// `g`, n x n.
    mass_matrix: Matrix<ExprId>,
    /// `A`, c x n.
    constraint_matrix: Matrix<ExprId>,
    /// `f`, n x 1.
    force: Matrix<ExprId>,
    /// `d`, c x 1.
    drift: Matrix<ExprId>,
    /// `qddot`, n x 1.
    accelerations: Matrix<ExprId>,
    /// `lambda`, c x 1.
    multipliers: Matrix<ExprId>,
}

impl Solved {
    fn of(
        model: &Model,
        cx: &mut Context,
        derivation: &LagrangeDalembert,
        solution: &[ExprId],
    ) -> Solved {
        let (accelerations, multipliers) = solution.split_at(model.n());
        let system = &derivation.saddle_point;
        Solved {
            mass_matrix: model.energy_expressions.mass_matrix.clone(),
            constraint_matrix: model.constraint_expressions.clone(),
            force: system.force.expressions.clone(),
            drift: system.drift.expressions(cx),
            accelerations: Matrix::column(accelerations.to_vec()),
            multipliers: Matrix::column(multipliers.to_vec()),
        }
    }

    /// The right-hand side `(f' - g' qddot + A'^T lambda, d' - A' qddot)`
    /// of the derivatives by `variable`.
    fn differentiated_by(
        &self,
        cx: &mut Context,
        variable: SymbolId,
    ) -> Result<(Matrix<ExprId>, Matrix<ExprId>), MatrixError> {
        let g_rate = self.mass_matrix.derivative(variable, cx);
        let a_rate = self.constraint_matrix.derivative(variable, cx);
        let inertial = g_rate.mul(&self.accelerations, cx)?;
        let reaction = a_rate.transpose().mul(&self.multipliers, cx)?;
        let force = self.force.derivative(variable, cx);
        let force = force.sub(&inertial, cx)?.add(&reaction, cx)?;
        let constrained = a_rate.mul(&self.accelerations, cx)?;
        let drift = self.drift.derivative(variable, cx).sub(&constrained, cx)?;
        Ok((force, drift))
    }
}

/// The `rows x 1` columns side by side.
fn side_by_side(columns: &[Matrix<ExprId>], rows: usize) -> Result<Matrix<ExprId>, MatrixError> {
    let entries = columns.iter().flat_map(Matrix::entries).copied().collect();
    Ok(Matrix::new(columns.len(), rows, entries)?.transpose())
}
