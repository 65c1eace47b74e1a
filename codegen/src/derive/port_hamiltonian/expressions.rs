//! The exact reduced form as expressions ([`ReducedExpressions`]): the matrices'
//! entries, the energy `Hbar = 1/2 alpha . (gbar_inv alpha) + V` and its
//! derivatives unexpanded, and the flow as the products
//! `xdot = Jbar dHbar/dx + Bbar u`, `y = Bbar^T dHbar/dx` of the exact
//! gradient's expressions (Duindam & Stramigioli, Theorem 1; MATH.md 3).

use super::{Exact, ReducedExpressions, reduced_energy, symbols_column};
use crate::model::Model;
use crate::sym::{Matrix, MatrixError, SymbolId};

impl Exact {
    /// The exact matrices as expressions, the energy `1/2 alpha . (gbar_inv
    /// alpha) + V` and its derivatives unexpanded, and the flow as the
    /// products `Jbar dHbar/dx + Bbar u`, `Bbar^T dHbar/dx` of the exact
    /// gradient's expressions.
    pub fn expressions(
        &self,
        model: &mut Model,
        momenta: &[SymbolId],
        inputs: &[SymbolId],
    ) -> Result<ReducedExpressions, MatrixError> {
        let state = {
            let mut state = model.coordinate_symbols();
            state.extend(momenta);
            state
        };
        let store = &mut model.store;
        let alpha = symbols_column(store, momenta);
        let u = symbols_column(store, inputs);
        let metric_inverse = self.metric_inverse.to_expression_matrix(store);
        let potential = store.expression_of(&model.potential_energy);
        let hamiltonian = reduced_energy(store, &alpha, &metric_inverse, potential)?;
        let gradient = state
            .iter()
            .map(|&x| store.derivative(hamiltonian, x))
            .collect();
        let exact_gradient = Matrix::column(
            self.gradient
                .iter()
                .map(|g| store.expression_of(g))
                .collect(),
        );
        let structure = self.structure.to_expression_matrix(store);
        let input_matrix = self.input_matrix.to_expression_matrix(store);
        let rhs = structure
            .mul(&exact_gradient, store)?
            .add(&input_matrix.mul(&u, store)?, store)?;
        let output = input_matrix.transpose().mul(&exact_gradient, store)?;
        Ok(ReducedExpressions {
            velocity_map: self.velocity_map.to_expression_matrix(store),
            momentum_map: self.momentum_map.to_expression_matrix(store),
            metric: self.metric.to_expression_matrix(store),
            metric_inverse,
            structure,
            input_matrix,
            hamiltonian,
            gradient,
            rhs: rhs.entries().to_vec(),
            output: output.entries().to_vec(),
        })
    }
}
