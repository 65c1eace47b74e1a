//! A run and what it writes: the simulation with the chosen integrator
//! and the `--stop-when` condition, `trajectory.csv`, the plots, and the
//! summary printed; for a model that
//! declares points (INTERFACE.md section 4), `tracks.csv`: `t` and each
//! point's position in ground axes (`P.x`, `P.y`, `P.z`) at every recorded
//! row, whose ground tracks (x, y) `path.png` draws with the path.

use super::arguments::{Integrator, SimulateArgs};
use super::inputs::Scope;
use super::start::InputError;
use super::stop::{Comparison, stop_condition};
use crate::formulation::{AtDimension, Formulation, with_dimension};
use chaplygin::plot;
use chaplygin::runtime::integrate::{DiscreteGradient, DormandPrince, Midpoint, Rk4};
use chaplygin::runtime::linalg::Square;
use chaplygin::runtime::nalgebra::Const;
use chaplygin::runtime::record::{CsvRecorder, Recorder, Table};
use chaplygin::runtime::simulate::{Advance, Simulation, StopCondition, Summary};
use std::error::Error;
use std::io;
use std::time::{Duration, Instant};

/// The points' positions at a configuration, three entries per point.
pub(super) type PositionsAt<'a> = Box<dyn Fn(&[f64]) -> Result<Vec<f64>, Box<dyn Error>> + 'a>;

/// A model's declared points: their names and their positions in ground
/// axes at a configuration `q` (the first `n` entries of the state),
/// flattened point by point.
pub(super) struct Points<'a> {
    /// The points' names, in declared order.
    pub(super) names: Vec<String>,
    /// The number of coordinates.
    pub(super) n: usize,
    /// `positions(q)`, three entries per point.
    pub(super) positions: PositionsAt<'a>,
}

/// Runs `formulation` from `x0` with the chosen integrator (or the
/// formulation's default, see [`Integrator::chosen_or_default`]) until
/// `--stop-when`, read against the names of `scope`, holds or the end,
/// writing `trajectory.csv`, with `points` `tracks.csv`, and the plots into
/// `--out`, and prints the summary.
pub(super) fn execute(
    formulation: &dyn Formulation,
    x0: &[f64],
    (args, scope): (&SimulateArgs, &Scope<'_>),
    (figure4, points): (Option<plot::Figure4>, Option<Points<'_>>),
) -> Result<(), Box<dyn Error>> {
    let stop = args
        .stop_when
        .as_deref()
        .map(|text| Comparison::parse(text, scope))
        .transpose()?;
    let integrator = Integrator::chosen_or_default(args.integrator, formulation.is_structured());
    if integrator == Integrator::DiscreteGradient && !formulation.is_structured() {
        return Err(InputError::Unsupported(
            "the discrete-gradient integrator needs the structured (reduced) form: use --formulation reduced".into(),
        )
        .into());
    }
    std::fs::create_dir_all(&args.out)?;
    let csv_path = args.out.join("trajectory.csv");
    let mut recorder = Both(CsvRecorder::create(&csv_path)?, Table::new());
    let run = Settings {
        integrator,
        args,
        stop: stop.as_ref(),
    };
    let outcome = with_dimension!(x0.len(), D => integrate::<D>(formulation, x0, &run, &mut recorder),
        _ => Err(InputError::Unsupported(format!(
            "the state has {} entries; the command line runs up to {}",
            x0.len(),
            crate::formulation::MAX_DIMENSION
        )).into()));
    let Both(_, table) = recorder;
    let tracks = match &points {
        Some(points) => Some(tracks(&table, points)?),
        None => None,
    };
    let plots = write_plots(&table, tracks.as_ref(), &args.out, figure4);
    let report = outcome?;
    crate::say(&format!("{report}\n"))?;
    crate::say(&format!("wrote {}\n", csv_path.display()))?;
    if let Some(tracks) = &tracks {
        let tracks_path = args.out.join("tracks.csv");
        write_table(tracks, &tracks_path)?;
        crate::say(&format!("wrote {}\n", tracks_path.display()))?;
    }
    for plot in plots? {
        crate::say(&format!("wrote {}\n", plot.display()))?;
    }
    Ok(())
}

/// The points' positions at every row of `table`: `t` then `P.x`, `P.y`,
/// `P.z` for each point `P`.
fn tracks(table: &Table, points: &Points<'_>) -> Result<Table, Box<dyn Error>> {
    let mut tracks = Table::new();
    let mut columns = vec!["t".to_string()];
    for name in &points.names {
        columns.extend(["x", "y", "z"].map(|axis| format!("{name}.{axis}")));
    }
    tracks.start(&columns)?;
    for row in &table.rows {
        let q = &row[1..=points.n];
        let mut tracked = vec![row[0]];
        tracked.extend((points.positions)(q)?);
        tracks.record(&tracked)?;
    }
    Ok(tracks)
}

/// Writes `table` as CSV at `path`.
fn write_table(table: &Table, path: &std::path::Path) -> io::Result<()> {
    let mut csv = CsvRecorder::create(path)?;
    csv.start(&table.columns)?;
    for row in &table.rows {
        csv.record(row)?;
    }
    csv.finish()
}

/// The plots of what was recorded (`chaplygin::plot`), with the points'
/// ground tracks from `tracks` and Figure 4 with `figure4`.
fn write_plots(
    table: &Table,
    tracks: Option<&Table>,
    out: &std::path::Path,
    figure4: Option<plot::Figure4>,
) -> Result<Vec<std::path::PathBuf>, plot::PlotError> {
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

/// What a run is made with: the integrator, the arguments and the stop
/// condition.
struct Settings<'a> {
    integrator: Integrator,
    args: &'a SimulateArgs,
    stop: Option<&'a Comparison>,
}

/// What a finished run prints.
struct Report {
    integrator: Integrator,
    engine: &'static str,
    steps: usize,
    t: f64,
    energy_drift: f64,
    max_constraint_residual: f64,
    max_holonomic_residual: Option<f64>,
    chart_switches: usize,
    stopped: Option<String>,
    seconds: f64,
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "t = {}: {} steps of {} in {:.3} s, engine {}; energy drift (relative) {:.3e}; max constraint residual {:.3e}",
            self.t,
            self.steps,
            self.integrator.name(),
            self.seconds,
            self.engine,
            self.energy_drift,
            self.max_constraint_residual
        )?;
        if let Some(residual) = self.max_holonomic_residual {
            write!(f, "; max holonomic residual {residual:.3e}")?;
        }
        write!(f, "; chart switches {}", self.chart_switches)?;
        if let Some(condition) = &self.stopped {
            write!(f, "; stopped at t = {}: {condition}", self.t)?;
        }
        Ok(())
    }
}

