//! `chaplygin plan` (docs/INTERFACE.md section 13) run as a command: a
//! point mass moved between rests, whose optimal cost `12 m^2 / T^3` is
//! known in closed form, over a given or a free duration, to a hard or a
//! soft goal, and restarted from its own `plan.csv`; `plan.csv` with
//! `trajectory.csv`'s columns; and bad requests refused in one line.

use crate::support::{chaplygin, column, read_csv, scratch};
use std::path::Path;
use std::process::Output;

/// `m xddot = push`.
const POINT_MASS: &str = "pub struct PointMass {
    coordinates: [x],
    parameters: [m = 2.0],
    kinetic_energy: m/2*dot(x)^2,
    inputs: [push = x],
}";

/// `chaplygin` with `arguments` on the point mass, written into `dir`.
fn run(dir: &Path, command: &str, arguments: &[&str]) -> Output {
    let model = dir.join("point_mass.model");
    std::fs::write(&model, POINT_MASS).expect("the model is written");
    let out = dir.join(command);
    let mut all = vec![
        command,
        model.to_str().expect("UTF-8"),
        "--out",
        out.to_str().expect("UTF-8"),
    ];
    all.extend(arguments);
    chaplygin(&all)
}

const REST_TO_REST: [&str; 10] = [
    "--duration",
    "2",
    "--start",
    "x=0",
    "--start",
    "dot(x)=0",
    "--goal",
    "x=1",
    "--goal",
    "dot(x)=0",
];

#[test]
fn a_point_mass_plan_meets_its_closed_form_cost() {
    let dir = scratch("plan-point-mass");
    let mut arguments = REST_TO_REST.to_vec();
    arguments.extend(["--nodes", "41"]);
    let output = run(dir.path(), "plan", &arguments);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(stdout.contains("a verified optimum"), "{stdout}");
    let json = std::fs::read_to_string(dir.path().join("plan/plan.json")).expect("plan.json");
    let report: serde_json::Value = serde_json::from_str(&json).expect("JSON");
    // 12 m^2 / T^3 with m = 2, T = 2; the midpoint rule's error on 41 nodes
    // is 3.8e-3 (h^2 / 4 of it, from the library's convergence test).
    let objective = report["objective"].as_f64().expect("a number");
    assert!((objective - 6.0).abs() < 5e-3, "{objective}");
    assert_eq!(report["nodes"], 41);
    assert_eq!(report["scheme"], "midpoint");
    for residual in ["primal", "dual", "complementarity"] {
        let value = report["kkt"][residual].as_f64().expect("a number");
        assert!(value <= 1e-6, "{residual} {value}");
    }
    let (header, rows) = read_csv(&dir.path().join("plan/plan.csv"));
    assert_eq!(rows.len(), 41);
    let x = column(&header, &rows, "x");
    assert_eq!((x[0], x[40]), (0.0, 1.0));
    let simulated = run(
        dir.path(),
        "simulate",
        &["--formulation", "lagrange", "--t-end", "0.01"],
    );
    assert!(simulated.status.success());
    let (trajectory_header, _) = read_csv(&dir.path().join("simulate/trajectory.csv"));
    assert_eq!(header, trajectory_header);
}

/// The standard error of a refused plan: one line, `error: ` and `says`.
fn refused(arguments: &[&str], says: &str) {
    let dir = scratch("plan-refused");
    let output = run(dir.path(), "plan", arguments);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("error: ") && stderr.contains(says),
        "{stderr}"
    );
    assert!(!dir.path().join("plan/plan.json").exists());
}

#[test]
fn bad_plans_are_refused_in_one_line() {
    let with = |extra: &[&'static str]| {
        let mut all = REST_TO_REST.to_vec();
        all.extend(extra);
        if !extra.contains(&"--nodes") {
            all.extend(["--nodes", "11"]);
        }
        all
    };
    refused(&with(&["--goal", "y=1"]), "--goal: unknown name `y`");
    refused(&with(&["--nodes", "1"]), "at least 2 nodes");
    refused(
        &with(&["--bound", "x=:0.5"]),
        "lies outside --bound x=-inf:0.5",
    );
    refused(&with(&["--bound", "push=-0.1:0.1"]), "no verified optimum");
}

