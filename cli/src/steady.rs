//! `chaplygin steady MODEL [--at NAME=EXPR]... [--input NAME=EXPR]...
//! --solve NAME,... [--guess NAME=VALUE]... [--trace VAR=START:STOP:STEP]
//! [--param NAME=VALUE]... [--out DIR]` (docs/INTERFACE.md section 14), over
//! `chaplygin::driver::steady`: the steady motion near the guess, its
//! eigenvalues and whether it is stable, as `chaplygin linearize` prints
//! them; with `--trace`, the family followed over VAR's grid, its folds,
//! changes of stability and end, `DIR/steady.csv` (a row per grid point
//! crossed, VAR first) and `DIR/steady.png`. With `--out`,
//! `DIR/steady.csv` (one row: the unknowns, every
//! coordinate and velocity, the inputs, `radius` for a model with a planar
//! symmetry, the eigenvalues `re_i, im_i` and `stable`); an unknown that
//! is a coordinate has its column among the coordinates.

use crate::linearize::describe;
use crate::model_args::{ModelArgs, loaded};
use chaplygin::driver::Failure;
use chaplygin::driver::linearize::sweep;
use chaplygin::driver::simulate::{assignment, expression_assignment};
use chaplygin::driver::steady::trace::{self, Family};
use chaplygin::driver::steady::{Columns, Request, SteadyMotion, header, problem, row, steady};
use chaplygin::plot::{SteadyFamily, write_steady_plot};
use chaplygin::runtime::record::shortest_decimal;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The arguments of `chaplygin steady`.
#[derive(Debug, clap::Args)]
pub struct SteadyArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// A coordinate (`phi=0.1`) or a velocity (`dot(theta_r)=-v/rR`) of the
    /// steady motion; EXPR may use the parameters and the unknowns.
    #[arg(long = "at", value_name = "NAME=EXPR", value_parser = expression_assignment)]
    pub at: Vec<(String, String)>,
    /// An input's constant value, an expression of the parameters and the
    /// unknowns (`steer_torque=0`); inputs not given are zero.
    #[arg(long = "input", value_name = "NAME=EXPR", value_parser = expression_assignment)]
    pub inputs: Vec<(String, String)>,
    /// The unknowns: variables of the --at and --input expressions, or
    /// coordinates --at leaves free, comma-separated.
    #[arg(long, value_name = "NAME,...", value_delimiter = ',', required = true)]
    pub solve: Vec<String>,
    /// Where an unknown starts, `NAME=VALUE` (0 unless given).
    #[arg(long = "guess", value_parser = assignment)]
    pub guess: Vec<(String, f64)>,
    /// Follow the family over VAR (a variable of the expressions) from
    /// START to STOP by STEP, from the first solution.
    #[arg(long, value_name = "VAR=START:STOP:STEP", value_parser = trace_grid)]
    pub trace: Option<sweep::Sweep>,
    /// A parameter's value, `NAME=VALUE`.
    #[arg(long = "param", value_parser = assignment)]
    pub params: Vec<(String, f64)>,
    /// Where to write `steady.csv` (and with `--trace`, `steady.png`;
    /// default `out` there).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// `VAR=START:STOP:STEP`, its errors named by `--trace`.
fn trace_grid(text: &str) -> Result<sweep::Sweep, String> {
    sweep::parse(text).map_err(|error| error.replacen("--sweep", "--trace", 1))
}

