//! `chaplygin plan` (docs/INTERFACE.md section 13) run as a command: a
//! point mass moved between rests, whose optimal cost `12 m^2 / T^3` is
//! known in closed form; `plan.csv` with `trajectory.csv`'s columns; and
//! bad requests refused in one line.

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

/// Both Hessians reach the closed-form cost, and `plan.json` names the one
/// used: the exact one by default.
#[test]
fn each_hessian_reaches_the_closed_form_cost_and_is_named() {
    let dir = scratch("plan-hessians");
    for (choice, solver) in [
        (None, "ripopt (exact Hessian)"),
        (Some("lbfgs"), "ripopt (L-BFGS Hessian)"),
    ] {
        let mut arguments = REST_TO_REST.to_vec();
        arguments.extend(["--nodes", "21"]);
        arguments.extend(choice.map(|h| ["--hessian", h]).into_iter().flatten());
        let output = run(dir.path(), "plan", &arguments);
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        let json = std::fs::read_to_string(dir.path().join("plan/plan.json")).expect("plan.json");
        let report: serde_json::Value = serde_json::from_str(&json).expect("JSON");
        // 12 m^2 / T^3 = 6; the midpoint rule's error on 21 nodes is
        // 0.015 (h^2 / 4 of it, h = 0.1).
        let objective = report["objective"].as_f64().expect("a number");
        assert!((objective - 6.0).abs() < 2e-2, "{objective}");
        assert_eq!(report["solver"], solver);
    }
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
