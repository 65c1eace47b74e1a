//! What `plan` and `identify` show and do while the solver runs: on a
//! terminal, one line per iteration on standard error (its number,
//! objective, and primal and dual infeasibility); Ctrl-C stops the solve
//! at its next iteration, and before it gets there a second Ctrl-C ends
//! the command at once, writing nothing.

use chaplygin::driver::Failure;
use chaplygin::driver::plan::nlp::{Hessian, Iteration, Ripopt};
use std::io::IsTerminal;
use std::ops::ControlFlow;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

/// The solver `plan` and `identify` run: ripopt, on the Hessian asked for.
#[derive(Debug, clap::Args)]
pub struct SolverArgs {
    /// The Hessian of the Lagrangian the solver works with: the exact one
    /// from the model's second derivatives, or an L-BFGS approximation.
    #[arg(long, value_enum, default_value = "exact")]
    hessian: Hessian,
}

impl SolverArgs {
    /// The solver asked for.
    pub fn solver(&self) -> Ripopt {
        Ripopt {
            hessian: self.hessian,
        }
    }
}

/// Set by Ctrl-C: the solve stops at its next iteration.
static STOP: AtomicBool = AtomicBool::new(false);

/// An answer not kept (a solve stopped by Ctrl-C, a plan departing from
/// its replay), written to `out` for inspection.
#[derive(Debug, thiserror::Error)]
#[error("{reason}; {what} is in {}", out.display())]
pub struct Written {
    /// The library's word on it.
    pub reason: Failure,
    /// What was written.
    pub what: &'static str,
    /// Where.
    pub out: PathBuf,
}

/// What a stopped solve writes.
pub const LAST_ITERATE: &str = "the last iterate, not verified,";

/// Makes Ctrl-C stop the solve that [`observer`] watches, from now on.
///
/// # Errors
/// Ctrl-C's handler cannot be set.
pub fn stop_on_ctrl_c() -> Result<(), Failure> {
    ctrlc::set_handler(|| {
        if STOP.swap(true, Ordering::Relaxed) {
            std::process::exit(130);
        }
    })?;
    Ok(())
}

/// The observer of a solve: it shows each iteration where standard error
/// is a terminal (under a header it prints now), and stops the solve
/// after Ctrl-C (with [`stop_on_ctrl_c`]).
pub fn observer() -> impl FnMut(&Iteration) -> ControlFlow<()> {
    let terminal = std::io::stderr().is_terminal();
    if terminal {
        eprintln!("{}", iteration_header());
    }
    move |iteration: &Iteration| {
        if terminal {
            eprintln!("{}", iteration_line(iteration));
        }
        match STOP.load(Ordering::Relaxed) {
            true => ControlFlow::Break(()),
            false => ControlFlow::Continue(()),
        }
    }
}

/// The columns of the iterations' lines.
fn iteration_header() -> String {
    format!(
        "{:>5} {:>17} {:>9} {:>9}",
        "iter", "objective", "primal", "dual"
    )
}

/// One iteration as a line under [`iteration_header`].
fn iteration_line(iteration: &Iteration) -> String {
    format!(
        "{:>5} {:>17.9e} {:>9.2e} {:>9.2e}",
        iteration.number, iteration.objective, iteration.primal, iteration.dual
    )
}
