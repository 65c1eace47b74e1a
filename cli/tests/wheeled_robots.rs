//! Car-like robots declared as their users write them
//! (`tests/models/car.model`, `ackermann_car.model`, `parallel_car.model`):
//! redundant contact rows dropped with a note, a body the contacts lock
//! said in words, degrees of freedom decided on the holonomic surface, and
//! runs from heading 0 and pi without a declared symmetry. The turning
//! radius is checked against the classical Ackermann geometry.

use crate::support::{chaplygin, column, read_csv};
use serde_json::Value;

fn model(name: &str) -> String {
    format!(
        "{}/../tests/models/{name}.model",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// The `constraints` section of `derive MODEL --format json`.
fn analysis(name: &str) -> Value {
    let output = chaplygin(&["derive", &model(name), "--format", "json"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let json: Value = serde_json::from_slice(&output.stdout).expect("the JSON parses");
    json["constraints"].clone()
}

/// The dropped rows as `(name, where)`.
fn dropped(constraints: &Value) -> Vec<(String, String)> {
    let rows = constraints["redundant_rows"].as_array().expect("a list");
    let text = |row: &Value, key: &str| row[key].as_str().expect("a string").to_string();
    rows.iter()
        .map(|row| (text(row, "constraint"), text(row, "where")))
        .collect()
}

/// A run of the car `name` with `arguments`: its summary line and its
/// trajectory's header and rows.
fn simulated(name: &str, arguments: &[&str]) -> (String, (Vec<String>, Vec<Vec<f64>>)) {
    let out = tempfile::tempdir().expect("a temporary directory");
    let directory = out.path().to_str().expect("a path");
    let path = model(name);
    let all = [
        &["simulate", path.as_str()],
        arguments,
        &["--out", directory],
    ]
    .concat();
    let output = chaplygin(&all);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{name} {arguments:?}: {stderr}");
    let summary = String::from_utf8_lossy(&output.stdout).to_string();
    (summary, read_csv(&out.path().join("trajectory.csv")))
}

fn names(value: &Value) -> Vec<&str> {
    let list = value.as_array().expect("a list");
    list.iter()
        .map(|name| name.as_str().expect("a name"))
        .collect()
}

#[test]
fn a_car_with_both_rear_lateral_rows_derives_naming_the_dropped_row() {
    let constraints = analysis("car");
    let everywhere = "everywhere".to_string();
    assert_eq!(
        dropped(&constraints),
        [("rear_right_roll_2".to_string(), everywhere)]
    );
    let output = chaplygin(&["derive", &model("car")]);
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        text.contains("redundant contact rows dropped: rear_right_roll_2 (implied by the rows before it everywhere)"),
        "{text}"
    );
}

#[test]
fn the_parallel_steered_car_is_reported_unable_to_move() {
    let constraints = analysis("parallel_car");
    assert_eq!(constraints["degrees_of_freedom"], 1);
    let locked = &constraints["locked_bodies"];
    assert_eq!(
        names(&locked["bodies"]),
        ["chassis", "rear_left", "rear_right"]
    );
    assert_eq!(names(&locked["moving_coordinates"]), ["delta"]);
    let output = chaplygin(&["derive", &model("parallel_car")]);
    let text = String::from_utf8_lossy(&output.stdout);
    let line = "bodies unable to move: chassis, rear_left, rear_right (every allowed velocity \
                moves only delta)";
    assert!(text.contains(line), "{text}");
}

/// With independent steering the chassis is locked too until the two
/// front axles meet the rear axle's line at one point, which only the
/// Ackermann linkage makes hold everywhere.
#[test]
fn the_ackermann_car_with_every_row_has_two_degrees_of_freedom() {
    let constraints = analysis("ackermann_car");
    assert_eq!(constraints["degrees_of_freedom"], 2);
    let surface = "on the surface of the holonomic constraints".to_string();
    assert_eq!(
        dropped(&constraints),
        [
            ("rear_right_roll_2".to_string(), "everywhere".to_string()),
            ("front_right_roll_2".to_string(), surface),
        ]
    );
    assert_eq!(
        names(&constraints["locked_bodies"]["bodies"]),
        Vec::<&str>::new()
    );
    // Nine coordinates, the linkage, and the rear differential's integral
    // r (phi_rr - phi_rl) = 2 b theta + const leave seven reachable.
    assert_eq!(constraints["reachable_dimension"], 7);
    let unlinked = analysis("car");
    assert_eq!(
        names(&unlinked["locked_bodies"]["bodies"]),
        ["chassis", "rear_left", "rear_right"]
    );
}

/// The reduced form without a declared symmetry runs from heading 0 and
/// pi (where a chart's elimination in order meets a zero pivot although
/// its minor is regular), and keeps the constraints and the linkage.
#[test]
fn the_ackermann_car_runs_from_heading_zero_and_pi() {
    for heading in ["0", "3.141592653589793"] {
        let initial = format!("theta={heading}");
        let arguments = ["--t-end", "2", "--input", "drive=1", "--initial", &initial];
        let (_, (header, rows)) = simulated("ackermann_car", &arguments);
        let distance = column(&header, &rows, "x").last().copied().expect("rows");
        let theta0: f64 = heading.parse().expect("a number");
        assert!(
            distance * theta0.cos() > 0.05,
            "heading {heading}: x = {distance}"
        );
        let largest = |name: &str| {
            column(&header, &rows, name)
                .iter()
                .fold(0.0f64, |m, v| m.max(v.abs()))
        };
        assert!(largest("constraint_residual") < 1e-12);
        assert!(largest("holonomic_residual") < 1e-12);
    }
}

/// The rear axle's midpoint turns on the radius of the Ackermann geometry:
/// `tan(delta_l) = l / (R - b)` for the inner wheel, and
/// `R = l (cot(delta_l) + cot(delta_r)) / 2` from both.
#[test]
fn the_ackermann_car_turns_on_the_geometrys_radius() {
    let (_, (header, rows)) = simulated(
        "ackermann_car",
        &[
            "--formulation",
            "lagrange",
            "--t-end",
            "1",
            "--input",
            "drive=1",
            "--input",
            "steer_left=-50*(delta_l-0.3)-5*dot(delta_l)",
            "--initial",
            "delta_l=0.3",
            "--initial",
            "dot(delta_l)=0",
            "--initial",
            "dot(phi_rl)=2",
        ],
    );
    let value = |name: &str| column(&header, &rows, name);
    let (l, b) = (1.0, 0.4);
    let (dx, dy, dtheta) = (value("dot(x)"), value("dot(y)"), value("dot(theta)"));
    let (left, right) = (value("delta_l"), value("delta_r"));
    for i in 0..rows.len() {
        let radius = dx[i].hypot(dy[i]) / dtheta[i];
        let inner = l / left[i].tan() + b;
        let both = l * (1.0 / left[i].tan() + 1.0 / right[i].tan()) / 2.0;
        assert!(
            (radius / inner - 1.0).abs() < 1e-9,
            "row {i}: {radius} against {inner}"
        );
        assert!(
            (radius / both - 1.0).abs() < 1e-9,
            "row {i}: {radius} against {both}"
        );
    }
}

/// The drive torque's work equals the energy gained: the test integrates
/// the power `u (dot(phi_rl) + dot(phi_rr))` of the trajectory by Simpson's
/// rule, and the summary reports the run's own power balance instead of
/// an energy drift.
#[test]
fn the_drive_torques_work_is_the_energy_gained() {
    let (summary, (header, rows)) = simulated(
        "ackermann_car",
        &[
            "--formulation",
            "lagrange",
            "--t-end",
            "1",
            "--dt",
            "0.005",
            "--input",
            "drive=2",
            "--initial",
            "delta_l=0.2",
            "--initial",
            "dot(delta_l)=0",
            "--initial",
            "dot(phi_rl)=0",
        ],
    );
    let balance: f64 = summary
        .split("power balance ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .unwrap_or_else(|| panic!("a power balance in {summary}"))
        .parse()
        .expect("a number");
    assert!(balance < 1e-7, "{summary}");
    let value = |name: &str| column(&header, &rows, name);
    let (energy, left, right) = (value("energy"), value("dot(phi_rl)"), value("dot(phi_rr)"));
    let power: Vec<f64> = left
        .iter()
        .zip(&right)
        .map(|(l, r)| 2.0 * (l + r))
        .collect();
    let h = 0.005;
    let pairs = (power.len() - 1) / 2;
    let work: f64 = (0..pairs)
        .map(|i| h / 3.0 * (power[2 * i] + 4.0 * power[2 * i + 1] + power[2 * i + 2]))
        .sum();
    let gained = energy[2 * pairs] - energy[0];
    assert!(gained > 1.0, "{gained}");
    assert!(
        (gained - work).abs() < 1e-8 * gained,
        "{gained} against {work}"
    );
}

/// Murray and Sastry's kinematic car: drive and steer reach every
/// direction by the second bracket, growth vector (2, 3, 4).
#[test]
fn the_kinematic_cars_growth_vector_is_2_3_4() {
    let constraints = analysis("kinematic_car");
    assert_eq!(constraints["growth_vector"], serde_json::json!([2, 3, 4]));
    assert_eq!(constraints["classification"], "completely nonholonomic");
}

/// With its linkage the car reaches every configuration of the surface
/// but the rear differential's integral: nonholonomic, not completely,
/// at 7 = n - h - 1; the Chaplygin ball, with its unit-norm constraint,
/// reaches `n - h` and is completely nonholonomic there.
#[test]
fn completeness_is_judged_on_the_holonomic_surface() {
    assert_eq!(analysis("ackermann_car")["classification"], "nonholonomic");
    let ball = chaplygin(&[
        "derive",
        "--format",
        "json",
        &format!(
            "{}/../models/chaplygin_ball.model",
            env!("CARGO_MANIFEST_DIR")
        ),
    ]);
    assert!(
        ball.status.success(),
        "{}",
        String::from_utf8_lossy(&ball.stderr)
    );
    let json: Value = serde_json::from_slice(&ball.stdout).expect("the JSON parses");
    assert_eq!(json["constraints"]["reachable_dimension"], 5);
    assert_eq!(
        json["constraints"]["classification"],
        "completely nonholonomic"
    );
}

/// The linkage solved for the right wheel's angle by `atan` is the same
/// surface: the same rows are dropped, and the car turns as the geometry
/// says.
#[test]
fn the_linkage_written_with_atan_is_the_same_car() {
    let constraints = analysis("ackermann_car_atan");
    assert_eq!(constraints["degrees_of_freedom"], 2);
    assert_eq!(dropped(&constraints), dropped(&analysis("ackermann_car")));
}
