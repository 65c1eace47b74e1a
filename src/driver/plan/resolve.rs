//! A plan's request read against its model: the parameters set, the
//! conditions and bounds turned into the variables' bounds, the first
//! guess (`--guess`'s columns interpolated, else the start and goal
//! interpolated, else 0, inside the bounds), the costs read; and the
//! solution written as `plan.csv`'s rows. In the reduced and momentum
//! forms the conditions and the guess, resolved on `(q, qdot, u)`, become
//! the variables `(q, alpha, u)` or `(q, rdot, p, u)` (`form`'s docs). With `--free-duration` the
//! duration follows the nodes' variables, started at `--duration` and
//! bounded below by [`Request::SHORTEST`] times it (near `T = 0` the
//! defects cannot move the state, and the solver would not return).

mod ends;
mod goal;
pub(super) mod guess;

use super::Request;
use super::form::Form;
use super::initial::{self, Held};
use super::transcription::{Costs, Grid, Transcription};
use crate::driver::engine::Loaded;
use crate::driver::expression::{Expression, ExpressionError, Scope, constant};
use crate::driver::interpreted::holonomic_residual;
use crate::driver::setup::with_parameters;
use crate::runtime::record::Table;
use chaplygin_codegen::interpret::{InterpretedModel, evaluated};
use guess::Guess;

/// A request that does not make a plan of its model, stated in one line.
#[derive(Debug, PartialEq, thiserror::Error)]
pub enum RequestError {
    /// Fewer than two nodes.
    #[error("--nodes {0}: a plan needs at least 2 nodes")]
    Nodes(usize),
    /// A duration that is not positive and finite.
    #[error("--duration {0}: the duration must be positive and finite")]
    Duration(f64),
    /// A first guess of a free duration that is not positive and finite.
    #[error("--duration {0}: the free duration's first guess must be positive and finite")]
    FirstDuration(f64),
    /// A table (`--guess`, `--data`) that cannot be read.
    #[error("{flag} {path}: {reason}")]
    GuessFile {
        /// The flag it came with.
        flag: &'static str,
        /// The file.
        path: String,
        /// Why.
        reason: String,
    },
    /// A table with columns that are not the model's.
    #[error("{flag} {path}: unknown columns {unknown} (t, {known}{others})")]
    GuessColumns {
        /// The flag it came with.
        flag: &'static str,
        /// The other columns read and ignored, as a phrase.
        others: &'static str,
        /// The file.
        path: String,
        /// The columns unknown.
        unknown: String,
        /// A node's variables.
        known: String,
    },
    /// A tolerance that is not positive and finite.
    #[error("--tol {0}: the tolerance must be positive and finite")]
    Tolerance(f64),
    /// A replay's tolerance that is not positive and finite.
    #[error("--replay-tol {0}: the replay's tolerance must be positive and finite")]
    ReplayTolerance(f64),
    /// A name that is no coordinate, velocity or input.
    #[error("{flag}: unknown name `{name}` (coordinates, `dot(q)` velocities, inputs: {known})")]
    UnknownName {
        /// The flag it came with.
        flag: &'static str,
        /// What was given.
        name: String,
        /// The names there are.
        known: String,
    },
    /// A start or goal given to an input.
    #[error("{flag} {name}: `{name}` is an input; bound it with --bound instead")]
    InputCondition {
        /// The flag it came with.
        flag: &'static str,
        /// The input.
        name: String,
    },
    /// A bound that is not `LO:HI`.
    #[error("--bound {name}={text}: expected LO:HI (either may be empty)")]
    Range {
        /// What it bounds.
        name: String,
        /// The text given.
        text: String,
    },
    /// A bound whose lower end exceeds its upper end.
    #[error(
        "--bound {name}: the lower end {lo} exceeds the upper end {hi}: the plan is infeasible"
    )]
    Empty {
        /// What it bounds.
        name: String,
        /// The lower end.
        lo: f64,
        /// The upper end.
        hi: f64,
    },
    /// A start or goal outside a bound.
    #[error("{flag} {name}={value} lies outside --bound {name}={lo}:{hi}: the plan is infeasible")]
    Outside {
        /// The flag it came with.
        flag: &'static str,
        /// What it sets.
        name: String,
        /// Its value.
        value: f64,
        /// The bound's ends.
        lo: f64,
        /// The bound's upper end.
        hi: f64,
    },
    /// A value that is not an expression of the parameters.
    #[error("{flag} {name}: {source}")]
    Value {
        /// The flag it came with.
        flag: &'static str,
        /// What it sets.
        name: String,
        /// Why.
        source: ExpressionError,
    },
    /// A bound on a velocity the form's state does not hold.
    #[error(
        "--bound {name}: the {form} form's state does not hold this velocity; bound it with \
         --formulation lagrange"
    )]
    UnheldVelocityBound {
        /// The velocity.
        name: String,
        /// The form.
        form: &'static str,
    },
    /// An end with some velocities given in a form whose state does not
    /// hold them.
    #[error(
        "{flag}: the {form} form fixes an end's state from all its velocities and coordinates \
         (or all velocities 0), but {missing} are not given; give them, or use --formulation \
         lagrange"
    )]
    PartialVelocities {
        /// The flag of the end.
        flag: &'static str,
        /// The form.
        form: &'static str,
        /// The names not given.
        missing: String,
    },
    /// A start off the model's constraints.
    #[error("the start is off the model's constraints: residual {0:.1e}")]
    StartOffConstraints(f64),
    /// A goal whose given velocities no allowed velocity at its pose has.
    #[error(
        "--goal: the given velocities break the model's constraints at the goal's pose (least \
         residual {0:.1e}, relative to them)"
    )]
    GoalOffConstraints(f64),
}

