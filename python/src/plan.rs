//! `chaplygin.Model.plan` (native part): the plan a request asks of a
//! model (`chaplygin::driver::plan`, the one library API the command line
//! also runs), solved with the GIL released; Ctrl-C (a pending
//! `KeyboardInterrupt`) stops the solve at its next iteration and raises.

use crate::convert::{matrix, to_python};
use chaplygin::driver::engine::Loaded;
use chaplygin::driver::plan::nlp::Ripopt;
use chaplygin::driver::plan::{self, Request, Scheme};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::ops::ControlFlow;

/// The scheme called `name`.
pub fn scheme_named(name: &str) -> PyResult<Scheme> {
    (Scheme::ALL.iter().copied())
        .find(|scheme| scheme.name() == name)
        .ok_or_else(|| {
            let names: Vec<&str> = Scheme::ALL.iter().map(|scheme| scheme.name()).collect();
            PyValueError::new_err(format!(
                "unknown scheme `{name}` (schemes: {})",
                names.join(", ")
            ))
        })
}

/// The verified plan `request` asks of `loaded`: a dict of its `columns`,
/// `data` (one row per node) and `report` (`plan.json`'s text).
///
/// # Errors
/// `ValueError` for bad input or an answer that is not a verified
/// optimum; `KeyboardInterrupt` where Ctrl-C stops the solve.
pub fn plan<'py>(
    py: Python<'py>,
    loaded: Loaded,
    request: &Request,
) -> PyResult<Bound<'py, PyDict>> {
    let mut signal = None;
    let mut observer = |_: &plan::nlp::Iteration| match Python::attach(|py| py.check_signals()) {
        Ok(()) => ControlFlow::Continue(()),
        Err(error) => {
            signal = Some(error);
            ControlFlow::Break(())
        }
    };
    let planned =
        py.detach(|| plan::plan_watched(loaded, request, &Ripopt::default(), &mut observer));
    if let Some(signal) = signal {
        return Err(signal);
    }
    let planned = planned.map_err(|error| to_python(py, error))?;
    let result = PyDict::new(py);
    let values = planned.table.rows.iter().flatten().copied().collect();
    result.set_item("columns", planned.table.columns.clone())?;
    result.set_item("data", matrix(py, values, planned.table.columns.len())?)?;
    result.set_item("report", planned.report.to_json().to_string())?;
    Ok(result)
}
