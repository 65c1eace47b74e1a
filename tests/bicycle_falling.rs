//! The benchmark bicycle falling over at 3 m/s, below its weave speed, run
//! until it lies on its side (README, "Chart switching" and "Where a run
//! ends"). The steer swings round through +-90 degrees, where the basis of
//! D chosen in the body frame (the rear wheel's rate an independent speed)
//! degenerates while the constraint rows stay independent: the reduced form
//! changes to the chart with the front wheel's rate independent and runs on
//! with its energy kept to round-off, and the Lagrange-d'Alembert form (an
//! independent formulation, no basis of D) runs the same motion. Run on
//! without a stop condition, both stop where the front wheel's plane turns
//! horizontal and its contact point, the lowest point of the rim, is
//! undefined: the error names that square root.

use crate::support::{chaplygin, read_csv};
use std::path::PathBuf;

/// Upright at 3 m/s (`dot(theta_r) = -10` with `rR = 0.3`), leaning at
/// 0.2 rad/s, steer at rest, 1 ms steps.
const FALL: [&str; 8] = [
    "--initial",
    "dot(theta_r)=-10",
    "--initial",
    "dot(phi)=0.2",
    "--initial",
    "dot(delta)=0",
    "--dt",
    "0.001",
];

/// A run's summary line and columns.
struct Run {
    summary: String,
    header: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl Run {
    fn column(&self, name: &str) -> Vec<f64> {
        let i = self
            .header
            .iter()
            .position(|column| column == name)
            .unwrap_or_else(|| panic!("a column `{name}` in {:?}", self.header));
        self.rows.iter().map(|row| row[i]).collect()
    }
}

fn out(name: &str) -> PathBuf {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("falling-{name}"));
    let _ = std::fs::remove_dir_all(&out);
    out
}

/// The fall in `formulation` with `integrator` until the lean passes 1 rad.
fn until_it_lies_down(formulation: &str, integrator: &str) -> Run {
    let options = ["--formulation", formulation, "--integrator", integrator];
    let name = format!("{formulation}-{integrator}");
    until_the_lean_passes_1_rad(&name, &[&options[..], &FALL[..]].concat())
}

/// `simulate bicycle` with `options` until the lean passes 1 rad (at most
/// 4 s), written into the directory `name`.
fn until_the_lean_passes_1_rad(name: &str, options: &[&str]) -> Run {
    let out = out(name);
    let mut arguments = vec![
        "simulate",
        "bicycle",
        "--t-end",
        "4",
        "--stop-when",
        "abs(phi) > 1",
        "--out",
        out.to_str().expect("a UTF-8 path"),
    ];
    arguments.extend(options);
    let output = chaplygin(&arguments);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{name}: {stderr}");
    let summary = String::from_utf8_lossy(&output.stdout)
        .lines()
        .next()
        .expect("a summary line")
        .to_string();
    let (header, rows) = read_csv(&out.join("trajectory.csv"));
    Run {
        summary,
        header,
        rows,
    }
}

/// The lean passes 1 rad at the last row (the crossing located within its
/// step), the steer has swung through +-90 degrees, the front contact stays
/// on the ground (`|f| <= 1e-9`) and the pitch moves continuously, on its
/// branch near 0 (a jump to the other branch of the contact would be a
/// jump of order pi).
fn assert_fell_through_the_steer_singularity(run: &Run) {
    let phi = run.column("phi");
    let last = *phi.last().expect("rows");
    assert!((last.abs() - 1.0).abs() < 1e-6, "{last}");
    assert!(phi[..phi.len() - 1].iter().all(|p| p.abs() <= 1.0));
    assert!(run.summary.contains("stopped at t = "), "{}", run.summary);
    assert!(run.summary.ends_with(": abs(phi) > 1"), "{}", run.summary);
    let steer = run.column("delta");
    let widest = steer.iter().fold(0.0_f64, |m, d| m.max(d.abs()));
    assert!(widest > std::f64::consts::FRAC_PI_2, "{widest}");
    let holonomic = run.column("holonomic_residual");
    assert!(holonomic.iter().all(|f| *f < 1e-9));
    let pitch = run.column("theta_b");
    let jump = pitch
        .windows(2)
        .map(|w| (w[1] - w[0]).abs())
        .fold(0.0, f64::max);
    assert!(jump < 0.05, "{jump}");
    assert!(pitch.iter().all(|p| p.abs() < 0.5));
}

