//! A `.model` file seen as the runtime's [`Dynamics`], for linearization
//! and initial states without recompiling: the interpreter runs the
//! same programs the compiled items are emitted from, `acceleration_jacobian`
//! among them, so the Jacobians are as exact as the compiled model's, and
//! `holonomic_residual` and `holonomic_jacobian` for the configuration
//! constraints.

use crate::interpreted::evaluated;
use chaplygin::runtime::linearize::{Dynamics, GroupFactor};
use chaplygin::runtime::nalgebra::{DMatrix, DVector};
use chaplygin_codegen::interpret::InterpretedModel;

/// An interpreted model seen as [`Dynamics`].
pub struct InterpretedDynamics(pub InterpretedModel);

impl Dynamics for InterpretedDynamics {
    fn coordinates(&self) -> Vec<String> {
        self.0.names().coordinates.clone()
    }

    fn constraints(&self) -> Vec<String> {
        self.0.names().constraints.clone()
    }

    fn holonomic(&self) -> Vec<String> {
        self.0.names().holonomic.clone()
    }

    fn inputs(&self) -> usize {
        self.0.sizes().p
    }

    fn symmetry(&self) -> Vec<GroupFactor> {
        self.0.symmetry().to_vec()
    }

    fn holonomic_residual(&self, q: &[f64]) -> DVector<f64> {
        DVector::from_vec(evaluated(self.0.call("holonomic_residual", &[q])))
    }

    fn holonomic_jacobian(&self, q: &[f64]) -> DMatrix<f64> {
        let h = self.0.names().holonomic.len();
        let jacobian = evaluated(self.0.call("holonomic_jacobian", &[q]));
        DMatrix::from_row_slice(h, q.len(), &jacobian)
    }

    fn mass_matrix(&self, q: &[f64]) -> DMatrix<f64> {
        let n = q.len();
        DMatrix::from_row_slice(n, n, &evaluated(self.0.mass_matrix(q)))
    }

    fn constraint_matrix(&self, q: &[f64]) -> DMatrix<f64> {
        let (n, c) = (q.len(), self.0.sizes().c);
        DMatrix::from_row_slice(c, n, &evaluated(self.0.constraint_matrix(q)))
    }

    fn acceleration(&self, q: &[f64], qdot: &[f64], u: &[f64]) -> DVector<f64> {
        DVector::from_vec(evaluated(self.0.acceleration(q, qdot, u)).0)
    }

    fn acceleration_jacobian(
        &self,
        q: &[f64],
        qdot: &[f64],
        u: &[f64],
    ) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>) {
        let (n, p) = (q.len(), u.len());
        let (by_q, by_qdot, by_u) = evaluated(self.0.acceleration_jacobian(q, qdot, u));
        (
            DMatrix::from_row_slice(n, n, &by_q),
            DMatrix::from_row_slice(n, n, &by_qdot),
            DMatrix::from_row_slice(n, p, &by_u),
        )
    }
}
