//! The energy drift a run reports is relative to the run's kinetic energy
//! and the range of its potential (docs/INTERFACE.md section 12), so a
//! constant added to the potential, which changes no motion, changes no
//! drift. The truth is the model itself: `V + c` has the same equations of
//! motion as `V`.

use crate::support::in_process::Model;
use crate::support::scratch;

/// A skate held on its heading by a torsion spring `k (1 - cos(theta))`,
/// its potential raised by the parameter `c`.
const SKATE: &str = "pub struct RaisedSkate {
    coordinates: [x, y, theta],
    parameters: [m = 1.0, inertia = 0.05, k = 0.5, c = 0.0],
    kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) + inertia/2*dot(theta)^2,
    potential_energy: k*(1 - cos(theta)) + c,
    constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
}
";

/// The number after `energy drift ` in a summary line.
fn drift(summary: &str) -> f64 {
    let after = summary
        .split("energy drift ")
        .nth(1)
        .unwrap_or_else(|| panic!("a drift in {summary}"));
    after.split(' ').next().unwrap().parse().expect(summary)
}

/// Coarse fixed RK4 steps drift by some 1e-6 of the skate's energy; the
/// potential raised by 1000, which divided the drift relative to `|E(0)|`
/// by some 1400, leaves it as it is (to the round-off of 1000 in the
/// energies, 1e-13).
#[test]
fn a_constant_added_to_the_potential_reports_the_same_drift() {
    let directory = scratch("energy-drift-raised");
    let path = directory.path().join("raised_skate.model");
    std::fs::write(&path, SKATE).expect("written");
    let model = Model::load(path.to_str().expect("path"), "jit");
    let run = |c: &str| {
        let options = [
            "--integrator",
            "rk4",
            "--fixed-step",
            "--dt",
            "0.05",
            "--t-end",
            "20",
            "--initial",
            "dot(x)=1",
            "--initial",
            "dot(theta)=3",
            "--param",
            c,
        ];
        let run = model.simulate(&options).expect("a run");
        drift(&run.outcome.expect("to the end"))
    };
    let (plain, raised) = (run("c=0"), run("c=1000"));
    assert!(plain > 1e-9, "{plain:e}");
    assert!(
        (raised - plain).abs() <= 1e-3 * plain,
        "{raised:e} against {plain:e}"
    );
}
