//! A model read from its text seen as the runtime's [`Dynamics`] at sizes
//! known at run time, for linearization and initial states without
//! recompiling: its engine runs the same programs the compiled items are
//! emitted from, `acceleration_jacobian` among them, so the Jacobians are
//! as exact as the compiled model's, and `holonomic_residual` and
//! `holonomic_jacobian` for the configuration constraints.

use super::{InterpretedModel, evaluated};
use chaplygin_runtime::linearize::{Dynamics, GroupFactor};
use chaplygin_runtime::nalgebra::{DMatrix, DVector};

impl Dynamics for InterpretedModel {
    fn coordinates(&self) -> Vec<String> {
        self.names().coordinates.clone()
    }

    fn constraints(&self) -> Vec<String> {
        self.names().constraints.clone()
    }

    fn holonomic(&self) -> Vec<String> {
        self.names().holonomic.clone()
    }

    fn inputs(&self) -> usize {
        self.sizes().p
    }

    fn symmetry(&self) -> Vec<GroupFactor> {
        self.symmetry().to_vec()
    }

    fn holonomic_residual(&self, q: &[f64]) -> DVector<f64> {
        DVector::from_vec(evaluated(self.call("holonomic_residual", &[q])))
    }

    fn holonomic_jacobian(&self, q: &[f64]) -> DMatrix<f64> {
        let h = self.names().holonomic.len();
        let jacobian = evaluated(self.call("holonomic_jacobian", &[q]));
        DMatrix::from_row_slice(h, q.len(), &jacobian)
    }

    fn mass_matrix(&self, q: &[f64]) -> DMatrix<f64> {
        let n = q.len();
        DMatrix::from_row_slice(n, n, &evaluated(self.mass_matrix(q)))
    }

    fn constraint_matrix(&self, q: &[f64]) -> DMatrix<f64> {
        let (n, c) = (q.len(), self.sizes().c);
        DMatrix::from_row_slice(c, n, &evaluated(self.constraint_matrix(q)))
    }

    fn acceleration(&self, q: &[f64], qdot: &[f64], u: &[f64]) -> DVector<f64> {
        DVector::from_vec(evaluated(self.acceleration(q, qdot, u)).0)
    }

    fn acceleration_jacobian(
        &self,
        q: &[f64],
        qdot: &[f64],
        u: &[f64],
    ) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>) {
        let (n, p) = (q.len(), u.len());
        let (by_q, by_qdot, by_u) = evaluated(self.acceleration_jacobian(q, qdot, u));
        (
            DMatrix::from_row_slice(n, n, &by_q),
            DMatrix::from_row_slice(n, n, &by_qdot),
            DMatrix::from_row_slice(n, p, &by_u),
        )
    }
}