/// What a start or goal is checked against: `|A qdot|` and `|f(q)|` up
/// to this.
const ON_CONSTRAINTS: f64 = 1e-10;

/// `plan.csv`'s columns after the nodes' variables (`holonomic_residual`
/// only with configuration constraints, `chart` only in the reduced form
/// of a model with constraints).
pub(super) const DERIVED_COLUMNS: [&str; 4] = [
    "energy",
    "constraint_residual",
    "holonomic_residual",
    "chart",
];

/// `--guess`: a table of `plan.csv`'s columns, its derived ones ignored.
const GUESS_TABLE: guess::Table = guess::Table {
    flag: "--guess",
    ignored: &DERIVED_COLUMNS,
    others: " and plan.csv's others",
};

/// The names of a node's variables: the coordinates, `dot(q)`, the
/// inputs.
pub(super) fn node_columns(model: &InterpretedModel) -> Vec<String> {
    let names = model.names();
    let velocities = names.coordinates.iter().map(|q| format!("dot({q})"));
    let mut columns: Vec<String> = names
        .coordinates
        .iter()
        .cloned()
        .chain(velocities)
        .collect();
    columns.extend(names.inputs.iter().cloned());
    columns
}

/// The variables' bounds and guess, and the cost, built up from a request.
struct Resolver<'a> {
    columns: Vec<String>,
    /// The number of coordinates.
    n: usize,
    parameters: Vec<(&'a str, f64)>,
    nodes: usize,
    lo: Vec<f64>,
    hi: Vec<f64>,
    /// The start's and goal's values, by column.
    ends: [Vec<Option<f64>>; 2],
}

