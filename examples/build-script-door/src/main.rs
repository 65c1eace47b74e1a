//! The build-script door: `pushed_sleigh.model` compiled by `build.rs`,
//! simulated in its reduced port-Hamiltonian form with the implicit midpoint
//! rule under a constant push, the trajectory written as CSV to standard
//! output.
//!
//! ```text
//! cargo run -p build-script-door > pushed_sleigh.csv
//! ```

use chaplygin::runtime::integrate::Midpoint;
use chaplygin::runtime::record::CsvRecorder;
use chaplygin::runtime::simulate::Simulation;
use chaplygin::runtime::system::Reduced;

include!(concat!(env!("OUT_DIR"), "/pushed_sleigh.rs"));

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let sleigh = PushedSleigh::default();
    let q = [0.0, 0.0, 0.2];
    let alpha = sleigh.momenta(&q, &[0.2f64.cos(), 0.2f64.sin(), 1.0]);
    let system = Reduced::constant(&sleigh, [0.1]);
    let mut csv = CsvRecorder::new(std::io::stdout().lock());
    let summary = Simulation::new(Midpoint::default())
        .span(0.0, 10.0)
        .step(0.01)
        .record_every(10)
        .run(&system, [q[0], q[1], q[2], alpha[0], alpha[1]], &mut csv)?;
    eprintln!(
        "{} steps to t = {}; largest constraint residual {:.1e}",
        summary.steps, summary.t, summary.max_constraint_residual
    );
    Ok(())
}
