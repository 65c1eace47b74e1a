//! The exact reduced form as expressions ([`Forms`]): the matrices'
//! entries, the energy `Hbar = 1/2 alpha . (gbar_inv alpha) + V` and its
//! derivatives unexpanded, and the flow as the products
//! `xdot = Jbar dHbar/dx + Bbar u`, `y = Bbar^T dHbar/dx` of the exact
//! gradient's expressions (Duindam & Stramigioli, Theorem 1; MATH.md 3).

use super::{Exact, Forms};
use crate::model::Model;
use crate::sym::{ExprMatrix, MatrixError, Rational, SymbolId};

impl Exact {
    /// The exact matrices as expressions, the energy `1/2 alpha . (gbar_inv
    /// alpha) + V` and its derivatives unexpanded, and the flow as the
    /// products `Jbar dHbar/dx + Bbar u`, `Bbar^T dHbar/dx` of the exact
    /// gradient's expressions.
    pub fn forms(
        &self,
        model: &mut Model,
        momenta: &[SymbolId],
        inputs: &[SymbolId],
    ) -> Result<Forms, MatrixError> {
        let state = {
            let mut state = model.coordinate_symbols();
            state.extend(momenta);
            state
        };
        let store = &mut model.store;
        let alpha = ExprMatrix::column(momenta.iter().map(|&a| store.symbol(a)).collect());
        let u = ExprMatrix::column(inputs.iter().map(|&i| store.symbol(i)).collect());
        let metric_inverse = ExprMatrix::of(&self.metric_inverse, store);
        let twice_kinetic = alpha
            .transpose()
            .mul(&metric_inverse.mul(&alpha, store)?, store)?
            .get(0, 0);
        let half = store.number(Rational::HALF);
        let kinetic = store.mul2(half, twice_kinetic);
        let potential = store.expression_of(&model.potential_energy);
        let hamiltonian = store.add2(kinetic, potential);
        let gradient = state
            .iter()
            .map(|&x| store.derivative(hamiltonian, x))
            .collect();
        let exact_gradient = ExprMatrix::column(
            self.gradient
                .iter()
                .map(|g| store.expression_of(g))
                .collect(),
        );
        let structure = ExprMatrix::of(&self.structure, store);
        let input_matrix = ExprMatrix::of(&self.input_matrix, store);
        let rhs = structure
            .mul(&exact_gradient, store)?
            .add(&input_matrix.mul(&u, store)?, store)?;
        let output = input_matrix.transpose().mul(&exact_gradient, store)?;
        Ok(Forms {
            velocity_map: ExprMatrix::of(&self.velocity_map, store),
            momentum_map: ExprMatrix::of(&self.momentum_map, store),
            metric: ExprMatrix::of(&self.metric, store),
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
