//! `chaplygin plan MODEL --duration T --nodes N [--scheme
//! backward-euler|midpoint] [--start NAME=EXPR]... [--goal NAME=EXPR]...
//! [--minimize EXPR] [--bound NAME=LO:HI]... [--param NAME=VALUE]...
//! [--tol TOL] [--hessian exact|lbfgs] --out DIR` (docs/INTERFACE.md section 13), over
//! `chaplygin::driver::plan`: optimal inputs and trajectory by direct
//! collocation, verified by the KKT conditions from the exact derivatives.
//! It writes `DIR/plan.csv` (the columns of `trajectory.csv`, one row per
//! node) and `DIR/plan.json` (the objective, grid, solver, iterations,
//! time, status and KKT residuals), and prints a summary line. An answer
//! that is not a verified optimum is an error, and nothing is written.

use crate::model_args::{ModelArgs, loaded};
use crate::output::write_table;
use chaplygin::driver::Failure;
use chaplygin::driver::plan::nlp::{Hessian, Ripopt};
use chaplygin::driver::plan::{self, Request};
use std::path::PathBuf;

/// The arguments of `chaplygin plan`.
#[derive(Debug, clap::Args)]
pub struct PlanArgs {
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    request: Request,
    /// The Hessian of the Lagrangian the solver works with: the exact one
    /// from the model's second derivatives, or an L-BFGS approximation.
    #[arg(long, value_enum, default_value = "exact")]
    hessian: Hessian,
    /// The directory for `plan.csv` and `plan.json`.
    #[arg(long, default_value = "out")]
    out: PathBuf,
}

/// Runs `chaplygin plan`.
///
/// # Errors
/// Bad input, an answer that is not a verified optimum, or an I/O error.
pub fn run(args: &PlanArgs) -> Result<(), Failure> {
    let solver = Ripopt {
        hessian: args.hessian,
    };
    let plan = plan::plan(loaded(&args.model)?, &args.request, &solver)?;
    let (csv, json) = (args.out.join("plan.csv"), args.out.join("plan.json"));
    write_table(&plan.table, &csv)?;
    let report = &plan.report;
    std::fs::write(&json, format!("{:#}\n", report.to_json()))?;
    crate::say(&format!(
        "objective {:.9e}: a verified optimum ({}, {} nodes, {}) after {} iterations in {:.2} s; \
         KKT residuals primal {:.1e}, dual {:.1e}, complementarity {:.1e}\nwrote {}\nwrote {}\n",
        report.objective,
        report.scheme.name(),
        report.nodes,
        report.solver,
        report.iterations,
        report.seconds,
        report.kkt.primal,
        report.kkt.dual,
        report.kkt.complementarity,
        csv.display(),
        json.display(),
    ))?;
    Ok(())
}
