//! `chaplygin simulate --stop-when COND` and `--input` feedback laws of the
//! state, against closed forms: the Chaplygin sleigh with its blade under
//! the centre of mass turns at a constant rate, so its heading crosses 1
//! where a line does; the rolling disk's heading and rotation under a PD
//! steering law and a damping drive torque are those of linear
//! oscillators; the benchmark bicycle at 2 m/s, below its weave speed,
//! falls without a steering law and stays upright with one. Every
//! formulation, the built-in on the JIT and its `.model` file on the
//! interpreter.
//!
//! The closed-form checks run in this process ([`Model`]: each model
//! derived and compiled once, the options read as the binary reads them);
//! the stops at the start and at equality, the refused conditions and the
//! recorded inputs run the binary.

use crate::support::in_process::{Finished, Model};
use crate::support::{chaplygin, read_csv, scratch};
use std::f64::consts::PI;
use std::process::Output;
use tempfile::TempDir;

const SLEIGH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/sleigh.model");
const DISK: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/rolling_disk.model");

/// A finished run: its summary line and its trajectory.
struct Run {
    summary: String,
    header: Vec<String>,
    rows: Vec<Vec<f64>>,
}

impl Run {
    fn column(&self, name: &str) -> Vec<f64> {
        crate::support::column(&self.header, &self.rows, name)
    }

    /// The last row's value of `name`.
    fn last(&self, name: &str) -> f64 {
        *self.column(name).last().expect("a row")
    }

    /// The time after `stopped at t = ` in the summary, and the condition.
    fn stopped(&self) -> (f64, &str) {
        let after = self
            .summary
            .split("; stopped at t = ")
            .nth(1)
            .unwrap_or_else(|| panic!("not stopped: {}", self.summary));
        let (t, condition) = after.split_once(": ").expect("t = T: COND");
        (t.parse().expect("a time"), condition)
    }
}

/// The output of `chaplygin simulate` with `arguments`, and the scratch
/// directory named after `name` it wrote into (removed when dropped).
fn output(name: &str, arguments: &[&str]) -> (Output, TempDir) {
    let out = scratch(&format!("stop-{name}"));
    let mut all = vec!["simulate"];
    all.extend(arguments);
    all.extend(["--out", out.path().to_str().expect("a UTF-8 path")]);
    (chaplygin(&all), out)
}

