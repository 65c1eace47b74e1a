//! `chaplygin simulate` run in this process: the model read from its text,
//! derived and compiled once for all the tests here ([`Model::load`]), then
//! run as often as they need through `chaplygin::driver::simulate`, which
//! the binary calls, its options read by the binary's own definitions
//! (`Request`'s clap arguments). For tests whose subject is the numbers of
//! many runs rather than the command line itself: a run of the binary
//! derives and compiles its model again each time (about a second of CPU
//! for the benchmark bicycle in the test build) and draws its plots. What a
//! run here returns is what the binary prints and writes: the summary line,
//! or the error after `error: `, and the rows of `trajectory.csv`.

use chaplygin::driver::catalog::lookup;
use chaplygin::driver::engine::{EngineChoice, Loaded, load};
use chaplygin::driver::simulate::{Request, prepare, simulate};
use chaplygin::runtime::record::{Recorder, Table};
use clap::Parser;
use std::sync::{Mutex, OnceLock, PoisonError};

/// `chaplygin simulate`'s options but the model, the engine and `--out`.
#[derive(Parser)]
struct Options {
    #[command(flatten)]
    request: Request,
}

/// A model loaded on an engine, for many runs.
pub struct Model {
    loaded: Loaded,
}

/// What a run printed and recorded.
pub struct Simulated {
    /// The summary line of a finished run, or the one-line error (without
    /// `error: `) of a failed one.
    pub outcome: Result<String, String>,
    /// The `warning:` lines the binary would print after the summary.
    pub warnings: Vec<String>,
    /// The columns of the trajectory.
    pub header: Vec<String>,
    /// Its rows, as far as the run got.
    pub rows: Vec<Vec<f64>>,
}

/// A run that finished: its summary line and what it recorded.
pub struct Finished {
    pub summary: String,
    pub header: Vec<String>,
    pub rows: Vec<Vec<f64>>,
}

impl Model {
    /// `model` (a built-in's name or a file's path) loaded on `engine`
    /// (`jit` or `interpret`) once for all the tests of this binary that
    /// run it: the first to ask loads it (the benchmark bicycle takes about
    /// a second of CPU in the test build), the others wait for it and share
    /// it.
    pub fn load(model: &str, engine: &str) -> &'static Self {
        type Cell = &'static OnceLock<Model>;
        static LOADED: Mutex<Vec<(String, String, Cell)>> = Mutex::new(Vec::new());
        let cell = {
            let mut loaded = LOADED.lock().unwrap_or_else(PoisonError::into_inner);
            let found = (loaded.iter()).find(|(name, on, _)| name == model && on == engine);
            match found {
                Some(&(_, _, cell)) => cell,
                None => {
                    let cell: Cell = Box::leak(Box::new(OnceLock::new()));
                    loaded.push((model.to_string(), engine.to_string(), cell));
                    cell
                }
            }
        };
        cell.get_or_init(|| Self::loaded_now(model, engine))
    }

    /// `model` loaded on `engine` by this call.
    fn loaded_now(model: &str, engine: &str) -> Self {
        let engine = match engine {
            "jit" => EngineChoice::Jit,
            "interpret" => EngineChoice::Interpret,
            _ => panic!("no engine `{engine}`"),
        };
        let source = lookup(model).unwrap_or_else(|error| panic!("{model}: {error}"));
        let loaded = load(&source, engine).unwrap_or_else(|error| panic!("{model}: {error}"));
        assert!(loaded.fallback.is_none(), "{model}: {:?}", loaded.fallback);
        Self { loaded }
    }

    /// The configuration and velocity `(q, qdot)` of the `n` coordinates
    /// at each of `rows` (`t`, then the state) of a run with `options`:
    /// the formulation's own, as an input law reads them (for the reduced
    /// form `velocities(q, alpha)` in the chart the run starts in).
    pub fn configurations_velocities(
        &self,
        options: &[&str],
        n: usize,
        rows: &[Vec<f64>],
    ) -> Vec<(Vec<f64>, Vec<f64>)> {
        let prepared = prepare(self.loaded.clone(), &request(options))
            .unwrap_or_else(|error| panic!("{options:?}: {error}"));
        let dimension = prepared.x0.len();
        (rows.iter())
            .map(|row| {
                let (mut q, mut qdot) = (vec![0.0; n], vec![0.0; n]);
                (prepared.formulation).configuration_velocity(
                    &row[1..=dimension],
                    &mut q,
                    &mut qdot,
                );
                (q, qdot)
            })
            .collect()
    }

    /// `chaplygin simulate MODEL` with `options`; `Err` with the message
    /// where the binary would refuse them before the run.
    pub fn simulate(&self, options: &[&str]) -> Result<Simulated, String> {
        let request = request(options);
        let finished = simulate(self.loaded.clone(), &request, &mut Nothing, &mut |_| {})
            .map_err(|error| error.to_string())?;
        let Table { columns, rows } = finished.table;
        let warnings = (finished.outcome.as_ref()).map_or_else(
            |_| Vec::new(),
            |report| {
                (report.warnings().iter())
                    .map(|w| report.explain(w))
                    .collect()
            },
        );
        Ok(Simulated {
            outcome: finished
                .outcome
                .map(|report| report.to_string())
                .map_err(|error| error.to_string()),
            warnings,
            header: columns,
            rows,
        })
    }

    /// `chaplygin simulate MODEL` with `options`, a run that must finish:
    /// a refusal or a failure panics, with the options in the message.
    pub fn finished(&self, options: &[&str]) -> Finished {
        let run = (self.simulate(options)).unwrap_or_else(|error| panic!("{options:?}: {error}"));
        Finished {
            summary: (run.outcome).unwrap_or_else(|error| panic!("{options:?}: {error}")),
            header: run.header,
            rows: run.rows,
        }
    }
}

impl Simulated {
    /// The column `name` of the rows recorded.
    pub fn column(&self, name: &str) -> Vec<f64> {
        super::column(&self.header, &self.rows, name)
    }
}

/// `chaplygin simulate MODEL OPTIONS`'s request.
fn request(options: &[&str]) -> Request {
    let arguments = std::iter::once("simulate").chain(options.iter().copied());
    Options::try_parse_from(arguments)
        .unwrap_or_else(|error| panic!("{options:?}: {error}"))
        .request
}

/// A recorder that keeps nothing (the run's own table keeps every row).
struct Nothing;

impl Recorder for Nothing {
    fn start(&mut self, _: &[String]) -> std::io::Result<()> {
        Ok(())
    }

    fn record(&mut self, _: &[f64]) -> std::io::Result<()> {
        Ok(())
    }

    fn finish(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}
