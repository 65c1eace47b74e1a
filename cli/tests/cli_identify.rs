//! `chaplygin identify` (docs/INTERFACE.md section 13) run as a command: a
//! point mass pushed from rest by a constant force `F` moves as `x = F t^2
//! / (2 m)`, a motion the midpoint rule follows exactly, so its mass is
//! recovered from that motion to round-off; `estimate.json`, `fit.csv`
//! and the printed estimates; bad data refused in one line; Ctrl-C ends
//! the solve with its last iterate written.

use crate::support::{chaplygin, column, interrupted, read_csv, scratch};
use std::path::{Path, PathBuf};
use std::process::Output;

/// `m xddot = push`, its default mass not the truth `m = 2`.
const POINT_MASS: &str = "pub struct PointMass {
    coordinates: [x],
    parameters: [m = 1.0],
    kinetic_energy: m/2*dot(x)^2,
    inputs: [push = x],
}";

/// `chaplygin identify` on the point mass with `data` as `--data`.
fn identify(dir: &Path, data: &str, arguments: &[&str]) -> Output {
    let model = dir.join("point_mass.model");
    std::fs::write(&model, POINT_MASS).expect("the model is written");
    let file = dir.join("data.csv");
    std::fs::write(&file, data).expect("the data are written");
    let out = dir.join("identify");
    let mut all = vec![
        "identify",
        model.to_str().expect("UTF-8"),
        "--data",
        file.to_str().expect("UTF-8"),
        "--out",
        out.to_str().expect("UTF-8"),
    ];
    all.extend(arguments);
    chaplygin(&all)
}

/// `x = 3 t^2 / 4` under `push = 3`, `m = 2`, on 21 rows over 2 s.
fn pushed_from_rest() -> String {
    let mut text = String::from("t,x,push\n");
    for i in 0..21 {
        let t = 0.1 * i as f64;
        text.push_str(&format!("{t},{},3\n", 0.75 * t * t));
    }
    text
}

/// `estimate.json` in `out`.
fn estimate(out: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(out.join("estimate.json")).expect("written");
    serde_json::from_str(&text).expect("JSON")
}

