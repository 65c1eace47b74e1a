//! The benchmark bicycle falling over at 3 m/s, below its weave speed, run
//! until it lies on its side (docs/guide/simulating.md, "Chart switching" and "Where a run
//! ends"). The steer swings round through +-90 degrees, where the basis of
//! D chosen in the body frame (the rear wheel's rate an independent speed)
//! degenerates while the constraint rows stay independent: the reduced form
//! changes to the chart with the front wheel's rate independent and runs on
//! with its energy kept to round-off, and the Lagrange-d'Alembert form (an
//! independent formulation, no basis of D) runs the same motion. Run on
//! without a stop condition, both stop where the front wheel's plane turns
//! horizontal and its contact point, the lowest point of the rim, is
//! undefined: the error names that square root.
//!
//! Each run of the binary derives and compiles the bicycle again (some 5 s
//! of CPU in the test build, a fall 0.3 to 1.3 s): the falls run in this
//! process, on the bicycle loaded once for all the tests ([`Model`]), the
//! reduced form's fall, which three tests read, once for them all
//! ([`reduced_fall`]); the binary runs the first of the runs on to the flat
//! wheel, its exit status, its one line on standard error and the rows it
//! wrote.

use crate::support::in_process::{Finished, Model};
use crate::support::{FALL, chaplygin, read_csv};
use std::path::PathBuf;
use std::sync::OnceLock;

/// A run's summary line and columns.
struct Run {
    summary: String,
    header: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl Run {
    fn column(&self, name: &str) -> Vec<f64> {
        crate::support::column(&self.header, &self.rows, name)
    }
}

fn out(name: &str) -> PathBuf {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("falling-{name}"));
    let _ = std::fs::remove_dir_all(&out);
    out
}

/// The bicycle built in, loaded on the JIT.
fn bicycle() -> &'static Model {
    Model::load("bicycle", "jit")
}

/// The fall of the reduced form with the discrete gradient until the lean
/// passes 1 rad, run once for the tests that read it.
fn reduced_fall() -> &'static Run {
    static FALL: OnceLock<Run> = OnceLock::new();
    FALL.get_or_init(|| until_it_lies_down(bicycle(), "reduced", "discrete-gradient"))
}

/// The fall of `bicycle` in `formulation` with `integrator` until the lean
/// passes 1 rad.
fn until_it_lies_down(bicycle: &Model, formulation: &str, integrator: &str) -> Run {
    let options = ["--formulation", formulation, "--integrator", integrator];
    until_the_lean_passes_1_rad(bicycle, &[&options[..], &FALL[..]].concat())
}

/// `simulate bicycle` with `options` until the lean passes 1 rad (at most
/// 4 s), on the loaded `bicycle`.
fn until_the_lean_passes_1_rad(bicycle: &Model, options: &[&str]) -> Run {
    let mut arguments = vec!["--t-end", "4", "--stop-when", "abs(phi) > 1"];
    arguments.extend(options);
    let Finished {
        summary,
        header,
        rows,
    } = bicycle.finished(&arguments);
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
    let run = reduced_fall();
    assert_fell_through_the_steer_singularity(run);
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
    let bicycle = bicycle();
    let lagrange = until_it_lies_down(bicycle, "lagrange", "rk4");
    assert_fell_through_the_steer_singularity(&lagrange);
    let reduced = reduced_fall();
    let end = |run: &Run| *run.column("t").last().expect("rows");
    assert!((end(&lagrange) - end(reduced)).abs() < 1e-3);
}