/// A successful run of `chaplygin simulate` with `arguments`.
fn simulate(name: &str, arguments: &[&str]) -> Run {
    let (output, out) = output(name, arguments);
    assert!(
        output.status.success(),
        "{arguments:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let summary = String::from_utf8_lossy(&output.stdout)
        .lines()
        .next()
        .expect("a summary line")
        .to_string();
    let (header, rows) = read_csv(&out.path().join("trajectory.csv"));
    Run {
        summary,
        header,
        rows,
    }
}

/// A successful run of the loaded `model` with `options` (those of
/// `chaplygin simulate` but the model, the engine and `--out`), in this
/// process: the closed-form checks below take some 60 runs, each of which
/// the binary would derive and compile its model for again.
fn simulated(model: &Model, options: &[&str]) -> Run {
    let Finished {
        summary,
        header,
        rows,
    } = model.finished(options);
    Run {
        summary,
        header,
        rows,
    }
}

/// The formulations and integrators a model without configuration
/// constraints runs in.
const RUNS: [(&str, &str); 9] = [
    ("reduced", "rk4"),
    ("reduced", "dopri5"),
    ("reduced", "midpoint"),
    ("reduced", "discrete-gradient"),
    ("lagrange", "rk4"),
    ("lagrange", "dopri5"),
    ("lagrange", "midpoint"),
    ("momentum", "rk4"),
    ("momentum", "dopri5"),
];

/// The sleigh with its blade under the centre of mass (`a = 0`): the
/// blade's sideways force then acts through the centre of mass and exerts
/// no torque, so the turning rate is constant and the heading is
/// `theta(t) = 0.1 + 0.7 t`, which exceeds 1 at `t = 0.9/0.7`. Every
/// integrator follows a linear heading exactly, so the stop lies within
/// the located bracket, 1e-9, of that time, in every formulation, on the JIT
/// and on the interpreter; the last row is there, its heading 1 to 1e-9.
#[test]
fn the_sleigh_stops_where_its_heading_crosses_1() {
    let crossing = 0.9 / 0.7;
    for (model, engine) in [("sleigh", "jit"), (SLEIGH, "interpret")] {
        let loaded = Model::load(model, engine);
        for (formulation, integrator) in RUNS {
            let context = format!("{model} {formulation} {integrator}");
            let run = simulated(
                loaded,
                &[
                    "--formulation",
                    formulation,
                    "--integrator",
                    integrator,
                    "--param",
                    "a=0",
                    "--initial",
                    "theta=0.1",
                    "--initial",
                    "dot(x)=1",
                    "--initial",
                    "dot(theta)=0.7",
                    "--stop-when",
                    "theta > 1",
                    "--t-end",
                    "5",
                ],
            );
            let (t, condition) = run.stopped();
            assert_eq!(condition, "theta > 1", "{context}");
            assert!((t - crossing).abs() < 1e-9, "{context}: {t}");
            assert_eq!(run.last("t"), t, "{context}");
            assert!(run.summary.starts_with(&format!("t = {t}: ")), "{context}");
            let theta = run.last("theta");
            assert!(theta > 1.0 && theta - 1.0 < 1e-9, "{context}: {theta}");
        }
    }
}

/// A condition that holds at the start stops the run there: one row, no
/// step, a clean exit.
#[test]
fn a_condition_true_at_the_start_stops_before_any_step() {
    let run = simulate("start", &["sleigh", "--stop-when", "t + 1 > x"]);
    assert_eq!(run.stopped(), (0.0, "t + 1 > x"));
    assert!(run.summary.starts_with("t = 0: 0 steps"), "{}", run.summary);
    assert_eq!(run.rows.len(), 1);
}

/// At equality an inclusive comparison holds and a strict one does not:
/// the sleigh starts at `x = 0`, so `x >= 0` stops it before any step and
/// `x > 0` lets it run (it moves forward and stops after its first step).
#[test]
fn an_inclusive_condition_holds_at_equality() {
    let run = simulate("inclusive", &["sleigh", "--stop-when", "x >= 0"]);
    assert_eq!(run.stopped(), (0.0, "x >= 0"));
    assert_eq!(run.rows.len(), 1);
    let run = simulate(
        "strict",
        &[
            "sleigh",
            "--initial",
            "dot(x)=1",
            "--initial",
            "dot(theta)=0",
            "--stop-when",
            "x > 0",
        ],
    );
    let (t, _) = run.stopped();
    assert!(t > 0.0 && run.rows.len() > 1, "{}", run.summary);
}

/// A condition that is not one comparison of known names is refused in
/// one line naming it (the sleigh has no inputs to name).
#[test]
fn conditions_that_are_not_one_comparison_of_known_names_are_refused() {
    for (condition, says) in [
        (
            "theta",
            "--stop-when theta: no comparison `<`, `<=`, `>` or `>=`",
        ),
        (
            "0 < theta < 1",
            "--stop-when 0 < theta < 1: 2 comparisons; a condition is one",
        ),
        (
            "abs(psi) > 1",
            "--stop-when abs(psi) > 1: `psi` is not `t`, a parameter or a coordinate",
        ),
        (
            "dot(m) > 1",
            "--stop-when dot(m) > 1: `dot(m)`: `m` is not a coordinate",
        ),
    ] {
        for model in ["sleigh", SLEIGH] {
            let (output, _) = output("refused", &[model, "--stop-when", condition]);
            assert!(!output.status.success(), "{model} {condition}");
            let message = String::from_utf8_lossy(&output.stderr);
            assert_eq!(message.trim_end().lines().count(), 1, "{message}");
            assert_eq!(message.trim_end(), format!("error: {says}"));
        }
    }
}

/// The rolling disk's steering law
/// `u_steer = -j_vertical (4 (theta - 1) + 2 dot(theta))`, a PD law on
/// its heading, whose inertia is `j_vertical`: the heading obeys
/// `theta'' + 2 theta' + 4 (theta - 1) = 0`, from rest at 0
/// `theta = 1 - exp(-t) (cos(sqrt(3) t) + sin(sqrt(3) t)/sqrt(3))`.
const STEERING: &str = "u_steer=-j_vertical*(4*(theta-1)+2*dot(theta))";

/// The heading under [`STEERING`].
fn heading(t: f64) -> f64 {
    let w = 3f64.sqrt();
    1.0 - (-t).exp() * ((w * t).cos() + (w * t).sin() / w)
}

/// The drive torque `u_drive = -0.5 dot(phi)` on the rolling inertia
/// `m r^2 + j_axle = 0.375` damps the rolling rate from 1 as
/// `exp(-t/0.75)`: `phi = 0.75 (1 - exp(-t/0.75))`.
fn rotation(t: f64) -> f64 {
    0.75 * (1.0 - (-t / 0.75).exp())
}

fn disk_arguments<'a>(model: &'a str, formulation: &'a str, integrator: &'a str) -> Vec<&'a str> {
    vec![
        model,
        "--formulation",
        formulation,
        "--integrator",
        integrator,
        "--initial",
        "dot(phi)=1",
        "--initial",
        "dot(theta)=0",
        "--input",
        STEERING,
        "--input",
        "u_drive=-0.5*dot(phi)",
        "--t-end",
        "5",
    ]
}