/// Runs `chaplygin steady`.
///
/// # Errors
/// Bad input, no steady motion near the guess, an I/O error.
pub fn run(args: &SteadyArgs) -> Result<(), Failure> {
    let request = Request {
        params: &args.params,
        at: &args.at,
        inputs: &args.inputs,
        solve: &args.solve,
        guess: &args.guess,
        trace: args.trace.as_ref().map(|grid| grid.variable.as_str()),
    };
    let loaded = loaded(&args.model)?;
    let names = loaded.model.names().clone();
    let columns = Columns {
        coordinates: &names.coordinates,
        inputs: &names.inputs,
    };
    if let Some(grid) = &args.trace {
        let values =
            (grid.grid()).map_err(|error| error.to_string().replacen("--sweep", "--trace", 1))?;
        let family = trace::trace(&problem(loaded.model, &request)?, &values)?;
        let out = args.out.clone().unwrap_or_else(|| PathBuf::from("out"));
        return traced(&columns, (&grid.variable, &family), &out);
    }
    let motion = steady(loaded.model, &request)?;
    crate::say(&report(&motion))?;
    let Some(out) = &args.out else {
        return Ok(());
    };
    let file = out.join("steady.csv");
    let text = format!(
        "{}\n{}\n",
        header(&columns, &motion).join(","),
        fields(&columns, &motion)
    );
    sweep::write(&file, &text)
        .map_err(|error| format!("cannot write {}: {error}", file.display()))?;
    Ok(crate::say(&format!("wrote {}\n", file.display()))?)
}

/// The unknowns found, the radius, the eigenvalues and the verdict.
fn report(motion: &SteadyMotion) -> String {
    let mut text = format!(
        "steady motion after {} Gauss-Newton steps (largest rate left {:e}):\n",
        motion.steps, motion.residual
    );
    for (name, value) in &motion.values {
        let _ = writeln!(text, "  {name} = {value}");
    }
    if let Some(radius) = motion.radius {
        let _ = writeln!(text, "radius of the body frame origin's circle: {radius}");
    }
    text.push_str(&describe(&motion.linear, "as given"));
    if !motion.family.is_empty() {
        text.push_str("zero eigenvalues along the family of steady motions, in the directions:\n");
    }
    for direction in &motion.family {
        let terms: Vec<String> = (direction.iter())
            .map(|(entry, coefficient)| format!("{coefficient:+.6e} {entry}"))
            .collect();
        let _ = writeln!(text, "  {}", terms.join(" "));
    }
    text
}

/// Prints what happened along `family`, writes `steady.csv` and
/// `steady.png` in `out`.
fn traced(
    columns: &Columns<'_>,
    (variable, family): (&str, &Family),
    out: &Path,
) -> Result<(), Failure> {
    crate::say(&family.report(variable))?;
    let Some(first) = family.rows.first() else {
        return Ok(());
    };
    let mut text = format!("{variable},{}\n", header(columns, &first.motion).join(","));
    for entry in &family.rows {
        let value = shortest_decimal(entry.value);
        let _ = writeln!(text, "{value},{}", fields(columns, &entry.motion));
    }
    let file = out.join("steady.csv");
    sweep::write(&file, &text)
        .map_err(|error| format!("cannot write {}: {error}", file.display()))?;
    let png_file = out.join("steady.png");
    let (unknown, _) = (first.motion.values.iter())
        .find(|(name, _)| !columns.coordinates.contains(name))
        .unwrap_or(&first.motion.values[0]);
    let at = |motion: &SteadyMotion| {
        (motion.values.iter())
            .find(|(name, _)| name == unknown)
            .map_or(f64::NAN, |(_, v)| *v)
    };
    let plotted = SteadyFamily {
        variable: variable.to_string(),
        unknown: unknown.clone(),
        points: family
            .rows
            .iter()
            .map(|r| (r.value, at(&r.motion)))
            .collect(),
        stable: family.rows.iter().map(|r| r.motion.stable()).collect(),
    };
    write_steady_plot(&plotted, &png_file)?;
    Ok(crate::say(&format!(
        "wrote {} and {}\n",
        file.display(),
        png_file.display()
    ))?)
}

/// The values of a row of `steady.csv`, comma-separated.
fn fields(columns: &Columns<'_>, motion: &SteadyMotion) -> String {
    let values: Vec<String> = (row(columns, motion).into_iter())
        .map(shortest_decimal)
        .collect();
    values.join(",")
}
