//! Singularities of the coordinates (docs/INTERFACE.md section 4): `derive`
//! warns where the mass matrix loses rank. The truths are the textbook
//! kinematics of Euler angles: the rates of z-x-z angles give the angular
//! velocity through a matrix of determinant `-sin(theta)` (Goldstein,
//! *Classical Mechanics*, eq. 4.125), and the rolling disk's z-x-y angles
//! (heading, lean, spin) lose one where the spin axis `(0, cos(phi),
//! sin(phi))` meets the heading axis `z`, at `cos(phi) = 0`. Euler
//! parameters, planar headings and a constant mass matrix have no such set.

use crate::support::in_process::Model;
use crate::support::{chaplygin, scratch};
use serde_json::Value;

/// The models' directory.
const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

/// `derive PATH --format json`'s `constraints.coordinate_singularities`,
/// and `derive PATH`'s text.
fn singularities(path: &str) -> (Value, String) {
    let json = chaplygin(&["derive", path, "--format", "json"]);
    assert!(
        json.status.success(),
        "{}",
        String::from_utf8_lossy(&json.stderr)
    );
    let document: Value = serde_json::from_slice(&json.stdout).expect("json");
    let text = chaplygin(&["derive", path]);
    assert!(
        text.status.success(),
        "{}",
        String::from_utf8_lossy(&text.stderr)
    );
    (
        document["constraints"]["coordinate_singularities"].clone(),
        String::from_utf8_lossy(&text.stdout).into_owned(),
    )
}

/// The warning `derive` prints for `set` of `coordinate`.
fn warning(set: &str, coordinate: &str) -> String {
    format!(
        "mass matrix loses rank where {set} (coordinates {coordinate}): a singularity of the \
         coordinates, not of the mechanics; orient(...) frames have none"
    )
}

/// Asserts `derive` warns of `model`'s one set `set` of `coordinate`, in
/// the JSON and twice in the text (the document's fact and `REPORT`).
fn assert_warned(model: &str, set: &str, coordinate: &str) {
    let (sets, text) = singularities(&format!("{ROOT}/{model}"));
    assert_eq!(
        sets,
        serde_json::json!([{"coordinates": [coordinate], "set": set}])
    );
    assert_eq!(text.matches(&warning(set, coordinate)).count(), 2, "{text}");
}

#[test]
fn the_zxz_ball_is_warned_where_sin_theta_vanishes() {
    assert_warned(
        "tests/models/chaplygin_ball_zxz.model",
        "sin(theta) = 0",
        "theta",
    );
}

#[test]
fn the_rolling_disk_is_warned_where_it_lies_flat() {
    assert_warned("models/rolling_disk_3d.model", "cos(phi) = 0", "phi");
}

#[test]
fn euler_parameters_and_planar_headings_get_no_warning() {
    for model in [
        "models/chaplygin_ball.model",
        "models/snakeboard.model",
        "models/sleigh.model",
    ] {
        let (sets, text) = singularities(&format!("{ROOT}/{model}"));
        assert_eq!(sets, serde_json::json!([]), "{model}");
        assert!(!text.contains("mass matrix loses rank"), "{model}: {text}");
        assert!(text.contains("coordinate singularities: none"), "{model}");
    }
}

#[test]
fn a_constant_mass_matrix_gets_no_warning() {
    let directory = scratch("coordinate-singularities-constant");
    let path = directory.path().join("free.model");
    let model = "pub struct Free {\n    coordinates: [x, y, theta],\n    \
                 parameters: [m = 2.0, inertia = 0.3],\n    \
                 kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) + inertia/2*dot(theta)^2,\n}\n";
    std::fs::write(&path, model).expect("written");
    let (sets, text) = singularities(path.to_str().expect("path"));
    assert_eq!(sets, serde_json::json!([]));
    assert!(!text.contains("mass matrix loses rank"), "{text}");
}

