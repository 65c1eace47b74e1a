//! `chaplygin._chaplygin`, the native module of the `chaplygin` Python
//! package (docs/INTERFACE.md section 8): a thin binding over
//! `chaplygin::driver`, the engine the command line runs. A model is read
//! from its text (a built-in's or a `.model` file's), its programs compiled
//! to native code at run time (the interpreter where Cranelift does not
//! support the host); it simulates, linearizes, maps stability over
//! designs and evaluates its right-hand sides, NumPy arrays in and out. The Python layer
//! (`chaplygin/__init__.py`) wraps what this module returns into
//! `Trajectory` and `Linearization` objects, raises `SimulationError`, and
//! turns the derivation document into SymPy expressions.

mod convert;
mod design;
mod linearization;
mod model;
mod plan;
mod rhs;

use chaplygin::driver::catalog::{self, BUILT_IN, Source};
use chaplygin::driver::engine::EngineChoice;
use model::Model;
use pyo3::exceptions::{PyFileNotFoundError, PyValueError};
use pyo3::prelude::*;
use std::path::Path;

/// The names of the built-in models.
#[pyfunction]
fn builtins() -> Vec<&'static str> {
    BUILT_IN.iter().map(|model| model.name).collect()
}

/// The built-in model called `name`, derived from its text, its programs
/// run by `engine` (`"jit"` or `"interpret"`).
#[pyfunction]
#[pyo3(signature = (name, engine = "jit"))]
fn builtin(py: Python<'_>, name: &str, engine: &str) -> PyResult<Model> {
    let built_in = catalog::built_in(name).ok_or_else(|| {
        PyValueError::new_err(format!(
            "unknown built-in model `{name}` (built-ins: {})",
            catalog::names()
        ))
    })?;
    Model::load(py, Source::BuiltIn(built_in), engine_named(engine)?)
}

/// The model of a `.model` file at `path_or_text`, or of the model text
/// itself (any text with a `{`), derived, its programs run by `engine`.
#[pyfunction]
#[pyo3(signature = (path_or_text, engine = "jit"))]
fn load(py: Python<'_>, path_or_text: &str, engine: &str) -> PyResult<Model> {
    let engine = engine_named(engine)?;
    let path = Path::new(path_or_text);
    let source = if !path_or_text.contains('{') && path.is_file() {
        let text = std::fs::read_to_string(path)?;
        Source::File {
            path: path_or_text.to_string(),
            text,
        }
    } else if path_or_text.contains('{') {
        Source::File {
            path: "<string>".to_string(),
            text: path_or_text.to_string(),
        }
    } else {
        return Err(PyFileNotFoundError::new_err(format!(
            "no .model file at `{path_or_text}` (give a path, or the model text itself)"
        )));
    };
    Model::load(py, source, engine)
}

/// `"jit"` or `"interpret"`.
fn engine_named(name: &str) -> PyResult<EngineChoice> {
    match name {
        "jit" => Ok(EngineChoice::Jit),
        "interpret" => Ok(EngineChoice::Interpret),
        _ => Err(PyValueError::new_err(format!(
            "unknown engine `{name}` (engines: jit, interpret)"
        ))),
    }
}

#[pymodule]
fn _chaplygin(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add_function(wrap_pyfunction!(builtins, module)?)?;
    module.add_function(wrap_pyfunction!(builtin, module)?)?;
    module.add_function(wrap_pyfunction!(load, module)?)?;
    module.add_class::<Model>()?;
    module.add_class::<rhs::Rhs>()?;
    Ok(())
}
