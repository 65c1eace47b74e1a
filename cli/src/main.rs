//! `chaplygin`: the command line of Chaplygin (docs/INTERFACE.md section 3),
//! over `chaplygin::driver`.
//!
//! ```text
//! chaplygin list
//! chaplygin derive MODEL [--format text|latex|json|rust]
//! chaplygin simulate MODEL [--formulation reduced|lagrange|momentum] [--integrator rk4|dopri5|midpoint|discrete-gradient]
//!                          [--controller none|energy] [--t-end T] [--dt H] [--stop-when COND]
//!                          [--engine jit|interpret] [--out DIR] [--animate [--fps F]]
//!                          [--param NAME=VALUE]... [--initial NAME=EXPRESSION]... [--input NAME=EXPRESSION]...
//! chaplygin linearize MODEL [--at NAME=EXPR]... [--sweep VAR=START:STOP:STEP]
//!                           [--param NAME=VALUE]... [--engine jit|interpret] [--out DIR]
//!                           [--canonical Q1,Q2,... --canonical-speed VAR[=V1,V2] [--canonical-gravity NAME]]
//! chaplygin steady MODEL [--at NAME=EXPR]... [--input NAME=EXPR]... --solve NAME,... [--guess NAME=VALUE]...
//!                        [--param NAME=VALUE]... [--engine jit|interpret] [--out DIR]
//! chaplygin map MODEL --speed VAR=START:STOP:STEP --param NAME=START:STOP:STEP [--param NAME2=START:STOP:STEP]
//!                     [--at NAME=EXPR]... [--param NAME=VALUE]... [--jobs N] [--engine jit|interpret] [--out DIR]
//! chaplygin gait MODEL --shape A,B,... --cycle NAME=EXPR... --period T [--cycles N] [--steps S]
//!                      [--param NAME=VALUE]... [--initial pI=VALUE]... [--engine jit|interpret] [--out DIR]
//! chaplygin plan MODEL --duration T [--free-duration] --nodes N [--scheme backward-euler|midpoint|hermite-simpson]
//!                      [--start NAME=EXPR]... [--goal NAME=EXPR]... [--minimize EXPR] [--final-cost EXPR]
//!                      [--bound NAME=LO:HI]... [--param NAME=VALUE]... [--guess FILE.csv]
//!                      [--tol TOL] [--engine jit|interpret] [--out DIR]
//! chaplygin identify MODEL --data FILE.csv --estimate NAME[=GUESS]... [--nodes N] [--scheme ...]
//!                          [--param NAME=VALUE]... [--tol TOL] [--engine jit|interpret] [--out DIR]
//! ```
//!
//! MODEL is a built-in model's name or the path of a `.model` file. Either
//! runs from its text, without rustc: its derived programs compiled to
//! native code at run time (`--engine jit`, the default) or interpreted
//! (`--engine interpret`). `--input` laws are
//! expressions of `t`, the parameters, the coordinates and their velocities
//! `dot(q)` (feedback laws such as `steer_torque=50*phi+50*dot(phi)`);
//! `--stop-when` ends a run cleanly where one comparison of these and the
//! inputs first holds (`'abs(phi) > 1'`). Every failure of a run is one line
//! on standard error and a non-zero exit status (a malformed command line
//! gets clap's usage message).

mod animate_args;
mod gait;
mod identify;
mod linearize;
mod map;
mod model_args;
mod options;
mod output;
mod plan;
mod simulate;
mod solve_watch;
mod steady;

use clap::Parser;
use std::error::Error;
use std::io::{ErrorKind, Write};
use std::process::ExitCode;

fn main() -> ExitCode {
    let command = options::Command::parse();
    match command.run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) if closed_output(error.as_ref()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}

/// Writes `text` to standard output.
///
/// # Errors
/// The output's; where it is a pipe its reader closed (`| head`), the
/// command ends quietly (see [`closed_output`]).
pub fn say(text: &str) -> std::io::Result<()> {
    std::io::stdout().lock().write_all(text.as_bytes())
}

/// Whether `error` is standard output closed by its reader.
fn closed_output(error: &(dyn Error + 'static)) -> bool {
    error
        .downcast_ref::<std::io::Error>()
        .is_some_and(|error| error.kind() == ErrorKind::BrokenPipe)
}
