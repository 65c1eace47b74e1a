//! `chaplygin.Rhs`: one formulation's right-hand side `f(t, x, u)` and its
//! Jacobian `df/dx`, for `scipy.integrate.solve_ivp` and other integrators
//! of the caller's choice.

use crate::convert::{assignments, matrix, to_python};
use chaplygin::driver::simulate::Prepared;
use numpy::{PyArray1, PyArray2, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The right-hand side `f(t, x, u=None)` of one formulation of a model,
/// the inputs from its input laws unless `u` is given; `jacobian(t, x,
/// u=None)` is `df/dx` (exact for the reduced form, central differences
/// for the others, as the simulator's).
#[pyclass(unsendable, module = "chaplygin._chaplygin")]
pub struct Rhs {
    prepared: Prepared,
}

impl Rhs {
    /// The right-hand side of `prepared`.
    pub fn new(prepared: Prepared) -> Self {
        Self { prepared }
    }

    /// `x` checked against the state's size.
    fn checked_state<'a>(&self, x: &'a PyReadonlyArray1<'_, f64>) -> PyResult<&'a [f64]> {
        let x = x.as_slice()?;
        let d = self.prepared.x0.len();
        if x.len() != d {
            return Err(PyValueError::new_err(format!(
                "the state has {d} entries, x has {}",
                x.len()
            )));
        }
        Ok(x)
    }

    /// `u` checked against the number of inputs.
    fn inputs(&self, u: Option<&PyReadonlyArray1<'_, f64>>) -> PyResult<Option<Vec<f64>>> {
        let Some(u) = u else {
            return Ok(None);
        };
        let u = u.as_slice()?;
        let p = self.prepared.input_count();
        if u.len() != p {
            return Err(PyValueError::new_err(format!(
                "the model has {p} inputs, u has {}",
                u.len()
            )));
        }
        Ok(Some(u.to_vec()))
    }
}

#[pymethods]
impl Rhs {
    /// `f(t, x)` with the inputs `u` (the input laws' if `None`).
    #[pyo3(signature = (t, x, u = None))]
    fn __call__<'py>(
        &self,
        py: Python<'py>,
        t: f64,
        x: PyReadonlyArray1<'py, f64>,
        u: Option<PyReadonlyArray1<'py, f64>>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let x = self.checked_state(&x)?;
        let u = self.inputs(u.as_ref())?;
        let mut xdot = vec![0.0; x.len()];
        self.prepared
            .with_inputs(u.as_deref(), |formulation| formulation.rhs(t, x, &mut xdot));
        Ok(PyArray1::from_vec(py, xdot))
    }

    /// `df/dx` at `(t, x)` with the inputs `u` (the input laws' if
    /// `None`), a `(d, d)` array.
    #[pyo3(signature = (t, x, u = None))]
    fn jacobian<'py>(
        &self,
        py: Python<'py>,
        t: f64,
        x: PyReadonlyArray1<'py, f64>,
        u: Option<PyReadonlyArray1<'py, f64>>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let x = self.checked_state(&x)?;
        let u = self.inputs(u.as_ref())?;
        let d = x.len();
        let mut jacobian = vec![0.0; d * d];
        self.prepared.with_inputs(u.as_deref(), |formulation| {
            formulation.jacobian(t, x, &mut jacobian);
        });
        matrix(py, jacobian, d)
    }

    /// The names of the state's entries.
    #[getter]
    fn state(&self) -> Vec<String> {
        self.prepared.formulation.state_names()
    }

    /// The energy `H(x)`.
    fn energy(&self, x: PyReadonlyArray1<'_, f64>) -> PyResult<f64> {
        Ok(self.prepared.formulation.energy(self.checked_state(&x)?))
    }

    /// A consistent state from the model's defaults and `initial`
    /// (`{name: value or expression}` of coordinates and velocities
    /// `dot(q)`, the velocities not given solved from the constraints).
    #[pyo3(signature = (initial = None))]
    fn initial_state<'py>(
        &self,
        py: Python<'py>,
        initial: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let given = assignments(initial)?;
        let x = self
            .prepared
            .initial_state(&given)
            .map_err(|error| to_python(py, error))?;
        Ok(PyArray1::from_vec(py, x))
    }
}
