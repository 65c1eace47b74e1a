//! Chart switching through the command line (docs/guide/simulating.md, "Chart switching"):
//! a `.model` file whose basis of D degenerates where its constraint row
//! does not (`tests/models/sleigh_no_symmetry.model`) runs through those
//! configurations in the interpreted reduced form, the summary line counts
//! the switches and `trajectory.csv` has a `chart` column; a basis regular
//! everywhere is never changed; a declared momentum basis hands over to a
//! run-time chart where it degenerates.

use crate::support::{chaplygin, column, read_csv, scratch};
use std::f64::consts::PI;

const FIXTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/models/sleigh_no_symmetry.model"
);

/// Runs `simulate` with `arguments` into a scratch directory named after
/// `name`: the summary line, the CSV's header and its rows.
fn simulate(name: &str, arguments: &[&str]) -> (String, Vec<String>, Vec<Vec<f64>>) {
    let out = scratch(&format!("charts-{name}"));
    let mut all = vec!["simulate"];
    all.extend(arguments);
    all.extend(["--out", out.path().to_str().expect("path")]);
    let output = chaplygin(&all);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{arguments:?}: {stderr}");
    let summary = String::from_utf8_lossy(&output.stdout)
        .lines()
        .next()
        .expect("a summary line")
        .to_string();
    let (header, rows) = read_csv(&out.path().join("trajectory.csv"));
    (summary, header, rows)
}

/// Asserts the recorded energies differ from the first by less than 1e-12
/// of it.
fn assert_energy_kept(energy: &[f64]) {
    let drift = energy
        .iter()
        .map(|e| (e - energy[0]).abs())
        .fold(0.0, f64::max);
    assert!(drift < 1e-12 * energy[0], "{drift:e}");
}

/// The number after `chart switches ` in a summary line.
fn switches(summary: &str) -> usize {
    summary
        .split("chart switches ")
        .nth(1)
        .and_then(|rest| rest.split(|c: char| !c.is_ascii_digit()).next())
        .and_then(|count| count.parse().ok())
        .unwrap_or_else(|| panic!("no switch count in {summary}"))
}

#[test]
fn a_model_file_runs_through_its_basis_singularities_by_switching_charts() {
    let (summary, header, rows) = simulate(
        "sleigh",
        &[
            FIXTURE,
            "--initial",
            "dot(x)=-0.2",
            "--initial",
            "dot(theta)=3",
            "--t-end",
            "20",
        ],
    );
    assert!(summary.contains("discrete-gradient"), "{summary}");
    let theta = column(&header, &rows, "theta");
    // theta passes pi/2, 3 pi/2, 5 pi/2 and 7 pi/2, where the chart of
    // dot(y) degenerates: into the chart of dot(x) and back each time
    assert!(theta.last().expect("rows") > &(3.5 * PI), "{summary}");
    let count = switches(&summary);
    assert!(count >= 7, "{summary}");
    let chart = column(&header, &rows, "chart");
    assert_eq!(chart.windows(2).filter(|w| w[0] != w[1]).count(), count);
    assert!(chart.iter().all(|&c| c == 0.0 || c == 1.0));
    assert_energy_kept(&column(&header, &rows, "energy"));
    let residual = column(&header, &rows, "constraint_residual");
    assert!(residual.iter().all(|&r| r < 1e-9));
}

/// The sleigh's basis chosen in the body frame is regular at every
/// heading: the run never changes chart (its `chart` column, there for
/// every model with constraints since the run-time charts could take over,
/// stays 0).
#[test]
fn a_basis_regular_everywhere_is_never_changed() {
    let (summary, header, rows) = simulate("one-chart", &["sleigh", "--t-end", "1"]);
    assert_eq!(switches(&summary), 0, "{summary}");
    assert!(column(&header, &rows, "chart").iter().all(|&c| c == 0.0));
}

