//! Python values to the driver's and back: keyword dictionaries to
//! assignments, errors to the package's exceptions.

use chaplygin::driver::document::Rejected;
use numpy::{Element, PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::error::Error;

/// `{name: value}` with values numbers or expressions (strings), as
/// `NAME=EXPRESSION` assignments; `None` is none.
pub fn assignments(values: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, String)>> {
    let Some(values) = values else {
        return Ok(Vec::new());
    };
    values
        .iter()
        .map(|(name, value)| {
            let name: String = name.extract()?;
            let text = match value.extract::<String>() {
                Ok(text) => text,
                Err(_) => number_text(
                    &name,
                    value.extract::<f64>().map_err(|_| not_a_value(&name))?,
                )?,
            };
            Ok((name, text))
        })
        .collect()
}

/// `{name: number}` as `NAME=VALUE` assignments; `None` is none.
pub fn numbers(values: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, f64)>> {
    let Some(values) = values else {
        return Ok(Vec::new());
    };
    values
        .iter()
        .map(|(name, value)| {
            let name: String = name.extract()?;
            let number: f64 = value.extract().map_err(|_| not_a_value(&name))?;
            if !number.is_finite() {
                return Err(PyValueError::new_err(format!(
                    "{name}: {number} is not finite"
                )));
            }
            Ok((name, number))
        })
        .collect()
}

/// A finite number as an expression that reads back to it exactly.
fn number_text(name: &str, number: f64) -> PyResult<String> {
    if !number.is_finite() {
        return Err(PyValueError::new_err(format!(
            "{name}: {number} is not finite"
        )));
    }
    Ok(format!("{number}"))
}

fn not_a_value(name: &str) -> PyErr {
    PyTypeError::new_err(format!(
        "{name}: expected a number or an expression (a string)"
    ))
}

/// An exception class of `chaplygin._errors`.
fn exception_class<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("chaplygin._errors")?.getattr(name)
}

/// `error` as a Python exception: a rejected model as
/// `chaplygin.ModelError` (its line, column and message), anything else as
/// `ValueError` with its one-line description.
pub fn to_python(py: Python<'_>, error: Box<dyn Error>) -> PyErr {
    match error.downcast::<Rejected>() {
        Ok(rejected) => model_error(py, &rejected),
        Err(error) => PyValueError::new_err(error.to_string()),
    }
}

/// `chaplygin.ModelError` of a rejected model.
pub fn model_error(py: Python<'_>, rejected: &Rejected) -> PyErr {
    let raised = exception_class(py, "ModelError").and_then(|class| {
        class.call1((
            rejected.rendered.clone(),
            rejected.line,
            rejected.column,
            rejected.message.clone(),
        ))
    });
    match raised {
        Ok(exception) => PyErr::from_value(exception),
        Err(error) => error,
    }
}

/// `values` (row-major, `columns` to a row) as a 2-D array.
pub fn matrix<T: Element>(
    py: Python<'_>,
    values: Vec<T>,
    columns: usize,
) -> PyResult<Bound<'_, PyArray2<T>>> {
    let rows = values.len().checked_div(columns).unwrap_or(0);
    PyArray1::from_vec(py, values).reshape([rows, columns])
}
