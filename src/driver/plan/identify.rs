//! Parameter estimation by collocation (docs/INTERFACE.md section 13):
//! the parameters `theta` named by `--estimate` and every node's state
//! `x_i` (the initial one too) that fit the measured columns of a table,
//!
//! ```text
//! minimize  sum over measured (i, k) of (x_{i,k} - d_{i,k})^2
//! subject to  the collocation defects of d(q, qdot)/dt = (qdot, qddot(q, qdot, u; theta)),
//!             the model's constraints at the first node (`initial`),
//! ```
//!
//! the nodes at the table's own times, however unevenly spaced (or, with
//! `--nodes`, evenly spread over its span, the data interpolated there),
//! and the inputs `u` held at the table's values, not variables:
//! interpolated where the scheme applies them (the midpoint rule's node
//! `i` at `t_i + h_i/2`, the other schemes' at their nodes). The defects
//! are the plan's ([`super::transcription`]), each interval `i` on its own
//! step `h_i = t_{i+1} - t_i`,
//! their derivatives by `theta` exact: at each stage `X_k`,
//!
//! ```text
//! d defect / d theta = - h sum_k w_k (f_theta(X_k) + f_x(X_k) dX_k/d theta),
//! dX_k/d theta = c_k h (f_theta(x_i) - f_theta(x_{i+1})),
//! ```
//!
//! with `f_theta = (0, d qddot / d theta)` the model's
//! `acceleration_parameter_jacobian`; `c_k` is nonzero only at
//! Hermite-Simpson's midpoint. The solver works on the exact Hessian of
//! the Lagrangian (`hessian`), or on its L-BFGS approximation where asked,
//! from the data where they measure and elsewhere from the model's motion
//! from the first row (`guess`).
//!
//! The standard errors are the Gauss-Newton ones of a least-squares fit
//! under equality constraints (Bard, "Nonlinear Parameter Estimation",
//! Academic Press 1974, sections 7-5 and 7-22; Seber and Wild, "Nonlinear
//! Regression", Wiley 1989, section 2.1): with `r` the `m` residuals,
//! `J_r` their Jacobian by all variables and `Z` a basis of the null space
//! of the constraints' Jacobian `C` at the optimum,
//!
//! ```text
//! Cov = s^2 Z (Z^T J_r^T J_r Z)^+ Z^T,   s^2 = RSS / (m - rank(J_r Z)).
//! ```
//!
//! The defects fix each node's state from the one before, so `Z` is the
//! sensitivity of the states to `xi = (x_0, theta)`: `S_0 = (I, 0)`,
//! `S_{i+1} = -B_i^{-1} (A_i S_i + P_i (0, I))` with `A_i`, `B_i`, `P_i`
//! the defect's derivatives by `x_i`, `x_{i+1}` and `theta`, times a basis
//! `Z_0` of the directions of `xi` the initial constraints leave free. Initial
//! states that no measured column sees leave `J_r Z` rank deficient: the
//! pseudo-inverse and the rank leave them out of the parameters'
//! covariance and of the degrees of freedom.
//!
//! [`identify_watched`] tells an observer of each of the solver's
//! iterations, as [`super::plan_watched`] does; an observer that stops the
//! solve gets the last iterate back as [`Interrupted`].
//! [`identify_table`] reads the data from a table in memory instead of
//! `--data`'s file.

use super::kkt::Residuals;
use super::nlp::{Nlp, Observer, Solution, Solver};
use super::resolve::guess::{Guess, Table as TableKind};
use super::resolve::{DERIVED_COLUMNS, RequestError, node_columns};
use super::transcription::{Costs, Grid, Scheme, StagePoint, Transcription};
use super::{Watched, interrupted, last_residuals, solve_watched, verified};
use crate::driver::Failure;
use crate::driver::engine::Loaded;
use crate::driver::expression::{Expression, Scope};
use crate::driver::setup::with_parameters;
use crate::runtime::nalgebra::DMatrix;
use crate::runtime::record::{Recorder, Table};
use chaplygin_codegen::interpret::evaluated;
use initial::{initial_row_name, initial_rows};
use std::cell::RefCell;
use std::ops::ControlFlow;
use std::path::PathBuf;