/// `plan.json` of a successful run in `dir`'s `plan`.
fn report(dir: &Path, output: &Output) -> serde_json::Value {
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let json = std::fs::read_to_string(dir.join("plan/plan.json")).expect("plan.json");
    serde_json::from_str(&json).expect("JSON")
}

/// `min T + int u^2` for the point mass with `m = 1` moved by 1: over a
/// given `T` the cost is `T + 12/T^3`, least at `T = sqrt 6` where it is
/// `8/sqrt 6`; Hermite-Simpson is exact on the optimum's cubic.
#[test]
fn a_free_duration_plan_by_hermite_simpson_meets_its_closed_form() {
    let dir = scratch("plan-free-duration");
    let mut arguments = REST_TO_REST.to_vec();
    arguments.extend([
        "--nodes",
        "21",
        "--param",
        "m=1",
        "--scheme",
        "hermite-simpson",
        "--free-duration",
        "--final-cost",
        "t",
    ]);
    let report = report(dir.path(), &run(dir.path(), "plan", &arguments));
    let duration = report["duration"].as_f64().expect("a number");
    let objective = report["objective"].as_f64().expect("a number");
    assert!((duration - 6.0_f64.sqrt()).abs() < 1e-6, "{duration}");
    assert!(
        (objective - 8.0 / 6.0_f64.sqrt()).abs() < 1e-8,
        "{objective}"
    );
    assert_eq!(report["scheme"], "hermite-simpson");
    let (header, rows) = read_csv(&dir.path().join("plan/plan.csv"));
    assert!((column(&header, &rows, "t")[20] - duration).abs() < 1e-12);
}

/// A soft goal `12 (x(T) - 1)^2` for the point mass with `m = 1` over `T =
/// 1`: reaching `y` costs `12 y^2`, so `y = 1/2` and the cost is 6.
#[test]
fn a_final_cost_plan_meets_its_closed_form() {
    let dir = scratch("plan-final-cost");
    let arguments = [
        "--duration",
        "1",
        "--nodes",
        "11",
        "--param",
        "m=1",
        "--scheme",
        "hermite-simpson",
        "--start",
        "x=0",
        "--start",
        "dot(x)=0",
        "--goal",
        "dot(x)=0",
        "--final-cost",
        "12*(x - 1)^2",
    ];
    let report = report(dir.path(), &run(dir.path(), "plan", &arguments));
    let objective = report["objective"].as_f64().expect("a number");
    assert!((objective - 6.0).abs() < 1e-7, "{objective}");
    let (header, rows) = read_csv(&dir.path().join("plan/plan.csv"));
    assert!((column(&header, &rows, "x")[10] - 0.5).abs() < 1e-7);
}

/// A plan restarted from its own `plan.csv` on a finer grid reaches the
/// same optimum (the midpoint rule's objective on 21 nodes, `12 m^2 / T^3`
/// to within its `h^2` error).
#[test]
fn a_plan_csv_is_a_guess() {
    let dir = scratch("plan-guess");
    let mut coarse = REST_TO_REST.to_vec();
    coarse.extend(["--nodes", "11"]);
    report(dir.path(), &run(dir.path(), "plan", &coarse));
    let guess = dir.path().join("guess.csv");
    std::fs::rename(dir.path().join("plan/plan.csv"), &guess).expect("moved");
    let mut fine = REST_TO_REST.to_vec();
    fine.extend(["--nodes", "21", "--guess", guess.to_str().expect("UTF-8")]);
    let report = report(dir.path(), &run(dir.path(), "plan", &fine));
    let objective = report["objective"].as_f64().expect("a number");
    assert!((objective - 6.0).abs() < 2e-2, "{objective}");
}

#[test]
fn bad_guesses_and_free_durations_are_refused_in_one_line() {
    let dir = scratch("plan-bad-guess");
    let guess = dir.path().join("guess.csv");
    std::fs::write(&guess, "t,x,y\n0,0,0\n1,1,0\n").expect("written");
    let mut arguments = REST_TO_REST.to_vec();
    arguments.extend(["--nodes", "11", "--guess", guess.to_str().expect("UTF-8")]);
    refused(&arguments, "guess.csv: unknown columns y");
    let mut free = REST_TO_REST[2..].to_vec();
    free.extend(["--nodes", "11", "--free-duration", "--duration", "0"]);
    refused(
        &free,
        "--duration 0: the free duration's first guess must be positive",
    );
}
