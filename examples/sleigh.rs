//! The Chaplygin sleigh declared with `chaplygin::model!` and simulated in
//! its reduced port-Hamiltonian form: sent backwards along its blade while
//! turning, it swings round and slides on forwards, its blade trailing.
//!
//! ```text
//! cargo run --example sleigh
//! ```
//!
//! Its speed `v` along the blade and its turning rate `w` obey
//! `vdot = a w^2`, `wdot = -m a v w / (I + m a^2)` (Bloch, *Nonholonomic
//! Mechanics and Control*, section 1.7), which keep the energy
//! `E = (m v^2 + (I + m a^2) w^2) / 2`: the speed tends to
//! `sqrt(2 E / m)` and the turning stops. The program prints the motion
//! every half second and that terminal speed.

use chaplygin::runtime::integrate::DormandPrince;
use chaplygin::runtime::record::Table;
use chaplygin::runtime::simulate::Simulation;
use chaplygin::runtime::system::Reduced;
use std::error::Error;
use std::io::Write;

chaplygin::model! {
    /// The Chaplygin sleigh: a knife edge (the blade) at `(x, y)`, heading
    /// `theta`, its centre of mass a distance `a` ahead of the blade.
    pub struct Sleigh {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.1, a = 0.5],
        kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
            + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
        symmetry: se2(x, y, theta),
    }
}

fn main() -> Result<(), Box<dyn Error>> {
    report(&mut std::io::stdout().lock())
}

/// Simulates 8 s of the sleigh from `v = -0.5`, `w = 1` and writes the
/// motion every half second to `out`.
///
/// # Errors
/// A failed run or write.
pub fn report(out: &mut impl Write) -> Result<(), Box<dyn Error>> {
    let sleigh = Sleigh::default();
    let (v0, w0) = (-0.5, 1.0);
    let q = [0.0, 0.0, 0.0];
    let qdot = [v0, 0.0, w0];
    let alpha = sleigh.momenta(&q, &qdot);
    let energy = sleigh.energy(&q, &qdot);
    writeln!(
        out,
        "The Chaplygin sleigh (m = {}, I = {}, a = {}) sent backwards at {v0} m/s, turning at {w0} rad/s:",
        sleigh.m, sleigh.inertia, sleigh.a
    )?;
    writeln!(
        out,
        "its energy {energy} J carries it on at sqrt(2 E / m) = {} m/s.",
        (2.0 * energy / sleigh.m).sqrt()
    )?;
    let tight = DormandPrince {
        rtol: 1e-11,
        atol: 1e-11,
        ..Default::default()
    };
    let mut table = Table::new();
    let summary = Simulation::new(tight).span(0.0, 8.0).step(0.5).run(
        &Reduced::constant(&sleigh, []),
        [q[0], q[1], q[2], alpha[0], alpha[1]],
        &mut table,
    )?;
    writeln!(out, "    t   speed v   turning w   heading theta")?;
    for row in &table.rows {
        let (q, alpha) = ([row[1], row[2], row[3]], [row[4], row[5]]);
        let qdot = sleigh.velocities(&q, &alpha);
        let speed = q[2].cos() * qdot[0] + q[2].sin() * qdot[1];
        writeln!(
            out,
            "{:5.1} {speed:9.6} {:11.6} {:15.6}",
            row[0], qdot[2], q[2]
        )?;
    }
    writeln!(
        out,
        "energy drift {:.1e}, largest blade slip {:.1e}",
        summary.energy_drift, summary.max_constraint_residual
    )?;
    Ok(())
}
