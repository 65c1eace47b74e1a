//! `chaplygin linearize MODEL [--at NAME=EXPR]... [--sweep VAR=START:STOP:STEP]
//! [--param NAME=VALUE]... [--out DIR] [--canonical Q1,Q2,... --canonical-speed
//! VAR[=V1,V2] [--canonical-gravity NAME]]` (INTERFACE.md section 5): the
//! operating point from `--at` (`chaplygin::runtime::linearize::point`),
//! the linear system about it with the symmetry reduced and the constraints
//! eliminated (`chaplygin::runtime::linearize::steady`), its eigenvalues;
//! with `--sweep`, `DIR/eigenvalues.csv`, `DIR/eigenvalues.png` and the
//! intervals of VAR where the motion is asymptotically stable and where it
//! is neutrally stable (every eigenvalue but the conserved quantities'
//! zeros on the imaginary axis), their ends refined by bisection between
//! grid points (`sweep::refined_intervals`); with
//! `--canonical Q1,Q2 --canonical-speed VAR`, the canonical form
//! `M qddot + v C1 qdot + (g K0 + v^2 K2) q = f` of Meijaard et al. (2007)
//! in those coordinates (`canonical`). The inputs are zero.

mod canonical;
mod expression;
mod sweep;

use crate::catalog::{self, Source};
use crate::engine::{self, EngineChoice};
use crate::interpreted::dynamics::InterpretedDynamics;
pub use canonical::CanonicalSpeed;
use chaplygin::plot::{EigenvalueSweep, write_eigenvalue_plot};
use chaplygin::runtime::linearize::{
    self as runtime_linearize, Dynamics, LinearSystem, OperatingPoint, PointError, SteadyError,
};
use expression::{ExpressionError, evaluate};
use std::collections::BTreeMap;
use std::error::Error;
use std::fmt::Write as _;
use std::path::PathBuf;
use sweep::Interval;
pub use sweep::Sweep;

/// The arguments of `chaplygin linearize`.
#[derive(Debug, clap::Args)]
pub struct LinearizeArgs {
    /// A built-in model's name, or the path of a `.model` file.
    pub model: String,
    /// A coordinate (`phi=0`) or a velocity (`dot(theta)=-v/r`) of the
    /// operating point; EXPR may use the parameters, the sweep variable and
    /// the `--canonical-speed` variable.
    #[arg(long = "at", value_name = "NAME=EXPR", value_parser = at)]
    pub at: Vec<(String, String)>,
    /// Sweep VAR from START to STOP (included when on the grid) by STEP.
    #[arg(long, value_parser = sweep::parse)]
    pub sweep: Option<Sweep>,
    /// A parameter's value, `NAME=VALUE`.
    #[arg(long = "param", value_parser = crate::simulate::assignment)]
    pub params: Vec<(String, f64)>,
    /// Where `--sweep` writes `eigenvalues.csv` and `eigenvalues.png`.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// What runs a model from its text: native code compiled at run time,
    /// or the IR interpreter.
    #[arg(long, value_enum, default_value_t = EngineChoice::Jit)]
    pub engine: EngineChoice,
    /// Print the canonical form M qddot + v C1 qdot + (g K0 + v^2 K2) q = f
    /// (Meijaard et al. 2007) in these coordinates, comma-separated
    /// (`phi,delta`); f are the inputs, one per coordinate.
    #[arg(
        long,
        value_name = "Q1,Q2,...",
        value_delimiter = ',',
        requires = "canonical_speed",
        conflicts_with = "sweep"
    )]
    pub canonical: Vec<String>,
    /// The speed v of `--canonical`: a variable the `--at` expressions use,
    /// set to 1 and 2 (`VAR`) or to V1 and V2 (`VAR=V1,V2`).
    #[arg(
        long,
        value_name = "VAR[=V1,V2]",
        value_parser = canonical::speed,
        requires = "canonical"
    )]
    pub canonical_speed: Option<CanonicalSpeed>,
    /// The gravity parameter of `--canonical`: K0 is the speed-independent
    /// stiffness divided by its value.
    #[arg(long, value_name = "NAME", default_value = "g", requires = "canonical")]
    pub canonical_gravity: String,
}

/// `NAME=EXPR`.
fn at(text: &str) -> Result<(String, String), String> {
    let (name, expression) = text
        .split_once('=')
        .ok_or_else(|| format!("expected NAME=EXPR, found `{text}`"))?;
    Ok((name.trim().to_string(), expression.trim().to_string()))
}