impl Resolver<'_> {
    /// The column `name` is, from `flag`.
    fn column(&self, flag: &'static str, name: &str) -> Result<usize, RequestError> {
        let name: String = name.chars().filter(|c| !c.is_whitespace()).collect();
        self.columns
            .iter()
            .position(|c| *c == name)
            .ok_or_else(|| RequestError::UnknownName {
                flag,
                name,
                known: self.columns.join(", "),
            })
    }

    /// The value of `text`, from `flag` for `name`.
    fn value(&self, flag: &'static str, name: &str, text: &str) -> Result<f64, RequestError> {
        constant(text, &self.parameters).map_err(|source| RequestError::Value {
            flag,
            name: name.to_string(),
            source,
        })
    }

    /// `--bound NAME=LO:HI` at every node.
    fn bound(&mut self, name: &str, text: &str) -> Result<(), RequestError> {
        let column = self.column("--bound", name)?;
        let range = || RequestError::Range {
            name: name.to_string(),
            text: text.to_string(),
        };
        let (lo, hi) = text.split_once(':').ok_or_else(range)?;
        let end = |text: &str, infinite: f64| match text.trim() {
            "" => Ok(infinite),
            text => self.value("--bound", name, text),
        };
        let (lo, hi) = (end(lo, f64::NEG_INFINITY)?, end(hi, f64::INFINITY)?);
        if lo > hi {
            let name = name.to_string();
            return Err(RequestError::Empty { name, lo, hi });
        }
        let width = self.columns.len();
        for node in 0..self.nodes {
            let j = node * width + column;
            self.lo[j] = self.lo[j].max(lo);
            self.hi[j] = self.hi[j].min(hi);
        }
        Ok(())
    }

    /// `--start` (`end` 0) or `--goal` (`end` 1) `NAME=EXPR`.
    fn condition(&mut self, end: usize, name: &str, text: &str) -> Result<(), RequestError> {
        let flag = ["--start", "--goal"][end];
        let column = self.column(flag, name)?;
        if column >= 2 * self.n {
            let name = name.to_string();
            return Err(RequestError::InputCondition { flag, name });
        }
        let value = self.value(flag, name, text)?;
        let j = [0, self.nodes - 1][end] * self.columns.len() + column;
        if value < self.lo[j] || value > self.hi[j] {
            let (name, lo, hi) = (self.columns[column].clone(), self.lo[j], self.hi[j]);
            return Err(RequestError::Outside {
                flag,
                name,
                value,
                lo,
                hi,
            });
        }
        (self.lo[j], self.hi[j]) = (value, value);
        self.ends[end][column] = Some(value);
        Ok(())
    }

    /// The nodes' variables: `read`'s columns at the nodes' times, `step`
    /// apart; the rest the start and goal interpolated, else 0; all inside
    /// the bounds.
    fn guess(&self, read: Option<&Guess>, step: f64) -> Vec<f64> {
        let width = self.columns.len();
        let last = (self.nodes - 1) as f64;
        let mut guess: Vec<f64> = (0..self.nodes * width)
            .map(|j| {
                let (node, column) = (j / width, j % width);
                let s = node as f64 / last;
                match (self.ends[0][column], self.ends[1][column]) {
                    (Some(a), Some(b)) => a + s * (b - a),
                    (Some(a), None) | (None, Some(a)) => a,
                    (None, None) => 0.0,
                }
            })
            .collect();
        for (node, values) in guess.chunks_mut(width).enumerate() {
            for (column, value) in read.into_iter().flat_map(|r| r.at(node as f64 * step)) {
                values[column] = value;
            }
        }
        for (j, value) in guess.iter_mut().enumerate() {
            *value = value.clamp(self.lo[j], self.hi[j]);
        }
        guess
    }

    /// The bounds and guess of `form`'s variables `(q, x2, u)` from the
    /// ones of `(q, qdot, u)`: the state's second part `x2` (`alpha`, or
    /// `(rdot, p)`) fixed at an end whose velocities are given, else
    /// guessed as the state of `(q, qdot)`, free but for the bounds of the
    /// velocities it holds.
    fn in_form(
        &self,
        (form, model): (Form, &InterpretedModel),
        (lo, hi, guess): (&[f64], &[f64], &[f64]),
    ) -> Result<[Vec<f64>; 3], RequestError> {
        let (n, width) = (self.n, self.columns.len());
        let [start, goal] = [0, 1].map(|end| {
            let flag = ["--start", "--goal"][end];
            let (given, at) = (&self.ends[end], end * (self.nodes - 1) * width);
            let q = &guess[at..at + n];
            ends::end_state(form, model, (flag, q), (&given[..n], &given[n..2 * n]))
        });
        let fixed = [start?, goal?];
        let second = form.state(model) - n;
        let held: Vec<Option<usize>> = (0..n).map(|i| form.velocity_column(model, i)).collect();
        let mut variables: [Vec<f64>; 3] = Default::default();
        for node in 0..self.nodes {
            let at = node * width;
            let (q, qdot) = (&guess[at..at + n], &guess[at + n..at + 2 * n]);
            let ends = [node == 0, node == self.nodes - 1];
            let given = (0..2).filter(|&e| ends[e]).find_map(|e| fixed[e].clone());
            let middles = given.map_or_else(
                || {
                    let mut middles =
                        [vec![f64::NEG_INFINITY; second], vec![f64::INFINITY; second]];
                    for (i, column) in held.iter().enumerate() {
                        if let Some(column) = column {
                            middles[0][column - n] = lo[at + n + i];
                            middles[1][column - n] = hi[at + n + i];
                        }
                    }
                    let [lo, hi] = middles;
                    [lo, hi, form.state_of(model, q, qdot).split_off(n)]
                },
                |x2| [x2.clone(), x2.clone(), x2],
            );
            for ((out, values), middle) in variables.iter_mut().zip([lo, hi, guess]).zip(middles) {
                out.extend_from_slice(&values[at..at + n]);
                out.extend(middle);
                out.extend_from_slice(&values[at + 2 * n..at + width]);
            }
        }
        Ok(variables)
    }

    /// The model's constraints the plan holds at its first node: none
    /// where the start is given whole (it is checked to meet them), the
    /// configuration constraints where it leaves a coordinate free, and in
    /// the Lagrange form the velocity constraints where it leaves a
    /// coordinate or a velocity free, unless every velocity is given 0.
    /// (The reduced and momentum states meet the velocity constraints by
    /// construction.)
    ///
    /// # Errors
    /// [`RequestError::StartOffConstraints`] for a start whose given
    /// coordinates, or whole state, break them.
    fn held_at_start(
        &self,
        model: &InterpretedModel,
        form: Form,
    ) -> Result<Vec<Held>, RequestError> {
        let n = self.n;
        let start = &self.ends[0][..2 * n];
        let given = |range: std::ops::Range<usize>| -> Option<Vec<f64>> {
            start[range].iter().copied().collect()
        };
        let (q, qdot) = (given(0..n), given(n..2 * n));
        let off = |residual: f64| residual > ON_CONSTRAINTS;
        if let Some(q) = &q {
            let residual = holonomic_residual(model, q).unwrap_or(0.0);
            if off(residual) {
                return Err(RequestError::StartOffConstraints(residual));
            }
            if let Some(qdot) = &qdot {
                let residual = constraint_residual(model, q, qdot);
                return if off(residual) {
                    Err(RequestError::StartOffConstraints(residual))
                } else {
                    Ok(Vec::new())
                };
            }
        }
        let at_rest = qdot.is_some_and(|qdot| qdot.iter().all(|v| *v == 0.0));
        let free = [q.is_none(), form == Form::Lagrange && !at_rest];
        Ok(initial::declared(model)
            .into_iter()
            .filter(|held| match held {
                Held::Configuration => free[0],
                Held::Velocity => free[1],
            })
            .collect())
    }
}

