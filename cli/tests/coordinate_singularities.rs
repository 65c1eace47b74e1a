//! Singularities of the coordinates (docs/INTERFACE.md section 4): `derive`
//! warns where the mass matrix loses rank. The truths are the textbook
//! kinematics of Euler angles: the rates of z-x-z angles give the angular
//! velocity through a matrix of determinant `-sin(theta)` (Goldstein,
//! *Classical Mechanics*, eq. 4.125), and the rolling disk's z-x-y angles
//! (heading, lean, spin) lose one where the spin axis `(0, cos(phi),
//! sin(phi))` meets the heading axis `z`, at `cos(phi) = 0`. Euler
//! parameters, planar headings and a constant mass matrix have no such set.

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
