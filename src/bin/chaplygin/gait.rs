//! `chaplygin gait MODEL --shape a,b --cycle 'a=EXPR' --cycle 'b=EXPR'
//! --period T [--param NAME=VALUE]... [--cycles N] [--initial pI=VALUE]...
//! [--out DIR]` (docs/INTERFACE.md section 9), over
//! `chaplygin::driver::gait`: the net displacement per cycle of a
//! prescribed periodic shape trajectory, `DIR/cycle.csv` (`t`, the
//! coordinates, the momenta) and `DIR/gait_path.png`.

use crate::model_args::{ModelArgs, loaded};
use crate::output::{plotted, write_table};
use chaplygin::driver::gait::{GaitRequest, gait};
use chaplygin::driver::simulate::{assignment, expression_assignment};
use chaplygin::plot;
use chaplygin::runtime::record::shortest_decimal;
use std::collections::BTreeSet;
use std::error::Error;
use std::path::PathBuf;

/// The arguments of `chaplygin gait`.
#[derive(Debug, clap::Args)]
pub struct GaitArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// The shape coordinates the gait prescribes, comma-separated: every
    /// coordinate the model's symmetry does not move.
    #[arg(long, value_name = "A,B,...", value_delimiter = ',', required = true)]
    shape: Vec<String>,
    /// A shape coordinate's law `NAME=EXPR`, an expression of `t` and the
    /// parameters (`phi=0.5*sin(t)`), periodic with `--period`; one per
    /// shape coordinate.
    #[arg(long = "cycle", value_name = "NAME=EXPR", value_parser = expression_assignment, required = true)]
    cycle: Vec<(String, String)>,
    /// The period T of the laws.
    #[arg(long)]
    period: f64,
    /// The cycles run.
    #[arg(long, default_value_t = 1)]
    cycles: usize,
    /// RK4 steps per period.
    #[arg(long, default_value_t = 2000)]
    steps: usize,
    /// A parameter's value, `NAME=VALUE`.
    #[arg(long = "param", value_parser = assignment)]
    params: Vec<(String, f64)>,
    /// An initial momentum `pI=VALUE` (zero unless given).
    #[arg(long = "initial", value_parser = assignment)]
    initial: Vec<(String, f64)>,
    /// Where `cycle.csv` and `gait_path.png` are written.
    #[arg(long, default_value = "out")]
    out: PathBuf,
}

/// Runs `chaplygin gait`.
///
/// # Errors
/// Bad input, a model a gait does not move, or an I/O error.
pub fn run(args: &GaitArgs) -> Result<(), Box<dyn Error>> {
    let shape: BTreeSet<&str> = args.shape.iter().map(String::as_str).collect();
    let laws: BTreeSet<&str> = args.cycle.iter().map(|(name, _)| name.as_str()).collect();
    if shape != laws {
        return Err(format!(
            "--shape names {} but --cycle gives laws for {}",
            args.shape.join(", "),
            laws.into_iter().collect::<Vec<_>>().join(", ")
        )
        .into());
    }
    let request = GaitRequest {
        cycle: args.cycle.clone(),
        period: args.period,
        cycles: args.cycles,
        steps: args.steps,
        params: args.params.clone(),
        initial: args.initial.clone(),
    };
    let run = gait(loaded(&args.model)?, &request)?;
    let mut text = String::new();
    for (k, cycle) in run.cycles.iter().enumerate() {
        let [x, y, theta] = cycle.displacement;
        let label = match k {
            0 => "net displacement per cycle".to_string(),
            _ => format!("cycle {}", k + 1),
        };
        let [x, y, theta] = [x, y, theta].map(shortest_decimal);
        text.push_str(&format!("{label}: x = {x}, y = {y}, theta = {theta}\n"));
    }
    crate::say(&text)?;
    let csv_path = args.out.join("cycle.csv");
    write_table(&run.table, &csv_path)?;
    let png_path = args.out.join("gait_path.png");
    plot::write_path_plot(&plotted(&run.table)?, &png_path)?;
    crate::say(&format!(
        "wrote {}\nwrote {}\n",
        csv_path.display(),
        png_path.display()
    ))?;
    Ok(())
}