/// How `--data` is read: `trajectory.csv`'s derived columns ignored.
const DATA: TableKind = TableKind {
    flag: "--data",
    ignored: &DERIVED_COLUMNS,
    others: " and trajectory.csv's others",
};

/// What to estimate, from which data, on which grid.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct Request {
    /// A CSV with `t`, any coordinates or velocities `dot(q)` by name
    /// (measured) and the inputs applied, by name (0 where not given);
    /// `trajectory.csv`'s `energy` and residual columns are ignored, and a
    /// run in the reduced or momentum form is read in the velocities its
    /// state gives.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILE.csv"))]
    pub data: PathBuf,
    /// `NAME[=GUESS]`: a parameter to estimate, from GUESS or its value
    /// (repeatable).
    #[cfg_attr(feature = "cli", arg(long = "estimate", required = true, value_parser = estimate_assignment))]
    pub estimate: Vec<(String, Option<f64>)>,
    /// The number of nodes, evenly spread over the data's time span, the
    /// data interpolated at them [default: the data's own times, one node
    /// per row].
    #[cfg_attr(feature = "cli", arg(long))]
    pub nodes: Option<usize>,
    /// The collocation scheme.
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value_t = Scheme::Midpoint))]
    pub scheme: Scheme,
    /// A model parameter, `NAME=VALUE` (repeatable).
    #[cfg_attr(feature = "cli", arg(long = "param", value_parser = crate::driver::simulate::assignment))]
    pub params: Vec<(String, f64)>,
    /// The solver's tolerance; the KKT conditions are verified to 100
    /// times it.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = super::Request::TOL))]
    pub tol: f64,
}

/// `NAME` or `NAME=GUESS`.
///
/// # Errors
/// A GUESS that is not a number.
pub fn estimate_assignment(text: &str) -> Result<(String, Option<f64>), String> {
    match text.split_once('=') {
        None => Ok((text.trim().to_string(), None)),
        Some((name, value)) => value
            .trim()
            .parse()
            .map(|value| (name.trim().to_string(), Some(value)))
            .map_err(|_| format!("`{value}` is not a number")),
    }
}

/// Why an estimate was not made, beyond the plan's reasons.
#[derive(Debug, PartialEq, thiserror::Error)]
pub enum IdentifyError {
    /// A name that is no parameter of the model.
    #[error("--estimate {name}: unknown parameter (the model's: {known})")]
    UnknownEstimate {
        /// What was given.
        name: String,
        /// The parameters there are.
        known: String,
    },
    /// Fewer measured values than unknowns the data can fix.
    #[error(
        "--data {path}: too few rows: {measured} measured values for {unknowns} unknowns (the \
         initial state and the estimates)"
    )]
    TooFewRows {
        /// The file.
        path: String,
        /// The measured values.
        measured: usize,
        /// The initial state's size and the estimates'.
        unknowns: usize,
    },
    /// Data that measure no coordinate or velocity.
    #[error("--data {0}: it measures no coordinate or velocity")]
    NothingMeasured(String),
    /// Fewer than two nodes.
    #[error("--nodes {0}: an estimate needs at least 2 nodes")]
    Nodes(usize),
}

/// The observer stopped the solve: the last iterate, not an estimate.
#[derive(Debug, thiserror::Error)]
#[error("{}", interrupted(.0.iterations, &.0.kkt))]
pub struct Interrupted(pub Box<Estimate>);

/// A verified estimate.
#[derive(Clone, Debug)]
pub struct Estimate {
    /// Each estimated parameter's name and value.
    pub parameters: Vec<(String, f64)>,
    /// Their standard errors, in the same order.
    pub standard_errors: Vec<f64>,
    /// `sqrt(RSS / m)` over the `m` measured values.
    pub residual_rms: f64,
    /// The solver's iterations.
    pub iterations: usize,
    /// The KKT residuals, computed from the exact derivatives.
    pub kkt: Residuals,
    /// `t`, the fitted coordinates and velocities, and each measured
    /// column's data as `data(NAME)`, one row per node.
    pub fit: Table,
}

