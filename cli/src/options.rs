//! The command line: its commands, and what each does with its arguments
//! (those of `simulate`, `linearize`, `steady`, `map`, `gait`, `plan` and `identify` are
//! defined with them).

use crate::gait::{self, GaitArgs};
use crate::identify::{self, IdentifyArgs};
use crate::linearize::{self, LinearizeArgs};
use crate::map::{self, MapArgs};
use crate::plan::{self, PlanArgs};
use crate::simulate::{self, SimulateArgs};
use crate::steady::{self, SteadyArgs};
use chaplygin::driver::Failure;
use chaplygin::driver::catalog::{self, lookup};
use chaplygin::driver::document::{self, Format};
use clap::{Parser, Subcommand};

/// Nonholonomic mechanical models compiled into verified simulators.
#[derive(Debug, Parser)]
#[command(name = "chaplygin", version, about)]
pub struct Command {
    #[command(subcommand)]
    action: Action,
}

#[derive(Debug, Subcommand)]
enum Action {
    /// The built-in models, with their sizes and classification.
    List,
    /// Print the derived equations and the derivation report.
    Derive {
        /// A built-in model's name, or the path of a `.model` file.
        model: String,
        /// Output format.
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
    },
    /// Simulate a model to `--t-end`, or to where `--stop-when` holds,
    /// writing `trajectory.csv` and PNG plots.
    Simulate(Box<SimulateArgs>),
    /// Linearize about a steady motion and print the eigenvalues; with
    /// `--sweep`, write `eigenvalues.csv` and `eigenvalues.png`; with
    /// `--canonical`, print the canonical form M, C1, K0, K2.
    Linearize(Box<LinearizeArgs>),
    /// Find a steady motion from unknowns of its point (`--solve`), print
    /// them, its eigenvalues and whether it is stable; with `--out`, write
    /// `steady.csv`.
    Steady(Box<SteadyArgs>),
    /// The self-stable speeds of a steady motion over a grid of one or two
    /// parameters, on every core, writing `map.csv` and `map.png`.
    Map(Box<MapArgs>),
    /// The net displacement per cycle of a prescribed periodic shape
    /// trajectory, writing `cycle.csv` and `gait_path.png`.
    Gait(Box<GaitArgs>),
    /// Optimal inputs and trajectory between a start and a goal by direct
    /// collocation, verified by the KKT conditions, writing `plan.csv` and
    /// `plan.json`.
    Plan(Box<PlanArgs>),
    /// Estimate parameters from measured data by collocation, verified by
    /// the KKT conditions, writing `estimate.json` and `fit.csv`.
    Identify(Box<IdentifyArgs>),
}

impl Command {
    /// Runs the command.
    ///
    /// # Errors
    /// A one-line description of what went wrong.
    pub fn run(self) -> Result<(), Failure> {
        match self.action {
            Action::List => Ok(crate::say(&catalog::listing())?),
            Action::Derive { model, format } => {
                Ok(crate::say(&document::document(&lookup(&model)?, format)?)?)
            }
            Action::Simulate(args) => simulate::run(&args),
            Action::Linearize(args) => linearize::run(&args),
            Action::Steady(args) => steady::run(&args),
            Action::Map(args) => map::run(&args),
            Action::Gait(args) => gait::run(&args),
            Action::Plan(args) => plan::run(&args),
            Action::Identify(args) => identify::run(&args),
        }
    }
}
