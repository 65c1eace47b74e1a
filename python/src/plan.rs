//! `chaplygin.Model.plan` and `chaplygin.Model.identify` (native part):
//! the plan or estimate a request asks of a model
//! (`chaplygin::driver::plan`, the one library API the command line also
//! runs), solved with the GIL released; Ctrl-C (a pending
//! `KeyboardInterrupt`) stops the solve at its next iteration and raises,
//! and raises as the call returns where it came after the last iteration.

use crate::convert::{matrix, to_python};
use chaplygin::driver::Failure;
use chaplygin::driver::engine::Loaded;
use chaplygin::driver::plan::identify::{self, Request as IdentifyRequest};
use chaplygin::driver::plan::nlp::{Iteration, Observer, Ripopt};
use chaplygin::driver::plan::{self, Request, Scheme};
use chaplygin::runtime::record::Table;
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

/// What `solve` returns, run with the GIL released and an observer that
/// stops it where Ctrl-C is pending.
///
/// # Errors
/// `KeyboardInterrupt` where Ctrl-C came during the call; `ValueError` for
/// the solve's own failure.
fn interruptible<T: Send>(
    py: Python<'_>,
    solve: impl FnOnce(&mut Observer<'_>) -> Result<T, Failure> + Send,
) -> PyResult<T> {
    let mut signal = None;
    let mut observer = |_: &Iteration| match Python::attach(|py| py.check_signals()) {
        Ok(()) => ControlFlow::Continue(()),
        Err(error) => {
            signal = Some(error);
            ControlFlow::Break(())
        }
    };
    let solved = py.detach(|| solve(&mut observer));
    if let Some(signal) = signal {
        return Err(signal);
    }
    // Ctrl-C after the solve's last iteration (while the answer is
    // verified) raises too, as the call returns.
    py.check_signals()?;
    solved.map_err(|error| to_python(py, error))
}

/// `table`'s `columns` and `data` (one row per node) set in `result`.
fn set_table(py: Python<'_>, result: &Bound<'_, PyDict>, table: &Table) -> PyResult<()> {
    let values = table.rows.iter().flatten().copied().collect();
    result.set_item("columns", table.columns.clone())?;
    result.set_item("data", matrix(py, values, table.columns.len())?)
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
    let planned = interruptible(py, |observer| {
        plan::plan_watched(loaded, request, &Ripopt::default(), observer)
    })?;
    let result = PyDict::new(py);
    set_table(py, &result, &planned.table)?;
    result.set_item("report", planned.report.to_json().to_string())?;
    Ok(result)
}

/// The verified estimate `request` asks of `loaded`, from `table` where
/// given (`request.data` naming it in messages), else from the CSV at
/// `request.data`: a dict of the fit's `columns` and `data` (one row per
/// node) and `report` (`estimate.json`'s text).
///
/// # Errors
/// `ValueError` for bad input or an answer that is not a verified
/// optimum; `KeyboardInterrupt` where Ctrl-C stops the solve.
pub fn identify<'py>(
    py: Python<'py>,
    loaded: Loaded,
    request: &IdentifyRequest,
    table: Option<&Table>,
) -> PyResult<Bound<'py, PyDict>> {
    let estimate = interruptible(py, |observer| {
        let solver = Ripopt::default();
        match table {
            Some(table) => identify::identify_table(loaded, request, table, &solver, observer),
            None => identify::identify_watched(loaded, request, &solver, observer),
        }
    })?;
    let result = PyDict::new(py);
    set_table(py, &result, &estimate.fit)?;
    result.set_item("report", estimate.to_json().to_string())?;
    Ok(result)
}
