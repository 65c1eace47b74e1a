//! The state's second part at a plan's ends in a form whose state does
//! not hold the velocities (docs/INTERFACE.md section 13,
//! `--formulation`): the start and the goal name coordinates and
//! velocities `dot(q)`; the reduced state `(q, alpha)` holds the momenta,
//! `dot(q) = X(q) alpha`, the momentum equation's `(q, rdot, p)` the shape
//! velocities and the momenta, `dot(q) = g(q) xi(r, rdot, p)`. Both
//! velocities are linear in the state's second part `x2`.

use super::RequestError;
use crate::driver::plan::form::Form;
use crate::runtime::nalgebra::DMatrix;
use chaplygin_codegen::interpret::InterpretedModel;

/// The second part `x2` of the state that an end's conditions fix, from
/// its coordinates `q` (its first guess) and its given coordinates and
/// velocities (`None` where not given): none where no velocity is given;
/// 0 where the given ones are 0 and determine `x2` (their rows of `d
/// qdot / d x2` have full rank); the state of `(q, qdot)` where every
/// coordinate and velocity is given.
///
/// # Errors
/// [`RequestError::PartialVelocities`] for any other end.
pub(super) fn end_state(
    form: Form,
    model: &InterpretedModel,
    (flag, q): (&'static str, &[f64]),
    (given_q, given_qdot): (&[Option<f64>], &[Option<f64>]),
) -> Result<Option<Vec<f64>>, RequestError> {
    if given_qdot.iter().all(Option::is_none) {
        return Ok(None);
    }
    let n = model.sizes().n;
    let second = form.state(model) - n;
    let at_rest = given_qdot.iter().flatten().all(|v| *v == 0.0);
    if at_rest && determines_state(form, model, q, given_qdot) {
        return Ok(Some(vec![0.0; second]));
    }
    let (coordinates, velocities): (Vec<f64>, Vec<f64>) = (
        given_q.iter().flatten().copied().collect(),
        given_qdot.iter().flatten().copied().collect(),
    );
    if coordinates.len() == n && velocities.len() == n {
        return Ok(Some(
            form.state_of(model, &coordinates, &velocities).split_off(n),
        ));
    }
    let names = Form::Lagrange.state_names(model);
    let given = given_q.iter().chain(given_qdot);
    let missing: Vec<String> = (given.zip(names))
        .filter(|(v, _)| v.is_none())
        .map(|(_, name)| name)
        .collect();
    let (missing, form) = (missing.join(", "), form.name());
    Err(RequestError::PartialVelocities {
        flag,
        form,
        missing,
    })
}

/// Whether the `given` velocities' rows of `d qdot / d x2` at `q` have
/// full rank.
fn determines_state(
    form: Form,
    model: &InterpretedModel,
    q: &[f64],
    given: &[Option<f64>],
) -> bool {
    let second = form.state(model) - q.len();
    let rows: Vec<usize> = (0..given.len()).filter(|&i| given[i].is_some()).collect();
    let columns: Vec<Vec<f64>> = (0..second)
        .map(|j| {
            let unit = (0..second).map(|i| f64::from(u8::from(i == j)));
            let x: Vec<f64> = q.iter().copied().chain(unit).collect();
            form.velocities(model, &x)
        })
        .collect();
    let by_x2 = DMatrix::from_fn(rows.len(), second, |r, j| columns[j][rows[r]]);
    by_x2.rank(RANK_TOLERANCE) == second
}

/// The singular value below which `d qdot / d x2`'s given rows lose
/// rank, an absolute one: its entries are of order one in the catalog's
/// models.
const RANK_TOLERANCE: f64 = 1e-9;
