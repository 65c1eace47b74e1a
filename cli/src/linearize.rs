//! `chaplygin linearize MODEL [--at NAME=EXPR]... [--sweep VAR=START:STOP:STEP]
//! [--param NAME=VALUE]... [--out DIR] [--canonical Q1,Q2,... --canonical-speed
//! VAR[=V1,V2] [--canonical-gravity NAME]]` (docs/INTERFACE.md section 5),
//! over `chaplygin::driver::linearize`: the operating point from `--at`,
//! the linear system about it and its eigenvalues; with `--sweep`,
//! `DIR/eigenvalues.csv`, `DIR/eigenvalues.png` and the intervals of VAR
//! where the motion is asymptotically stable and where it is neutrally
//! stable, their ends refined by bisection between grid points; with
//! `--canonical Q1,Q2 --canonical-speed VAR`, the canonical form
//! `M qddot + v C1 qdot + (g K0 + v^2 K2) q = f` of Meijaard et al. (2007)
//! in those coordinates. The inputs are zero.

use crate::model_args::{ModelArgs, loaded};
use chaplygin::driver::Failure;
use chaplygin::driver::linearize::canonical::{self, CanonicalSpeed};
use chaplygin::driver::linearize::sweep::{self, Interval, Sweep};
use chaplygin::driver::linearize::{LinearizeError, SweepAnalysis, linearize_at};
use chaplygin::driver::setup::{self, Asked, Setup};
use chaplygin::driver::simulate::{assignment, expression_assignment};
use chaplygin::plot::{EigenvalueSweep, write_eigenvalue_plot};
use chaplygin::runtime::linearize::LinearSystem;
use std::fmt::Write as _;
use std::path::PathBuf;

/// The arguments of `chaplygin linearize`.
#[derive(Debug, clap::Args)]
pub struct LinearizeArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// A coordinate (`phi=0`) or a velocity (`dot(theta)=-v/r`) of the
    /// operating point; EXPR may use the parameters, the sweep variable and
    /// the `--canonical-speed` variable.
    #[arg(long = "at", value_name = "NAME=EXPR", value_parser = expression_assignment)]
    pub at: Vec<(String, String)>,
    /// Sweep VAR from START to STOP (included when on the grid) by STEP.
    #[arg(long, value_parser = sweep::parse)]
    pub sweep: Option<Sweep>,
    /// A parameter's value, `NAME=VALUE`.
    #[arg(long = "param", value_parser = assignment)]
    pub params: Vec<(String, f64)>,
    /// Where `--sweep` writes `eigenvalues.csv` and `eigenvalues.png`.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
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

/// Runs `chaplygin linearize`.
///
/// # Errors
/// Bad input, a point that is not a steady motion, an I/O error.
pub fn run(args: &LinearizeArgs) -> Result<(), Failure> {
    let variable = (args.canonical_speed.as_ref().map(|speed| &speed.variable))
        .or(args.sweep.as_ref().map(|grid| &grid.variable));
    let variables: Vec<&str> = variable.iter().map(|name| name.as_str()).collect();
    let asked = Asked {
        params: &args.params,
        state_flag: "--at",
        state: &args.at,
        variables: &variables,
        ..Asked::default()
    };
    let setup = setup::resolve(loaded(&args.model)?.model, &asked)?;
    analyse(&setup, args)
}

/// Linearizes at one point, or over the sweep.
fn analyse(setup: &Setup, args: &LinearizeArgs) -> Result<(), Failure> {
    if let Some(speed) = &args.canonical_speed {
        let request = canonical::Request {
            coordinates: &args.canonical,
            speed,
            gravity: &args.canonical_gravity,
        };
        let form = canonical::canonical_form(setup, &request)?;
        return Ok(crate::say(&form)?);
    }
    let Some(grid) = &args.sweep else {
        let linear = linearize_at(setup, &[], &[])?;
        return Ok(crate::say(&describe(&linear, "zero"))?);
    };
    let values = grid.grid().map_err(LinearizeError::from)?;
    let analysis = chaplygin::driver::linearize::sweep(setup, (&grid.variable, &values))?;
    let csv_file = args.out.join("eigenvalues.csv");
    let eigenvalues = analysis.eigenvalues();
    sweep::write(
        &csv_file,
        &sweep::csv(&analysis.variable, &values, &eigenvalues),
    )
    .map_err(|error| format!("cannot write {}: {error}", csv_file.display()))?;
    let png_file = args.out.join("eigenvalues.png");
    let plotted = EigenvalueSweep {
        variable: analysis.variable.clone(),
        values,
        eigenvalues,
        stable: analysis
            .stable
            .iter()
            .map(|interval| interval.refined)
            .collect(),
    };
    write_eigenvalue_plot(&plotted, &png_file)?;
    let wrote = format!("wrote {} and {}\n", csv_file.display(), png_file.display());
    crate::say(&wrote)?;
    Ok(crate::say(&stability(&analysis))?)
}

/// The state, the eigenvalues and the verdict of one linearization, the
/// inputs described as `inputs`.
pub fn describe(linear: &LinearSystem, inputs: &str) -> String {
    let mut text = format!(
        "linear system in ({}), inputs {inputs}\neigenvalues (by descending real part):\n",
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

/// The intervals of the sweep where the motion is asymptotically stable,
/// then neutrally stable, each `(grid, refined)`, as printed.
fn stability(analysis: &SweepAnalysis) -> String {
    let (variable, conserved) = (&analysis.variable, analysis.conserved);
    let kinds: [(&str, &[Interval]); 2] = [
        ("asymptotically stable", &analysis.stable),
        ("neutrally stable", &analysis.neutral),
    ];
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
