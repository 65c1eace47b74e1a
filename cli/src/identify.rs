//! `chaplygin identify MODEL --data FILE.csv --estimate NAME[=GUESS]...
//! [--nodes N] [--scheme backward-euler|midpoint|hermite-simpson] [--param
//! NAME=VALUE]... [--tol TOL] [--hessian exact|lbfgs] --out DIR` (docs/INTERFACE.md section 13),
//! over `chaplygin::driver::plan::identify`: the parameters that fit the
//! measured columns by collocation, verified by the KKT conditions from
//! the exact derivatives.
//!
//! It writes `DIR/estimate.json` (the parameters, their standard errors,
//! the residuals' RMS, the iterations and the KKT residuals), `DIR/fit.csv`
//! (`t`, the fitted states and each measured column's data as
//! `data(NAME)`) and `DIR/fit.png` (the measured columns against their
//! fit), and prints `NAME = value +- standard error` per estimate. An
//! answer that is not a verified optimum is an error, and nothing is
//! written.
//!
//! On a terminal, standard error shows one line per solver iteration
//! (`crate::solve_watch`). Ctrl-C stops the solve at its current iterate,
//! which is written as above with `fit.csv`'s first line `# not verified:
//! ...` and `estimate.json`'s `status` `interrupted`, its KKT residuals
//! computed there; the command then fails saying so.

use crate::model_args::{ModelArgs, loaded};
use crate::output::{write_marked_table, write_table};
use crate::simulate::write_plots;
use crate::solve_watch::{self, SolverArgs, Written};
use chaplygin::driver::Failure;
use chaplygin::driver::plan::Report;
use chaplygin::driver::plan::identify::{self, Estimate, Request};
use chaplygin::plot;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct IdentifyArgs {
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    request: Request,
    #[command(flatten)]
    solver: SolverArgs,
    #[arg(long, default_value = "out")]
    out: PathBuf,
}

/// Runs `chaplygin identify`.
///
/// # Errors
/// Bad input, an answer that is not a verified optimum, Ctrl-C (after
/// writing the last iterate), or an I/O error.
pub fn run(args: &IdentifyArgs) -> Result<(), Failure> {
    solve_watch::stop_on_ctrl_c()?;
    let loaded = loaded(&args.model)?;
    let mut observer = solve_watch::observer();
    let solver = args.solver.solver();
    match identify::identify_watched(loaded, &args.request, &solver, &mut observer) {
        Ok(estimate) => write(args, &estimate, true),
        Err(failure) => match failure.downcast::<identify::Interrupted>() {
            Ok(stopped) => {
                write(args, &stopped.0, false)?;
                Err(Written {
                    reason: stopped,
                    what: solve_watch::LAST_ITERATE,
                    out: args.out.clone(),
                }
                .into())
            }
            Err(failure) => Err(failure),
        },
    }
}

/// Writes `estimate.json`, `fit.csv` (marked as not verified for an
/// interrupted solve) and `fit.png`, and prints the estimates.
fn write(args: &IdentifyArgs, estimate: &Estimate, verified: bool) -> Result<(), Failure> {
    let (csv, json) = (args.out.join("fit.csv"), args.out.join("estimate.json"));
    let mut report = estimate.to_json();
    if verified {
        write_table(&estimate.fit, &csv)?;
    } else {
        let mark = format!(
            "not verified: interrupted after {} iterations (estimate.json)",
            estimate.iterations
        );
        write_marked_table(&estimate.fit, &csv, &mark)?;
        report["status"] = Report::INTERRUPTED.into();
    }
    std::fs::write(&json, format!("{report:#}\n"))?;
    if verified {
        for ((name, value), error) in estimate.parameters.iter().zip(&estimate.standard_errors) {
            crate::say(&format!("{name} = {value:.9e} +- {error:.3e}\n"))?;
        }
        crate::say(&format!(
            "residual RMS {:.3e}: a verified optimum after {} iterations; KKT residuals primal \
             {:.1e}, dual {:.1e}, complementarity {:.1e}\n",
            estimate.residual_rms,
            estimate.iterations,
            estimate.kkt.primal,
            estimate.kkt.dual,
            estimate.kkt.complementarity,
        ))?;
    }
    crate::say(&format!(
        "wrote {}\nwrote {}\n",
        csv.display(),
        json.display()
    ))?;
    let measured: Vec<String> = estimate
        .fit
        .columns
        .iter()
        .filter_map(|c| c.strip_prefix("data(")?.strip_suffix(')'))
        .flat_map(|name| [name.to_string(), format!("data({name})")])
        .collect();
    let fit = plot::Series {
        name: "fit".into(),
        title: "Data against the fit".into(),
        y_desc: "measured columns".into(),
        columns: measured,
    };
    for plot in write_plots(&estimate.fit, None, &args.out, None, vec![fit])? {
        crate::say(&format!("wrote {}\n", plot.display()))?;
    }
    Ok(())
}
