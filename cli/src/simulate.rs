//! `chaplygin simulate` (docs/INTERFACE.md section 3): a model (a built-in
//! or a `.model` file, read from its text and run on the engine `--engine`
//! chooses) simulated as `chaplygin::driver::simulate` runs a request,
//! writing `trajectory.csv` as it runs, the plots, and for a model that
//! declares points (docs/INTERFACE.md section 4) `tracks.csv`: `t` and each
//! point's position in ground axes (`P.x`, `P.y`, `P.z`) at every recorded
//! row, whose ground tracks (x, y) `path.png` draws with the path; it
//! prints the summary, where and why the run stopped. With `--animate`
//! it also writes `animation.html`, the run in 3D as one offline page
//! (`crate::animate_args`), for a failed run too, of the rows before the
//! failure.

use crate::animate_args::{AnimateArgs, Drawn};
use crate::model_args::{ModelArgs, loaded};
use crate::output::write_table;
use chaplygin::driver::Failure;
use chaplygin::driver::simulate::{self, Controller, Finished, Request};
use chaplygin::plot;
use chaplygin::runtime::record::{CsvRecorder, Recorder, Table};
use std::io;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The arguments of `chaplygin simulate`.
#[derive(Debug, clap::Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    request: Request,
    /// The directory for `trajectory.csv` and the plots.
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Fail (exit status 1) where the run is not accurate to its tolerance:
    /// a conservative run's energy drift, or a constraint residual, beyond
    /// what the tolerance allows (otherwise a warning on stderr).
    #[arg(long)]
    strict: bool,
    #[command(flatten)]
    animate: AnimateArgs,
}

/// A run not accurate to its tolerance, with `--strict`.
#[derive(Debug, thiserror::Error)]
#[error("the run is not accurate to its tolerance (--strict): {warnings} warning(s) above")]
struct Untrusted {
    warnings: usize,
}

/// Runs `chaplygin simulate`.
///
/// # Errors
/// Bad input, a failed simulation, or an I/O error.
pub fn run(args: &SimulateArgs) -> Result<(), Failure> {
    let loaded = loaded(&args.model)?;
    let drawn = args.animate.drawn(&loaded)?;
    let csv_path = args.out.join("trajectory.csv");
    let mut csv = CsvOnStart {
        path: csv_path.clone(),
        file: None,
    };
    let finished = with_progress_bar(|progress| {
        simulate::simulate(loaded, &args.request, &mut csv, progress)
    })?;
    let figure4 = (args.request.controller == Controller::Energy).then(|| figure4(&finished));
    let plots = write_plots(
        &finished.table,
        finished.tracks.as_ref(),
        &args.out,
        figure4,
        Vec::new(),
    );
    let report = match finished.outcome {
        Ok(report) => report,
        Err(failure) => {
            if let Some(drawn) = drawn {
                animate_until_failure(drawn, &finished.table, &finished.parameters, &args.out);
            }
            return Err(failure);
        }
    };
    crate::say(&format!("{report}\n"))?;
    crate::say(&format!("wrote {}\n", csv_path.display()))?;
    if let Some(tracks) = &finished.tracks {
        let tracks_path = args.out.join("tracks.csv");
        write_table(tracks, &tracks_path)?;
        crate::say(&format!("wrote {}\n", tracks_path.display()))?;
    }
    for plot in plots? {
        crate::say(&format!("wrote {}\n", plot.display()))?;
    }
    if let Some(drawn) = drawn {
        drawn.write(&finished.table, &finished.parameters, &args.out)?;
    }
    let warnings = report.warnings();
    for warning in &warnings {
        eprintln!("{}", report.explain(warning));
    }
    if args.strict && !warnings.is_empty() {
        return Err(Untrusted {
            warnings: warnings.len(),
        }
        .into());
    }
    Ok(())
}

/// With `--animate`, a failed run's rows are drawn too, as its
/// `trajectory.csv` and plots keep them: the page shows the motion up to
/// where it failed. A page that cannot be made is said on standard error,
/// the run's own failure being the error reported.
fn animate_until_failure(drawn: Drawn, table: &Table, parameters: &[(String, f64)], out: &Path) {
    if table.rows.is_empty() {
        return;
    }
    if let Err(error) = drawn.write(table, parameters, out) {
        eprintln!("the rows before the failure are not animated: {error}");
    }
}

