//! The exact reduced form as expressions ([`ReducedExpressions`]): the matrices'
//! entries, the energy `Hbar = 1/2 alpha . (gbar_inv alpha) + V` and its
//! derivatives unexpanded, and the flow as the products
//! `xdot = Jbar dHbar/dx + Bbar u`, `y = Bbar^T dHbar/dx` of the exact
//! gradient's expressions (Duindam & Stramigioli, Theorem 1; MATH.md 3).

use super::{
    Exact, ReducedExpressions, RhsJacobian, reduced_energy, state_jacobian, symbols_column,
};
use crate::model::Model;
use crate::sym::Context;
use crate::sym::{Matrix, MatrixError, SymbolId};

impl Exact {
    /// The exact matrices as expressions, the energy `1/2 alpha . (gbar_inv
    /// alpha) + V` and its derivatives unexpanded, and the flow as the
    /// products `Jbar dHbar/dx + Bbar u`, `Bbar^T dHbar/dx` of the exact
    /// gradient's expressions.
    pub fn expressions(
        &self,
        model: &Model,
        cx: &mut Context,
        momenta: &[SymbolId],
        inputs: &[SymbolId],
    ) -> Result<ReducedExpressions, MatrixError> {
        let state = {
            let mut state = model.coordinate_symbols();
            state.extend(momenta);
            state
        };
        let alpha = symbols_column(cx, momenta);
        let u = symbols_column(cx, inputs);
        let metric_inverse = self.metric_inverse.to_expression_matrix(cx);
        let potential = cx.expression_of(&model.potential_energy);
        let hamiltonian = reduced_energy(cx, &alpha, &metric_inverse, potential)?;
        let gradient = state
            .iter()
            .map(|&x| cx.derivative(hamiltonian, x))
            .collect();
        let exact_gradient =
            Matrix::column(self.gradient.iter().map(|g| cx.expression_of(g)).collect());
        let structure = self.structure.to_expression_matrix(cx);
        let input_matrix = self.input_matrix.to_expression_matrix(cx);
        let rhs = structure
            .mul(&exact_gradient, cx)?
            .add(&input_matrix.mul(&u, cx)?, cx)?;
        let output = input_matrix.transpose().mul(&exact_gradient, cx)?;
        let rhs_jacobian = RhsJacobian::Differentiated(state_jacobian(cx, &state, rhs.entries()));
        Ok(ReducedExpressions {
            velocity_map: self.velocity_map.to_expression_matrix(cx),
            momentum_map: self.momentum_map.to_expression_matrix(cx),
            metric: self.metric.to_expression_matrix(cx),
            metric_inverse,
            structure,
            input_matrix,
            hamiltonian,
            gradient,
            rhs: rhs.entries().to_vec(),
            rhs_jacobian,
            output: output.entries().to_vec(),
        })
    }
}