/// The sleigh with a declared momentum basis `(g X)^T` for the coordinate
/// basis `X = [(1, tan(theta), 0), (0, 0, 1)]`, whose momenta are
/// unbounded where the heading passes `+-pi/2` although the blade's row is
/// regular there.
const TAN_SLEIGH: &str = "
pub struct TanSleigh {
    coordinates: [x, y, theta],
    parameters: [m = 1.0, inertia = 0.1, a = 0.5],
    kinetic_energy: m/2*((dot(x) - a*sin(theta)*dot(theta))^2
        + (dot(y) + a*cos(theta)*dot(theta))^2) + inertia/2*dot(theta)^2,
    constraints: [blade = -sin(theta)*dot(x) + cos(theta)*dot(y)],
    momentum_basis: [
        forward = [m, m*tan(theta), 0],
        turning = [-m*a*sin(theta), m*a*cos(theta), inertia + m*a^2],
    ],
}
";

/// Where the declared basis degenerates, the step that fails in it is
/// taken again in the run-time chart of coordinate partitioning, and the
/// run goes on through `theta = pi/2` (the switches counted) with its
/// energy kept to the discrete gradient's round-off (fixed steps); its end is the
/// Lagrange-d'Alembert run's (Dormand-Prince, an independent formulation
/// with multipliers) to the discrete gradient's second order: the
/// difference falls about 4 times when the step halves.
#[test]
fn a_declared_basis_hands_over_to_a_run_time_chart_where_it_degenerates() {
    let directory = scratch("charts-tan-sleigh");
    let model = directory.path().join("tan_sleigh.model");
    std::fs::write(&model, TAN_SLEIGH).expect("written");
    let model = model.to_str().expect("a UTF-8 path");
    let start = [
        "--initial",
        "theta=1.2",
        "--initial",
        "dot(theta)=1",
        "--initial",
        "dot(x)=0.1",
        "--t-end",
        "10",
    ];
    let run = |name: &str, extra: &[&str]| {
        let mut arguments = vec![model];
        arguments.extend(start);
        arguments.extend(extra);
        simulate(name, &arguments)
    };
    let (_, header, rows) = run(
        "tan-reference",
        &["--formulation", "lagrange", "--integrator", "dopri5"],
    );
    let end = |header: &[String], rows: &[Vec<f64>]| {
        ["x", "y", "theta"].map(|name| *column(header, rows, name).last().expect("rows"))
    };
    let reference = end(&header, &rows);
    let mut errors = Vec::new();
    for dt in ["0.01", "0.005"] {
        let (summary, header, rows) = run(&format!("tan-{dt}"), &["--dt", dt, "--fixed-step"]);
        assert!(switches(&summary) >= 2, "{summary}");
        let theta = column(&header, &rows, "theta");
        assert!(theta.last().expect("rows") > &2.5, "through pi/2");
        assert_energy_kept(&column(&header, &rows, "energy"));
        let reached = end(&header, &rows);
        let error = (0..3)
            .map(|i| (reached[i] - reference[i]).abs())
            .fold(0.0, f64::max);
        errors.push(error);
    }
    assert!(
        errors[0] < 2e-2 && errors[0] > 3.0 * errors[1],
        "{errors:?}"
    );
}

#[test]
fn derive_lists_the_charts() {
    let output = chaplygin(&["derive", FIXTURE]);
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        text.contains(
            "the runtime switches where the active one degenerates): 0: dot(y); 1: dot(x)"
        ),
        "{text}"
    );
}

/// The planar pendulum in Cartesian coordinates
/// (`tests/models/planar_pendulum.model`): its row `2 x dot(x) + 2 z
/// dot(z)` solved for `dot(x)` divides by `x`, which vanishes where the bob
/// passes below or above the pivot (and the chart of `dot(z)` where `z`
/// does). Let go at `(0.6, 0.8)` it swings round and round, through `x = 0`
/// three times in 5 s, switching between the two charts (seven times), with
/// its energy kept by the discrete gradient's fixed steps.
#[test]
fn the_cartesian_pendulum_swings_through_x_0_by_switching_charts() {
    let pendulum = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/models/planar_pendulum.model"
    );
    let (summary, header, rows) = simulate(
        "pendulum",
        &[
            pendulum,
            "--initial",
            "x=0.6",
            "--t-end",
            "5",
            "--fixed-step",
        ],
    );
    let x = column(&header, &rows, "x");
    let crossings = x
        .windows(2)
        .filter(|w| w[0].signum() != w[1].signum())
        .count();
    assert_eq!(crossings, 3);
    assert!(switches(&summary) >= 2 * crossings, "{summary}");
    assert_energy_kept(&column(&header, &rows, "energy"));
}
