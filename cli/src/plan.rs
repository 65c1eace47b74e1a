//! `chaplygin plan MODEL --duration T [--free-duration] --nodes N
//! [--scheme backward-euler|midpoint|hermite-simpson] [--start
//! NAME=EXPR]... [--goal NAME=EXPR]... [--minimize EXPR] [--final-cost
//! EXPR] [--bound NAME=LO:HI]... [--param NAME=VALUE]... [--guess
//! FILE.csv] [--tol TOL] [--hessian exact|lbfgs] [--formulation lagrange|reduced]
//! [--replay-tol R] [--animate [--fps F]] --out DIR` (docs/INTERFACE.md
//! section 13), over `chaplygin::driver::plan`: optimal inputs and
//! trajectory by direct collocation, verified by the KKT conditions from
//! the exact derivatives and by its replay.
//!
//! It writes `DIR/plan.csv` (the columns of `trajectory.csv` in the
//! plan's formulation, one row per node), `DIR/plan.json` (the objective, grid, solver, iterations, time,
//! status and KKT residuals), the plots `simulate` draws (`path.png`,
//! `energy.png`, `constraint_residual.png`) with `states.png` (the
//! coordinates and velocities against `t`) and `inputs.png`, with
//! `--animate` `animation.html` of the nodes (`crate::animate_args`), and
//! prints a summary line. An answer that is not a verified optimum is an
//! error, and nothing is written. A verified optimum whose replay departs
//! from it by more than `--replay-tol` is written with `plan.csv`'s first
//! line `# not a motion of the model: ...`, and the command fails saying
//! where it departs most.
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
use crate::solve_watch::{self, SolverArgs, Written};
use chaplygin::driver::Failure;
use chaplygin::driver::plan::replay::Replay;
use chaplygin::driver::plan::{self, Plan, PlanError, Request, Restart};
use chaplygin::plot;
use std::path::{Path, PathBuf};

/// The arguments of `chaplygin plan`.
#[derive(Debug, clap::Args)]
pub struct PlanArgs {
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    request: Request,
    #[command(flatten)]
    solver: SolverArgs,
    /// How far the plan's inputs, replayed from its start, may leave its
    /// nodes: a fraction of each coordinate's and velocity's scale, its
    /// range over the plan (at least a tenth of the largest of its kind).
    #[arg(long, default_value_t = Replay::TOLERANCE)]
    replay_tol: f64,
    /// The directory for `plan.csv`, `plan.json` and the plots.
    #[arg(long, default_value = "out")]
    out: PathBuf,
    #[command(flatten)]
    animate: AnimateArgs,
}

/// The plan's columns drawn against `t`: the states (coordinates and
/// velocities, or momenta) and the inputs.
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
    let form = plan::formulation(args.request.formulation, &loaded.model)?;
    let drawn = args.animate.drawn(&loaded)?;
    let drawings = Drawings {
        states: form.state_names(&loaded.model),
        inputs: loaded.model.names().inputs.clone(),
    };
    let solver = args.solver.solver();
    let mut observer = solve_watch::observer();
    let planned = plan::plan_within(
        loaded,
        &args.request,
        &solver,
        args.replay_tol,
        &mut observer,
    );
    match planned {
        Ok(plan) => write(args, &plan, None, &drawings, drawn),
        Err(failure) => match failure.downcast::<PlanError>() {
            Ok(error) => written(args, *error, &drawings, drawn),
            Err(failure) => Err(failure),
        },
    }
}

/// Writes the plan of an interrupted solve, or of one whose replay
/// departs from it, marked as not kept, and fails with `error`; fails
/// with any other error at once.
fn written(
    args: &PlanArgs,
    error: PlanError,
    drawings: &Drawings,
    drawn: Option<Drawn>,
) -> Result<(), Failure> {
    let (plan, mark, what) = match &error {
        PlanError::Interrupted(last) => (
            last,
            format!(
                "not verified: interrupted after {} iterations (plan.json)",
                last.report.iterations
            ),
            solve_watch::LAST_ITERATE,
        ),
        PlanError::Departs(departed) => (
            departed,
            "not a motion of the model: its replay departs from it (plan.json's replay)".into(),
            "the plan, marked,",
        ),
        _ => return Err(error.into()),
    };
    write(args, plan, Some(&mark), drawings, drawn)?;
    Err(Written {
        reason: error.into(),
        what,
        out: args.out.clone(),
    }
    .into())
}

/// The words on a plan solved again from its default guess, the inputs
/// nudged.
fn restarted(restart: &Restart) -> String {
    format!(
        ", from the default guess with the inputs nudged by {} sin(pi t / T) \
         (from the default guess itself the solver ended {} after {} iterations, unverified)",
        Request::NUDGE,
        restart.status,
        restart.iterations
    )
}

/// Writes `plan.csv` (its first line `# MARK` for a plan not kept),
/// `plan.json`, the plots and the animation, and says so.
fn write(
    args: &PlanArgs,
    plan: &Plan,
    mark: Option<&str>,
    drawings: &Drawings,
    drawn: Option<Drawn>,
) -> Result<(), Failure> {
    let (csv, json) = (args.out.join("plan.csv"), args.out.join("plan.json"));
    let report = &plan.report;
    match mark {
        None => write_table(&plan.table, &csv)?,
        Some(mark) => write_marked_table(&plan.table, &csv, mark)?,
    }
    std::fs::write(&json, format!("{:#}\n", report.to_json()))?;
    if mark.is_none() {
        crate::say(&format!(
            "objective {:.9e}: a verified optimum ({}, {} nodes, {}) after {} iterations in \
             {:.2} s{}; KKT residuals primal {:.1e}, dual {:.1e}, complementarity {:.1e}; \
             replayed within {:.1e} of its variables' scales\n",
            report.objective,
            report.scheme.name(),
            report.nodes,
            report.solver,
            report.iterations,
            report.seconds,
            report.restart.as_ref().map_or_else(String::new, restarted),
            report.kkt.primal,
            report.kkt.dual,
            report.kkt.complementarity,
            report.replay.largest.relative,
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