/// The run in dimension `D`.
fn integrate<const D: usize>(
    formulation: &dyn Formulation,
    x0: &[f64],
    settings: &Settings<'_>,
    recorder: &mut impl Recorder,
) -> Result<Report, Box<dyn Error>>
where
    Const<D>: Square,
{
    let system = AtDimension::<D>(formulation);
    let x0: [f64; D] = core::array::from_fn(|i| x0[i]);
    let stop = settings
        .stop
        .map(|comparison| stop_condition::<D>(formulation, comparison));
    let run = (settings.args, stop);
    let started = Instant::now();
    let summary = match settings.integrator {
        Integrator::Rk4 => run_with(Rk4, &system, x0, run, recorder),
        Integrator::Midpoint => run_with(Midpoint::default(), &system, x0, run, recorder),
        Integrator::DiscreteGradient => {
            run_with(DiscreteGradient::default(), &system, x0, run, recorder)
        }
        Integrator::Dopri5 => run_with(DormandPrince::default(), &system, x0, run, recorder),
    }?;
    let holonomic = formulation.holonomic_residual(x0.as_slice()).is_some();
    Ok(Report {
        integrator: settings.integrator,
        engine: formulation.engine(),
        steps: summary.steps,
        t: summary.t,
        energy_drift: summary.energy_drift,
        max_constraint_residual: summary.max_constraint_residual,
        max_holonomic_residual: holonomic.then_some(summary.max_holonomic_residual),
        chart_switches: summary.chart_switches,
        stopped: summary.stopped,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// One integrator's run until `stop` holds, with a progress bar once it
/// has taken a second.
fn run_with<M, C, const D: usize>(
    method: M,
    system: &AtDimension<'_, D>,
    x0: [f64; D],
    (args, stop): (&SimulateArgs, C),
    recorder: &mut impl Recorder,
) -> Result<Summary<D>, Box<dyn Error>>
where
    M: for<'a> Advance<AtDimension<'a, D>, D>,
    C: StopCondition<D>,
{
    let bar = indicatif::ProgressBar::with_draw_target(
        Some(1000),
        indicatif::ProgressDrawTarget::hidden(),
    );
    let started = Instant::now();
    let progress = |fraction: f64| {
        if bar.is_hidden() && started.elapsed() > Duration::from_secs(1) {
            bar.set_draw_target(indicatif::ProgressDrawTarget::stderr());
        }
        bar.set_position((fraction * 1000.0) as u64);
    };
    let summary = Simulation::new(method)
        .span(0.0, args.t_end)
        .step(args.dt)
        .stop_when(stop)
        .run_with_progress(system, x0, recorder, progress);
    bar.finish_and_clear();
    Ok(summary?)
}

/// A recorder writing into two.
struct Both<A, B>(A, B);

impl<A: Recorder, B: Recorder> Recorder for Both<A, B> {
    fn start(&mut self, columns: &[String]) -> io::Result<()> {
        self.0.start(columns)?;
        self.1.start(columns)
    }

    fn record(&mut self, row: &[f64]) -> io::Result<()> {
        self.0.record(row)?;
        self.1.record(row)
    }

    fn finish(&mut self) -> io::Result<()> {
        self.0.finish()?;
        self.1.finish()
    }
}
