//! `chaplygin.Model` (native part): a model read from its text, its names
//! and parameters, and what it does: simulate, linearize, find steady
//! motions, plan inputs, estimate parameters, accelerate,
//! evaluate its right-hand sides, document its derivation.

use crate::convert::{
    ArrayLike, assignments, flat, matrix, model_error, numbers, to_python, vector,
};
use crate::design;
use crate::linearization;
use crate::plan;
use crate::rhs::Rhs;
use chaplygin::driver::animation;
use chaplygin::driver::catalog::Source;
use chaplygin::driver::design_map::Motion;
use chaplygin::driver::document::{self, Format};
use chaplygin::driver::engine::{self, EngineChoice, Loaded};
use chaplygin::driver::gait::{self, GaitRequest, OptimalGaitRequest};
use chaplygin::driver::plan::Request as PlanRequest;
use chaplygin::driver::plan::identify::Request as IdentifyRequest;
use chaplygin::driver::setup::{self, Asked, with_parameters};
use chaplygin::driver::simulate::{self, Controller, FormulationChoice, Integrator, Request};
use chaplygin::driver::steady::Request as SteadyRequest;
use chaplygin::gait_design::{Cost, Design, Direction};
use chaplygin::runtime::record::{Recorder, Table};
use chaplygin::runtime::simulate::SimulationError;
use chaplygin_codegen::interpret::Sizes;
use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::{PyRuntimeWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::ffi::CString;
use std::io;

/// A model read from its text (a built-in's or a `.model` file's), derived
/// exactly, its programs compiled to native code; shared between threads
/// (its native code is immutable once compiled).
#[pyclass(module = "chaplygin._chaplygin")]
pub struct Model {
    loaded: Loaded,
    source: Source,
}

impl Model {
    /// The model of `source`, its programs run by `engine`.
    pub fn load(py: Python<'_>, source: Source, engine: EngineChoice) -> PyResult<Self> {
        let loaded =
            engine::load(&source, engine).map_err(|rejected| model_error(py, &rejected))?;
        if let Some(error) = &loaded.fallback {
            let warning = py.get_type::<PyRuntimeWarning>();
            let message = CString::new(format!("{error}; running the interpreter"))?;
            PyErr::warn(py, &warning, &message, 1)?;
        }
        Ok(Self { loaded, source })
    }

    /// The loaded model, cloned: a run sets its own parameters.
    fn fresh(&self) -> Loaded {
        self.loaded.clone()
    }
}

/// A recorder that keeps nothing (the driver's own table keeps the rows).
struct Nowhere;

impl Recorder for Nowhere {
    fn start(&mut self, _columns: &[String]) -> io::Result<()> {
        Ok(())
    }

    fn record(&mut self, _row: &[f64]) -> io::Result<()> {
        Ok(())
    }

    fn finish(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// A table as `(columns, data)`.
fn table<'py>(
    py: Python<'py>,
    table: &Table,
) -> PyResult<(Vec<String>, Bound<'py, PyArray2<f64>>)> {
    let values = table.rows.iter().flatten().copied().collect();
    Ok((
        table.columns.clone(),
        matrix(py, values, table.columns.len())?,
    ))
}

/// The formulation called `name`.
fn formulation_named(name: &str) -> PyResult<FormulationChoice> {
    match name {
        "reduced" => Ok(FormulationChoice::Reduced),
        "lagrange" => Ok(FormulationChoice::Lagrange),
        "momentum" => Ok(FormulationChoice::Momentum),
        _ => Err(PyValueError::new_err(format!(
            "unknown formulation `{name}` (formulations: reduced, lagrange, momentum)"
        ))),
    }
}

/// The integrator called `name`.
fn integrator_named(name: &str) -> PyResult<Integrator> {
    Integrator::ALL
        .into_iter()
        .find(|integrator| integrator.name() == name)
        .ok_or_else(|| {
            let names: Vec<&str> = Integrator::ALL.iter().map(|i| i.name()).collect();
            PyValueError::new_err(format!(
                "unknown integrator `{name}` (integrators: {})",
                names.join(", ")
            ))
        })
}

/// The direction called `name`.
fn direction_named(name: &str) -> PyResult<Direction> {
    match name {
        "forward" => Ok(Direction::Forward),
        "lateral" => Ok(Direction::Lateral),
        "rotate" => Ok(Direction::Rotate),
        _ => Err(PyValueError::new_err(format!(
            "unknown direction `{name}` (directions: forward, lateral, rotate)"
        ))),
    }
}

/// The cost called `name`.
fn cost_named(name: &str) -> PyResult<Cost> {
    match name {
        "length" => Ok(Cost::Length),
        "none" => Ok(Cost::None),
        _ => Err(PyValueError::new_err(format!(
            "unknown cost `{name}` (costs: length, none)"
        ))),
    }
}

/// The controller called `name`.
fn controller_named(name: &str) -> PyResult<Controller> {
    match name {
        "none" => Ok(Controller::None),
        "energy" => Ok(Controller::Energy),
        _ => Err(PyValueError::new_err(format!(
            "unknown controller `{name}` (controllers: none, energy)"
        ))),
    }
}

/// A failed run's time, state and message, for `chaplygin.SimulationError`.
fn failure<'py>(
    py: Python<'py>,
    error: &(dyn std::error::Error + 'static),
) -> PyResult<Bound<'py, PyDict>> {
    let failure = PyDict::new(py);
    failure.set_item("message", error.to_string())?;
    let simulation = error.downcast_ref::<SimulationError>();
    failure.set_item("t", simulation.and_then(SimulationError::time))?;
    let state = simulation
        .and_then(SimulationError::state)
        .map(|state| PyArray1::from_slice(py, state));
    failure.set_item("state", state)?;
    Ok(failure)
}

#[pymethods]
impl Model {
    /// The built-in's name, or the file's path (`"<string>"` for text).
    #[getter]
    fn name(&self) -> &str {
        match self.loaded.built_in {
            Some(built_in) => built_in.name,
            None => &self.loaded.label,
        }
    }

    /// The coordinates `q`, in order.
    #[getter]
    fn coordinates(&self) -> Vec<String> {
        self.loaded.model.names().coordinates.clone()
    }

    /// The velocities `dot(q)`, in order.
    #[getter]
    fn velocities(&self) -> Vec<String> {
        let coordinates = &self.loaded.model.names().coordinates;
        coordinates.iter().map(|q| format!("dot({q})")).collect()
    }

    /// The inputs `u`, in order.
    #[getter]
    fn inputs(&self) -> Vec<String> {
        self.loaded.model.names().inputs.clone()
    }

    /// The velocity constraints (rows of `A(q)`), in order.
    #[getter]
    fn constraints(&self) -> Vec<String> {
        self.loaded.model.names().constraints.clone()
    }

    /// The configuration constraints `f(q) = 0`, in order.
    #[getter]
    fn holonomic(&self) -> Vec<String> {
        self.loaded.model.names().holonomic.clone()
    }

    /// The reduced momenta `alpha` (the momentum basis rows), in order.
    #[getter]
    fn momenta(&self) -> Vec<String> {
        self.loaded.model.names().momenta.clone()
    }

    /// The parameters and their default values.
    #[getter]
    fn parameters<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let parameters = PyDict::new(py);
        let model = &self.loaded.model;
        for (name, value) in model
            .names()
            .parameters
            .iter()
            .zip(model.parameter_values())
        {
            parameters.set_item(name, value)?;
        }
        Ok(parameters)
    }

    /// What runs the model's programs: `"jit"` or `"interpret"`.
    #[getter]
    fn engine(&self) -> &'static str {
        self.loaded.model.engine().name()
    }

    /// The derivation report.
    #[getter]
    fn report(&self) -> &str {
        self.loaded.model.report()
    }

    /// Simulates the model; returns `(columns, data, tracks, summary,
    /// failure)`, `summary` a dict and `failure` `None` for a finished run,
    /// else the other way round (the rows before the failure kept).
    #[pyo3(signature = (t_end, dt, initial, params, inputs, formulation, integrator, stop_when, controller, rtol, atol, fixed_step, prescribe))]
    #[allow(clippy::too_many_arguments)]
    fn simulate<'py>(
        &self,
        py: Python<'py>,
        t_end: f64,
        dt: f64,
        initial: Option<&Bound<'py, PyDict>>,
        params: Option<&Bound<'py, PyDict>>,
        inputs: Option<&Bound<'py, PyDict>>,
        formulation: &str,
        integrator: Option<&str>,
        stop_when: Option<String>,
        controller: &str,
        rtol: f64,
        atol: f64,
        fixed_step: bool,
        prescribe: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let request = Request {
            formulation: formulation_named(formulation)?,
            integrator: integrator.map(integrator_named).transpose()?,
            controller: controller_named(controller)?,
            t_end,
            dt,
            rtol,
            atol,
            fixed_step,
            stop_when,
            params: numbers(params)?,
            initial: assignments(initial)?,
            inputs: assignments(inputs)?,
            prescribe: assignments(prescribe)?,
        };
        let loaded = self.fresh();
        let finished = py
            .detach(|| simulate::simulate(loaded, &request, &mut Nowhere, &mut |_| {}))
            .map_err(|error| to_python(py, error))?;
        let run = PyDict::new(py);
        let (columns, data) = table(py, &finished.table)?;
        run.set_item("columns", columns)?;
        run.set_item("data", data)?;
        let tracks = finished
            .tracks
            .as_ref()
            .map(|tracks| table(py, tracks))
            .transpose()?;
        run.set_item("tracks", tracks)?;
        match &finished.outcome {
            Ok(report) => {
                let summary = PyDict::new(py);
                summary.set_item("t_end", report.t)?;
                summary.set_item("steps", report.steps)?;
                summary.set_item("integrator", report.integrator.name())?;
                summary.set_item("engine", report.engine)?;
                summary.set_item("energy_drift", report.energy_drift)?;
                summary.set_item("power_balance", report.power_balance)?;
                summary.set_item("energy_scale", report.energy_scale)?;
                summary.set_item("max_constraint_residual", report.max_constraint_residual)?;
                summary.set_item("max_holonomic_residual", report.max_holonomic_residual)?;
                summary.set_item("chart_switches", report.chart_switches)?;
                summary.set_item("split_steps", report.split_steps)?;
                summary.set_item("accepted_steps", report.effort.accepted)?;
                summary.set_item("rejected_steps", report.effort.rejected)?;
                summary.set_item("newton_iterations", report.effort.newton_iterations)?;
                summary.set_item("stopped", report.stopped.clone())?;
                summary.set_item("seconds", report.seconds)?;
                let warnings = (report.warnings().iter())
                    .map(|warning| report.explain(warning))
                    .collect::<Vec<_>>();
                summary.set_item("warnings", warnings)?;
                run.set_item("summary", summary)?;
                run.set_item("failure", py.None())?;
            }
            Err(error) => {
                run.set_item("summary", py.None())?;
                run.set_item("failure", failure(py, error.as_ref())?)?;
            }
        }
        Ok(run)
    }

    /// The optimal plan over `[0, duration]` on `nodes` nodes
    /// (docs/INTERFACE.md section 13): `start` and `goal` fix coordinates
    /// and velocities at the ends, `minimize` is the running cost (the sum
    /// of the inputs squared by default), `bounds` maps names to `LO:HI`;
    /// `final_cost` is a cost at the end, `free_duration` makes the
    /// duration an unknown (`duration` its first guess), `guess` is a CSV
    /// to start from, `formulation` the form the nodes hold; returns a
    /// dict of `columns`, `data` and `report` (`plan.json`'s text).
    #[pyo3(signature = (duration, nodes, scheme, start, goal, minimize, bounds, params, tol, final_cost, free_duration, guess, formulation))]
    #[allow(clippy::too_many_arguments)]
    fn plan<'py>(
        &self,
        py: Python<'py>,
        duration: f64,
        nodes: usize,
        scheme: &str,
        start: Option<&Bound<'py, PyDict>>,
        goal: Option<&Bound<'py, PyDict>>,
        minimize: Option<String>,
        bounds: Option<&Bound<'py, PyDict>>,
        params: Option<&Bound<'py, PyDict>>,
        tol: f64,
        final_cost: Option<String>,
        free_duration: bool,
        guess: Option<std::path::PathBuf>,
        formulation: &str,
    ) -> PyResult<Bound<'py, PyDict>> {
        let request = PlanRequest {
            duration,
            nodes,
            scheme: plan::scheme_named(scheme)?,
            formulation: formulation_named(formulation)?,
            start: assignments(start)?,
            goal: assignments(goal)?,
            minimize,
            bounds: assignments(bounds)?,
            params: numbers(params)?,
            tol,
            final_cost,
            free_duration,
            guess,
        };
        plan::plan(py, self.fresh(), &request)
    }

    /// The parameters `estimate` names (`(name, guess or None)`), fitted
    /// to data by collocation at the rows' own times (or on `nodes` nodes
    /// evenly spread) with `scheme` (docs/INTERFACE.md section 13): the table
    /// `(columns, rows)` where given, `data` naming it in messages, else
    /// the CSV at `data`; returns a dict of the fit's `columns`, `data` and
    /// `report` (`estimate.json`'s text).
    #[pyo3(signature = (data, table, estimate, nodes, scheme, params, tol))]
    #[allow(clippy::too_many_arguments)]
    fn identify<'py>(
        &self,
        py: Python<'py>,
        data: std::path::PathBuf,
        table: Option<(Vec<String>, Vec<Vec<f64>>)>,
        estimate: Vec<(String, Option<f64>)>,
        nodes: Option<usize>,
        scheme: &str,
        params: Option<&Bound<'py, PyDict>>,
        tol: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let request = IdentifyRequest {
            data,
            estimate,
            nodes,
            scheme: plan::scheme_named(scheme)?,
            params: numbers(params)?,
            tol,
        };
        let table = table.map(|(columns, rows)| Table { columns, rows });
        plan::identify(py, self.fresh(), &request, table.as_ref())
    }

    /// Linearizes about the steady motion `at` (`{name: value or
    /// expression}`), or over `sweep = (variable, values)`; returns a dict
    /// (see `chaplygin.Linearization`).
    #[pyo3(signature = (at, params, sweep))]
    fn linearize<'py>(
        &self,
        py: Python<'py>,
        at: Option<&Bound<'py, PyDict>>,
        params: Option<&Bound<'py, PyDict>>,
        sweep: Option<(String, ArrayLike<'py>)>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let (params, at) = (numbers(params)?, assignments(at)?);
        let variables: Vec<&str> = sweep
            .iter()
            .map(|(variable, _)| variable.as_str())
            .collect();
        let asked = Asked {
            params: &params,
            state_flag: "at",
            state: &at,
            variables: &variables,
            ..Asked::default()
        };
        let setup = setup::resolve(self.fresh().model, &asked)
            .map_err(|error| PyValueError::new_err(error.to_string()))?;
        match &sweep {
            None => linearization::at_point(py, &setup),
            Some((variable, values)) => {
                let values = flat(values, "sweep's values")?;
                linearization::over_sweep(py, &setup, (variable, &values))
            }
        }
    }

    /// Finds the steady motion of `at` and `inputs` (`{name: value or
    /// expression}`) in the unknowns `solve` from `guess`, or with `trace
    /// = (variable, values)` follows its family; returns a dict (see
    /// `chaplygin.Steady` and `chaplygin.SteadyFamily`).
    #[pyo3(signature = (at, inputs, solve, guess, params, trace))]
    #[allow(clippy::too_many_arguments)]
    fn steady<'py>(
        &self,
        py: Python<'py>,
        at: Option<&Bound<'py, PyDict>>,
        inputs: Option<&Bound<'py, PyDict>>,
        solve: Vec<String>,
        guess: Option<&Bound<'py, PyDict>>,
        params: Option<&Bound<'py, PyDict>>,
        trace: Option<(String, ArrayLike<'py>)>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let (at, inputs) = (assignments(at)?, assignments(inputs)?);
        let (guess, params) = (numbers(guess)?, numbers(params)?);
        let request = SteadyRequest {
            params: &params,
            at: &at,
            inputs: &inputs,
            solve: &solve,
            guess: &guess,
            trace: trace.as_ref().map(|(variable, _)| variable.as_str()),
        };
        match &trace {
            None => linearization::steady_motion(py, self.fresh().model, &request),
            Some((variable, values)) => {
                let values = flat(values, "trace's values")?;
                linearization::steady_family(py, self.fresh().model, &request, (variable, &values))
            }
        }
    }

    /// Runs the shape laws `cycle` (`{name: expression of t}`, period
    /// `period`) for `cycles` periods; returns `(columns, data,
    /// displacements)`, one row `(x, y, theta)` per cycle.
    #[pyo3(signature = (cycle, period, cycles, steps, params, initial))]
    #[allow(clippy::too_many_arguments)]
    fn gait<'py>(
        &self,
        py: Python<'py>,
        cycle: &Bound<'py, PyDict>,
        period: f64,
        cycles: usize,
        steps: usize,
        params: Option<&Bound<'py, PyDict>>,
        initial: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let request = GaitRequest {
            cycle: assignments(Some(cycle))?,
            period,
            cycles,
            steps,
            params: numbers(params)?,
            initial: numbers(initial)?,
        };
        let loaded = self.fresh();
        let run = py
            .detach(|| gait::gait(loaded, &request))
            .map_err(|error| to_python(py, error))?;
        let result = PyDict::new(py);
        let (columns, data) = table(py, &run.table)?;
        result.set_item("columns", columns)?;
        result.set_item("data", data)?;
        let displacements = run
            .cycles
            .iter()
            .flat_map(|cycle| cycle.displacement)
            .collect();
        result.set_item("displacements", matrix(py, displacements, 3)?)?;
        Ok(result)
    }

    /// The loop that moves a model furthest from rest (`chaplygin gait
    /// --optimize`): its laws, coefficients, efficiency, length,
    /// displacement, each start's efficiency and its run.
    #[pyo3(signature = (direction, harmonics, cost, period, starts, margin, limit, steps, params))]
    #[allow(clippy::too_many_arguments)]
    fn optimal_gait<'py>(
        &self,
        py: Python<'py>,
        direction: &str,
        harmonics: usize,
        cost: &str,
        period: f64,
        starts: usize,
        margin: f64,
        limit: f64,
        steps: usize,
        params: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let design = Design {
            direction: direction_named(direction)?,
            cost: cost_named(cost)?,
            harmonics,
            period,
            starts,
            margin,
            limit,
            steps,
            ..Design::default()
        };
        let request = OptimalGaitRequest {
            design,
            params: numbers(params)?,
        };
        let loaded = self.fresh();
        let found = py
            .detach(|| gait::optimal_gait(loaded, &request))
            .map_err(|error| to_python(py, error))?;
        let optimum = &found.optimum;
        let result = PyDict::new(py);
        result.set_item("laws", found.laws.clone())?;
        let per = optimum.shape_loop.per_coordinate();
        let coefficients = optimum.shape_loop.coefficients.clone();
        result.set_item("coefficients", matrix(py, coefficients, per)?)?;
        result.set_item("efficiency", optimum.efficiency())?;
        result.set_item("length", optimum.evaluation.length)?;
        let displacement = optimum.evaluation.displacement.to_vec();
        result.set_item("displacement", PyArray1::from_vec(py, displacement))?;
        result.set_item("starts", optimum.starts.clone())?;
        let (columns, data) = table(py, &found.run.table)?;
        result.set_item("columns", columns)?;
        result.set_item("data", data)?;
        let displacements = (found.run.cycles.iter())
            .flat_map(|cycle| cycle.displacement)
            .collect();
        result.set_item("displacements", matrix(py, displacements, 3)?)?;
        Ok(result)
    }

    /// The right-hand side of a formulation, closed by the input laws.
    #[pyo3(signature = (formulation, params, inputs))]
    fn rhs(
        &self,
        py: Python<'_>,
        formulation: &str,
        params: Option<&Bound<'_, PyDict>>,
        inputs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Rhs> {
        let request = Request {
            formulation: formulation_named(formulation)?,
            params: numbers(params)?,
            inputs: assignments(inputs)?,
            ..Request::default()
        };
        let prepared =
            simulate::prepare(self.fresh(), &request).map_err(|error| to_python(py, error))?;
        Ok(Rhs::new(prepared))
    }

    /// The Lagrange-d'Alembert accelerations and multipliers
    /// `(qddot, lambda)` at `(q, qdot)` under the inputs `u` (zero if
    /// `None`).
    #[pyo3(signature = (q, qdot, u = None))]
    #[allow(clippy::type_complexity)]
    fn acceleration<'py>(
        &self,
        py: Python<'py>,
        q: ArrayLike<'py>,
        qdot: ArrayLike<'py>,
        u: Option<ArrayLike<'py>>,
    ) -> PyResult<(Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>)> {
        let model = &self.loaded.model;
        let Sizes { n, p, .. } = model.sizes();
        let q = vector(&q, "q", n, "one per coordinate")?;
        let qdot = vector(&qdot, "qdot", n, "one per coordinate")?;
        let u = match &u {
            Some(u) => vector(u, "u", p, "one per input")?,
            None => vec![0.0; p],
        };
        let (qddot, lambda) = model
            .acceleration(&q, &qdot, &u)
            .map_err(|error| PyValueError::new_err(error.to_string()))?;
        Ok((
            PyArray1::from_vec(py, qddot),
            PyArray1::from_vec(py, lambda),
        ))
    }

    /// At each row of `points` (values of the parameters `names`; the
    /// others at `params` or their defaults), the self-stable speeds of the
    /// steady motion `at` over `speed = (variable, values)` and where it
    /// gains or loses an unstable mode, on `jobs` threads (every core by
    /// default) with the GIL released; one dict per point.
    #[pyo3(signature = (at, params, speed, names, points, jobs))]
    #[allow(clippy::too_many_arguments)]
    fn design_points<'py>(
        &self,
        py: Python<'py>,
        at: Option<&Bound<'py, PyDict>>,
        params: Option<&Bound<'py, PyDict>>,
        speed: (String, ArrayLike<'py>),
        names: Vec<String>,
        points: ArrayLike<'py>,
        jobs: Option<usize>,
    ) -> PyResult<Bound<'py, PyList>> {
        let mut model = self.fresh().model;
        with_parameters(&mut model, &numbers(params)?)
            .map_err(|error| PyValueError::new_err(error.to_string()))?;
        let at = assignments(at)?;
        let speeds = flat(&speed.1, "speed's values")?;
        let motion = Motion {
            at: &at,
            speed: (&speed.0, &speeds),
        };
        let points = design::rows(&points, names.len())?;
        design::stability_at(py, &model, (&names, &points), motion, jobs)
    }

    /// The built-in model's name, or `None` for a model read from a file
    /// or a text.
    #[getter]
    fn builtin_name(&self) -> Option<&'static str> {
        match &self.source {
            Source::BuiltIn(built_in) => Some(built_in.name),
            Source::File { .. } => None,
        }
    }

    /// The page animating a run of this model (docs/INTERFACE.md section
    /// 10): its recorded `columns` and `rows` (`t`, then the coordinates),
    /// at the parameters `params`, `fps` frames per second of simulated
    /// time.
    #[pyo3(signature = (columns, rows, params, fps))]
    fn animation(
        &self,
        columns: Vec<String>,
        rows: Vec<Vec<f64>>,
        params: Option<&Bound<'_, PyDict>>,
        fps: f64,
    ) -> PyResult<String> {
        let value_error = |error: &dyn std::fmt::Display| PyValueError::new_err(error.to_string());
        let mut model = self.loaded.model.clone();
        let label = &self.loaded.label;
        animation::check(&model, label).map_err(|e| value_error(&e))?;
        with_parameters(&mut model, &numbers(params)?).map_err(|e| value_error(&e))?;
        animation::page(&model, label, &Table { columns, rows }, fps).map_err(|e| value_error(&e))
    }

    /// The model's text, as read.
    #[getter]
    fn text(&self) -> &str {
        self.source.text()
    }

    /// The derivation document as `"text"`, `"latex"` or `"json"`, or
    /// `"rust"`: the Rust the model compiles to.
    #[pyo3(signature = (format = "text"))]
    fn document(&self, py: Python<'_>, format: &str) -> PyResult<String> {
        let format = match format {
            "text" => Format::Text,
            "latex" => Format::Latex,
            "json" => Format::Json,
            "rust" => Format::Rust,
            _ => {
                return Err(PyValueError::new_err(format!(
                    "unknown format `{format}` (formats: text, latex, json, rust)"
                )));
            }
        };
        py.detach(|| document::document(&self.source, format))
            .map_err(|error| to_python(py, error))
    }
}