/// The largest `|A(q) qdot|`.
fn constraint_residual(model: &InterpretedModel, q: &[f64], qdot: &[f64]) -> f64 {
    evaluated(model.constraint_residual(q, qdot))
        .iter()
        .fold(0.0, |worst, r| worst.max(r.abs()))
}

/// The checks of the request's numbers.
fn check_numbers(request: &Request) -> Result<(), RequestError> {
    if request.nodes < 2 {
        return Err(RequestError::Nodes(request.nodes));
    }
    if !(request.duration.is_finite() && request.duration > 0.0) {
        return Err(if request.free_duration {
            RequestError::FirstDuration(request.duration)
        } else {
            RequestError::Duration(request.duration)
        });
    }
    if !(request.tol.is_finite() && request.tol > 0.0) {
        return Err(RequestError::Tolerance(request.tol));
    }
    Ok(())
}

/// The plan `request` asks of `loaded`, transcribed.
///
/// # Errors
/// A [`RequestError`], an unknown parameter, or a cost that is not an
/// expression of the names in scope.
pub(super) fn transcribe(
    loaded: Loaded,
    request: &Request,
) -> Result<Transcription, crate::driver::Failure> {
    check_numbers(request)?;
    let mut model = loaded.model;
    let form = super::formulation(request.formulation, &model)?;
    let parameters = with_parameters(&mut model, &request.params)?;
    let columns = node_columns(&model);
    let size = request.nodes * columns.len();
    let mut resolver = Resolver {
        ends: [vec![None; columns.len()], vec![None; columns.len()]],
        columns,
        n: model.sizes().n,
        parameters: parameters.iter().map(|(n, v)| (n.as_str(), *v)).collect(),
        nodes: request.nodes,
        lo: vec![f64::NEG_INFINITY; size],
        hi: vec![f64::INFINITY; size],
    };
    for (name, text) in &request.bounds {
        resolver.bound(name, text)?;
        let column = resolver.column("--bound", name)?;
        let velocity = column.checked_sub(resolver.n).filter(|&i| i < resolver.n);
        if velocity.is_some_and(|i| form.velocity_column(&model, i).is_none()) {
            let (name, form) = (name.clone(), form.name());
            return Err(RequestError::UnheldVelocityBound { name, form }.into());
        }
    }
    for (end, conditions) in [&request.start, &request.goal].into_iter().enumerate() {
        for (name, text) in conditions {
            resolver.condition(end, name, text)?;
        }
    }
    if let Some(residual) = goal::residual(&model, &resolver.ends[1])
        && residual > ON_CONSTRAINTS
    {
        return Err(RequestError::GoalOffConstraints(residual).into());
    }
    let held = resolver.held_at_start(&model, form)?;
    let costs = Costs {
        running: running_cost(&model, &resolver.parameters, request.minimize.as_deref())?,
        terminal: request
            .final_cost
            .as_deref()
            .map(|text| final_cost(&model, &resolver.parameters, text))
            .transpose()?,
    };
    let read = request
        .guess
        .as_deref()
        .map(|path| Guess::of_model((GUESS_TABLE, &model, &[]), path, None))
        .transpose()?;
    let step = request.duration / (request.nodes - 1) as f64;
    let guess = resolver.guess(read.as_ref(), step);
    let [mut lo, mut hi, mut guess] = match form {
        Form::Lagrange => [resolver.lo, resolver.hi, guess],
        _ => resolver.in_form((form, &model), (&resolver.lo, &resolver.hi, &guess))?,
    };
    if request.free_duration {
        lo.push(Request::SHORTEST * request.duration);
        hi.push(f64::INFINITY);
        guess.push(request.duration);
    }
    let grid = Grid {
        nodes: request.nodes,
        duration: request.duration,
        free_duration: request.free_duration,
        fractions: None,
    };
    Ok(
        Transcription::new(model, request.scheme, grid, costs, (lo, hi, guess))
            .in_form(form)
            .holding_start(held),
    )
}

