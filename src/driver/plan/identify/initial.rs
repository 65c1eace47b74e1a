//! The initial state held to the model's constraints: with `xi = (x_0,
//! theta)`,
//!
//! ```text
//! c_0(xi) = (f(q_0; theta), A(q_0; theta) qdot_0) = 0,
//! ```
//!
//! the configuration constraints (`holonomic_residual`, where the model
//! declares some) and the velocity constraints (`constraint_residual`).
//! The collocation keeps them after node 0: the formulation's
//! accelerations hold `d/dt (A qdot) = 0` and `d^2/dt^2 f = 0`. Their
//! values, Jacobian and Hessian by `xi` are the programs' own and their
//! forward second derivatives along the state's and the estimates' input
//! slots ([`chaplygin_codegen::ir::Program::curvatures`]), exact.
//!
//! Estimates that move along `c_0 = 0` only: the standard errors' initial
//! sensitivities are a basis `Z_0` of the null space of `dc_0/dxi` (the
//! tangent of `c_0 = 0` at the optimum), not the identity.

use super::Fit;
use crate::runtime::nalgebra::DMatrix;
use chaplygin_codegen::interpret::{InterpretedModel, evaluated};

/// The initial constraints at a point: their values, their Jacobian by
/// `xi` (rows x (2n + P)) and each one's Hessian by `xi`.
pub(super) struct InitialTerms {
    pub(super) values: Vec<f64>,
    pub(super) jacobian: DMatrix<f64>,
    pub(super) hessians: Vec<DMatrix<f64>>,
}

/// The number of initial constraints `model` declares.
pub(super) fn initial_rows(model: &InterpretedModel) -> usize {
    model.names().holonomic.len() + model.sizes().c
}

impl Fit {
    /// The initial constraints' rows come after the defects'.
    pub(super) fn defects(&self) -> usize {
        (self.times.len() - 1) * self.state()
    }

    /// `c_0` and its derivatives at `xi = (x_0, theta)`, the model's
    /// estimated parameters set to `theta`.
    pub(super) fn initial_terms(&self, model: &InterpretedModel, x0: &[f64]) -> InitialTerms {
        let (n, estimated) = (self.state() / 2, self.indices.len());
        let dim = 2 * n + estimated;
        let mut terms = InitialTerms {
            values: Vec::new(),
            jacobian: DMatrix::zeros(0, dim),
            hessians: Vec::new(),
        };
        if !model.names().holonomic.is_empty() {
            self.add_terms(model, "holonomic_residual", &x0[..n], &mut terms);
        }
        if model.sizes().c > 0 {
            self.add_terms(model, "constraint_residual", x0, &mut terms);
        }
        terms
    }

    /// Appends the rows of `function`, whose arguments are the first
    /// `arguments.len()` entries of the state.
    fn add_terms(
        &self,
        model: &InterpretedModel,
        function: &str,
        arguments: &[f64],
        terms: &mut InitialTerms,
    ) {
        let read = arguments.len();
        let program = model
            .programs()
            .find(|(name, _)| *name == function)
            .map(|(_, program)| program)
            .expect("a constrained model has its residual programs");
        let inputs: Vec<f64> = arguments
            .iter()
            .chain(model.parameter_values())
            .copied()
            .collect();
        let seeds: Vec<usize> = (0..read)
            .chain(self.indices.iter().map(|k| read + k))
            .collect();
        let curvatures = evaluated(program.curvatures(&inputs, &seeds).map_err(|source| {
            chaplygin_codegen::interpret::CallError::Program {
                function: function.to_string(),
                source,
            }
        }));
        let (d, dim, s) = (seeds.len(), terms.jacobian.ncols(), self.state());
        let column = |j: usize| if j < read { j } else { s + j - read };
        let values = &curvatures.tangents.values;
        let rows = terms.jacobian.nrows();
        terms.jacobian = terms
            .jacobian
            .clone()
            .resize_vertically(rows + values.len(), 0.0);
        for (i, value) in values.iter().enumerate() {
            terms.values.push(*value);
            let mut hessian = DMatrix::zeros(dim, dim);
            for j in 0..d {
                terms.jacobian[(rows + i, column(j))] = curvatures.tangents.derivatives[i * d + j];
                for l in 0..d {
                    hessian[(column(j), column(l))] = curvatures.second[(i * d + j) * d + l];
                }
            }
            terms.hessians.push(hessian);
        }
    }

    /// A basis of the null space of `dc_0/dxi` at `y` ((2n + P) x k), the
    /// identity without constraints.
    pub(super) fn initial_tangent(&self, y: &[f64]) -> DMatrix<f64> {
        let z = self.transcribed(y);
        let transcription = self.transcription.borrow();
        let terms = self.initial_terms(transcription.model(), &z[..self.state()]);
        let dim = terms.jacobian.ncols();
        if terms.values.is_empty() {
            return DMatrix::identity(dim, dim);
        }
        let gram = terms.jacobian.transpose() * &terms.jacobian;
        let eigen = gram.symmetric_eigen();
        let largest = eigen.eigenvalues.amax();
        let free: Vec<usize> = (0..dim)
            .filter(|&k| eigen.eigenvalues[k] <= largest * 1e-12)
            .collect();
        DMatrix::from_fn(dim, free.len(), |r, c| eigen.eigenvectors[(r, free[c])])
    }
}
