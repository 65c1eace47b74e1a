//! Design points for `chaplygin.design_map`: at each row of values of some
//! parameters, the self-stable speeds of a steady motion and where it
//! gains or loses an unstable mode (`chaplygin::driver::design_map`), on
//! rayon's threads with the GIL released.

use crate::convert::{ArrayLike, array_entries, shape};
use chaplygin::driver::design_map::{self, Motion, Run};
use chaplygin::driver::linearize::{LinearizeError, Stability};
use chaplygin_codegen::interpret::InterpretedModel;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::sync::atomic::AtomicBool;

/// The rows of the 2-D array argument `points`, each of `columns` values.
pub fn rows(points: &ArrayLike<'_>, columns: usize) -> PyResult<Vec<Vec<f64>>> {
    let (values, lengths) = array_entries(points)?;
    match lengths[..] {
        [_, width] if width == columns && columns > 0 => {
            Ok(values.chunks(columns).map(<[f64]>::to_vec).collect())
        }
        _ => Err(PyValueError::new_err(format!(
            "points must have shape (n, {columns}), a row of values of the parameters varied; \
             it has shape {}",
            shape(&lengths)
        ))),
    }
}

/// At each of `points` (values of the parameters `names`), the stability
/// of `motion` over its speeds, computed on `jobs` threads (every core by
/// default) with the GIL released: a list with, per point, a dict of
/// `intervals` (`(from, to)` pairs), `changes` (`(speed, before, after)`
/// counts of unstable modes) and `failure` (`None`, or why the point
/// could not be linearized).
pub fn stability_at<'py>(
    py: Python<'py>,
    model: &InterpretedModel,
    (names, points): (&[String], &[Vec<f64>]),
    motion: Motion<'_>,
    jobs: Option<usize>,
) -> PyResult<Bound<'py, PyList>> {
    let stop = AtomicBool::new(false);
    let run = Run {
        jobs,
        done: &|| {},
        stop: &stop,
    };
    let found = py
        .detach(|| design_map::stability_at(model, names, points, motion, &run))
        .map_err(|error| PyValueError::new_err(error.to_string()))?;
    let list = PyList::empty(py);
    for result in found {
        list.append(point(py, result)?)?;
    }
    Ok(list)
}

/// One design point's result as a dict.
fn point<'py>(
    py: Python<'py>,
    result: Option<Result<Stability, LinearizeError>>,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    match result {
        Some(Ok(stability)) => {
            let intervals: Vec<(f64, f64)> = stability.stable.iter().map(|i| i.refined).collect();
            let changes: Vec<(f64, usize, usize)> = (stability.changes.iter())
                .map(|change| (change.value, change.counts.0, change.counts.1))
                .collect();
            dict.set_item("intervals", intervals)?;
            dict.set_item("changes", changes)?;
            dict.set_item("failure", py.None())?;
        }
        Some(Err(error)) => {
            dict.set_item("intervals", Vec::<(f64, f64)>::new())?;
            dict.set_item("changes", Vec::<(f64, usize, usize)>::new())?;
            dict.set_item("failure", error.to_string())?;
        }
        None => dict.set_item("failure", "not computed")?,
    }
    Ok(dict)
}