/// `run` with a progress bar on standard error once it has taken a second.
fn with_progress_bar<T>(run: impl FnOnce(&mut dyn FnMut(f64)) -> T) -> T {
    let bar = indicatif::ProgressBar::with_draw_target(
        Some(1000),
        indicatif::ProgressDrawTarget::hidden(),
    );
    let started = Instant::now();
    let mut progress = |fraction: f64| {
        if bar.is_hidden() && started.elapsed() > Duration::from_secs(1) {
            bar.set_draw_target(indicatif::ProgressDrawTarget::stderr());
        }
        bar.set_position((fraction * 1000.0) as u64);
    };
    let result = run(&mut progress);
    bar.finish_and_clear();
    result
}

/// Figure 4 of Duindam & Stramigioli of the energy-controlled snakeboard:
/// its momenta, the torso spring's state, its mass and inertia and the
/// gain `kt`.
fn figure4(finished: &Finished) -> plot::Figure4 {
    let value = |name: &str| {
        (finished.parameters.iter())
            .find(|(parameter, _)| parameter == name)
            .map_or(f64::NAN, |(_, value)| *value)
    };
    plot::Figure4 {
        alpha1: "group".into(),
        alpha2: "torso".into(),
        xt: "xt".into(),
        m: value("m"),
        jt: value("jt"),
        kt: value("kt"),
    }
}

/// A CSV recorder whose file (and its directory) is created when the run
/// starts, so that input rejected before it writes nothing.
struct CsvOnStart {
    path: PathBuf,
    file: Option<CsvRecorder<io::BufWriter<std::fs::File>>>,
}

impl Recorder for CsvOnStart {
    fn start(&mut self, columns: &[String]) -> io::Result<()> {
        if let Some(dir) = self.path.parent() {
            std::fs::create_dir_all(dir)?;
        }
        self.file
            .insert(CsvRecorder::create(&self.path)?)
            .start(columns)
    }

    fn record(&mut self, row: &[f64]) -> io::Result<()> {
        self.file.as_mut().map_or(Ok(()), |file| file.record(row))
    }

    fn finish(&mut self) -> io::Result<()> {
        self.file.as_mut().map_or(Ok(()), Recorder::finish)
    }
}

/// The plots of what was recorded (`chaplygin::plot`), with the points'
/// ground tracks from `tracks`, Figure 4 with `figure4`, and `series`
/// against `t`.
pub fn write_plots(
    table: &Table,
    tracks: Option<&Table>,
    out: &Path,
    figure4: Option<plot::Figure4>,
    series: Vec<plot::Series>,
) -> Result<Vec<PathBuf>, plot::PlotError> {
    if table.rows.is_empty() {
        return Ok(Vec::new());
    }
    let mut columns = table.columns.clone();
    let ground = tracks.map(ground_tracks).unwrap_or_default();
    columns.extend(
        ground
            .iter()
            .flat_map(|(track, _)| [track.x.clone(), track.y.clone()]),
    );
    let mut plotted = plot::Table::new(columns)?;
    for (i, row) in table.rows.iter().enumerate() {
        let mut row = row.clone();
        if let Some(tracks) = tracks {
            row.extend(
                ground
                    .iter()
                    .flat_map(|&(_, j)| [tracks.rows[i][j], tracks.rows[i][j + 1]]),
            );
        }
        plotted.push_row(row)?;
    }
    let spec = plot::PlotSpec::for_table(&plotted)
        .with_tracks(ground.into_iter().map(|(track, _)| track).collect());
    let spec = match figure4 {
        Some(figure4) => spec.with_figure4(figure4),
        None => spec,
    };
    let spec = series.into_iter().fold(spec, plot::PlotSpec::with_series);
    plot::write_plots(&plotted, &spec, out)
}

/// The tracks' ground x and y columns, each with the index of its x
/// column in `tracks` (its y column is the next).
fn ground_tracks(tracks: &Table) -> Vec<(plot::Track, usize)> {
    (1..tracks.columns.len())
        .step_by(3)
        .map(|j| {
            let x = tracks.columns[j].clone();
            let point = x.trim_end_matches(".x").to_string();
            let y = tracks.columns[j + 1].clone();
            (plot::Track { point, x, y }, j)
        })
        .collect()
}
