//! Python values to the driver's and back: keyword dictionaries to
//! assignments, array arguments to vectors, errors to the package's
//! exceptions.

use chaplygin::driver::document::Rejected;
use numpy::{
    AllowTypeChange, Element, PyArray1, PyArray2, PyArrayLikeDyn, PyArrayMethods,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::error::Error;

/// An array argument as `numpy.asarray(value, dtype=float)` reads it: a
/// list, a tuple, a scalar, an array of any dtype that converts to float
/// and of any strides.
pub type ArrayLike<'py> = PyArrayLikeDyn<'py, f64, AllowTypeChange>;

/// The entries of an array argument, row-major, and its shape. An array
/// whose data are not aligned for `f64` (as one a cluster sent may be) is
/// copied first: a view needs them aligned.
pub fn array_entries(array: &ArrayLike<'_>) -> PyResult<(Vec<f64>, Vec<usize>)> {
    let align = std::mem::align_of::<f64>();
    let aligned = (array.data() as usize).is_multiple_of(align)
        && (array.strides().iter()).all(|stride| stride.unsigned_abs().is_multiple_of(align));
    if !aligned {
        let copy: ArrayLike<'_> = array.as_any().call_method0("copy")?.extract()?;
        return array_entries(&copy);
    }
    let view = array.as_array();
    Ok((view.iter().copied().collect(), view.shape().to_vec()))
}

/// The entries of the array argument `name`: one-dimensional, or a scalar
/// for one entry.
pub fn flat(array: &ArrayLike<'_>, name: &str) -> PyResult<Vec<f64>> {
    let (values, lengths) = array_entries(array)?;
    if lengths.len() > 1 {
        return Err(PyValueError::new_err(format!(
            "{name} must be one-dimensional; it has shape {}",
            shape(&lengths)
        )));
    }
    Ok(values)
}

/// The entries of the array argument `name`, which must be `expected`
/// (`what` they are, for the message).
pub fn vector(
    array: &ArrayLike<'_>,
    name: &str,
    expected: usize,
    what: &str,
) -> PyResult<Vec<f64>> {
    let values = flat(array, name)?;
    if values.len() != expected {
        return Err(PyValueError::new_err(format!(
            "{name} must have shape ({expected},), {what}; it has shape {}",
            shape(array.shape())
        )));
    }
    Ok(values)
}

/// A shape as NumPy prints it: `()`, `(7,)`, `(2, 3)`.
pub fn shape(lengths: &[usize]) -> String {
    match lengths {
        [length] => format!("({length},)"),
        _ => {
            let lengths: Vec<String> = lengths.iter().map(usize::to_string).collect();
            format!("({})", lengths.join(", "))
        }
    }
}

/// `{name: value}` with values numbers, expressions (strings) or lists of
/// them (`"omega(F)": [wx, wy, wz]`), as `NAME=EXPRESSION` assignments (a
/// number as the decimal that reads back to it exactly, a list as
/// `[a, b, c]`); `None` is none.
pub fn assignments(values: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, String)>> {
    entries(values, |name, value| {
        match value.extract::<Vec<Bound<'_, PyAny>>>() {
            Ok(entries) if value.extract::<String>().is_err() => {
                let texts = (entries.iter())
                    .map(|entry| assignment(name, entry))
                    .collect::<PyResult<Vec<String>>>()?;
                Ok(format!("[{}]", texts.join(", ")))
            }
            _ => assignment(name, value),
        }
    })
}

/// A number or an expression as the text of an assignment.
fn assignment(name: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    match value.extract::<String>() {
        Ok(text) => Ok(text),
        Err(_) => finite(name, value).map(|number| format!("{number}")),
    }
}

/// `{name: number}` as `NAME=VALUE` assignments; `None` is none.
pub fn numbers(values: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, f64)>> {
    entries(values, finite)
}

/// Each `(name, read(name, value))` of the dictionary `values`; `None` is
/// none.
fn entries<T>(
    values: Option<&Bound<'_, PyDict>>,
    read: impl Fn(&str, &Bound<'_, PyAny>) -> PyResult<T>,
) -> PyResult<Vec<(String, T)>> {
    let Some(values) = values else {
        return Ok(Vec::new());
    };
    values
        .iter()
        .map(|(name, value)| {
            let name: String = name.extract()?;
            let read = read(&name, &value)?;
            Ok((name, read))
        })
        .collect()
}

/// The value given for `name` as a finite number.
fn finite(name: &str, value: &Bound<'_, PyAny>) -> PyResult<f64> {
    let number: f64 = value.extract().map_err(|_| {
        PyTypeError::new_err(format!(
            "{name}: expected a number or an expression (a string)"
        ))
    })?;
    match number.is_finite() {
        true => Ok(number),
        false => Err(PyValueError::new_err(format!(
            "{name}: {number} is not finite"
        ))),
    }
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
