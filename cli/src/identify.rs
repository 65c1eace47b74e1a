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

use crate::model_args::{ModelArgs, loaded};
use crate::output::write_table;
use crate::simulate::write_plots;
use chaplygin::driver::Failure;
use chaplygin::driver::plan::identify::{self, Estimate, Request};
use chaplygin::driver::plan::nlp::{Hessian, Ripopt};
use chaplygin::plot;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct IdentifyArgs {
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    request: Request,
    /// The Hessian of the Lagrangian the solver works with: the exact one
    /// from the model's second derivatives, or an L-BFGS approximation.
    #[arg(long, value_enum, default_value = "exact")]
    hessian: Hessian,
    #[arg(long, default_value = "out")]
    out: PathBuf,
}

pub fn run(args: &IdentifyArgs) -> Result<(), Failure> {
    let loaded = loaded(&args.model)?;
    let estimate = identify::identify(
        loaded,
        &args.request,
        &Ripopt {
            hessian: args.hessian,
        },
    )?;
    write(args, &estimate)
}

/// Writes `estimate.json`, `fit.csv` and `fit.png`, and prints the
/// estimates.
fn write(args: &IdentifyArgs, estimate: &Estimate) -> Result<(), Failure> {
    let (csv, json) = (args.out.join("fit.csv"), args.out.join("estimate.json"));
    write_table(&estimate.fit, &csv)?;
    std::fs::write(&json, format!("{:#}\n", estimate.to_json()))?;
    for ((name, value), error) in estimate.parameters.iter().zip(&estimate.standard_errors) {
        crate::say(&format!("{name} = {value:.9e} +- {error:.3e}\n"))?;
    }
    crate::say(&format!(
        "residual RMS {:.3e}: a verified optimum after {} iterations; KKT residuals primal \
         {:.1e}, dual {:.1e}, complementarity {:.1e}\nwrote {}\nwrote {}\n",
        estimate.residual_rms,
        estimate.iterations,
        estimate.kkt.primal,
        estimate.kkt.dual,
        estimate.kkt.complementarity,
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
