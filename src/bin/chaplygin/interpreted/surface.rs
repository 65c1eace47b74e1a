//! An interpreted model kept on its configuration constraints `f(q) = 0`
//! after each step, as `chaplygin::runtime::projection::Surface` keeps a
//! compiled one: the configuration onto `f(q) = 0` (Newton's minimum-norm
//! updates, `projection::configuration`), then the velocity onto
//! `ker A(q)` at the projected configuration in the kinetic-energy metric
//! (`projection::velocity`). Each formulation rebuilds the rest of its
//! state from the projected `(q, qdot)`.

use crate::interpreted::evaluated;
use chaplygin::runtime::nalgebra::{DMatrix, DVector, Dyn};
use chaplygin::runtime::projection::{self, ProjectionError, Settings};
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
/// then `qdot` onto `ker A(q)` there.
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
    Ok(())
}
