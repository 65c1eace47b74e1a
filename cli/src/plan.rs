//! `chaplygin plan MODEL --duration T [--free-duration] --nodes N
//! [--scheme backward-euler|midpoint|hermite-simpson] [--start
//! NAME=EXPR]... [--goal NAME=EXPR]... [--minimize EXPR] [--final-cost
//! EXPR] [--bound NAME=LO:HI]... [--param NAME=VALUE]... [--guess
//! FILE.csv] [--tol TOL] [--hessian exact|lbfgs] [--animate [--fps F]]
//! --out DIR` (docs/INTERFACE.md section 13), over `chaplygin::driver::plan`: optimal inputs and trajectory by
//! direct collocation, verified by the KKT conditions from the exact
//! derivatives.
//!
//! It writes `DIR/plan.csv` (the columns of `trajectory.csv`, one row per
//! node), `DIR/plan.json` (the objective, grid, solver, iterations, time,
//! status and KKT residuals), the plots `simulate` draws (`path.png`,
//! `energy.png`, `constraint_residual.png`) with `states.png` (the
//! coordinates and velocities against `t`) and `inputs.png`, with
//! `--animate` `animation.html` of the nodes (`crate::animate_args`), and
//! prints a summary line. An answer that is not a verified optimum is an
//! error, and nothing is written.
//!
//! On a terminal, standard error shows one line per solver iteration
//! (`crate::solve_watch`). Ctrl-C stops the solve at its current iterate,
//! which is written as above with `plan.csv`'s first line `# not
//! verified: ...` and `plan.json`'s status `interrupted`, its KKT
//! residuals computed there; the command then fails saying so.

use crate::animate_args::{AnimateArgs, Drawn};
use crate::model_args::{ModelArgs, loaded};
use crate::output::{write_marked_table, write_table};
use crate::simulate::write_plots;
use crate::solve_watch::{self, Interrupted};
use chaplygin::driver::Failure;
use chaplygin::driver::plan::nlp::{Hessian, Ripopt};
use chaplygin::driver::plan::{self, Plan, PlanError, Request};
use chaplygin::plot;
use chaplygin::runtime::linearize::point::velocity_names;
use std::path::{Path, PathBuf};

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
    /// The directory for `plan.csv`, `plan.json` and the plots.
    #[arg(long, default_value = "out")]
    out: PathBuf,
    #[command(flatten)]
    animate: AnimateArgs,
}

/// The plan's columns drawn against `t`: the states (coordinates and
/// velocities) and the inputs.
struct Drawings {
    states: Vec<String>,
    inputs: Vec<String>,
}

/// Runs `chaplygin plan`.
///
/// # Errors
/// Bad input, an answer that is not a verified optimum, Ctrl-C (after
/// writing the last iterate), or an I/O error.
pub fn run(args: &PlanArgs) -> Result<(), Failure> {
    solve_watch::stop_on_ctrl_c()?;
    let loaded = loaded(&args.model)?;
    let drawn = args.animate.drawn(&loaded)?;
    let names = loaded.model.names();
    let mut states = names.coordinates.clone();
    states.extend(velocity_names(&names.coordinates));
    let drawings = Drawings {
        states,
        inputs: names.inputs.clone(),
    };
    let solver = Ripopt {
        hessian: args.hessian,
    };
    let mut observer = solve_watch::observer();
    match plan::plan_watched(loaded, &args.request, &solver, &mut observer) {
        Ok(plan) => write(args, &plan, &drawings, drawn),
        Err(failure) => match failure.downcast::<PlanError>() {
            Ok(error) => match *error {
                PlanError::Interrupted(last) => {
                    write(args, &last, &drawings, drawn)?;
                    Err(Interrupted {
                        reason: PlanError::Interrupted(last).into(),
                        out: args.out.clone(),
                    }
                    .into())
                }
                other => Err(other.into()),
            },
            Err(failure) => Err(failure),
        },
    }
}

/// Writes `plan.csv` (marked as not verified for an interrupted solve),
/// `plan.json`, the plots and the animation, and says so.
fn write(
    args: &PlanArgs,
    plan: &Plan,
    drawings: &Drawings,
    drawn: Option<Drawn>,
) -> Result<(), Failure> {
    let (csv, json) = (args.out.join("plan.csv"), args.out.join("plan.json"));
    let report = &plan.report;
    let verified = report.status != plan::Report::INTERRUPTED;
    if verified {
        write_table(&plan.table, &csv)?;
    } else {
        let mark = format!(
            "not verified: interrupted after {} iterations (plan.json)",
            report.iterations
        );
        write_marked_table(&plan.table, &csv, &mark)?;
    }
    std::fs::write(&json, format!("{:#}\n", report.to_json()))?;
    if verified {
        crate::say(&format!(
            "objective {:.9e}: a verified optimum ({}, {} nodes, {}) after {} iterations in \
             {:.2} s; KKT residuals primal {:.1e}, dual {:.1e}, complementarity {:.1e}\n",
            report.objective,
            report.scheme.name(),
            report.nodes,
            report.solver,
            report.iterations,
            report.seconds,
            report.kkt.primal,
            report.kkt.dual,
            report.kkt.complementarity,
        ))?;
    }
    crate::say(&format!(
        "wrote {}\nwrote {}\n",
        csv.display(),
        json.display()
    ))?;
    for plot in plots(plan, drawings, &args.out)? {
        crate::say(&format!("wrote {}\n", plot.display()))?;
    }
    if let Some(drawn) = drawn {
        drawn.write(&plan.table, &args.request.params, &args.out)?;
    }
    Ok(())
}

/// The plots `simulate` draws of the plan's rows, with its states and
/// inputs against `t`.
fn plots(plan: &Plan, drawings: &Drawings, out: &Path) -> Result<Vec<PathBuf>, plot::PlotError> {
    let states = plot::Series {
        name: "states".into(),
        title: "States at the nodes".into(),
        y_desc: "coordinates and velocities".into(),
        columns: drawings.states.clone(),
    };
    let inputs = plot::Series {
        name: "inputs".into(),
        title: "Inputs at the nodes".into(),
        y_desc: "inputs".into(),
        columns: drawings.inputs.clone(),
    };
    write_plots(&plan.table, None, out, None, vec![states, inputs])
}
