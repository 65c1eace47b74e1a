//! A run and what it writes: the simulation with the chosen integrator,
//! `trajectory.csv`, the plots, and the summary printed.

use super::arguments::{Integrator, SimulateArgs};
use super::start::InputError;
use crate::formulation::{Formulation, Sized, with_dimension};
use chaplygin::plot;
use chaplygin::runtime::integrate::{DiscreteGradient, DormandPrince, Midpoint, Rk4};
use chaplygin::runtime::linalg::Square;
use chaplygin::runtime::nalgebra::Const;
use chaplygin::runtime::record::{CsvRecorder, Recorder, Table};
use chaplygin::runtime::simulate::{Advance, Simulation, Summary};
use std::error::Error;
use std::io;
use std::time::{Duration, Instant};

/// Runs `formulation` from `x0` with the chosen integrator (or the
/// formulation's default, see [`Integrator::chosen_or_default`]), writing
/// `trajectory.csv` and the plots into `--out`, and prints the summary.
pub(super) fn execute(
    formulation: &dyn Formulation,
    x0: &[f64],
    args: &SimulateArgs,
    figure4: Option<plot::Figure4>,
) -> Result<(), Box<dyn Error>> {
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
    let outcome = with_dimension!(x0.len(), D => integrate::<D>(formulation, x0, (integrator, args), &mut recorder),
        _ => Err(InputError::Unsupported(format!(
            "the state has {} entries; the command line runs up to {}",
            x0.len(),
            crate::formulation::MAX_DIMENSION
        )).into()));
    let Both(_, table) = recorder;
    let plots = write_plots(&table, &args.out, figure4);
    let report = outcome?;
    println!("{report}");
    println!("wrote {}", csv_path.display());
    for plot in plots? {
        println!("wrote {}", plot.display());
    }
    Ok(())
}

/// The plots of what was recorded (`chaplygin::plot`), Figure 4 with
/// `figure4`.
fn write_plots(
    table: &Table,
    out: &std::path::Path,
    figure4: Option<plot::Figure4>,
) -> Result<Vec<std::path::PathBuf>, plot::PlotError> {
    if table.rows.is_empty() {
        return Ok(Vec::new());
    }
    let mut plotted = plot::Table::new(table.columns.clone())?;
    for row in &table.rows {
        plotted.push_row(row.clone())?;
    }
    let spec = plot::PlotSpec::for_table(&plotted);
    let spec = match figure4 {
        Some(figure4) => spec.with_figure4(figure4),
        None => spec,
    };
    plot::write_plots(&plotted, &spec, out)
}

/// What a finished run prints.
struct Report {
    integrator: Integrator,
    steps: usize,
    t: f64,
    energy_drift: f64,
    max_constraint_residual: f64,
    max_holonomic_residual: Option<f64>,
    seconds: f64,
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "t = {}: {} steps of {} in {:.3} s; energy drift (relative) {:.3e}; max constraint residual {:.3e}",
            self.t,
            self.steps,
            self.integrator.name(),
            self.seconds,
            self.energy_drift,
            self.max_constraint_residual
        )?;
        match self.max_holonomic_residual {
            Some(residual) => write!(f, "; max holonomic residual {residual:.3e}"),
            None => Ok(()),
        }
    }
}

/// The run in dimension `D`.
fn integrate<const D: usize>(
    formulation: &dyn Formulation,
    x0: &[f64],
    (integrator, args): (Integrator, &SimulateArgs),
    recorder: &mut impl Recorder,
) -> Result<Report, Box<dyn Error>>
where
    Const<D>: Square,
{
    let system = Sized::<D>(formulation);
    let x0: [f64; D] = core::array::from_fn(|i| x0[i]);
    let started = Instant::now();
    let summary = match integrator {
        Integrator::Rk4 => run_with(Rk4, &system, x0, args, recorder),
        Integrator::Midpoint => run_with(Midpoint::default(), &system, x0, args, recorder),
        Integrator::DiscreteGradient => {
            run_with(DiscreteGradient::default(), &system, x0, args, recorder)
        }
        Integrator::Dopri5 => run_with(DormandPrince::default(), &system, x0, args, recorder),
    }?;
    let holonomic = formulation.holonomic_residual(x0.as_slice()).is_some();
    Ok(Report {
        integrator,
        steps: summary.steps,
        t: summary.t,
        energy_drift: summary.energy_drift,
        max_constraint_residual: summary.max_constraint_residual,
        max_holonomic_residual: holonomic.then_some(summary.max_holonomic_residual),
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// One integrator's run, with a progress bar once it has taken a second.
fn run_with<M, const D: usize>(
    method: M,
    system: &Sized<'_, D>,
    x0: [f64; D],
    args: &SimulateArgs,
    recorder: &mut impl Recorder,
) -> Result<Summary<D>, Box<dyn Error>>
where
    M: for<'a> Advance<Sized<'a, D>, D>,
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