/// A problem with the command's input or its operating point, in one line.
#[derive(Debug, thiserror::Error)]
pub enum LinearizeError {
    /// `--at` names neither a coordinate nor a velocity.
    #[error("--at: unknown name `{name}` (coordinates and `dot(q)` velocities: {known})")]
    UnknownName {
        /// The name given.
        name: String,
        /// The names there are.
        known: String,
    },
    /// The sweep variable is also a parameter.
    #[error(
        "--sweep: `{0}` is a parameter; sweep a new name and use it in --at or --param expressions"
    )]
    ParameterSwept(String),
    /// An `--at` expression.
    #[error("--at: {0}")]
    Expression(#[from] ExpressionError),
    /// The operating point.
    #[error(transparent)]
    Point(#[from] PointError),
    /// The steady motion or its linearization.
    #[error(transparent)]
    Steady(#[from] SteadyError),
    /// The grid.
    #[error(transparent)]
    Sweep(#[from] sweep::SweepError),
    /// A problem at one point of a sweep.
    #[error("at {variable} = {value}: {source}")]
    AtSweepValue {
        /// The sweep variable.
        variable: String,
        /// Its value there.
        value: f64,
        /// What went wrong.
        source: Box<LinearizeError>,
    },
}

/// Runs `chaplygin linearize`.
///
/// # Errors
/// Bad input, a point that is not a steady motion, an I/O error.
pub fn run(args: &LinearizeArgs) -> Result<(), Box<dyn Error>> {
    let source = catalog::lookup(&args.model)?;
    let (path, text) = match &source {
        Source::File { path, text } => (path.as_str(), text.as_str()),
        Source::BuiltIn(built_in) => (built_in.name, built_in.source),
    };
    let mut model = engine::load(path, text, args.engine)?;
    let known = model.names().parameters.clone();
    let known: Vec<&str> = known.iter().map(String::as_str).collect();
    crate::simulate::set_parameters(&known, &args.params, &mut |name, value| {
        model.set_parameter(name, value).is_ok()
    })?;
    let parameters = known
        .iter()
        .zip(model.parameter_values())
        .map(|(name, value)| (name.to_string(), *value))
        .collect();
    analyse(&InterpretedDynamics(model), parameters, args)
}

/// Linearizes at one point, or over the sweep.
fn analyse(
    model: &dyn Dynamics,
    parameters: BTreeMap<String, f64>,
    args: &LinearizeArgs,
) -> Result<(), Box<dyn Error>> {
    if let Some(speed) = &args.canonical_speed {
        let request = canonical::Request {
            coordinates: &args.canonical,
            speed,
            gravity: &args.canonical_gravity,
        };
        let form = canonical::canonical_form(model, &parameters, &args.at, &request)?;
        return Ok(crate::say(&form)?);
    }
    let Some(sweep) = &args.sweep else {
        let linear = linearize_at(model, &parameters, &args.at, &[])?;
        return Ok(crate::say(&describe(&linear))?);
    };
    if parameters.contains_key(&sweep.variable) {
        return Err(LinearizeError::ParameterSwept(sweep.variable.clone()).into());
    }
    let values = sweep.grid().map_err(LinearizeError::from)?;
    let mut eigenvalues = Vec::with_capacity(values.len());
    let mut linears = Vec::with_capacity(values.len());
    for &value in &values {
        let mut names = parameters.clone();
        names.insert(sweep.variable.clone(), value);
        let linear = linearize_at(model, &names, &args.at, &[]).map_err(|source| {
            LinearizeError::AtSweepValue {
                variable: sweep.variable.clone(),
                value,
                source: Box::new(source),
            }
        })?;
        eigenvalues.push(linear.eigenvalues.iter().map(|e| (e.re, e.im)).collect());
        linears.push(linear);
    }
    // The zeros of conserved quantities are those every point of the family
    // has: a point with more has an eigenvalue crossing zero.
    let conserved = linears
        .iter()
        .map(LinearSystem::conserved_zeros)
        .min()
        .unwrap_or(0);
    // A grid point is stable by a margin; between grid points the change
    // of stability is where the largest real part crosses zero.
    let verdicts = |holds: Verdict, between: Verdict| {
        let on_grid: Vec<bool> = linears.iter().map(|l| holds(l, conserved)).collect();
        sweep::refined_intervals(&values, &on_grid, |value| {
            let mut names = parameters.clone();
            names.insert(sweep.variable.clone(), value);
            linearize_at(model, &names, &args.at, &[])
                .map(|linear| between(&linear, conserved))
                .map_err(|source| LinearizeError::AtSweepValue {
                    variable: sweep.variable.clone(),
                    value,
                    source: Box::new(source),
                })
        })
    };
    let stable = verdicts(LinearSystem::is_stable_modulo, |linear, conserved| {
        linear.largest_real_part_modulo(conserved) < 0.0
    })?;
    let neutral = verdicts(
        LinearSystem::is_neutral_modulo,
        LinearSystem::is_neutral_modulo,
    )?;
    let csv_file = args.out.join("eigenvalues.csv");
    sweep::write(
        &csv_file,
        &sweep::csv(&sweep.variable, &values, &eigenvalues),
    )
    .map_err(|error| format!("cannot write {}: {error}", csv_file.display()))?;
    let png_file = args.out.join("eigenvalues.png");
    let plotted = EigenvalueSweep {
        variable: sweep.variable.clone(),
        values: values.clone(),
        eigenvalues,
        stable: stable.iter().map(|interval| interval.refined).collect(),
    };
    write_eigenvalue_plot(&plotted, &png_file)?;
    let wrote = format!("wrote {} and {}\n", csv_file.display(), png_file.display());
    crate::say(&wrote)?;
    Ok(crate::say(&stability(
        &sweep.variable,
        conserved,
        [
            ("asymptotically stable", &stable),
            ("neutrally stable", &neutral),
        ],
    ))?)
}

/// The point `--at` describes with the names bound, linearized, the
/// entries named `independent` kept in the state.
fn linearize_at(
    model: &dyn Dynamics,
    names: &BTreeMap<String, f64>,
    at: &[(String, String)],
    independent: &[&str],
) -> Result<LinearSystem, LinearizeError> {
    let coordinates = model.coordinates();
    let velocities = runtime_linearize::point::velocity_names(&coordinates);
    let mut q = vec![None; coordinates.len()];
    let mut qdot = vec![None; coordinates.len()];
    for (name, text) in at {
        let value = evaluate(text, names)?;
        if let Some(i) = coordinates.iter().position(|c| c == name) {
            q[i] = Some(value);
        } else if let Some(i) = velocities.iter().position(|v| v == name) {
            qdot[i] = Some(value);
        } else {
            return Err(LinearizeError::UnknownName {
                name: name.clone(),
                known: coordinates
                    .iter()
                    .chain(&velocities)
                    .cloned()
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        }
    }
    let point = OperatingPoint::solve(model, &q, &qdot)?;
    let u = vec![0.0; model.inputs()];
    Ok(runtime_linearize::linearize(
        model,
        &point,
        &u,
        independent,
    )?)
}

/// The state, the eigenvalues and the verdict of one linearization.
fn describe(linear: &LinearSystem) -> String {
    let mut text = format!(
        "linear system in ({}), inputs zero\neigenvalues (by descending real part):\n",
        linear.state.join(", ")
    );
    for &eigenvalue in &linear.eigenvalues {
        let zero = if linear.is_zero(eigenvalue) {
            "   (zero)"
        } else {
            ""
        };
        let sign = if eigenvalue.im < 0.0 { '-' } else { '+' };
        let _ = writeln!(
            text,
            "  {:>16.9e} {sign} {:.9e} i{zero}",
            eigenvalue.re,
            eigenvalue.im.abs()
        );
    }
    let verdict = if linear.is_stable() { "yes" } else { "no" };
    let _ = writeln!(
        text,
        "asymptotically stable: {verdict} ({} zeros counted as conserved quantities)",
        linear.conserved_zeros()
    );
    text
}

/// Whether a linear system about a point of the sweep is stable in some
/// sense, the family's zeros of conserved quantities discounted.
type Verdict = fn(&LinearSystem, usize) -> bool;

/// The intervals of the sweep where the motion is asymptotically stable,
/// then neutrally stable, each `(grid, refined)`, as printed.
fn stability(variable: &str, conserved: usize, kinds: [(&str, &[Interval]); 2]) -> String {
    let mut text = String::new();
    for (kind, intervals) in kinds {
        if intervals.is_empty() {
            let _ = writeln!(text, "{kind} for no {variable} on the grid");
            continue;
        }
        let _ = writeln!(
            text,
            "{kind} (modulo {conserved} zeros of conserved quantities) for {variable} in \
             (ends refined by bisection between grid points):"
        );
        for interval in intervals {
            let ((first, last), (from, to)) = (interval.grid, interval.refined);
            let _ = writeln!(
                text,
                "  [{from:.9}, {to:.9}] (grid points [{first}, {last}])"
            );
        }
    }
    text
}
