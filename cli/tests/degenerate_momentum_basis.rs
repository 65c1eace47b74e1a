//! A run of the momentum formulation (MATH.md 4) that reaches a
//! degenerate reconstruction stops with the structured error, naming the
//! time and the configuration, in the compiled adapter and through the
//! command line's interpreted one: the lever blade
//! (`tests/models/lever_blade.model`), `(phi - 1) v_side + dot(s) = 0`, whose
//! row is regular at `phi = 1` but whose reconstruction
//! `xi = -A_nh rdot + e I^-1 p` divides by `phi - 1`. With `dot(phi) = 0.7`
//! from `phi = 0.5` (no force acts on `phi`), `phi` crosses 1 at
//! `t = 5/7`, inside the step to `t = 0.72`.

use crate::support::{chaplygin, read_csv, scratch};
use chaplygin::runtime::integrate::Rk4;
use chaplygin::runtime::record::Table;
use chaplygin::runtime::simulate::{RECONSTRUCTION, Simulation, SimulationError};
use chaplygin::runtime::system::Momentum;

chaplygin::model! {
    /// The lever blade of `tests/models/lever_blade.model`.
    pub struct LeverBlade {
        coordinates: [x, y, theta, s, phi],
        parameters: [m = 1.0, inertia = 0.1, ms = 0.5, mp = 0.2],
        kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) + inertia/2*dot(theta)^2
            + ms/2*dot(s)^2 + mp/2*dot(phi)^2,
        constraints: [lever = (phi - 1)*(-sin(theta)*dot(x) + cos(theta)*dot(y)) + dot(s)],
        symmetry: se2(x, y, theta),
    }
}

/// At `theta = 0` the side velocity is `dot(y) = 0.4`, so
/// `dot(s) = -(phi - 1) 0.4 = 0.2`.
const Q0: [f64; 5] = [0.0, 0.0, 0.0, 0.0, 0.5];
const QDOT0: [f64; 5] = [1.0, 0.4, 0.5, 0.2, 0.7];

#[test]
fn the_compiled_momentum_form_stops_where_phi_crosses_1() {
    let blade = LeverBlade::default();
    let system = Momentum::constant(&blade, []);
    let x0: [f64; 9] = system.initial_state(&Q0, &QDOT0);
    let error = Simulation::new(Rk4)
        .span(0.0, 2.0)
        .run(&system, x0, &mut Table::new())
        .expect_err("the reconstruction degenerates at phi = 1");
    let SimulationError::Singular {
        t,
        quantity,
        state_names,
        state,
        ..
    } = error
    else {
        panic!("{error}");
    };
    assert_eq!(quantity, RECONSTRUCTION);
    assert!((t - 0.72).abs() < 1e-12, "{t}");
    assert_eq!(state_names[4], "phi");
    assert!((state[4] - (0.5 + 0.7 * 0.72)).abs() < 1e-12, "{state:?}");
    assert!(state.iter().all(|v| v.is_finite()));
}

fn simulate(formulation: &str, out: &std::path::Path) -> std::process::Output {
    let fixture = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/models/lever_blade.model"
    );
    let mut arguments = vec!["simulate", fixture, "--formulation", formulation];
    for initial in [
        "phi=0.5",
        "dot(x)=1",
        "dot(y)=0.4",
        "dot(theta)=0.5",
        "dot(s)=0.2",
        "dot(phi)=0.7",
    ] {
        arguments.extend(["--initial", initial]);
    }
    arguments.extend(["--t-end", "2", "--out", out.to_str().expect("path")]);
    chaplygin(&arguments)
}

#[test]
fn the_interpreted_momentum_form_stops_there_and_the_lagrange_form_runs_on() {
    let out = scratch("lever");
    let output = simulate("momentum", out.path());
    assert!(!output.status.success());
    let message = String::from_utf8_lossy(&output.stderr);
    assert_eq!(message.trim_end().lines().count(), 1, "{message}");
    for needle in [
        "singular configuration at t = 0.72",
        "momentum form's reconstruction",
        "phi = 1.004000",
    ] {
        assert!(message.contains(needle), "`{needle}` not in {message}");
    }
    let (_, rows) = read_csv(&out.path().join("trajectory.csv"));
    let last = rows.last().expect("the rows so far");
    assert!(last[0] < 0.72 && rows.len() > 50, "{last:?}");
    assert!(rows.iter().flatten().all(|v| v.is_finite()));
    let output = simulate("lagrange", out.path());
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}