/// `simulate` of the z-x-z ball with `arguments`: its status and the
/// lines of its standard error.
fn simulate_zxz(name: &str, arguments: &[&str]) -> (bool, Vec<String>) {
    let out = scratch(&format!("coordinate-singularities-{name}"));
    let model = format!("{ROOT}/tests/models/chaplygin_ball_zxz.model");
    let mut all = vec!["simulate", model.as_str()];
    all.extend(arguments);
    all.extend(["--out", out.path().to_str().expect("path")]);
    let output = chaplygin(&all);
    let stderr = String::from_utf8_lossy(&output.stderr);
    (
        output.status.success(),
        stderr.lines().map(str::to_string).collect(),
    )
}

/// The guard a run of the z-x-z ball stops on.
const THETA_GUARD: &str = "the coordinates theta: sin(theta) must not vanish (the mass matrix \
                           loses rank there, a singularity of the coordinates); turn the frame \
                           with orient(...) instead";

#[test]
fn a_run_from_gimbal_lock_is_refused_in_one_line() {
    let (success, lines) = simulate_zxz("start", &[]);
    assert!(!success);
    let [line] = &lines[..] else {
        panic!("one line: {lines:?}");
    };
    assert!(line.contains("at the initial state"), "{line}");
    assert!(line.contains(THETA_GUARD), "{line}");
    assert!(!line.contains("NaN") && !line.contains("inf"), "{line}");
}

/// Turning about the nutation axis from `theta = 0.3` back to `theta = 0`.
#[test]
fn a_run_that_reaches_gimbal_lock_stops_naming_it() {
    let (success, lines) = simulate_zxz(
        "reach",
        &[
            "--initial",
            "theta=0.3",
            "--initial",
            "omega(ball)=[-1,0,0]",
        ],
    );
    assert!(!success);
    let [line] = &lines[..] else {
        panic!("one line: {lines:?}");
    };
    assert!(line.contains("in the step from t = 0.29"), "{line}");
    assert!(line.contains(THETA_GUARD), "{line}");
    assert!(
        !line.contains("NaN") && !line.contains("constraint rows"),
        "{line}"
    );
}

/// The z-x-z ball's kinetic energy at `q = (x, y, psi, theta, phi)` moving
/// with `qdot`: `m/2 (xdot^2 + ydot^2) + 1/2 omega . I omega` (the centre
/// at height `r` over the contact), with the body-axes angular velocity of
/// the z-x-z angles (Goldstein, eq. 4.125, precession `psi`, spin `phi`)
/// `omega = (psidot sin(theta) sin(phi) + thetadot cos(phi),
/// psidot sin(theta) cos(phi) - thetadot sin(phi), psidot cos(theta) + phidot)`
/// and the model's `m = 1`, `I = diag(0.08, 0.1, 0.12)`.
fn ball_kinetic_energy(q: &[f64], qdot: &[f64]) -> f64 {
    let (theta, phi) = (q[3], q[4]);
    let [xdot, ydot, psidot, thetadot, phidot] = [0, 1, 2, 3, 4].map(|i| qdot[i]);
    let omega = [
        psidot * theta.sin() * phi.sin() + thetadot * phi.cos(),
        psidot * theta.sin() * phi.cos() - thetadot * phi.sin(),
        psidot * theta.cos() + phidot,
    ];
    let spin: f64 = (0..3)
        .map(|i| [0.08, 0.1, 0.12][i] * omega[i] * omega[i])
        .sum();
    0.5 * (xdot * xdot + ydot * ydot) + 0.5 * spin
}

/// `steps A accepted, R rejected, K Newton iterations` of a summary line.
fn effort(summary: &str) -> [usize; 3] {
    let after = summary
        .split("; steps ")
        .nth(1)
        .unwrap_or_else(|| panic!("the steps in {summary}"));
    let words: Vec<&str> = after.split([' ', ',', ';']).collect();
    [0, 3, 6].map(|i| words[i].parse().unwrap_or_else(|_| panic!("{summary}")))
}