/// At the default step of 10 ms, Newton's iteration of the discrete
/// gradient diverges where the steer whips round: the loop splits those
/// steps in halves and the fall goes on, its energy kept, to the lean of
/// 1 rad at a time within 0.02 s of the 1 ms run's (second order: the
/// 1 ms run is 1.1e-4 s from a 0.1 ms run, and 100 times that is 0.011 s).
#[test]
fn steps_too_long_for_the_whipping_steer_are_split_not_ended() {
    let bicycle = bicycle();
    let fine = reduced_fall();
    // the fall without its `--dt`: fixed steps of the default length, the
    // default integrator
    let coarse = until_the_lean_passes_1_rad(bicycle, &FALL[..7]);
    let summary = &coarse.summary;
    assert!(summary.contains("of discrete-gradient"), "{summary}");
    assert!(summary.contains("; steps split "), "{summary}");
    let end = |run: &Run| *run.column("t").last().expect("rows");
    assert!(
        (end(&coarse) - end(fine)).abs() < 0.02,
        "{} {}",
        end(&coarse),
        end(fine)
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
/// contact named, and never with a bare solver failure; the binary exits
/// with that one line on standard error (the first pairing through it, the
/// others in this process: the same message, the rows it wrote).
#[test]
fn run_on_it_stops_where_the_front_wheel_lies_flat() {
    let bicycle = bicycle();
    for (i, (formulation, integrator)) in [
        ("reduced", "discrete-gradient"),
        ("reduced", "rk4"),
        ("lagrange", "rk4"),
        ("lagrange", "midpoint"),
        ("lagrange", "dopri5"),
    ]
    .into_iter()
    .enumerate()
    {
        let mut options = vec![
            "--formulation",
            formulation,
            "--integrator",
            integrator,
            "--t-end",
            "4",
        ];
        // fixed steps of 1 ms but for dopri5, which follows its tolerance
        let fixed =
            (FALL.iter()).filter(|option| integrator != "dopri5" || **option != "--fixed-step");
        options.extend(fixed);
        let context = format!("{formulation} {integrator}");
        let (error, rows, header) = if i == 0 {
            let out = out(&format!("flat-{formulation}-{integrator}"));
            let mut arguments = vec![
                "simulate",
                "bicycle",
                "--out",
                out.to_str().expect("a UTF-8 path"),
            ];
            arguments.extend(&options);
            let output = chaplygin(&arguments);
            let stderr = String::from_utf8_lossy(&output.stderr);
            assert!(!output.status.success(), "{context}");
            assert_eq!(stderr.lines().count(), 1, "{context}: {stderr}");
            let (header, rows) = read_csv(&out.join("trajectory.csv"));
            (stderr.to_string(), rows, header)
        } else {
            let run = bicycle.simulate(&options).expect("the run starts");
            let error = run.outcome.expect_err(&context);
            assert_eq!(error.lines().count(), 1, "{context}: {error}");
            (error, run.rows, run.header)
        };
        assert!(
            error.contains("the model's domain ends in the step from t = 2.9")
                && error.contains("a square root in point `front_contact`"),
            "{context}: {error}"
        );
        let phi = header.iter().position(|h| h == "phi").expect("phi");
        let last = rows.last().expect("rows")[phi];
        assert!(last.abs() > 1.4, "{context}: lean {last}");
    }
}

/// With the steps following the default tolerance, every formulation and
/// integrator ends the fall at the lean of 1.2 within 1e-6 s of each
/// other (a fixed step of 10 ms leaves RK4 0.17 s late), the energy kept
/// to 1e-6, and to 1e-8 by the structure-preserving integrators
/// (docs/INTERFACE.md section 12).
#[test]
fn at_the_default_tolerance_every_integrator_ends_the_fall_at_the_same_time() {
    let bicycle = bicycle();
    let mut ends = Vec::new();
    for (formulation, integrator, drift_allowed) in [
        ("reduced", "dopri5", 1e-6),
        ("reduced", "rk4", 1e-6),
        ("reduced", "midpoint", 1e-8),
        ("reduced", "discrete-gradient", 1e-8),
        ("lagrange", "dopri5", 1e-6),
        ("lagrange", "rk4", 1e-6),
        ("lagrange", "midpoint", 1e-8),
    ] {
        let mut options = vec!["--formulation", formulation, "--integrator", integrator];
        options.extend(["--t-end", "5", "--stop-when", "abs(phi) > 1.2"]);
        options.extend(&FALL[..6]);
        let run = bicycle.simulate(&options).expect("the run starts");
        let summary = run.outcome.as_ref().expect(integrator);
        assert!(summary.ends_with(": abs(phi) > 1.2"), "{summary}");
        assert!(run.warnings.is_empty(), "{:?}", run.warnings);
        let energy = run.column("energy");
        let drift = energy
            .iter()
            .map(|e| ((e - energy[0]) / energy[0]).abs())
            .fold(0.0, f64::max);
        assert!(
            drift <= drift_allowed,
            "{formulation} {integrator}: drift {drift:e}"
        );
        ends.push(*run.column("t").last().expect("rows"));
    }
    let (first, last) = ends
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), t| {
            (a.min(*t), b.max(*t))
        });
    assert!(last - first < 1e-6, "{ends:?}");
}

/// RK4 at a fixed step of 20 ms gains 845 % of the falling bicycle's
/// energy, nearly all of the kinetic energy the run reaches, so its drift
/// relative to that is near 1 (0.9986): the binary prints the summary,
/// then one `warning:` line naming
/// the drift, its bound and what to change, and exits 0; with `--strict`
/// the same run exits 1. Steps following the default tolerance do not
/// warn (docs/INTERFACE.md section 12).
#[test]
fn a_run_beyond_its_tolerance_warns_and_strict_makes_it_an_error() {
    let run = |name: &str, extra: &[&str]| {
        let out = out(name);
        let mut arguments = vec!["simulate", "bicycle", "--integrator", "rk4"];
        arguments.extend(["--t-end", "5", "--stop-when", "abs(phi) > 1.2"]);
        arguments.extend(&FALL[..6]);
        arguments.extend(extra);
        arguments.extend(["--out", out.to_str().expect("a UTF-8 path")]);
        chaplygin(&arguments)
    };
    let coarse = ["--fixed-step", "--dt", "0.02"];
    let warned = run("rk4-20ms", &coarse);
    let stderr = String::from_utf8_lossy(&warned.stderr);
    assert!(warned.status.success(), "{stderr}");
    let warning = stderr.lines().find(|line| line.starts_with("warning: "));
    let warning = warning.unwrap_or_else(|| panic!("a warning in {stderr}"));
    let summary = String::from_utf8_lossy(&warned.stdout);
    let drift = |text: &str, label: &str| -> f64 {
        let after = text
            .split(label)
            .nth(1)
            .unwrap_or_else(|| panic!("{label} in {text}"));
        let number = after.split([';', ' ']).next().expect("a number");
        number
            .parse()
            .unwrap_or_else(|_| panic!("a number in {after}"))
    };
    let warned_drift = drift(warning, "energy drift of a run without inputs ");
    assert_eq!(warned_drift, drift(&summary, "energy drift "));
    assert!(warned_drift > 0.5, "{warning}");
    assert!(
        warning.contains("exceeds 1.0e-6") && warning.contains("--dt"),
        "{warning}"
    );
    let strict = run("rk4-20ms-strict", &[&coarse[..], &["--strict"]].concat());
    assert_eq!(strict.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&strict.stderr);
    assert!(
        stderr.contains("error: the run is not accurate to its tolerance (--strict)"),
        "{stderr}"
    );
    let controlled = run("rk4-controlled", &["--strict"]);
    let stderr = String::from_utf8_lossy(&controlled.stderr);
    assert!(
        controlled.status.success() && !stderr.contains("warning"),
        "{stderr}"
    );
}
