//! `chaplygin.Rhs`: one formulation's right-hand side `f(t, x, u)` and its
//! Jacobian `df/dx`, for `scipy.integrate.solve_ivp` and other integrators
//! of the caller's choice.

use crate::convert::{ArrayLike, assignments, matrix, to_python, vector};
use chaplygin::driver::simulate::Prepared;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The right-hand side `f(t, x, u=None)` of one formulation of a model,
/// the inputs from its input laws unless `u` is given; `jacobian(t, x,
/// u=None)` is `df/dx` (exact in every form, a feedback law's `du/dx` by
/// central differences, as the simulator's).
#[pyclass(unsendable, module = "chaplygin._chaplygin")]
pub struct Rhs {
    prepared: Prepared,
}

impl Rhs {
    /// The right-hand side of `prepared`.
    pub fn new(prepared: Prepared) -> Self {
        Self { prepared }
    }

    /// The state `x`, checked against the state's size.
    fn state_of(&self, x: &ArrayLike<'_>) -> PyResult<Vec<f64>> {
        vector(x, "x", self.prepared.x0.len(), "the state's entries")
    }

    /// The inputs `u`, checked against their number; `None` if not given.
    fn inputs(&self, u: Option<&ArrayLike<'_>>) -> PyResult<Option<Vec<f64>>> {
        let count = self.prepared.input_count();
        u.map(|u| vector(u, "u", count, "one per input"))
            .transpose()
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
        x: ArrayLike<'py>,
        u: Option<ArrayLike<'py>>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let x = self.state_of(&x)?;
        let u = self.inputs(u.as_ref())?;
        let mut xdot = vec![0.0; x.len()];
        self.prepared.with_inputs(u.as_deref(), |formulation| {
            formulation.rhs(t, &x, &mut xdot)
        });
        Ok(PyArray1::from_vec(py, xdot))
    }

    /// `df/dx` at `(t, x)` with the inputs `u` (the input laws' if
    /// `None`), a `(d, d)` array.
    #[pyo3(signature = (t, x, u = None))]
    fn jacobian<'py>(
        &self,
        py: Python<'py>,
        t: f64,
        x: ArrayLike<'py>,
        u: Option<ArrayLike<'py>>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let x = self.state_of(&x)?;
        let u = self.inputs(u.as_ref())?;
        let d = x.len();
        let mut jacobian = vec![0.0; d * d];
        self.prepared.with_inputs(u.as_deref(), |formulation| {
            formulation.jacobian(t, &x, &mut jacobian);
        });
        matrix(py, jacobian, d)
    }

    /// The names of the state's entries.
    #[getter]
    fn state(&self) -> Vec<String> {
        self.prepared.formulation.state_names()
    }

    /// The energy `H(x)`.
    fn energy(&self, x: ArrayLike<'_>) -> PyResult<f64> {
        Ok(self.prepared.formulation.energy(&self.state_of(&x)?))
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