impl Estimate {
    /// As `estimate.json` holds it.
    pub fn to_json(&self) -> serde_json::Value {
        let by_name = |values: Vec<(&String, f64)>| {
            values
                .into_iter()
                .map(|(name, value)| (name.clone(), serde_json::json!(value)))
                .collect::<serde_json::Map<_, _>>()
        };
        let names = self.parameters.iter().map(|(name, _)| name);
        serde_json::json!({
            "parameters": by_name(self.parameters.iter().map(|(n, v)| (n, *v)).collect()),
            "standard_errors": by_name(names.zip(self.standard_errors.iter().copied()).collect()),
            "residual_rms": self.residual_rms,
            "iterations": self.iterations,
            "kkt": {
                "primal": self.kkt.primal,
                "dual": self.kkt.dual,
                "complementarity": self.kkt.complementarity,
            },
        })
    }
}

/// The parameters `request` names, estimated from its data on `loaded`,
/// solved by `solver` and verified by the KKT conditions.
///
/// # Errors
/// Bad input (an unknown name, data columns that are not the model's,
/// too few rows, a `t` that does not increase), or an answer that is not a
/// verified optimum.
pub fn identify(
    loaded: Loaded,
    request: &Request,
    solver: &dyn Solver,
) -> Result<Estimate, Failure> {
    identify_watched(loaded, request, solver, &mut |_| ControlFlow::Continue(()))
}

/// [`identify`], telling `observer` of each of the solver's iterations.
///
/// # Errors
/// As [`identify`], and [`Interrupted`] with the last iterate where
/// `observer` stops the solve.
pub fn identify_watched(
    loaded: Loaded,
    request: &Request,
    solver: &dyn Solver,
    observer: &mut Observer<'_>,
) -> Result<Estimate, Failure> {
    let fit = Fit::new(loaded, request, None)?;
    estimate(&fit, request, solver, observer)
}

/// [`identify_watched`] on data in memory: `table`'s columns as the
/// CSV's; `request.data` names it in messages, and no file is read.
///
/// # Errors
/// As [`identify_watched`].
pub fn identify_table(
    loaded: Loaded,
    request: &Request,
    table: &Table,
    solver: &dyn Solver,
    observer: &mut Observer<'_>,
) -> Result<Estimate, Failure> {
    let fit = Fit::new(loaded, request, Some(table))?;
    estimate(&fit, request, solver, observer)
}

/// The estimate `fit` finds, solved by `solver` and verified, or the last
/// iterate where `observer` stops the solve.
fn estimate(
    fit: &Fit,
    request: &Request,
    solver: &dyn Solver,
    observer: &mut Observer<'_>,
) -> Result<Estimate, Failure> {
    let Watched {
        solution, stopped, ..
    } = solve_watched(solver, fit, request.tol, observer);
    if stopped {
        let kkt = last_residuals(fit, &solution);
        let rss = fit.objective(&solution.z).unwrap_or(f64::NAN);
        return Err(Interrupted(Box::new(fit.estimate(&solution, kkt, rss)?)).into());
    }
    let (kkt, rss) = verified(fit, &solution, request.tol)?;
    fit.estimate(&solution, kkt, rss)
}

/// The estimation as a nonlinear program: each node's state, then the
/// estimated parameters.
struct Fit {
    /// The defects, its model's parameters set to the variables' before
    /// each evaluation.
    transcription: RefCell<Transcription>,
    /// The estimated parameters' names, and their indices among the
    /// model's.
    names: Vec<String>,
    indices: Vec<usize>,
    /// The nodes' times.
    times: Vec<f64>,
    /// Each node's inputs.
    inputs: Vec<Vec<f64>>,
    /// The measured columns among a node's state, and each node's data in
    /// them.
    measured: Vec<usize>,
    data: Vec<Vec<f64>>,
    /// The state's column names.
    columns: Vec<String>,
    lo: Vec<f64>,
    hi: Vec<f64>,
    guess: Vec<f64>,
    /// The transcription's Jacobian entries kept (those by states), by
    /// their index among its entries.
    kept: Vec<usize>,
    structure: Vec<(usize, usize)>,
}

