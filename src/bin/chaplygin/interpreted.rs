//! A `.model` file simulated without recompiling: its emitted functions run
//! through the IR interpreter (`chaplygin_codegen::interpret`), in the
//! reduced or the Lagrange-d'Alembert formulation with constant inputs.
//!
//! The interpreter evaluates the same straight-line programs the compiled
//! code is emitted from, so a `.model` file and the compiled model agree to
//! round-off.

use crate::formulation::Formulation;
use chaplygin::runtime::monitor::{gram_regularity, hadamard_ratio};
use chaplygin::runtime::nalgebra::DMatrix;
use chaplygin::runtime::simulate::Regularity;
use chaplygin_codegen::interpret::{CallError, InterpretedModel};

/// The interpreter failed on a call whose arguments the formulation sized
/// itself: a defect, reported instead of wrong numbers.
pub(crate) fn evaluated<T>(result: Result<T, CallError>) -> T {
    result.unwrap_or_else(|error| panic!("interpreted model: {error}"))
}

/// `(q, alpha)` or `(q, qdot)` split at `n`.
fn split(x: &[f64], n: usize) -> (&[f64], &[f64]) {
    x.split_at(n)
}

/// The reduced form `x = (q, alpha)` of an interpreted model.
pub struct InterpretedReduced {
    /// The model.
    pub model: InterpretedModel,
    /// The constant inputs.
    pub inputs: Vec<f64>,
}

/// The Lagrange-d'Alembert form `x = (q, qdot)` of an interpreted model.
pub struct InterpretedDalembert {
    /// The model.
    pub model: InterpretedModel,
    /// The constant inputs.
    pub inputs: Vec<f64>,
}

/// The largest `|A(q) qdot|`.
fn residual(model: &InterpretedModel, q: &[f64], qdot: &[f64]) -> f64 {
    evaluated(model.constraint_residual(q, qdot))
        .iter()
        .fold(0.0, |worst, r| worst.max(r.abs()))
}

impl Formulation for InterpretedReduced {
    fn state_names(&self) -> Vec<String> {
        let names = self.model.names();
        names
            .coordinates
            .iter()
            .chain(&names.momenta)
            .cloned()
            .collect()
    }

    fn input_names(&self) -> Vec<String> {
        self.model.names().inputs.clone()
    }

    fn rhs(&self, _t: f64, x: &[f64], xdot: &mut [f64]) {
        xdot.copy_from_slice(&evaluated(self.model.reduced_rhs(x, &self.inputs)));
    }

    fn jacobian(&self, _t: f64, x: &[f64], jacobian: &mut [f64]) {
        jacobian.copy_from_slice(&evaluated(self.model.reduced_rhs_jacobian(x, &self.inputs)));
    }

    fn energy(&self, x: &[f64]) -> f64 {
        evaluated(self.model.hamiltonian(x))
    }

    fn is_structured(&self) -> bool {
        true
    }

    fn structure(
        &self,
        _t: f64,
        x: &[f64],
        j: &mut [f64],
        gradient: &mut [f64],
        forcing: &mut [f64],
    ) {
        j.copy_from_slice(&evaluated(self.model.structure_matrix(x)));
        gradient.copy_from_slice(&evaluated(self.model.hamiltonian_gradient(x)));
        let b = evaluated(self.model.input_matrix(x));
        let p = self.inputs.len();
        for (i, f) in forcing.iter_mut().enumerate() {
            *f = (0..p).map(|l| b[i * p + l] * self.inputs[l]).sum();
        }
    }

    fn inputs(&self, _t: f64, _x: &[f64], inputs: &mut [f64]) {
        inputs.copy_from_slice(&self.inputs);
    }

    fn constraint_residual(&self, x: &[f64]) -> f64 {
        let (q, alpha) = split(x, self.model.sizes().n);
        residual(&self.model, q, &evaluated(self.model.velocities(q, alpha)))
    }

    /// `det[A; V^T]` over its rows' norms, as the compiled models' `regularity`.
    fn regularity(&self, x: &[f64]) -> Regularity {
        let sizes = self.model.sizes();
        let q = &x[..sizes.n];
        let mut rows = evaluated(self.model.constraint_matrix(q));
        for j in 0..sizes.k {
            let unit: Vec<f64> = (0..sizes.k).map(|i| f64::from(u8::from(i == j))).collect();
            rows.extend(evaluated(self.model.velocities(q, &unit)));
        }
        Regularity {
            quantity: chaplygin::runtime::simulate::REDUCED,
            value: hadamard_ratio(DMatrix::from_row_slice(sizes.n, sizes.n, &rows)),
            signed: true,
        }
    }
}

impl Formulation for InterpretedDalembert {
    fn state_names(&self) -> Vec<String> {
        let coordinates = &self.model.names().coordinates;
        let velocities = coordinates.iter().map(|q| format!("dot({q})"));
        coordinates.iter().cloned().chain(velocities).collect()
    }

    fn input_names(&self) -> Vec<String> {
        self.model.names().inputs.clone()
    }

    fn rhs(&self, _t: f64, x: &[f64], xdot: &mut [f64]) {
        let (q, qdot) = split(x, self.model.sizes().n);
        let (qddot, _) = evaluated(self.model.acceleration(q, qdot, &self.inputs));
        xdot[..q.len()].copy_from_slice(qdot);
        xdot[q.len()..].copy_from_slice(&qddot);
    }

    /// Central differences, as the compiled Lagrange-d'Alembert adapter.
    fn jacobian(&self, t: f64, x: &[f64], jacobian: &mut [f64]) {
        let d = x.len();
        let (mut plus, mut minus) = (vec![0.0; d], vec![0.0; d]);
        let mut shifted = x.to_vec();
        for j in 0..d {
            let step = f64::EPSILON.cbrt() * x[j].abs().max(1.0);
            shifted[j] = x[j] + step;
            self.rhs(t, &shifted, &mut plus);
            shifted[j] = x[j] - step;
            self.rhs(t, &shifted, &mut minus);
            shifted[j] = x[j];
            for i in 0..d {
                jacobian[i * d + j] = (plus[i] - minus[i]) / (2.0 * step);
            }
        }
    }

    fn energy(&self, x: &[f64]) -> f64 {
        let (q, qdot) = split(x, self.model.sizes().n);
        evaluated(self.model.energy(q, qdot))
    }

    fn is_structured(&self) -> bool {
        false
    }

    fn structure(&self, _t: f64, _x: &[f64], _j: &mut [f64], _g: &mut [f64], _f: &mut [f64]) {}

    fn inputs(&self, _t: f64, _x: &[f64], inputs: &mut [f64]) {
        inputs.copy_from_slice(&self.inputs);
    }

    fn constraint_residual(&self, x: &[f64]) -> f64 {
        let (q, qdot) = split(x, self.model.sizes().n);
        residual(&self.model, q, qdot)
    }

    /// The Hadamard ratio of `A g^-1 A^T`, as the compiled models'
    /// `constraint_regularity`.
    fn regularity(&self, x: &[f64]) -> Regularity {
        let sizes = self.model.sizes();
        let q = &x[..sizes.n];
        let (g, a) = (
            evaluated(self.model.mass_matrix(q)),
            evaluated(self.model.constraint_matrix(q)),
        );
        let (g, a) = (
            DMatrix::from_row_slice(sizes.n, sizes.n, &g),
            DMatrix::from_row_slice(sizes.c, sizes.n, &a),
        );
        Regularity {
            quantity: chaplygin::runtime::simulate::MULTIPLIERS,
            value: gram_regularity(g, &a),
            signed: false,
        }
    }
}
