//! `chaplygin gait MODEL --shape a,b --cycle 'a=EXPR' --cycle 'b=EXPR'
//! --period T [--param NAME=VALUE]... [--cycles N] [--initial pI=VALUE]...
//! [--out DIR]` (docs/INTERFACE.md section 9), over
//! `chaplygin::driver::gait`: the net displacement per cycle of a
//! prescribed periodic shape trajectory, `DIR/cycle.csv` (`t`, the
//! coordinates, the momenta) and `DIR/gait_path.png`, and for a
//! principally kinematic model `DIR/curvature.png`; with `--optimize
//! forward|lateral|rotate [--harmonics N] [--cost length|none]`, the loop
//! that moves the model furthest (`chaplygin::gait_design`), its laws and
//! `DIR/gait.csv`; with `--animate [--fps F]`, `DIR/animation.html` of the
//! cycles run (`crate::animate_args`).

use crate::animate_args::{AnimateArgs, Drawn};
use crate::model_args::{ModelArgs, loaded};
use crate::output::{plotted, write_table};
use chaplygin::driver::Failure;
use chaplygin::driver::gait::{
    CurvatureGrid, GaitRequest, GaitRun, OptimalGait, OptimalGaitRequest, gait, optimal_gait,
};
use chaplygin::driver::simulate::{assignment, expression_assignment};
use chaplygin::gait_design::{Cost, Design, Direction};
use chaplygin::plot;
use chaplygin::runtime::record::shortest_decimal;
use std::collections::BTreeSet;
use std::f64::consts::PI;
use std::path::PathBuf;

/// The arguments of `chaplygin gait`.
#[derive(Debug, clap::Args)]
pub struct GaitArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// The shape coordinates the gait prescribes, comma-separated: every
    /// coordinate the model's symmetry does not move.
    #[arg(long, value_name = "A,B,...", value_delimiter = ',', required = true)]
    shape: Vec<String>,
    /// A shape coordinate's law `NAME=EXPR`, an expression of `t` and the
    /// parameters (`phi=0.5*sin(t)`), periodic with `--period`; one per
    /// shape coordinate.
    #[arg(long = "cycle", value_name = "NAME=EXPR", value_parser = expression_assignment, required_unless_present = "optimize")]
    cycle: Vec<(String, String)>,
    /// The period T of the laws (2 pi by default with `--optimize`).
    #[arg(long, required_unless_present = "optimize")]
    period: Option<f64>,
    /// Find the loop that moves the model furthest in this direction from
    /// rest, instead of running `--cycle`.
    #[arg(long, value_enum, conflicts_with = "cycle")]
    optimize: Option<Direction>,
    /// The Fourier harmonics of each shape coordinate's law (`--optimize`).
    #[arg(long, default_value_t = 1)]
    harmonics: usize,
    /// The displacement per unit of the loop's length in the shape
    /// coordinates, or per cycle (`--optimize`).
    #[arg(long, value_enum, default_value_t = Cost::Length)]
    cost: Cost,
    /// Random starts of the optimizer (`--optimize`).
    #[arg(long, default_value_t = 8)]
    starts: usize,
    /// Loops keep `|d(r)|`, the connection's divisor, above this fraction
    /// of its largest magnitude (`--optimize`).
    #[arg(long, default_value_t = 0.25)]
    margin: f64,
    /// Loops keep every shape coordinate within `[-limit, limit]`
    /// (`--optimize`; pi by default).
    #[arg(long, default_value_t = PI)]
    limit: f64,
    /// The cycles run.
    #[arg(long, default_value_t = 1)]
    cycles: usize,
    /// RK4 steps per period (2000, or 400 per evaluation with `--optimize`).
    #[arg(long)]
    steps: Option<usize>,
    /// A parameter's value, `NAME=VALUE`.
    #[arg(long = "param", value_parser = assignment)]
    params: Vec<(String, f64)>,
    /// An initial momentum `pI=VALUE` (zero unless given).
    #[arg(long = "initial", value_parser = assignment)]
    initial: Vec<(String, f64)>,
    /// Where `cycle.csv`, `gait_path.png`, `curvature.png`, `gait.csv`
    /// and `animation.html` are written.
    #[arg(long, default_value = "out")]
    out: PathBuf,
    #[command(flatten)]
    animate: AnimateArgs,
}

/// Runs `chaplygin gait`.
///
/// # Errors
/// Bad input, a model a gait does not move, or an I/O error.
pub fn run(args: &GaitArgs) -> Result<(), Failure> {
    if let Some(direction) = args.optimize {
        return optimize(args, direction);
    }
    let shape: BTreeSet<&str> = args.shape.iter().map(String::as_str).collect();
    let laws: BTreeSet<&str> = args.cycle.iter().map(|(name, _)| name.as_str()).collect();
    if shape != laws {
        return Err(format!(
            "--shape names {} but --cycle gives laws for {}",
            args.shape.join(", "),
            laws.into_iter().collect::<Vec<_>>().join(", ")
        )
        .into());
    }
    let request = GaitRequest {
        cycle: args.cycle.clone(),
        period: args.period.unwrap_or(2.0 * PI),
        cycles: args.cycles,
        steps: args.steps.unwrap_or(2000),
        params: args.params.clone(),
        initial: args.initial.clone(),
    };
    let loaded = loaded(&args.model)?;
    let drawn = args.animate.drawn(&loaded)?;
    let run = gait(loaded, &request)?;
    crate::say(&displacements(&run))?;
    write_run(run, args, drawn, Vec::new())
}

