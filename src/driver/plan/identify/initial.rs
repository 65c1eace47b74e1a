//! The initial state held to the model's constraints
//! ([`crate::driver::plan::initial`]): all of them, the fit's first state
//! being free, by `xi = (x_0, theta)`.
//!
//! Estimates that move along `c_0 = 0` only: the standard errors' initial
//! sensitivities are a basis `Z_0` of the null space of `dc_0/dxi` (the
//! tangent of `c_0 = 0` at the optimum), not the identity.

use super::Fit;
use crate::driver::plan::initial::{self, InitialTerms};
use crate::runtime::nalgebra::DMatrix;
use chaplygin_codegen::interpret::InterpretedModel;

/// The name of initial constraint `row`.
pub(super) fn initial_row_name(model: &InterpretedModel, row: usize) -> String {
    initial::row_name(model, &initial::declared(model), row)
}

/// The number of initial constraints `model` declares.
pub(super) fn initial_rows(model: &InterpretedModel) -> usize {
    initial::rows(model, &initial::declared(model))
}

impl Fit {
    /// The initial constraints' rows come after the defects'.
    pub(super) fn defects(&self) -> usize {
        (self.times.len() - 1) * self.state()
    }

    /// `c_0` and its derivatives at `xi = (x_0, theta)`, the model's
    /// estimated parameters set to `theta`.
    pub(super) fn initial_terms(&self, model: &InterpretedModel, x0: &[f64]) -> InitialTerms {
        let held = initial::declared(model);
        initial::initial_terms(model, &held, (x0, self.state()), &self.indices)
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