impl Fit {
    /// The program `request` asks of `loaded`, on the data in `table`, or
    /// without it in `request.data`'s file.
    fn new(loaded: Loaded, request: &Request, table: Option<&Table>) -> Result<Self, Failure> {
        let mut model = loaded.model;
        with_parameters(&mut model, &request.params)?;
        let known = model.names().parameters.clone();
        let mut indices = Vec::new();
        for (name, guess) in &request.estimate {
            let index = known.iter().position(|p| p == name).ok_or_else(|| {
                IdentifyError::UnknownEstimate {
                    name: name.clone(),
                    known: known.join(", "),
                }
            })?;
            if let Some(value) = guess {
                model.set_parameter(name, *value)?;
            }
            indices.push(index);
        }
        let columns = node_columns(&model);
        let path = request.data.display().to_string();
        let read = Guess::of_model((DATA, &model, &indices), &request.data, table)?;
        let times = node_times(&read, request.nodes)?;
        let nodes = times.len();
        let s = 2 * model.sizes().n;
        let measured: Vec<usize> = read.columns().filter(|c| *c < s).collect();
        if measured.is_empty() {
            return Err(IdentifyError::NothingMeasured(path).into());
        }
        let unknowns = s + indices.len();
        if nodes * measured.len() <= unknowns {
            let measured = nodes * measured.len();
            return Err(IdentifyError::TooFewRows {
                path,
                measured,
                unknowns,
            }
            .into());
        }
        let mut guess = vec![0.0; nodes * s];
        let mut inputs = vec![vec![0.0; columns.len() - s]; nodes];
        let mut data = vec![Vec::new(); nodes];
        let stage = &request.scheme.stages()[0];
        for (i, t) in times.iter().enumerate() {
            for (column, value) in read.at(*t) {
                if column < s {
                    guess[i * s + column] = value;
                    data[i].push(value);
                }
            }
            let interval = i.min(nodes - 2);
            let step = times[interval + 1] - times[interval];
            let applied = (stage.at - stage.inputs_at) * step;
            for (column, value) in read.at(t + applied).filter(|(c, _)| *c >= s) {
                inputs[i][column - s] = value;
            }
        }
        let full_guess = interleave(&guess, &inputs, s);
        guess.extend(indices.iter().map(|&k| model.parameter_values()[k]));
        let names = indices.iter().map(|&k| known[k].clone()).collect();
        let zero =
            Expression::parse("0", &Scope::default()).map_err(|source| RequestError::Value {
                flag: "--estimate",
                name: "0".into(),
                source,
            })?;
        let (first, last) = (times[0], times[nodes - 1]);
        let grid = Grid {
            nodes,
            duration: last - first,
            free_duration: false,
            fractions: Some(times.iter().map(|t| (t - first) / (last - first)).collect()),
        };
        let costs = Costs {
            running: zero,
            terminal: None,
        };
        let free = vec![f64::NEG_INFINITY; full_guess.len()];
        let bounds = (free.clone(), free.iter().map(|v| -v).collect(), full_guess);
        let transcription = Transcription::new(model, request.scheme, grid, costs, bounds);
        let size = guess.len();
        let mut fit = Self {
            transcription: RefCell::new(transcription),
            names,
            indices,
            times,
            inputs,
            measured,
            data,
            columns: columns[..s].to_vec(),
            lo: vec![f64::NEG_INFINITY; size],
            hi: vec![f64::INFINITY; size],
            guess,
            kept: Vec::new(),
            structure: Vec::new(),
        };
        fit.build_structure();
        if let Some(states) = fit.simulated_states() {
            fit.guess[..states.len()].copy_from_slice(&states);
        }
        Ok(fit)
    }

    /// The estimate at `solution`, with its KKT residuals `kkt` and
    /// residual sum of squares `rss`.
    fn estimate(&self, solution: &Solution, kkt: Residuals, rss: f64) -> Result<Estimate, Failure> {
        let measured = self.measured.len() * self.data.len();
        Ok(Estimate {
            parameters: self
                .names
                .iter()
                .zip(&solution.z[self.states()..])
                .map(|(name, value)| (name.clone(), *value))
                .collect(),
            standard_errors: self.standard_errors(&solution.z, rss),
            residual_rms: (rss / measured as f64).sqrt(),
            iterations: solution.iterations,
            kkt,
            fit: self.table(&solution.z)?,
        })
    }

