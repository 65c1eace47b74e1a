//! `chaplygin map MODEL --at ... --speed VAR=A:B:STEP --param NAME=A:B:STEP
//! [--param NAME2=A:B:STEP] [--param NAME=VALUE]... [--jobs N] [--out DIR]`
//! (docs/INTERFACE.md section 11), over `chaplygin::driver::design_map`:
//! at every design point of the grid of one or two parameters, the
//! self-stable speed intervals and where the number of unstable modes
//! changes, written to `DIR/map.csv` and drawn in `DIR/map.png`; a
//! progress bar on standard error; Ctrl-C writes the points done and
//! fails.

use crate::model_args::{ModelArgs, loaded};
use chaplygin::driver::Failure;
use chaplygin::driver::design_map::{self, Axis, Motion, Run};
use chaplygin::driver::linearize::sweep::{self, Sweep};
use chaplygin::driver::linearize::{LinearizeError, Stability};
use chaplygin::driver::setup::with_parameters;
use chaplygin::driver::simulate::{assignment, expression_assignment};
use chaplygin::plot::{DesignMapPlot, write_design_map};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

/// The arguments of `chaplygin map`.
#[derive(Debug, clap::Args)]
pub struct MapArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// A coordinate (`phi=0`) or a velocity (`dot(theta_r)=-v/rR`) of the
    /// steady motion; EXPR may use the parameters and the speed variable.
    #[arg(long = "at", value_name = "NAME=EXPR", value_parser = expression_assignment)]
    at: Vec<(String, String)>,
    /// The speed variable the `--at` expressions use, from START to STOP by
    /// STEP.
    #[arg(long, value_name = "VAR=START:STOP:STEP", value_parser = sweep::parse)]
    speed: Sweep,
    /// A parameter varied over the map (`NAME=START:STOP:STEP`, one or two)
    /// or fixed (`NAME=VALUE`).
    #[arg(long = "param", value_name = "NAME=START:STOP:STEP|NAME=VALUE", value_parser = design_parameter)]
    params: Vec<DesignParameter>,
    /// Threads (default: every core, or `RAYON_NUM_THREADS`); the map does
    /// not depend on it.
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
    jobs: Option<u16>,
    /// Where `map.csv` and `map.png` go.
    #[arg(long, default_value = "out")]
    out: PathBuf,
}

/// A `--param`: varied over a grid, or fixed.
#[derive(Clone, Debug)]
enum DesignParameter {
    Varied(Sweep),
    Fixed(String, f64),
}

/// Parses `NAME=START:STOP:STEP` or `NAME=VALUE`.
fn design_parameter(text: &str) -> Result<DesignParameter, String> {
    match text.contains(':') {
        true => sweep::parse(text).map(DesignParameter::Varied),
        false => assignment(text).map(|(name, value)| DesignParameter::Fixed(name, value)),
    }
}

/// Set by Ctrl-C: the points not yet started are left out.
static STOP: AtomicBool = AtomicBool::new(false);

/// Runs `chaplygin map`.
///
/// # Errors
/// Bad input (no varied parameter or more than two, an unknown name, an
/// empty grid), an I/O error, or Ctrl-C (after writing the points done).
pub fn run(args: &MapArgs) -> Result<(), Failure> {
    ctrlc::set_handler(|| STOP.store(true, Ordering::Relaxed))?;
    let axes = axes(&args.params)?;
    let mut model = loaded(&args.model)?.model;
    let fixed: Vec<(String, f64)> = (args.params.iter())
        .filter_map(|parameter| match parameter {
            DesignParameter::Fixed(name, value) => Some((name.clone(), *value)),
            DesignParameter::Varied(_) => None,
        })
        .collect();
    with_parameters(&mut model, &fixed)?;
    let speeds = args.speed.grid().map_err(LinearizeError::from)?;
    let names: Vec<String> = axes.iter().map(|axis| axis.name.clone()).collect();
    let points = design_map::grid(&axes);
    let bar = indicatif::ProgressBar::new(points.len() as u64);
    let motion = Motion {
        at: &args.at,
        speed: (&args.speed.variable, &speeds),
    };
    let run = Run {
        jobs: args.jobs.map(usize::from),
        done: &|| bar.inc(1),
        stop: &STOP,
    };
    let results = design_map::stability_at(&model, &names, &points, motion, &run)?;
    bar.finish_and_clear();
    let defaults = names.iter().map(|name| {
        let index = model.names().parameters.iter().position(|p| p == name);
        index.map_or(f64::NAN, |i| model.parameter_defaults()[i])
    });
    let plotted = DesignMapPlot {
        speed: args.speed.variable.clone(),
        axes: axes
            .iter()
            .map(|a| (a.name.clone(), a.values.clone()))
            .collect(),
        stable: results.iter().map(stable_ends).collect(),
        default: defaults.collect(),
    };
    write(args, &names, &points, &results, &plotted)
}

/// The varied parameters' axes: one or two.
fn axes(params: &[DesignParameter]) -> Result<Vec<Axis>, Failure> {
    let mut axes = Vec::new();
    for parameter in params {
        if let DesignParameter::Varied(grid) = parameter {
            axes.push(Axis {
                name: grid.variable.clone(),
                values: grid.grid().map_err(LinearizeError::from)?,
            });
        }
    }
    match axes.len() {
        1 | 2 => Ok(axes),
        found => Err(format!(
            "--param: vary one or two parameters (NAME=START:STOP:STEP), found {found}"
        )
        .into()),
    }
}

/// The stable intervals' refined ends of a computed point.
fn stable_ends(result: &Option<Result<Stability, LinearizeError>>) -> Option<Vec<(f64, f64)>> {
    let stability = result.as_ref()?.as_ref().ok()?;
    Some(stability.stable.iter().map(|i| i.refined).collect())
}

/// Writes `map.csv` and `map.png` and says what was done: the points
/// computed, those that failed, and an error if Ctrl-C left some out.
fn write(
    args: &MapArgs,
    names: &[String],
    points: &[Vec<f64>],
    results: &[Option<Result<Stability, LinearizeError>>],
    plotted: &DesignMapPlot,
) -> Result<(), Failure> {
    let csv_file = args.out.join("map.csv");
    sweep::write(&csv_file, &design_map::csv(names, points, results))
        .map_err(|error| format!("cannot write {}: {error}", csv_file.display()))?;
    let png_file = args.out.join("map.png");
    write_design_map(plotted, &png_file)?;
    let done = results.iter().flatten().count();
    let failed = results.iter().flatten().filter(|r| r.is_err()).count();
    let stable = (plotted.stable.iter().flatten())
        .filter(|intervals| !intervals.is_empty())
        .count();
    crate::say(&format!(
        "wrote {} and {}\n{done} design points: {stable} self-stable at some {}, \
         {failed} not linearized (see the failure column)\n",
        csv_file.display(),
        png_file.display(),
        args.speed.variable,
    ))?;
    match done < points.len() {
        true => Err(format!(
            "interrupted: {done} of {} design points computed and written",
            points.len()
        )
        .into()),
        false => Ok(()),
    }
}
