//! Car-like robots declared as their users write them
//! (`tests/models/car.model`, `ackermann_car.model`, `parallel_car.model`):
//! redundant contact rows dropped with a note, a body the contacts lock
//! said in words, degrees of freedom decided on the holonomic surface, and
//! runs from heading 0 and pi without a declared symmetry. The turning
//! radius is checked against the classical Ackermann geometry, and the
//! kinematic car's against `l / tan(phi)` with its steering angle
//! prescribed (`--prescribe`), the prescribed force's work against the
//! energy gained. A plan started from the pose alone completes its start
//! by the linkage.

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

/// The power balance a driven run's summary line reports.
fn power_balance(summary: &str) -> f64 {
    summary
        .split("power balance ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .unwrap_or_else(|| panic!("a power balance in {summary}"))
        .parse()
        .expect("a number")
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

/// The linkage ties the steer rates: from `cot(delta_r) = cot(delta_l) +
/// 2 b / l`, `dot(delta_r) = (sin(delta_r) / sin(delta_l))^2 dot(delta_l)`.
/// Given `dot(delta_l)` alone, the run starts at that `dot(delta_r)`;
/// given neither, it fails in one line asking for one of the two.
#[test]
fn one_steer_rate_gives_the_other_by_the_linkage() {
    let start = [
        "--t-end",
        "0.01",
        "--formulation",
        "lagrange",
        "--initial",
        "delta_l=0.3",
        "--initial",
        "dot(x)=1",
    ];
    let given = [&start[..], &["--initial", "dot(delta_l)=0.2"]].concat();
    let (_, (header, rows)) = simulated("ackermann_car", &given);
    let right = column(&header, &rows, "delta_r")[0];
    let rate = column(&header, &rows, "dot(delta_r)")[0];
    let linkage = (right.sin() / 0.3f64.sin()).powi(2) * 0.2;
    assert!((rate - linkage).abs() < 1e-12, "{rate} vs {linkage}");

    let path = model("ackermann_car");
    let output = chaplygin(&[&["simulate", path.as_str()], &start[..]].concat());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && stderr.lines().count() == 1,
        "{stderr}"
    );
    let asked = "leave 1 direction free among dot(delta_l), dot(delta_r), which the \
                 constraints tie: give 1 of them too";
    assert!(stderr.contains(asked), "{stderr}");
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
    let balance = power_balance(&summary);
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

/// A plan from the pose and the left front wheel's angle alone: the start
/// is held to the constraints, so the linkage sets the right wheel's
/// angle, `cot(delta_r) = cot(delta_l) + 2 b / l`, and the wheels' angles
/// and rates meet the rolling constraints at the first node.
#[test]
fn the_ackermann_cars_plan_completes_its_start_by_the_linkage() {
    let out = tempfile::tempdir().expect("a temporary directory");
    let directory = out.path().to_str().expect("a path");
    let path = model("ackermann_car");
    let at_rest = [
        "--start",
        "dot(x)=0",
        "--start",
        "dot(y)=0",
        "--start",
        "dot(theta)=0",
    ];
    let stopped = [
        "--goal",
        "dot(x)=0",
        "--goal",
        "dot(y)=0",
        "--goal",
        "dot(theta)=0",
    ];
    let pose = ["--start", "x=0", "--start", "y=0", "--start", "theta=0"];
    let all = [
        &["plan", path.as_str(), "--duration", "2", "--nodes", "11"][..],
        &pose,
        &["--start", "delta_l=0.2"],
        &at_rest,
        &["--goal", "x=0.5"],
        &stopped,
        &["--out", directory],
    ]
    .concat();
    let output = chaplygin(&all);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let (header, rows) = read_csv(&out.path().join("plan.csv"));
    let first = |name: &str| column(&header, &rows, name)[0];
    let (l, b) = (1.0, 0.4);
    let right = (1.0 / (1.0 / 0.2f64.tan() + 2.0 * b / l)).atan();
    assert!(
        (first("delta_r") - right).abs() < 1e-9,
        "{}",
        first("delta_r")
    );
    assert!(first("constraint_residual") < 1e-12);
    assert!(first("holonomic_residual") < 1e-12);
    let last = |name: &str| column(&header, &rows, name).last().copied().expect("rows");
    assert!((last("x") - 0.5).abs() < 1e-9);
}

/// Murray and Sastry's kinematic car: drive and steer reach every
/// direction by the second bracket, growth vector (2, 3, 4).
#[test]
fn the_kinematic_cars_growth_vector_is_2_3_4() {
    let constraints = analysis("kinematic_car");
    assert_eq!(constraints["growth_vector"], serde_json::json!([2, 3, 4]));
    assert_eq!(constraints["classification"], "completely nonholonomic");
}

/// The rear wheels' rolling rows differ by the differential of
/// `2 b theta + r phi_rl - r phi_rr` (by hand: the rows are
/// `cos(theta) xdot + sin(theta) ydot -+ b thetadot - r phidot`): derive
/// names that integral, its growth stops at 7 = n - h - 1, and a turning
/// run keeps the function constant, computed from the trajectory.
#[test]
fn the_rear_differentials_integral_is_named_and_kept() {
    let constraints = analysis("ackermann_car");
    assert_eq!(
        constraints["growth_vector"],
        serde_json::json!([2, 3, 5, 7])
    );
    let integrals = constraints["integrals"].as_array().expect("a list");
    let [integral] = &integrals[..] else {
        panic!("one integral: {integrals:?}")
    };
    let rows: Vec<(&str, &str)> = (integral["rows"].as_array().expect("rows").iter())
        .map(|row| {
            (
                row["constraint"].as_str().unwrap(),
                row["coefficient"].as_str().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        rows,
        [("rear_left_roll_1", "1"), ("rear_right_roll_1", "-1")]
    );
    assert!(integral["function"].is_string(), "{integral}");
    let (_, (header, rows)) = simulated(
        "ackermann_car",
        &[
            "--formulation",
            "lagrange",
            "--t-end",
            "2",
            "--input",
            "drive=1",
            "--input",
            "steer_left=-50*(delta_l-0.3)-5*dot(delta_l)",
            "--initial",
            "dot(delta_l)=0",
            "--initial",
            "dot(phi_rl)=2",
        ],
    );
    let value = |name: &str| column(&header, &rows, name);
    let (b, r) = (0.4, 0.15);
    let (theta, left, right) = (value("theta"), value("phi_rl"), value("phi_rr"));
    let integral: Vec<f64> = (0..rows.len())
        .map(|i| -(2.0 * b * theta[i] + r * left[i] - r * right[i]))
        .collect();
    assert!(theta.last().unwrap().abs() > 0.1, "the car turns");
    for (i, value) in integral.iter().enumerate() {
        assert!((value - integral[0]).abs() < 1e-9, "row {i}: {value}");
    }
}

/// The circumradius `abc / (4 area)` of three points.
fn circumradius([a, b, c]: [(f64, f64); 3]) -> f64 {
    let side = |p: (f64, f64), q: (f64, f64)| (p.0 - q.0).hypot(p.1 - q.1);
    let area = ((b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1)).abs() / 2.0;
    side(a, b) * side(b, c) * side(c, a) / (4.0 * area)
}

/// Steered by `--prescribe phi=0.3`, the kinematic car's rear axle's
/// midpoint runs on a circle of radius `l / tan(0.3)` (Murray and Sastry's
/// `theta' = v tan(phi) / l` at speed `v`): the circumradius of any three
/// rows of its path. Holding a constant angle takes no force, since no
/// constraint row has a `dot(phi)` term.
#[test]
fn the_kinematic_car_steered_at_a_constant_angle_runs_on_a_circle() {
    let arguments = [
        "--prescribe",
        "phi=0.3",
        "--initial",
        "dot(x)=1",
        "--t-end",
        "10",
    ];
    let (summary, (header, rows)) = simulated("kinematic_car", &arguments);
    assert!(power_balance(&summary) < 1e-7, "{summary}");
    let value = |name: &str| column(&header, &rows, name);
    let (x, y) = (value("x"), value("y"));
    let radius = 1.0 / 0.3f64.tan();
    let third = rows.len() / 3;
    for i in (0..third).step_by(50) {
        let points = [i, i + third, i + 2 * third].map(|j| (x[j], y[j]));
        let fitted = circumradius(points);
        assert!(
            (fitted - radius).abs() < 1e-6,
            "rows from {i}: {fitted} against {radius}"
        );
    }
    assert!(value("phi").iter().all(|phi| (phi - 0.3).abs() < 1e-9));
    assert!(value("force(phi)").iter().all(|force| force.abs() < 1e-12));
}

/// A steering angle that varies, `phi = 0.2 sin t`, in the reduced form
/// and the Lagrange-d'Alembert form: the angle and its rate follow the law
/// and its derivative, and the force is the steering row's
/// `js phi'' = force(phi)` (no constraint row has a `dot(phi)` term).
#[test]
fn a_prescribed_steering_angle_follows_its_law() {
    for formulation in ["reduced", "lagrange"] {
        let arguments = [
            "--prescribe",
            "phi=0.2*sin(t)",
            "--initial",
            "dot(x)=1",
            "--t-end",
            "5",
            "--formulation",
            formulation,
        ];
        let (_, (header, rows)) = simulated("kinematic_car", &arguments);
        let value = |name: &str| column(&header, &rows, name);
        let (t, phi, force) = (value("t"), value("phi"), value("force(phi)"));
        let js = 0.01;
        for i in 0..rows.len() {
            let law = 0.2 * t[i].sin();
            assert!(
                (phi[i] - law).abs() < 1e-8,
                "{formulation} at t = {}: {}",
                t[i],
                phi[i]
            );
            assert!(
                (force[i] + js * law).abs() < 1e-9,
                "{formulation} at t = {}",
                t[i]
            );
        }
        if formulation == "lagrange" {
            let rate = value("dot(phi)");
            let off =
                (0..rows.len()).fold(0.0f64, |m, i| m.max((rate[i] - 0.2 * t[i].cos()).abs()));
            assert!(off < 1e-8, "dot(phi) off by {off}");
        }
    }
}

/// The prescribed force's work is the energy gained: Simpson's rule on
/// `force(phi) dot(phi)` from the trajectory, against the energy column
/// and the closed form `js (dot(phi)(T)^2 - dot(phi)(0)^2) / 2`; the
/// summary reports the power balance.
#[test]
fn the_prescribed_forces_work_is_the_energy_gained() {
    let arguments = [
        "--prescribe",
        "phi=0.5*sin(2*t)",
        "--param",
        "js=0.5",
        "--initial",
        "dot(x)=1",
        "--formulation",
        "lagrange",
        "--t-end",
        "1",
        "--dt",
        "0.005",
    ];
    let (summary, (header, rows)) = simulated("kinematic_car", &arguments);
    let balance = power_balance(&summary);
    assert!(balance < 1e-7, "{summary}");
    let value = |name: &str| column(&header, &rows, name);
    let (energy, force, rate) = (value("energy"), value("force(phi)"), value("dot(phi)"));
    let power: Vec<f64> = force.iter().zip(&rate).map(|(f, v)| f * v).collect();
    let h = 0.005;
    let pairs = (power.len() - 1) / 2;
    let work: f64 = (0..pairs)
        .map(|i| h / 3.0 * (power[2 * i] + 4.0 * power[2 * i + 1] + power[2 * i + 2]))
        .sum();
    let end = 2 * pairs;
    let gained = energy[end] - energy[0];
    let closed = 0.5 / 2.0 * (rate[end].powi(2) - 1.0);
    assert!(gained.abs() > 0.1, "{gained}");
    assert!(
        (gained - work).abs() < 1e-8 * gained.abs(),
        "{gained} against {work}"
    );
    assert!((gained - closed).abs() < 1e-9, "{gained} against {closed}");
}

/// The snakeboard's wheel angle prescribed, `phi = 0.3 sin t`, in each
/// formulation: the momentum form takes it as a shape coordinate, and the
/// three agree on where the board goes; a group coordinate is refused
/// there.
#[test]
fn every_formulation_follows_a_prescribed_shape_coordinate() {
    let run = |formulation: &str, law: &str, free: &str| {
        let out = tempfile::tempdir().expect("a temporary directory");
        let directory = out.path().to_str().expect("a path");
        let arguments = [
            "simulate",
            "snakeboard",
            "--prescribe",
            law,
            "--initial",
            free,
            "--initial",
            "dot(psi)=0",
            "--t-end",
            "3",
            "--formulation",
            formulation,
            "--out",
            directory,
        ];
        let output = chaplygin(&arguments);
        let stderr = String::from_utf8_lossy(&output.stderr).to_string();
        let csv = output
            .status
            .success()
            .then(|| read_csv(&out.path().join("trajectory.csv")));
        (csv, stderr)
    };
    let mut ends = Vec::new();
    for formulation in ["reduced", "lagrange", "momentum"] {
        let (csv, stderr) = run(formulation, "phi=0.3*sin(t)", "dot(x)=1");
        let (header, rows) = csv.unwrap_or_else(|| panic!("{formulation}: {stderr}"));
        let value = |name: &str| column(&header, &rows, name);
        let (t, phi) = (value("t"), value("phi"));
        for (t, phi) in t.iter().zip(&phi) {
            assert!(
                (phi - 0.3 * t.sin()).abs() < 1e-8,
                "{formulation} at t = {t}: {phi}"
            );
        }
        ends.push([value("x"), value("y")].map(|v| *v.last().expect("rows")));
    }
    for end in &ends[1..] {
        let apart = (end[0] - ends[0][0]).hypot(end[1] - ends[0][1]);
        assert!(apart < 1e-6, "{ends:?}");
    }
    let (_, stderr) = run("momentum", "x=0.1*t", "dot(phi)=0");
    assert!(
        stderr
            .contains("--prescribe x: the momentum formulation prescribes shape coordinates only"),
        "{stderr}"
    );
}

/// What `--prescribe` refuses, each in one line naming the coordinate.
#[test]
fn prescriptions_that_cannot_be_followed_are_refused_in_one_line() {
    let path = model("kinematic_car");
    let pinned = tempfile::tempdir().expect("a temporary directory");
    let pinned_model = pinned.path().join("pinned.model");
    std::fs::write(
        &pinned_model,
        "pub struct Pinned {\n    coordinates: [x, y],\n    parameters: [m = 1.0],\n    \
         kinetic_energy: m/2*(dot(x)^2 + dot(y)^2),\n    constraints: [pin = dot(y)],\n}\n",
    )
    .expect("the model is written");
    let pinned_model = pinned_model.to_str().expect("a path");
    let cases: [(&str, &[&str], &str); 9] = [
        (
            &path,
            &["--prescribe", "w=0.3"],
            "--prescribe w: `w` is not a coordinate (coordinates: x, y, theta, phi)",
        ),
        (
            &path,
            &["--prescribe", "l=0.3"],
            "--prescribe l: `l` is a parameter, not a coordinate",
        ),
        (
            &path,
            &["--prescribe", "phi=0.3", "--prescribe", "phi=0.1"],
            "--prescribe phi: given twice",
        ),
        (
            &path,
            &["--prescribe", "phi=0.1*x"],
            "--prescribe phi=0.1*x: the law reads the state",
        ),
        (
            &path,
            &["--prescribe", "phi=dot(theta)"],
            "--prescribe phi=dot(theta): the law reads the state",
        ),
        (
            &path,
            &["--prescribe", "phi=0.3", "--initial", "dot(phi)=0"],
            "--prescribe phi: --initial gives dot(phi) too",
        ),
        (
            &path,
            &["--prescribe", "phi=ln(t)"],
            "--prescribe phi=ln(t): the law or its rate is not finite at t = 0",
        ),
        (
            &path,
            &["--prescribe", "phi=0.3", "--input", "force(phi)=1"],
            "unknown input `force(phi)` (inputs: steer)",
        ),
        (
            pinned_model,
            &["--prescribe", "y=0.3"],
            "--prescribe y: the constraints fix y: no force along it moves it",
        ),
    ];
    for (model, arguments, says) in cases {
        let all = [
            &["simulate", model, "--initial", "dot(x)=1", "--t-end", "1"],
            arguments,
        ]
        .concat();
        let output = chaplygin(&all);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{arguments:?} ran");
        assert!(stderr.contains(says), "{arguments:?}: {stderr}");
        assert_eq!(
            stderr.trim_end().lines().count(),
            1,
            "{arguments:?}: {stderr}"
        );
    }
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