/// Under the feedback laws the disk's heading and rotation are the closed
/// forms' in every formulation (the laws read `dot(theta)` and `dot(phi)`
/// off the reduced momenta and the momentum form's reconstruction too),
/// on the JIT and on the interpreter, to the integrators' orders at steps of 0.01
/// (measured: 3e-13 with Dormand-Prince, 1.05e-9 with RK4, 2.2e-5 with the
/// second-order implicit methods).
#[test]
fn feedback_laws_close_every_formulation_as_their_closed_form_says() {
    for (model, engine) in [("rolling-disk", "jit"), (DISK, "interpret")] {
        let loaded = Model::load(model, engine);
        for (formulation, integrator) in RUNS {
            let context = format!("{model} {formulation} {integrator}");
            let arguments = disk_arguments(model, formulation, integrator);
            let run = simulated(loaded, &arguments[1..]);
            let tolerance = match integrator {
                "dopri5" => 1e-12,
                "rk4" => 1e-8,
                _ => 1e-4,
            };
            let t = run.column("t");
            assert_eq!(*t.last().unwrap(), 5.0, "{context}");
            for (name, exact) in [("theta", heading as fn(f64) -> f64), ("phi", rotation)] {
                let error = t
                    .iter()
                    .zip(run.column(name))
                    .map(|(t, value)| (value - exact(*t)).abs())
                    .fold(0.0, f64::max);
                assert!(error < tolerance, "{context}: {name} off by {error:e}");
            }
        }
    }
}

/// The inputs recorded in the Lagrange-d'Alembert form are the laws at the
/// recorded state.
#[test]
fn the_recorded_inputs_are_the_laws_at_the_recorded_state() {
    let run = simulate(
        "recorded",
        &disk_arguments("rolling-disk", "lagrange", "rk4"),
    );
    let (theta, theta_rate, phi_rate) = (
        run.column("theta"),
        run.column("dot(theta)"),
        run.column("dot(phi)"),
    );
    let (steer, drive) = (run.column("u_steer"), run.column("u_drive"));
    for i in 0..run.rows.len() {
        let law = -0.0625 * (4.0 * (theta[i] - 1.0) + 2.0 * theta_rate[i]);
        assert!((steer[i] - law).abs() < 1e-12, "row {i}");
        assert!((drive[i] + 0.5 * phi_rate[i]).abs() < 1e-12, "row {i}");
    }
    assert!(steer.iter().any(|u| *u < -0.01), "the steering law turns");
}

