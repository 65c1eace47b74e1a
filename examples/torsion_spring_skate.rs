//! A user-declared model simulated with the runtime API: a skate (a knife
//! edge with its centre of mass on the blade) whose heading is held by a
//! torsion spring of stiffness `k` with the nonlinear energy
//! `k (1 - cos(theta))`. The energy is not quadratic, so Gonzalez's discrete
//! gradient keeps it where the implicit midpoint rule only nearly does.
//!
//! ```text
//! cargo run --example torsion_spring_skate
//! ```

use chaplygin::runtime::integrate::{DiscreteGradient, Midpoint};
use chaplygin::runtime::record::Table;
use chaplygin::runtime::simulate::{Advance, Simulation};
use chaplygin::runtime::system::{Constant, Reduced};

chaplygin::model! {
    /// A skate on the plane with a torsion spring on its heading.
    pub struct Skate {
        coordinates: [x, y, theta],
        parameters: [m = 1.0, inertia = 0.05, k = 0.5],
        kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) + inertia/2*dot(theta)^2,
        potential_energy: k*(1 - cos(theta)),
        constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
        momentum_basis: [
            forward = [m*cos(theta), m*sin(theta), 0],
            turning = [0, 0, inertia],
        ],
        drawing: [skate = box(center = [x, y, 0.03], heading = theta, size = [0.3, 0.08, 0.04])],
    }
}

/// Runs 100 s with steps of 0.05 and returns the largest relative energy
/// error and the final position.
fn run<M>(method: M, skate: &Skate) -> (f64, f64, f64)
where
    M: for<'a> Advance<Reduced<'a, Skate, Constant<0>, 0>, [f64; 5]>,
{
    let q = [0.0, 0.0, 0.0];
    let alpha = skate.momenta(&q, &[1.0, 0.0, 3.0]);
    let mut table = Table::new();
    let summary = Simulation::new(method)
        .span(0.0, 100.0)
        .step(0.05)
        .run(
            &Reduced::constant(skate, []),
            [q[0], q[1], q[2], alpha[0], alpha[1]],
            &mut table,
        )
        .expect("the skate stays regular");
    (summary.energy_drift, summary.state[0], summary.state[1])
}

fn main() -> std::io::Result<()> {
    report(&mut std::io::stdout().lock())
}

/// Runs the skate with both integrators and writes their energy drift and
/// end points to `out`.
///
/// # Errors
/// A failed write.
pub fn report(out: &mut impl std::io::Write) -> std::io::Result<()> {
    let skate = Skate::default();
    for (name, (drift, x, y)) in [
        (
            "discrete gradient",
            run(DiscreteGradient::default(), &skate),
        ),
        ("implicit midpoint", run(Midpoint::default(), &skate)),
    ] {
        writeln!(
            out,
            "{name:>17}: energy drift {drift:.2e}, at t = 100 the skate is at ({x:.4}, {y:.4})"
        )?;
    }
    Ok(())
}