/// The coordinates' and inputs' names of `model`.
fn scope_names(model: &InterpretedModel) -> (Vec<&str>, Vec<&str>) {
    let names = model.names();
    (
        names.coordinates.iter().map(String::as_str).collect(),
        names.inputs.iter().map(String::as_str).collect(),
    )
}

/// `--final-cost`, an expression of `t`, the state and the parameters.
fn final_cost(
    model: &InterpretedModel,
    parameters: &[(&str, f64)],
    text: &str,
) -> Result<Expression, RequestError> {
    let (coordinates, _) = scope_names(model);
    let scope = Scope {
        parameters,
        coordinates: &coordinates,
        ..Scope::default()
    };
    Expression::parse(text, &scope).map_err(|source| RequestError::Value {
        flag: "--final-cost",
        name: text.to_string(),
        source,
    })
}

/// `--minimize`, or the sum of the inputs squared.
fn running_cost(
    model: &InterpretedModel,
    parameters: &[(&str, f64)],
    minimize: Option<&str>,
) -> Result<Expression, RequestError> {
    let (coordinates, inputs) = scope_names(model);
    let scope = Scope {
        parameters,
        coordinates: &coordinates,
        inputs: &inputs,
        ..Scope::default()
    };
    let squares = inputs.iter().map(|u| format!("{u}^2")).collect::<Vec<_>>();
    let default = if squares.is_empty() {
        "0".to_string()
    } else {
        squares.join(" + ")
    };
    let text = minimize.unwrap_or(&default);
    Expression::parse(text, &scope).map_err(|source| RequestError::Value {
        flag: "--minimize",
        name: text.to_string(),
        source,
    })
}

/// `plan.csv`'s rows, as `trajectory.csv`'s in the plan's formulation:
/// `t`, the node's state and inputs, `energy`, `constraint_residual`,
/// with configuration constraints `holonomic_residual`, and in the
/// reduced form of a model with constraints its `chart`.
pub(super) fn table(
    transcription: &Transcription,
    z: &[f64],
) -> Result<Table, crate::driver::Failure> {
    let (model, form) = (transcription.model(), transcription.form());
    let (n, s) = (model.sizes().n, form.state(model));
    let holonomic = !model.names().holonomic.is_empty();
    let chart = form.chart(model);
    let mut columns = vec!["t".to_string()];
    columns.extend(form.state_names(model));
    columns.extend(model.names().inputs.iter().cloned());
    let derived = DERIVED_COLUMNS
        .iter()
        .zip([true, true, holonomic, chart.is_some()]);
    columns.extend(
        derived
            .filter(|(_, kept)| *kept)
            .map(|(c, _)| c.to_string()),
    );
    let mut table = Table::new();
    crate::runtime::record::Recorder::start(&mut table, &columns)?;
    let width = transcription.width();
    for (i, node) in z[..transcription.nodes() * width].chunks(width).enumerate() {
        let q = &node[..n];
        let qdot = form.velocities(model, &node[..s]);
        let mut row = vec![transcription.node_time(z, i)];
        row.extend_from_slice(&node[..s]);
        row.extend_from_slice(&transcription.held_inputs(z, i));
        row.push(evaluated(model.energy(q, &qdot)));
        row.push(constraint_residual(model, q, &qdot));
        row.extend(holonomic_residual(model, q));
        row.extend(chart.map(|c| c as f64));
        crate::runtime::record::Recorder::record(&mut table, &row)?;
    }
    Ok(table)
}