#[test]
fn the_reduced_form_changes_chart_where_the_steer_passes_90_degrees() {
    let run = until_it_lies_down("reduced", "discrete-gradient");
    assert_fell_through_the_steer_singularity(&run);
    assert!(!run.summary.contains("chart switches 0"), "{}", run.summary);
    let charts = run.column("chart");
    assert_eq!(charts[0], 0.0);
    assert!(charts.contains(&1.0), "the front wheel's chart");
    let energy = run.column("energy");
    let drift = energy
        .iter()
        .map(|e| (e - energy[0]).abs())
        .fold(0.0, f64::max);
    assert!(drift < 1e-10 * energy[0], "{drift:e}");
}

/// The Lagrange-d'Alembert equations (multipliers, no basis of D) with
/// RK4 fall the same way: the lean passes 1 rad within 1 ms of the reduced
/// form's time (both second-order accurate or better at 1 ms steps, through
/// a steer spinning at up to 40 rad/s).
#[test]
fn the_lagrange_dalembert_form_falls_the_same_way() {
    let lagrange = until_it_lies_down("lagrange", "rk4");
    assert_fell_through_the_steer_singularity(&lagrange);
    let reduced = until_it_lies_down("reduced", "discrete-gradient");
    let end = |run: &Run| *run.column("t").last().expect("rows");
    assert!((end(&lagrange) - end(&reduced)).abs() < 1e-3);
}

/// At the default step of 10 ms, Newton's iteration of the discrete
/// gradient diverges where the steer whips round: the loop splits those
/// steps in halves and the fall goes on, its energy kept, to the lean of
/// 1 rad at a time within 0.02 s of the 1 ms run's (second order: the
/// 1 ms run is 1.1e-4 s from a 0.1 ms run, and 100 times that is 0.011 s).
#[test]
fn steps_too_long_for_the_whipping_steer_are_split_not_ended() {
    let fine = until_it_lies_down("reduced", "discrete-gradient");
    // the fall without its `--dt`: the default step and integrator
    let coarse = until_the_lean_passes_1_rad("default-step", &FALL[..6]);
    let summary = &coarse.summary;
    assert!(summary.contains("of discrete-gradient"), "{summary}");
    assert!(summary.contains("; steps split "), "{summary}");
    let end = |run: &Run| *run.column("t").last().expect("rows");
    assert!(
        (end(&coarse) - end(&fine)).abs() < 0.02,
        "{} {}",
        end(&coarse),
        end(&fine)
    );
    let energy = coarse.column("energy");
    let drift = energy
        .iter()
        .map(|e| (e - energy[0]).abs())
        .fold(0.0, f64::max);
    assert!(drift < 1e-9 * energy[0], "{drift:e}");
}

/// Run on, the fall ends where the front wheel lies flat: every
/// formulation and integrator stops with the square root of the front
/// contact named, and never with a bare solver failure.
#[test]
fn run_on_it_stops_where_the_front_wheel_lies_flat() {
    for (formulation, integrator) in [
        ("reduced", "discrete-gradient"),
        ("reduced", "rk4"),
        ("lagrange", "rk4"),
        ("lagrange", "midpoint"),
        ("lagrange", "dopri5"),
    ] {
        let out = out(&format!("flat-{formulation}-{integrator}"));
        let mut arguments = vec![
            "simulate",
            "bicycle",
            "--formulation",
            formulation,
            "--integrator",
            integrator,
            "--t-end",
            "4",
            "--out",
            out.to_str().expect("a UTF-8 path"),
        ];
        arguments.extend(FALL);
        let output = chaplygin(&arguments);
        let stderr = String::from_utf8_lossy(&output.stderr);
        let context = format!("{formulation} {integrator}");
        assert!(!output.status.success(), "{context}");
        assert_eq!(stderr.lines().count(), 1, "{context}: {stderr}");
        assert!(
            stderr.contains("the model's domain ends in the step from t = 2.9")
                && stderr.contains("a square root in point `front_contact`"),
            "{context}: {stderr}"
        );
        let (header, rows) = read_csv(&out.join("trajectory.csv"));
        let phi = header.iter().position(|h| h == "phi").expect("phi");
        let last = rows.last().expect("rows")[phi];
        assert!(last.abs() > 1.4, "{context}: lean {last}");
    }
}