    /// The transcription's entries by states, renumbered, then each
    /// interval's dense block by the estimates; then the initial
    /// constraints' dense rows by `(x_0, theta)`.
    fn build_structure(&mut self) {
        let (s, w) = (self.state(), self.transcription.borrow().width());
        let transcription = self.transcription.borrow();
        for (index, &(row, column)) in transcription.jacobian_structure().iter().enumerate() {
            if column % w < s {
                self.kept.push(index);
                self.structure.push((row, column / w * s + column % w));
            }
        }
        let first = self.states();
        for row in 0..transcription.constraints() {
            self.structure
                .extend((0..self.names.len()).map(|j| (row, first + j)));
        }
        let defects = self.defects();
        for row in defects..defects + initial_rows(transcription.model()) {
            let estimates = (0..self.names.len()).map(|j| first + j);
            self.structure
                .extend((0..s).chain(estimates).map(|c| (row, c)));
        }
    }

    /// A node's state's size, `2n`.
    fn state(&self) -> usize {
        self.columns.len()
    }

    /// The number of state variables, `N 2n`.
    fn states(&self) -> usize {
        self.times.len() * self.state()
    }

    /// The transcription's variables at `y`, its model's estimated
    /// parameters set to `y`'s.
    fn transcribed(&self, y: &[f64]) -> Vec<f64> {
        let mut transcription = self.transcription.borrow_mut();
        let model = transcription.model_mut();
        for (name, value) in self.names.iter().zip(&y[self.states()..]) {
            model
                .set_parameter(name, *value)
                .expect("an estimated parameter is the model's");
        }
        interleave(&y[..self.states()], &self.inputs, self.state())
    }

    /// `d f / d theta` at `point` (2n x P, row-major), its `q` rows 0.
    fn rhs_by_parameters(&self, transcription: &Transcription, point: &StagePoint) -> Vec<f64> {
        let model = transcription.model();
        let n = model.sizes().n;
        let (q, qdot) = point.x.split_at(n);
        let by_estimates =
            evaluated(model.acceleration_parameter_jacobian(q, qdot, &point.u, &self.indices));
        let mut by = vec![0.0; n * self.indices.len()];
        by.extend(by_estimates);
        by
    }

    /// `dX/d theta` of a stage with slope coefficient `slopes` in interval
    /// `i` (2n x P, row-major): `c h (f_theta(x_i) - f_theta(x_{i+1}))`,
    /// zero where `c` is.
    fn stage_motion_by_parameters(
        &self,
        transcription: &Transcription,
        z: &[f64],
        i: usize,
        slopes: f64,
    ) -> Vec<f64> {
        let size = self.state() * self.indices.len();
        if slopes == 0.0 {
            return vec![0.0; size];
        }
        let c = slopes * transcription.step(z, i);
        let [first, last] = [i, i + 1]
            .map(|j| self.rhs_by_parameters(transcription, &transcription.node_point(z, j)));
        first.iter().zip(&last).map(|(a, b)| c * (a - b)).collect()
    }

    /// Interval `i`'s defect's derivative by the estimates (2n x P,
    /// row-major), at the transcription's variables `z`.
    fn defect_by_parameters(&self, transcription: &Transcription, z: &[f64], i: usize) -> Vec<f64> {
        let (s, estimated, h) = (self.state(), self.indices.len(), transcription.step(z, i));
        let mut defect = vec![0.0; s * estimated];
        for stage in transcription.scheme.stages() {
            let point = transcription.stage_point(z, i, stage);
            let mut by = self.rhs_by_parameters(transcription, &point);
            if stage.slopes != 0.0 {
                let (fx, _) = transcription.rhs_jacobian(&point);
                let fx = DMatrix::from_row_slice(s, s, &fx);
                let moved = self.stage_motion_by_parameters(transcription, z, i, stage.slopes);
                let through = fx * DMatrix::from_row_slice(s, estimated, &moved);
                for (k, b) in by.iter_mut().enumerate() {
                    *b += through[(k / estimated, k % estimated)];
                }
            }
            for (d, b) in defect.iter_mut().zip(&by) {
                *d -= h * stage.weight * b;
            }
        }
        defect
    }