/// A generic spin whose nutation dips to `theta = 0.0086` near `t = 13.75`
/// (the angles' rates `psidot`, `phidot` near 70 rad/s there, against 5
/// elsewhere), and one that keeps `theta` above 0.18.
const THROUGH_THE_DIP: [&str; 4] = [
    "--initial",
    "theta=0.05",
    "--initial",
    "omega(ball)=[0.5,0.3,5]",
];
const AWAY_FROM_IT: [&str; 4] = [
    "--initial",
    "theta=0.3",
    "--initial",
    "omega(ball)=[0.3,0.2,5]",
];

/// Through the dip every integrator keeps the kinetic energy (computed
/// here from each row's configuration and velocity) to 1e-6, in steps and
/// Newton iterations at most twice those of the spin away from it (1.07
/// to 1.54 times, measured), rejecting at most one trial in twenty (1.4%
/// with rk4): the time such a run takes is its steps', not a stall's.
#[test]
fn a_spin_past_gimbal_lock_keeps_its_kinetic_energy_in_proportionate_steps() {
    let model = Model::load(
        &format!("{ROOT}/tests/models/chaplygin_ball_zxz.model"),
        "jit",
    );
    for integrator in ["rk4", "dopri5", "midpoint", "discrete-gradient"] {
        let run = |start: &[&str]| {
            let mut options = vec!["--integrator", integrator, "--t-end", "15", "--dt", "0.01"];
            options.extend(start);
            let run = model.simulate(&options).expect("a run");
            let summary = run.outcome.clone().expect("to the end");
            let states = model.configurations_velocities(&options, 5, &run.rows);
            (run, effort(&summary), states)
        };
        let (dip, through, states) = run(&THROUGH_THE_DIP);
        let lowest = dip
            .column("theta")
            .iter()
            .fold(f64::INFINITY, |m, t| m.min(t.abs()));
        assert!(lowest < 0.01, "{integrator}: theta down to {lowest}");
        let energies: Vec<f64> = (states.iter())
            .map(|(q, qdot)| ball_kinetic_energy(q, qdot))
            .collect();
        let drift = energies
            .iter()
            .fold(0.0_f64, |m, e| m.max((e - energies[0]).abs()));
        assert!(
            drift <= 1e-6 * energies[0],
            "{integrator}: {drift:e} of {}",
            energies[0]
        );
        let (_, away, _) = run(&AWAY_FROM_IT);
        let [accepted, rejected, iterations] = through;
        assert!(
            accepted <= 2 * away[0],
            "{integrator}: {through:?} against {away:?}"
        );
        assert!(
            iterations <= 2 * away[2],
            "{integrator}: {through:?} against {away:?}"
        );
        assert!(
            20 * rejected <= accepted + rejected,
            "{integrator}: {through:?}"
        );
    }
}

/// A fixed-step run takes exactly its steps, none rejected, and RK4 no
/// Newton iteration; the midpoint rule at least one per step.
#[test]
fn a_fixed_step_run_reports_exactly_its_steps() {
    let model = Model::load(
        &format!("{ROOT}/tests/models/chaplygin_ball_zxz.model"),
        "jit",
    );
    let fixed = |integrator: &str| {
        let mut options = vec![
            "--fixed-step",
            "--integrator",
            integrator,
            "--t-end",
            "2",
            "--dt",
            "0.01",
        ];
        options.extend(AWAY_FROM_IT);
        let run = model.simulate(&options).expect("a run");
        effort(&run.outcome.expect("to the end"))
    };
    assert_eq!(fixed("rk4"), [200, 0, 0]);
    let [accepted, rejected, iterations] = fixed("midpoint");
    assert_eq!([accepted, rejected], [200, 0]);
    assert!(iterations >= accepted, "{iterations}");
}
