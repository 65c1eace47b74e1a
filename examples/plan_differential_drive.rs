//! A plan through the library (`chaplygin::driver::plan`): the
//! differential drive from rest at the origin to rest 0.3 ahead and 0.1 to
//! the left, facing the same way, in 4 s, with the least integral of its
//! wheel torques squared, by the midpoint rule on 21 nodes.
//!
//! ```text
//! cargo run --release --example plan_differential_drive
//! ```
//!
//! It prints the optimum's objective, the KKT residuals the library
//! computed from the exact derivatives, and the replay: the torques
//! integrated from the start, where they leave the drive against the
//! goal, and how far they depart from the plan's nodes. The command line's
//! `chaplygin plan differential-drive ...` (docs/guide/planning.md) is the
//! same plan.

use chaplygin::driver::Failure;
use chaplygin::driver::catalog::lookup;
use chaplygin::driver::engine::{EngineChoice, load};
use chaplygin::driver::plan::nlp::Ripopt;
use chaplygin::driver::plan::replay::replayed_states;
use chaplygin::driver::plan::{Request, Scheme, plan};
use chaplygin::driver::simulate::FormulationChoice;
use std::io::Write;

/// The coordinates, each at rest at 0 at the start.
const COORDINATES: [&str; 5] = ["x", "y", "theta", "phi_r", "phi_l"];

/// The goal: the pose, and the wheels still.
pub const GOAL: [(&str, f64); 5] = [
    ("x", 0.3),
    ("y", 0.1),
    ("theta", 0.0),
    ("dot(phi_r)", 0.0),
    ("dot(phi_l)", 0.0),
];

fn main() -> Result<(), Failure> {
    report(&mut std::io::stdout().lock())
}

/// `(NAME, VALUE)` pairs as a request's conditions.
fn assigned(pairs: impl IntoIterator<Item = (String, f64)>) -> Vec<(String, String)> {
    (pairs.into_iter())
        .map(|(name, value)| (name, value.to_string()))
        .collect()
}

/// The plan of 4 s on 21 nodes from rest at the origin to [`GOAL`].
pub fn request() -> Request {
    let positions = COORDINATES.iter().map(|q| (q.to_string(), 0.0));
    let velocities = COORDINATES.iter().map(|q| (format!("dot({q})"), 0.0));
    Request {
        duration: 4.0,
        free_duration: false,
        nodes: 21,
        scheme: Scheme::Midpoint,
        formulation: FormulationChoice::Lagrange,
        start: assigned(positions.chain(velocities)),
        goal: assigned(GOAL.iter().map(|(name, value)| (name.to_string(), *value))),
        minimize: None,
        final_cost: None,
        bounds: Vec::new(),
        params: Vec::new(),
        guess: None,
        tol: Request::TOL,
    }
}

/// Plans, and writes the objective, the KKT residuals, the replayed end
/// against the goal and the replay's largest departure to `out`.
///
/// # Errors
/// The model does not load, no verified optimum, a replay that departs,
/// a failed write.
pub fn report(out: &mut impl Write) -> Result<(), Failure> {
    let drive = load(&lookup("differential-drive")?, EngineChoice::Jit)?;
    let model = drive.model.clone();
    let planned = plan(drive, &request(), &Ripopt::default())?;
    let report = &planned.report;
    writeln!(
        out,
        "objective {:.9e} after {} iterations ({})",
        report.objective, report.iterations, report.solver
    )?;
    writeln!(
        out,
        "KKT residuals: primal {:.3e} dual {:.3e} complementarity {:.3e}",
        report.kkt.primal, report.kkt.dual, report.kkt.complementarity
    )?;
    let states = replayed_states((&model, report.formulation), report.scheme, &planned.table);
    let end = &states[states.len() - 1];
    let columns = &planned.table.columns[1..];
    writeln!(out, "replayed end against the goal:")?;
    for (name, goal) in GOAL {
        let index = columns.iter().position(|c| c == name).unwrap_or(0);
        writeln!(out, "  {name:>10} {:12.6} {goal:12.6}", end[index])?;
    }
    let largest = &report.replay.largest;
    writeln!(
        out,
        "replay departs most in {} at t = {:.2}: {:.3e}, {:.3e} of its range (allowed {})",
        largest.variable, largest.t, largest.size, largest.relative, report.replay.tolerance
    )?;
    Ok(())
}