    /// The standard errors of the estimates at `y`, with `rss` the
    /// residual sum of squares there.
    fn standard_errors(&self, y: &[f64], rss: f64) -> Vec<f64> {
        let sensitivity = self.sensitivities(y);
        let (s, estimated) = (self.state(), self.indices.len());
        let tangent = self.initial_tangent(y);
        let rows: Vec<f64> = sensitivity
            .iter()
            .flat_map(|block| {
                self.measured
                    .iter()
                    .flat_map(move |&k| block.row(k).iter().copied().collect::<Vec<_>>())
            })
            .collect();
        let m = rows.len() / (s + estimated);
        let jz = DMatrix::from_row_slice(m, s + estimated, &rows) * &tangent;
        let svd = jz.svd(false, true);
        let largest = svd.singular_values.max();
        let kept = |sigma: f64| sigma > largest * 1e-10;
        let rank = svd.singular_values.iter().filter(|v| kept(**v)).count();
        let variance = rss / (m - rank) as f64;
        let v_t = svd.v_t.expect("asked for");
        (0..estimated)
            .map(|j| {
                let along = tangent.row(s + j);
                let sum: f64 = svd
                    .singular_values
                    .iter()
                    .enumerate()
                    .filter(|(_, sigma)| kept(**sigma))
                    .map(|(r, sigma)| (v_t.row(r).dot(&along) / sigma).powi(2))
                    .sum();
                (variance * sum).sqrt()
            })
            .collect()
    }

    /// Each node's state's derivative by `(x_0, theta)` along the defects
    /// (2n x (2n + P) each).
    fn sensitivities(&self, y: &[f64]) -> Vec<DMatrix<f64>> {
        let (s, estimated) = (self.state(), self.indices.len());
        let dim = s + estimated;
        let mut values = vec![0.0; self.structure.len()];
        self.jacobian_values(y, &mut values);
        let intervals = self.times.len() - 1;
        let mut previous = vec![DMatrix::zeros(s, s); intervals];
        let mut next = previous.clone();
        let mut by_parameters = vec![DMatrix::zeros(s, dim); intervals];
        let defects = self.defects();
        for (&(row, column), value) in self.structure.iter().zip(&values) {
            if row >= defects {
                continue;
            }
            let (i, r) = (row / s, row % s);
            match column {
                c if c >= self.states() => by_parameters[i][(r, s + c - self.states())] += value,
                c if c / s == i => previous[i][(r, c % s)] += value,
                c => next[i][(r, c % s)] += value,
            }
        }
        let mut sensitivity = vec![DMatrix::identity(s, dim)];
        for i in 0..intervals {
            let pushed = &previous[i] * &sensitivity[i] + &by_parameters[i];
            let moved = next[i]
                .clone()
                .lu()
                .solve(&(-pushed))
                .unwrap_or_else(|| DMatrix::from_element(s, dim, f64::NAN));
            sensitivity.push(moved);
        }
        sensitivity
    }

    /// `fit.csv`'s rows at `y`.
    fn table(&self, y: &[f64]) -> Result<Table, Failure> {
        let s = self.state();
        let mut header = vec!["t".to_string()];
        header.extend(self.columns.iter().cloned());
        header.extend(
            self.measured
                .iter()
                .map(|&k| format!("data({})", self.columns[k])),
        );
        let mut table = Table::new();
        Recorder::start(&mut table, &header)?;
        for (i, t) in self.times.iter().enumerate() {
            let mut row = vec![*t];
            row.extend_from_slice(&y[i * s..(i + 1) * s]);
            row.extend_from_slice(&self.data[i]);
            Recorder::record(&mut table, &row)?;
        }
        Ok(table)
    }
}