/// `identify` of the mass from `data` (from m = 1.5) in `dir`, asserted to
/// succeed with m = 2 to 1e-6: its output, its directory and
/// `estimate.json`.
fn identified_mass(dir: &Path, data: &str) -> (Output, PathBuf, serde_json::Value) {
    let output = identify(dir, data, &["--estimate", "m=1.5"]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let out = dir.join("identify");
    let json = estimate(&out);
    let mass = json["parameters"]["m"].as_f64().expect("m");
    assert!((mass - 2.0).abs() < 1e-6, "m = {mass}");
    (output, out, json)
}

#[test]
fn the_mass_is_recovered_from_a_pushed_motion() {
    let dir = scratch("identify_point_mass");
    let (output, out, json) = identified_mass(dir.path(), &pushed_from_rest());
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(json["standard_errors"]["m"].as_f64().is_some(), "{json}");
    assert!(json["residual_rms"].as_f64().expect("rms") < 1e-6, "{json}");
    assert!(stdout.contains("m = 2.0000"), "{stdout}");
    let (header, rows) = read_csv(&out.join("fit.csv"));
    let (t, x) = (column(&header, &rows, "t"), column(&header, &rows, "x"));
    let data = column(&header, &rows, "data(x)");
    for ((t, x), d) in t.iter().zip(&x).zip(&data) {
        assert!((x - 0.75 * t * t).abs() < 1e-6 && (d - 0.75 * t * t).abs() < 1e-12);
    }
    assert!(out.join("fit.png").exists());
}

/// The same motion sampled at uneven times, `t_i = 0.1 i + 0.03 sin(3 i)`
/// (no two spacings alike): the nodes are the rows' own times, on which
/// the midpoint rule is still exact, so the mass is recovered to round-off
/// and `fit.csv` keeps the rows' times.
#[test]
fn the_mass_is_recovered_from_unevenly_sampled_data() {
    let dir = scratch("identify_uneven");
    let times: Vec<f64> = (0..21)
        .map(|i| 0.1 * i as f64 + 0.03 * (3.0 * i as f64).sin())
        .collect();
    let mut data = String::from("t,x,push\n");
    for t in &times {
        data.push_str(&format!("{t},{},3\n", 0.75 * t * t));
    }
    let (_, out, _) = identified_mass(dir.path(), &data);
    let (header, rows) = read_csv(&out.join("fit.csv"));
    let fitted = column(&header, &rows, "t");
    assert_eq!(fitted.len(), times.len());
    for (fitted, t) in fitted.iter().zip(&times) {
        assert!((fitted - t).abs() < 1e-9, "{fitted} vs {t}");
    }
}

#[test]
fn bad_data_fail_in_one_line() {
    let dir = scratch("identify_bad_data");
    let cases: [(&str, &[&str], &str); 4] = [
        (
            &pushed_from_rest(),
            &["--estimate", "k"],
            "--estimate k: unknown parameter",
        ),
        (
            "t,x,lean\n0,0,0\n1,1,0\n",
            &["--estimate", "m"],
            "unknown columns lean",
        ),
        ("t,x\n0,0\n1,1\n", &["--estimate", "m"], "too few rows"),
        (
            "t,x\n0,0\n2,1\n1,1\n3,2\n",
            &["--estimate", "m"],
            "row 3: `t` = 1 does not increase strictly from 2",
        ),
    ];
    for (data, arguments, said) in cases {
        let output = identify(dir.path(), data, arguments);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{said}");
        assert!(
            stderr.contains(said) && stderr.trim().lines().count() == 1,
            "{stderr}"
        );
    }
}

/// Ctrl-C (SIGINT) during a long solve: the command writes the last
/// iterate, `fit.csv` marked as not verified and `estimate.json` with the
/// status `interrupted` and its KKT residuals, and fails in one line.
#[test]
fn an_interrupted_estimate_keeps_its_last_iterate() {
    let dir = scratch("identify_interrupted");
    let out = dir.path().join("fit");
    let data = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/data/drive_mass_5.csv"
    );
    // the solve takes half a minute; its start, three seconds
    let out_text = out.display().to_string();
    let output = interrupted(&[
        "identify",
        "differential-drive",
        "--data",
        data,
        "--estimate",
        "m=4",
        "--nodes",
        "2001",
        "--out",
        &out_text,
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    let said =
        (stderr.strip_prefix("error: interrupted after ")).unwrap_or_else(|| panic!("{stderr}"));
    let report = estimate(&out);
    assert_eq!(report["status"], "interrupted");
    let iterations = report["iterations"].as_u64().expect("a count");
    assert!(
        said.starts_with(&format!("{iterations} iterations"))
            && said.ends_with(&format!(
                "the last iterate, not verified, is in {}\n",
                out.display()
            )),
        "{stderr}"
    );
    for residual in ["primal", "dual", "complementarity"] {
        assert!(report["kkt"][residual].is_number(), "{report}");
    }
    let text = std::fs::read_to_string(out.join("fit.csv")).expect("fit.csv");
    let (first, rest) = text.split_once('\n').expect("rows");
    assert_eq!(
        first,
        format!("# not verified: interrupted after {iterations} iterations (estimate.json)")
    );
    let unmarked = dir.path().join("unmarked.csv");
    std::fs::write(&unmarked, rest).expect("written");
    let (header, rows) = read_csv(&unmarked);
    assert_eq!(rows.len(), 2001);
    assert_eq!(column(&header, &rows, "data(x)")[0], 0.0);
}

/// The trailing racer (`tests/models/trailing_racer.model`).
fn trailing_racer() -> String {
    format!(
        "{}/../tests/models/trailing_racer.model",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// `simulate`'s `trajectory.csv` of the trailing racer turned by `u1 =
/// 0.1` for 12 s in `formulation`, written under `dir`.
fn racer_run(dir: &Path, formulation: &str) -> PathBuf {
    let out = dir.join(formulation);
    let arguments = [
        "simulate",
        &trailing_racer(),
        "--formulation",
        formulation,
        "--input",
        "u1=0.1",
        "--t-end",
        "12",
        "--dt",
        "0.05",
        "--out",
        out.to_str().expect("UTF-8"),
    ];
    let output = chaplygin(&arguments);
    assert!(output.status.success(), "{output:?}");
    out.join("trajectory.csv")
}

/// The trailing racer's `m2` from one run's trajectory, as `identify`
/// prints it, or its one-line error.
fn racer_mass(dir: &Path, data: &Path) -> Result<f64, String> {
    let out = dir.join("estimate");
    let arguments = [
        "identify",
        &trailing_racer(),
        "--data",
        data.to_str().expect("UTF-8"),
        "--estimate",
        "m2=0.4",
        "--out",
        out.to_str().expect("UTF-8"),
    ];
    let output = chaplygin(&arguments);
    if !output.status.success() {
        return Err(String::from_utf8_lossy(&output.stderr).trim().to_string());
    }
    Ok(estimate(&out)["parameters"]["m2"].as_f64().expect("m2"))
}

/// `simulate`'s trajectory is data in any formulation: the trailing
/// racer's reduced run, which changes charts as its joint swings through
/// the basis' singular angle, is read in the velocities of each row's
/// chart, and gives the Lagrange run's estimate of `m2`. Its momentum
/// run's `p1` gives the velocities through the masses, so estimating `m2`
/// from it is refused in one line.
#[test]
fn simulates_trajectory_in_any_form_is_data() {
    let scratch = scratch("identify_forms");
    let dir = scratch.path();
    let reduced = racer_run(dir, "reduced");
    let (header, rows) = read_csv(&reduced);
    let charts = column(&header, &rows, "chart");
    assert!(charts.contains(&0.0) && charts.contains(&1.0), "{charts:?}");
    let lagrange = racer_mass(dir, &racer_run(dir, "lagrange")).expect("an estimate");
    let from_reduced = racer_mass(dir, &reduced).expect("an estimate");
    assert!(
        (from_reduced - lagrange).abs() < 1e-7 * lagrange,
        "{from_reduced} against {lagrange}"
    );
    let refused = racer_mass(dir, &racer_run(dir, "momentum")).expect_err("refused");
    assert!(
        refused.ends_with(
            "its columns p1 give the velocities through the estimated m2; give the velocities \
             dot(q) instead (simulate --formulation lagrange)"
        ),
        "{refused}"
    );
}
