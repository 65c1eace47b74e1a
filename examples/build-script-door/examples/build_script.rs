//! The build-script door: `pushed_sleigh.model` compiled into Rust by this
//! package's `build.rs` (`chaplygin_codegen::Builder`), included from
//! `OUT_DIR`, and simulated in its reduced port-Hamiltonian form with the
//! implicit midpoint rule under a constant push along the blade.
//!
//! ```text
//! cargo run --example build_script
//! ```
//!
//! The program prints what the build script derived about the constraint
//! (its growth vector and classification, from `PushedSleigh::REPORT`) and
//! the run's power balance: the push is the only force that works, so the
//! energy the sleigh gains is the push times the distance its blade
//! travels.

use chaplygin::runtime::integrate::Midpoint;
use chaplygin::runtime::record::Table;
use chaplygin::runtime::simulate::Simulation;
use chaplygin::runtime::system::Reduced;
use std::error::Error;
use std::io::Write;

include!(concat!(env!("OUT_DIR"), "/pushed_sleigh.rs"));

/// The push along the blade, in newtons.
pub const PUSH: f64 = 0.1;

fn main() -> Result<(), Box<dyn Error>> {
    report(&mut std::io::stdout().lock())
}

/// Writes the constraint analysis and 10 s of the pushed sleigh's run to
/// `out`.
///
/// # Errors
/// A failed run or write.
pub fn report(out: &mut impl Write) -> Result<(), Box<dyn Error>> {
    writeln!(out, "pushed_sleigh.model, compiled by build.rs:")?;
    for line in PushedSleigh::REPORT.lines() {
        if line.contains("growth vector") || line.contains("classification") {
            writeln!(out, "  {}", line.trim())?;
        }
    }
    let sleigh = PushedSleigh::default();
    let q = [0.0, 0.0, 0.2];
    let alpha = sleigh.momenta(&q, &[0.2f64.cos(), 0.2f64.sin(), 1.0]);
    let mut table = Table::new();
    let summary = Simulation::new(Midpoint::default())
        .span(0.0, 10.0)
        .step(0.01)
        .run(
            &Reduced::constant(&sleigh, [PUSH]),
            [q[0], q[1], q[2], alpha[0], alpha[1]],
            &mut table,
        )?;
    let column = |name: &str| table.column(name).ok_or(format!("no column {name}"));
    let (x, y, energy) = (column("x")?, column("y")?, column("energy")?);
    let travelled: f64 = (1..x.len())
        .map(|i| (x[i] - x[i - 1]).hypot(y[i] - y[i - 1]))
        .sum();
    let gained = energy[energy.len() - 1] - energy[0];
    writeln!(
        out,
        "pushed along its blade by {PUSH} N from 1 m/s for {} s ({} steps of the midpoint rule):",
        summary.t, summary.steps
    )?;
    writeln!(
        out,
        "  the blade travelled {travelled:.9} m and the sleigh gained {gained:.9} J,"
    )?;
    writeln!(
        out,
        "  the push's work {:.9} J; the blade slipped by {:.1e} m/s at most",
        PUSH * travelled,
        summary.max_constraint_residual
    )?;
    Ok(())
}