/// The nodes' times: the data's own, or `nodes` of them evenly spread
/// over its span.
fn node_times(read: &Guess, nodes: Option<usize>) -> Result<Vec<f64>, IdentifyError> {
    let count = nodes.unwrap_or(read.rows());
    if count < 2 {
        return Err(IdentifyError::Nodes(count));
    }
    if nodes.is_none() {
        return Ok(read.times().to_vec());
    }
    let (first, last) = read.span();
    let step = (last - first) / (count - 1) as f64;
    Ok((0..count).map(|i| first + i as f64 * step).collect())
}

/// The nodes' states and inputs, node by node.
fn interleave(states: &[f64], inputs: &[Vec<f64>], s: usize) -> Vec<f64> {
    states
        .chunks(s)
        .zip(inputs)
        .flat_map(|(x, u)| x.iter().chain(u).copied())
        .collect()
}

impl Nlp for Fit {
    fn variables(&self) -> usize {
        self.guess.len()
    }

    fn constraints(&self) -> usize {
        self.defects() + initial_rows(self.transcription.borrow().model())
    }

    fn bounds(&self) -> (&[f64], &[f64]) {
        (&self.lo, &self.hi)
    }

    fn guess(&self) -> Vec<f64> {
        self.guess.clone()
    }

    fn objective(&self, y: &[f64]) -> Option<f64> {
        let s = self.state();
        let rss: f64 = self
            .data
            .iter()
            .enumerate()
            .flat_map(|(i, row)| {
                self.measured
                    .iter()
                    .zip(row)
                    .map(move |(&k, d)| (y[i * s + k] - d).powi(2))
            })
            .sum();
        rss.is_finite().then_some(rss)
    }

    fn gradient(&self, y: &[f64], gradient: &mut [f64]) -> bool {
        let s = self.state();
        gradient.fill(0.0);
        for (i, row) in self.data.iter().enumerate() {
            for (&k, d) in self.measured.iter().zip(row) {
                gradient[i * s + k] = 2.0 * (y[i * s + k] - d);
            }
        }
        super::transcription::finite(gradient)
    }

    fn residuals(&self, y: &[f64], residuals: &mut [f64]) -> bool {
        let z = self.transcribed(y);
        let transcription = self.transcription.borrow();
        let defects = self.defects();
        let finite = transcription.residuals(&z, &mut residuals[..defects]);
        let initial = self.initial_terms(transcription.model(), &z[..self.state()]);
        residuals[defects..].copy_from_slice(&initial.values);
        finite && super::transcription::finite(residuals)
    }

    fn jacobian_structure(&self) -> &[(usize, usize)] {
        &self.structure
    }

    fn describe_row(&self, y: &[f64], row: usize) -> String {
        let z = self.transcribed(y);
        let transcription = self.transcription.borrow();
        match row.checked_sub(self.defects()) {
            None => transcription.describe_defect(&z, row),
            Some(r) => format!(
                "the first row's {}",
                initial_row_name(transcription.model(), r)
            ),
        }
    }

    fn jacobian_values(&self, y: &[f64], values: &mut [f64]) -> bool {
        let z = self.transcribed(y);
        let transcription = self.transcription.borrow();
        let mut all = vec![0.0; transcription.jacobian_structure().len()];
        let finite = transcription.jacobian_values(&z, &mut all);
        for (value, &index) in values.iter_mut().zip(&self.kept) {
            *value = all[index];
        }
        let mut at = self.kept.len();
        for i in 0..self.times.len() - 1 {
            let block = self.defect_by_parameters(&transcription, &z, i);
            values[at..at + block.len()].copy_from_slice(&block);
            at += block.len();
        }
        let initial = self.initial_terms(transcription.model(), &z[..self.state()]);
        for (value, entry) in values[at..]
            .iter_mut()
            .zip(initial.jacobian.transpose().iter())
        {
            *value = *entry;
        }
        finite && super::transcription::finite(values)
    }

    fn hessian_structure(&self) -> Vec<(usize, usize)> {
        self.lagrangian_hessian_structure()
    }

    fn hessian_values(
        &self,
        y: &[f64],
        objective_factor: f64,
        multipliers: &[f64],
        values: &mut [f64],
    ) -> bool {
        self.lagrangian_hessian(y, objective_factor, multipliers, values)
    }
}

mod guess;
mod hessian;
mod initial;
#[cfg(test)]
mod tests;
