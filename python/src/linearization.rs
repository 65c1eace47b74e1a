//! Linearizations for `chaplygin.Model.linearize`: one steady motion, or
//! a sweep with its intervals of asymptotic and neutral stability, as
//! NumPy arrays; and for `chaplygin.Model.steady`, a steady motion found
//! from unknowns of its point.

use crate::convert::{matrix, to_python};
use chaplygin::driver::linearize::{self, sweep::Interval};
use chaplygin::driver::setup::Setup;
use chaplygin::driver::steady::{self, Request, trace};
use chaplygin::runtime::linearize::{LinearSystem, point};
use chaplygin::runtime::nalgebra::DMatrix;
use chaplygin_codegen::interpret::InterpretedModel;
use numpy::{Complex64, PyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

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

/// The steady motion of `request` on `model` (`chaplygin.Model.steady`):
/// `values` (the unknowns, every coordinate and `dot(q)`, the inputs and,
/// with a planar symmetry, `radius`), `eigenvalues`, `stable`, the
/// linear system's `state`, the `family` directions (a list of
/// `{entry: coefficient}`), the Gauss-Newton `steps` and the `residual`.
pub fn steady_motion<'py>(
    py: Python<'py>,
    model: InterpretedModel,
    request: &Request<'_>,
) -> PyResult<Bound<'py, PyDict>> {
    let names = model.names().clone();
    let motion = py
        .detach(|| steady::steady(model, request))
        .map_err(|error| to_python(py, error.into()))?;
    let values = PyDict::new(py);
    for (name, value) in &motion.values {
        values.set_item(name, value)?;
    }
    let velocities = point::velocity_names(&names.coordinates);
    let state = (names.coordinates.iter().zip(&motion.point.q))
        .chain(velocities.iter().zip(&motion.point.qdot))
        .chain(names.inputs.iter().zip(&motion.inputs));
    for (name, value) in state {
        values.set_item(name, value)?;
    }
    if let Some(radius) = motion.radius {
        values.set_item("radius", radius)?;
    }
    let family = PyList::empty(py);
    for direction in &motion.family {
        let entries = PyDict::new(py);
        for (entry, coefficient) in direction {
            entries.set_item(entry, coefficient)?;
        }
        family.append(entries)?;
    }
    let result = PyDict::new(py);
    result.set_item("values", values)?;
    result.set_item(
        "eigenvalues",
        PyArray1::from_vec(py, eigenvalues(&motion.linear)),
    )?;
    result.set_item("stable", motion.stable())?;
    result.set_item("state", motion.linear.state.clone())?;
    result.set_item("family", family)?;
    result.set_item("steps", motion.steps)?;
    result.set_item("residual", motion.residual)?;
    Ok(result)
}

/// The family of `request` on `model` over `values` of `variable`
/// (`chaplygin.Model.steady(trace=...)`): `columns` (the variable, then
/// those of `chaplygin steady --trace`'s `steady.csv`), `data` (a row per
/// value crossed, in the family's order) and `report` (its folds, changes
/// of stability and end, as the command prints them).
pub fn steady_family<'py>(
    py: Python<'py>,
    model: InterpretedModel,
    request: &Request<'_>,
    (variable, values): (&str, &[f64]),
) -> PyResult<Bound<'py, PyDict>> {
    let names = model.names().clone();
    let columns = steady::Columns {
        coordinates: &names.coordinates,
        inputs: &names.inputs,
    };
    let problem = steady::problem(model, request).map_err(|error| to_python(py, error.into()))?;
    let family = py
        .detach(|| trace::trace(&problem, values))
        .map_err(|error| to_python(py, error.into()))?;
    let mut header = vec![variable.to_string()];
    let mut data = Vec::new();
    for row in &family.rows {
        if header.len() == 1 {
            header.extend(steady::header(&columns, &row.motion));
        }
        data.push(row.value);
        data.extend(steady::row(&columns, &row.motion));
    }
    let result = PyDict::new(py);
    result.set_item("data", matrix(py, data, header.len())?)?;
    result.set_item("columns", header)?;
    result.set_item("report", family.report(variable))?;
    Ok(result)
}
