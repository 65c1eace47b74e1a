//! `chaplygin steady MODEL [--at NAME=EXPR]... [--input NAME=EXPR]...
//! --solve NAME,... [--guess NAME=VALUE]... [--param NAME=VALUE]...
//! [--out DIR]` (docs/INTERFACE.md section 14), over
//! `chaplygin::driver::steady`: the steady motion near the guess, its
//! eigenvalues and whether it is stable, as `chaplygin linearize` prints
//! them; with `--out`, `DIR/steady.csv` (one row: the unknowns, every
//! coordinate and velocity, the inputs, `radius` for a model with a planar
//! symmetry, the eigenvalues `re_i, im_i` and `stable`); an unknown that
//! is a coordinate has its column among the coordinates.

use crate::linearize::describe;
use crate::model_args::{ModelArgs, loaded};
use chaplygin::driver::Failure;
use chaplygin::driver::linearize::sweep;
use chaplygin::driver::simulate::{assignment, expression_assignment};
use chaplygin::driver::steady::{Request, SteadyMotion, steady};
use chaplygin::runtime::linearize::point::velocity_names;
use std::fmt::Write as _;
use std::path::PathBuf;

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
    /// A parameter's value, `NAME=VALUE`.
    #[arg(long = "param", value_parser = assignment)]
    pub params: Vec<(String, f64)>,
    /// Where to write `steady.csv`.
    #[arg(long)]
    pub out: Option<PathBuf>,
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
    };
    let loaded = loaded(&args.model)?;
    let names = loaded.model.names().clone();
    let motion = steady(loaded.model, &request)?;
    crate::say(&report(&motion))?;
    let Some(out) = &args.out else {
        return Ok(());
    };
    let file = out.join("steady.csv");
    let columns = Columns {
        coordinates: &names.coordinates,
        inputs: &names.inputs,
    };
    sweep::write(&file, &csv(&columns, &motion))
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

/// The model's names the columns of `steady.csv` take.
struct Columns<'a> {
    coordinates: &'a [String],
    inputs: &'a [String],
}

/// `steady.csv`: a header and one row.
fn csv(columns: &Columns<'_>, motion: &SteadyMotion) -> String {
    let variables = (motion.values.iter()).filter(|(name, _)| !columns.coordinates.contains(name));
    let mut header: Vec<String> = variables.clone().map(|(n, _)| n.clone()).collect();
    header.extend(columns.coordinates.iter().cloned());
    header.extend(velocity_names(columns.coordinates));
    header.extend(columns.inputs.iter().cloned());
    let mut row: Vec<f64> = variables.map(|(_, v)| *v).collect();
    row.extend(&motion.point.q);
    row.extend(&motion.point.qdot);
    row.extend(&motion.inputs);
    if let Some(radius) = motion.radius {
        header.push("radius".into());
        row.push(radius);
    }
    for (i, eigenvalue) in motion.linear.eigenvalues.iter().enumerate() {
        header.extend([format!("re_{}", i + 1), format!("im_{}", i + 1)]);
        row.extend([eigenvalue.re, eigenvalue.im]);
    }
    header.push("stable".into());
    row.push(f64::from(u8::from(motion.stable())));
    let fields: Vec<String> = row.iter().map(f64::to_string).collect();
    format!("{}\n{}\n", header.join(","), fields.join(","))
}
