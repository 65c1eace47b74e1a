//! Linearizations for `chaplygin.Model.linearize`: one steady motion, or
//! a sweep with its intervals of asymptotic and neutral stability, as
//! NumPy arrays.

use crate::convert::{matrix, to_python};
use chaplygin::driver::linearize::{self, sweep::Interval};
use chaplygin::driver::setup::Setup;
use chaplygin::runtime::linearize::LinearSystem;
use chaplygin::runtime::nalgebra::DMatrix;
use numpy::{Complex64, PyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The eigenvalues of `linear` as complex numbers.
fn eigenvalues(linear: &LinearSystem) -> Vec<Complex64> {
    let values = linear.eigenvalues.iter();
    values.map(|e| Complex64::new(e.re, e.im)).collect()
}

/// The linear system about the point of `setup`: its state's names, `A`, `B`,
/// the eigenvalues by descending real part, and whether the motion is
/// asymptotically and neutrally stable modulo the zeros of conserved
/// quantities.
pub fn at_point<'py>(py: Python<'py>, setup: &Setup) -> PyResult<Bound<'py, PyDict>> {
    let linear =
        linearize::linearize_at(setup, &[], &[]).map_err(|error| to_python(py, error.into()))?;
    let result = PyDict::new(py);
    result.set_item("state", linear.state.clone())?;
    result.set_item("a", matrix(py, row_major(&linear.a), linear.a.ncols())?)?;
    result.set_item("b", matrix(py, row_major(&linear.b), linear.b.ncols())?)?;
    result.set_item("eigenvalues", PyArray1::from_vec(py, eigenvalues(&linear)))?;
    let conserved = linear.conserved_zeros();
    result.set_item("conserved", conserved)?;
    result.set_item("stable", linear.is_stable_modulo(conserved))?;
    result.set_item("neutral", linear.is_neutral_modulo(conserved))?;
    Ok(result)
}

/// The entries of `m`, row by row.
fn row_major(m: &DMatrix<f64>) -> Vec<f64> {
    m.transpose().as_slice().to_vec()
}

/// The refined ends of `intervals`.
fn refined(intervals: &[Interval]) -> Vec<(f64, f64)> {
    intervals.iter().map(|interval| interval.refined).collect()
}

/// The point of `setup` linearized at each of `values` of `variable`: the
/// values, the eigenvalues (one row per value, by descending real part),
/// the intervals of asymptotic and neutral stability (ends refined by
/// bisection), and the zeros of conserved quantities discounted.
pub fn over_sweep<'py>(
    py: Python<'py>,
    setup: &Setup,
    (variable, values): (&str, &[f64]),
) -> PyResult<Bound<'py, PyDict>> {
    let analysis = py
        .detach(|| linearize::sweep(setup, (variable, values)))
        .map_err(|error| to_python(py, error.into()))?;
    let result = PyDict::new(py);
    result.set_item("variable", &analysis.variable)?;
    result.set_item(
        "state",
        analysis.systems.first().map(|linear| linear.state.clone()),
    )?;
    result.set_item("values", PyArray1::from_slice(py, &analysis.values))?;
    let modes = analysis
        .systems
        .first()
        .map_or(0, |linear| linear.eigenvalues.len());
    let rows = analysis.systems.iter().flat_map(eigenvalues).collect();
    result.set_item("eigenvalues", matrix(py, rows, modes)?)?;
    result.set_item("conserved", analysis.conserved)?;
    result.set_item("stable", refined(&analysis.stable))?;
    result.set_item("neutral", refined(&analysis.neutral))?;
    Ok(result)
}