/// A condition on an input: under [`STEERING`] the steering torque is
/// `4 j_vertical exp(-t) (cos(sqrt(3) t) - sin(sqrt(3) t)/sqrt(3))`, which
/// turns negative where `tan(sqrt(3) t) = sqrt(3)`, at `t = pi/(3 sqrt(3))`.
#[test]
fn a_condition_on_an_input_stops_where_its_closed_form_crosses() {
    let crossing = PI / (3.0 * 3f64.sqrt());
    for model in ["rolling-disk", DISK] {
        let loaded = Model::load(model, "jit");
        for (formulation, integrator) in RUNS.iter().filter(|(_, i)| *i != "midpoint") {
            let context = format!("{model} {formulation} {integrator}");
            let mut arguments = disk_arguments(model, formulation, integrator);
            arguments.extend(["--stop-when", "u_steer < 0"]);
            if *integrator == "discrete-gradient" {
                arguments.extend(["--dt", "0.001"]);
            }
            let run = simulated(loaded, &arguments[1..]);
            let (t, condition) = run.stopped();
            assert_eq!(condition, "u_steer < 0", "{context}");
            assert!((t - crossing).abs() < 1e-9, "{context}: {t}");
            let steer = run.last("u_steer");
            assert!(steer < 0.0 && steer > -1e-9, "{context}: {steer}");
        }
    }
}

/// The bicycle at 2 m/s, pushed in lean at 0.1 rad/s.
const BICYCLE_AT_2: [&str; 14] = [
    "bicycle",
    "--integrator",
    "rk4",
    "--initial",
    "dot(theta_r)=-2/rR",
    "--initial",
    "dot(phi)=0.1",
    "--initial",
    "dot(delta)=0",
    "--t-end",
    "10",
    "--dt",
    "0.002",
    "--formulation",
];

/// Below its weave speed (4.29 m/s) the benchmark bicycle falls: its
/// weave grows (at 2.7/s at 2 m/s) until the lean passes 0.5 rad, where
/// the run stops cleanly, within 3 s. Steering into the fall,
/// `steer_torque = 50 phi + 50 dot(phi)`, which places every eigenvalue of
/// the linearized closed loop in the left half plane (the slowest at
/// -1.47/s), keeps it upright for the 10 s: the lean stays below 0.007 rad,
/// below 3e-4 rad after 2 s, in the Lagrange-d'Alembert and the reduced
/// form alike (the same lean to 1e-11: measured 7e-13).
#[test]
fn steering_into_the_fall_keeps_the_bicycle_upright_below_its_weave_speed() {
    let bicycle = Model::load("bicycle", "jit");
    let mut leans = Vec::new();
    for formulation in ["lagrange", "reduced"] {
        let mut arguments = BICYCLE_AT_2.to_vec();
        arguments.extend([formulation, "--stop-when", "abs(phi) > 0.5"]);
        let falls = simulated(bicycle, &arguments[1..]);
        let (t, _) = falls.stopped();
        assert!(t < 3.0, "{formulation}: falls at {t}");
        assert!(
            (falls.last("phi").abs() - 0.5).abs() < 1e-6,
            "{formulation}"
        );

        let mut arguments = BICYCLE_AT_2.to_vec();
        arguments.extend([formulation, "--input", "steer_torque=50*phi+50*dot(phi)"]);
        let upright = simulated(bicycle, &arguments[1..]);
        assert_eq!(upright.last("t"), 10.0, "{formulation}");
        let lean: Vec<(f64, f64)> = upright
            .column("t")
            .into_iter()
            .zip(upright.column("phi"))
            .collect();
        let largest_after = |after: f64| {
            lean.iter()
                .filter(|(t, _)| *t >= after)
                .map(|(_, phi)| phi.abs())
                .fold(0.0, f64::max)
        };
        assert!(largest_after(0.0) < 0.007, "{formulation}");
        assert!(largest_after(2.0) < 3e-4, "{formulation}");
        assert!(largest_after(9.0) < 1e-7, "{formulation}");
        leans.push(upright.column("phi"));
    }
    let difference = leans[0]
        .iter()
        .zip(&leans[1])
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(difference < 1e-11, "{difference:e}");
}