/// `--optimize`: the loop, its laws, its run and `gait.csv`.
fn optimize(args: &GaitArgs, direction: Direction) -> Result<(), Failure> {
    let design = Design {
        direction,
        cost: args.cost,
        harmonics: args.harmonics,
        period: args.period.unwrap_or(2.0 * PI),
        starts: args.starts,
        steps: args.steps.unwrap_or(Design::default().steps),
        margin: args.margin,
        limit: args.limit,
        ..Design::default()
    };
    let request = OptimalGaitRequest {
        design,
        params: args.params.clone(),
    };
    let loaded = loaded(&args.model)?;
    let drawn = args.animate.drawn(&loaded)?;
    let found = optimal_gait(loaded, &request)?;
    let given: BTreeSet<&str> = args.shape.iter().map(String::as_str).collect();
    let shape: BTreeSet<&str> = found.shape.iter().map(String::as_str).collect();
    if given != shape {
        return Err(format!(
            "--shape names {} but the model's shape coordinates are {}",
            args.shape.join(", "),
            found.shape.join(", ")
        )
        .into());
    }
    crate::say(&summary(&found))?;
    let gait_csv = args.out.join("gait.csv");
    write_coefficients(&found, &gait_csv)?;
    write_run(found.run, args, drawn, vec![gait_csv])
}

/// The displacement line of each cycle.
fn displacements(run: &GaitRun) -> String {
    let mut text = String::new();
    for (k, cycle) in run.cycles.iter().enumerate() {
        let label = match k {
            0 => "net displacement per cycle".to_string(),
            _ => format!("cycle {}", k + 1),
        };
        let [x, y, theta] = cycle.displacement.map(shortest_decimal);
        text.push_str(&format!("{label}: x = {x}, y = {y}, theta = {theta}\n"));
    }
    text
}

/// The optimum's displacement, laws, efficiency and starts.
fn summary(found: &OptimalGait) -> String {
    let optimum = &found.optimum;
    let per = match optimum.scoring.cost {
        Cost::Length => "per unit length",
        Cost::None => "per cycle",
    };
    let starts: Vec<String> = optimum.starts.iter().map(|e| format!("{e:.6}")).collect();
    let laws: Vec<String> = (found.laws.iter())
        .map(|(name, law)| format!("{name}={law}"))
        .collect();
    format!(
        "{}optimal loop: {}\nefficiency: {} {per} (loop length {})\nstarts: {}\n",
        displacements(&found.run),
        laws.join("; "),
        shortest_decimal(optimum.efficiency()),
        shortest_decimal(optimum.evaluation.length),
        starts.join(", ")
    )
}

/// `gait.csv`: one row per shape coordinate, its constant then the cosine
/// and sine coefficients of each harmonic.
fn write_coefficients(found: &OptimalGait, path: &std::path::Path) -> Result<(), Failure> {
    let shape_loop = &found.optimum.shape_loop;
    let mut text = String::from("coordinate,constant");
    for k in 1..=shape_loop.harmonics {
        text.push_str(&format!(",cos{k},sin{k}"));
    }
    text.push('\n');
    for (name, row) in
        (found.shape.iter()).zip(shape_loop.coefficients.chunks(shape_loop.per_coordinate()))
    {
        let values: Vec<String> = row.iter().map(|&v| shortest_decimal(v)).collect();
        text.push_str(&format!("{name},{}\n", values.join(",")));
    }
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(path, text)?;
    Ok(())
}

/// `cycle.csv`, `gait_path.png` and, for a kinematic model,
/// `curvature.png` of `run` in `--out`, then the files written; with
/// `drawn`, `animation.html`.
fn write_run(
    run: GaitRun,
    args: &GaitArgs,
    drawn: Option<Drawn>,
    mut written: Vec<PathBuf>,
) -> Result<(), Failure> {
    let out = &args.out;
    let csv_path = out.join("cycle.csv");
    write_table(&run.table, &csv_path)?;
    let png_path = out.join("gait_path.png");
    plot::write_path_plot(&plotted(&run.table)?, &png_path)?;
    written.extend([csv_path, png_path]);
    if let Some(grid) = run.curvature {
        let path = out.join("curvature.png");
        plot::write_curvature_plot(&field(grid), &path)?;
        written.push(path);
    }
    let lines: Vec<String> = (written.iter())
        .map(|path| format!("wrote {}\n", path.display()))
        .collect();
    crate::say(&lines.concat())?;
    match drawn {
        Some(drawn) => drawn.write(&run.table, &args.params, out),
        None => Ok(()),
    }
}

/// The plot's view of the curvature grid.
fn field(grid: CurvatureGrid) -> plot::CurvatureField {
    let [x, y, theta] = grid.components;
    plot::CurvatureField {
        axes: grid.axes,
        first: grid.first,
        second: grid.second,
        panels: vec![
            ("x (forward)".to_string(), x),
            ("y (lateral)".to_string(), y),
            ("theta (rotation)".to_string(), theta),
        ],
        path: grid.path,
    }
}
