//! The reduced form's momenta at a plan's ends (docs/INTERFACE.md section
//! 13, `--formulation reduced`): the start and the goal name coordinates
//! and velocities `dot(q)`, the reduced state `(q, alpha)` holds the
//! momenta, `dot(q) = X(q) alpha`.

use super::RequestError;
use crate::driver::plan::reduced::{Form, momenta};
use crate::runtime::nalgebra::DMatrix;
use chaplygin_codegen::interpret::{InterpretedModel, evaluated};

/// The momenta an end's conditions fix, from its coordinates `q` (its
/// first guess) and its given coordinates and velocities (`None` where
/// not given): none where no velocity is given; 0 where the given ones
/// are 0 and determine `alpha` (their rows of `X(q)` have rank `k`);
/// `momenta(q, qdot)` where every coordinate and velocity is given.
///
/// # Errors
/// [`RequestError::ReducedVelocities`] for any other end.
pub(super) fn end_momenta(
    model: &InterpretedModel,
    (flag, q): (&'static str, &[f64]),
    (given_q, given_qdot): (&[Option<f64>], &[Option<f64>]),
) -> Result<Option<Vec<f64>>, RequestError> {
    if given_qdot.iter().all(Option::is_none) {
        return Ok(None);
    }
    let at_rest = given_qdot.iter().flatten().all(|v| *v == 0.0);
    if at_rest && determines_momenta(model, q, given_qdot) {
        return Ok(Some(vec![0.0; model.sizes().k]));
    }
    let (coordinates, velocities): (Vec<f64>, Vec<f64>) = (
        given_q.iter().flatten().copied().collect(),
        given_qdot.iter().flatten().copied().collect(),
    );
    let n = model.sizes().n;
    if coordinates.len() == n && velocities.len() == n {
        return Ok(Some(momenta(model, &coordinates, &velocities)));
    }
    let names = Form::Lagrange.state_names(model);
    let given = given_q.iter().chain(given_qdot);
    let missing: Vec<String> = (given.zip(names))
        .filter(|(v, _)| v.is_none())
        .map(|(_, name)| name)
        .collect();
    let missing = missing.join(", ");
    Err(RequestError::ReducedVelocities { flag, missing })
}

/// Whether the `given` velocities' rows of `X(q)` have rank `k`.
fn determines_momenta(model: &InterpretedModel, q: &[f64], given: &[Option<f64>]) -> bool {
    let k = model.sizes().k;
    let rows: Vec<usize> = (0..given.len()).filter(|&i| given[i].is_some()).collect();
    let columns: Vec<Vec<f64>> = (0..k)
        .map(|j| {
            let unit: Vec<f64> = (0..k).map(|i| f64::from(u8::from(i == j))).collect();
            evaluated(model.velocities(q, &unit))
        })
        .collect();
    let by_alpha = DMatrix::from_fn(rows.len(), k, |r, j| columns[j][rows[r]]);
    by_alpha.rank(RANK_TOLERANCE) == k
}

/// The singular value below which `X(q)`'s given rows lose rank, an
/// absolute one: `X`'s entries are of order one in the catalog's models.
const RANK_TOLERANCE: f64 = 1e-9;
