//! An interpreted model kept on its configuration constraints `f(q) = 0`
//! after each step, as `crate::runtime::projection::Surface` keeps a
//! compiled one: the configuration onto `f(q) = 0` (Newton's minimum-norm
//! updates, `projection::configuration`), then the velocity onto
//! `ker A(q)` at the projected configuration in the kinetic-energy metric
//! (`projection::velocity`). Each formulation rebuilds the rest of its
//! state from the projected `(q, qdot)`.
//!
//! Moving `q` onto `f(q) = 0` changes the energy `E = T(q, qdot) + V(q)` by
//! `dE/dq . dq`, a little at every step: with the discrete gradient, which
//! conserves `E` to round-off between projections, this was the whole of
//! the drift. The projection therefore keeps the energy the step arrived
//! with, as a projection onto the manifold of all the invariants (Hairer,
//! Lubich & Wanner, *Geometric Numerical Integration*, 2nd ed., section
//! IV.4): the projected velocity, in `ker A(q)`, is scaled by
//! `s = sqrt((E - V(q)) / T(q, qdot))`, which stays in `ker A(q)` and
//! differs from 1 by the projection's own small change of `E`.

use super::evaluated;
use crate::runtime::nalgebra::{DMatrix, DVector, Dyn};
use crate::runtime::projection::{self, ProjectionError, Settings};
use chaplygin_codegen::interpret::InterpretedModel;

/// Whether `model` declares configuration constraints.
pub(crate) fn keeps_configuration(model: &InterpretedModel) -> bool {
    !model.names().holonomic.is_empty()
}

/// `max |f(q)|`, `None` without configuration constraints.
pub(crate) fn holonomic_residual(model: &InterpretedModel, q: &[f64]) -> Option<f64> {
    keeps_configuration(model).then(|| {
        evaluated(model.call("holonomic_residual", &[q]))
            .iter()
            .fold(0.0_f64, |worst, f| worst.max(f.abs()))
    })
}

/// `q` onto `f(q) = 0` (unchanged without configuration constraints),
/// then `qdot` onto `ker A(q)` there, at the energy it had.
///
/// # Errors
/// A configuration constraint Newton's method cannot meet, named with its
/// residual; a singular metric or constraint Gram matrix.
pub(crate) fn onto_surface(
    model: &InterpretedModel,
    q: &mut [f64],
    qdot: &mut [f64],
) -> Result<(), ProjectionError> {
    let sizes = model.sizes();
    let energy = evaluated(model.energy(q, qdot));
    if keeps_configuration(model) {
        let names: Vec<&str> = model.names().holonomic.iter().map(String::as_str).collect();
        let h = names.len();
        let constraint = |q: &DVector<f64>| {
            let q = q.as_slice();
            let jacobian = evaluated(model.call("holonomic_jacobian", &[q]));
            (
                DVector::from_vec(evaluated(model.call("holonomic_residual", &[q]))),
                DMatrix::from_row_slice(h, q.len(), &jacobian),
            )
        };
        let projected = projection::configuration::<Dyn, Dyn>(
            DVector::from_column_slice(q),
            constraint,
            &names,
            Settings::default(),
        )?;
        q.copy_from_slice(projected.as_slice());
    }
    let (g, a) = (
        evaluated(model.mass_matrix(q)),
        evaluated(model.constraint_matrix(q)),
    );
    let projected = projection::velocity(
        DMatrix::from_row_slice(sizes.n, sizes.n, &g),
        &DMatrix::from_row_slice(sizes.c, sizes.n, &a),
        &DVector::from_column_slice(qdot),
    )?;
    qdot.copy_from_slice(projected.as_slice());
    restore_energy(model, q, qdot, energy);
    Ok(())
}

/// `qdot` scaled so that the energy at `(q, qdot)` is `energy`, when a
/// positive scale does it (not at rest, nor above the energy).
fn restore_energy(model: &InterpretedModel, q: &[f64], qdot: &mut [f64], energy: f64) {
    let potential = evaluated(model.energy(q, &vec![0.0; q.len()]));
    let kinetic = evaluated(model.energy(q, qdot)) - potential;
    let squared_scale = (energy - potential) / kinetic;
    if kinetic > 0.0 && squared_scale > 0.0 {
        let scale = squared_scale.sqrt();
        qdot.iter_mut().for_each(|v| *v *= scale);
    }
}
