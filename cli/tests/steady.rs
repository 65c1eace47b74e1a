//! `chaplygin steady` (docs/INTERFACE.md section 14): steady motions found
//! from unknowns of their point, checked against sources independent of
//! the tool. The rolling disk's steady turns against the Newton-Euler
//! condition of MATH.md section 6.2 and the radius `r |dot(theta)| /
//! |dot(psi)|` of its contact's circle; the benchmark bicycle's hands-free
//! turn at a small lean against the capsize speed of the linear benchmark
//! (Meijaard et al. 2007, closed form in `tests/support/benchmark_bicycle.rs`);
//! a turn simulated from the point found (in this process, as `simulate`
//! runs it) keeps its lean and steer, and its rear contact follows a
//! circle of the radius printed; the sleigh's
//! straight motions and their eigenvalue `-m a v / (I + m a^2)`; and bad
//! input, failing in one line.

use crate::support::benchmark_bicycle::BenchmarkParameters;
use crate::support::in_process::Model;
use crate::support::{chaplygin, column, read_csv};
use std::path::PathBuf;

/// `chaplygin steady MODEL ARGS --out DIR` run successfully: its standard
/// output, and the header and row of `steady.csv`.
fn steady(name: &str, model: &str, arguments: &[&str]) -> (String, Vec<String>, Vec<f64>) {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&out);
    let mut all = vec!["steady", model, "--out", out.to_str().expect("UTF-8")];
    all.extend_from_slice(arguments);
    let output = chaplygin(&all);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let (header, mut rows) = read_csv(&out.join("steady.csv"));
    assert_eq!(rows.len(), 1);
    let stdout = String::from_utf8(output.stdout).expect("UTF-8");
    (stdout, header, rows.remove(0))
}

/// The benchmark bicycle simulated for `t_end` seconds from `initial`
/// (`NAME=VALUE` each), in this process as `chaplygin simulate bicycle`
/// runs it, on the bicycle loaded once for all the tests
/// (`support::in_process`): the header and rows of its trajectory.
fn bicycle_run(t_end: &str, initial: &[String]) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut options = vec!["--t-end", t_end];
    for assignment in initial {
        options.extend(["--initial", assignment.as_str()]);
    }
    let run = Model::load("bicycle", "jit").finished(&options);
    (run.header, run.rows)
}

/// The value of the column `name` of a row.
fn value(header: &[String], row: &[f64], name: &str) -> f64 {
    column(header, &[row.to_vec()], name)[0]
}

/// The bicycle rolling at `v` (a variable), its lean and steer constant.
pub const ROLLING_AT_V: [&str; 6] = [
    "--at",
    "dot(theta_r)=-v/rR",
    "--at",
    "dot(phi)=0",
    "--at",
    "dot(delta)=0",
];

/// The bicycle's `--at` assignments of a steady turn at `lean`
/// (`phi=...`), [`ROLLING_AT_V`], then `rest`.
fn bicycle_turn<'a>(lean: &'a str, rest: &[&'a str]) -> Vec<&'a str> {
    let mut arguments = vec!["--at", lean];
    arguments.extend(ROLLING_AT_V);
    arguments.extend(rest);
    arguments
}

/// A hands-free turn's input, its unknowns the steer and speed, and the
/// guess 6 m/s.
const HANDS_FREE_FROM_6: [&str; 6] = [
    "--input",
    "steer_torque=0",
    "--solve",
    "delta,v",
    "--guess",
    "v=6",
];

/// The disk's parameters (`models/rolling_disk_3d.model`'s defaults).
const MASS: f64 = 1.0;
const RADIUS: f64 = 0.5;
const GRAVITY: f64 = 9.81;

/// The spin `dot(theta)` of the disk's steady turn at lean `phi` and
/// turning rate `omega`, from the Newton-Euler condition (MATH.md section
/// 6.2): `A W^2 sin cos - (C + m r^2) w2 W cos - m g r sin = 0` with
/// `w2 = dot(theta) + W sin(phi)`, `A = m r^2/4`, `C = m r^2/2`.
fn disk_spin(phi: f64, omega: f64) -> f64 {
    let (a, c) = (MASS * RADIUS * RADIUS / 4.0, MASS * RADIUS * RADIUS / 2.0);
    let (sin, cos) = phi.sin_cos();
    let axial = (a * omega * omega * sin * cos - MASS * GRAVITY * RADIUS * sin)
        / ((c + MASS * RADIUS * RADIUS) * omega * cos);
    axial - omega * sin
}

/// The spin solved at several leans and turning rates (each sign) meets
/// the classical condition to 1e-9, and the radius printed is that of the
/// contact's circle, `r |dot(theta)| / |dot(psi)|`.
#[test]
fn the_disks_steady_turns_meet_the_newton_euler_condition() {
    for (phi, omega) in [(0.3, 1.5), (-0.2, 4.0), (0.6, -2.0), (0.05, 10.0)] {
        let (lean, turning) = (format!("phi={phi}"), format!("dot(psi)={omega}"));
        let (stdout, header, row) = steady(
            "steady-disk",
            "rolling-disk-3d",
            &[
                "--at",
                &lean,
                "--at",
                &turning,
                "--at",
                "dot(phi)=0",
                "--at",
                "dot(theta)=s",
                "--solve",
                "s",
                "--guess",
                "s=1",
            ],
        );
        let spin = value(&header, &row, "s");
        let expected = disk_spin(phi, omega);
        assert!(
            (spin - expected).abs() <= 1e-9 * expected.abs().max(1.0),
            "lean {phi}, turning {omega}: {spin} vs {expected}\n{stdout}"
        );
        let radius = value(&header, &row, "radius");
        let circle = RADIUS * expected.abs() / omega.abs();
        assert!(
            (radius - circle).abs() <= 1e-9 * circle,
            "{radius} vs {circle}"
        );
        assert!(
            stdout.contains("along the family of steady motions"),
            "{stdout}"
        );
    }
}

/// The eigenvalues of the disk's steady turn at lean `phi`, turning rate
/// `omega` and spin `spin`, `(re, im)`, from its Newton-Euler equations
/// linearized in closed form (MATH.md section 6.2): two zeros and
/// `+-sqrt(lambda^2)`.
fn disk_eigenvalues(phi: f64, omega: f64, spin: f64) -> [(f64, f64); 4] {
    let (a, c) = (MASS * RADIUS * RADIUS / 4.0, MASS * RADIUS * RADIUS / 2.0);
    let (leaning, rolling) = (a + MASS * RADIUS * RADIUS, c + MASS * RADIUS * RADIUS);
    let (sin, cos) = phi.sin_cos();
    let axial = spin + omega * sin;
    let squared = (MASS * GRAVITY * RADIUS * cos
        - a * omega * omega * (2.0 * phi).cos()
        - rolling * omega * axial * sin
        + (rolling * axial - 2.0 * a * omega * sin) * (2.0 * a * omega * sin - c * axial) / a
        - MASS * RADIUS * RADIUS * omega * omega * cos * cos)
        / leaning;
    let root = squared.abs().sqrt();
    match squared >= 0.0 {
        true => [(0.0, 0.0), (0.0, 0.0), (root, 0.0), (-root, 0.0)],
        false => [(0.0, 0.0), (0.0, 0.0), (0.0, root), (0.0, -root)],
    }
}

/// The eigenvalues `(re_i, im_i)` of a row of `steady.csv`.
fn eigenvalues(header: &[String], row: &[f64]) -> Vec<(f64, f64)> {
    (1..)
        .map(|i| (format!("re_{i}"), format!("im_{i}")))
        .take_while(|(re, _)| header.contains(re))
        .map(|(re, im)| (value(header, row, &re), value(header, row, &im)))
        .collect()
}

/// The eigenvalues at stable (imaginary pair) and unstable (real pair)
/// steady turns equal those of the closed-form linearization, as sets,
/// to 1e-6: each expected one has its own computed one that near.
#[test]
fn the_disks_eigenvalues_meet_the_closed_form_linearization() {
    for (phi, omega) in [(0.3, 1.5), (0.6, -2.0), (0.05, 3.0), (-0.3, 3.0)] {
        let (lean, turning) = (format!("phi={phi}"), format!("dot(psi)={omega}"));
        let (stdout, header, row) = steady(
            "steady-disk-eigenvalues",
            "rolling-disk-3d",
            &[
                "--at",
                &lean,
                "--at",
                &turning,
                "--at",
                "dot(phi)=0",
                "--at",
                "dot(theta)=s",
                "--solve",
                "s",
                "--guess",
                "s=1",
            ],
        );
        let mut computed = eigenvalues(&header, &row);
        let expected = disk_eigenvalues(phi, omega, value(&header, &row, "s"));
        assert_eq!(computed.len(), expected.len(), "{stdout}");
        for (re, im) in expected {
            let distance = |e: &(f64, f64)| (e.0 - re).hypot(e.1 - im);
            let nearest = (0..computed.len())
                .min_by(|&i, &j| distance(&computed[i]).total_cmp(&distance(&computed[j])))
                .expect("an eigenvalue left");
            let found = computed.remove(nearest);
            assert!(
                distance(&found) <= 1e-6,
                "lean {phi}, turning {omega}: {found:?} vs ({re}, {im})\n{stdout}"
            );
        }
    }
}

/// The turning rate solved from the spin, a root of the condition's
/// quadratic in `dot(psi)`, meets it to 1e-9.
#[test]
fn the_disks_turning_rate_solves_the_quadratic() {
    let (_, header, row) = steady(
        "steady-disk-turning",
        "rolling-disk-3d",
        &[
            "--at",
            "phi=0.4",
            "--at",
            "dot(theta)=-6",
            "--at",
            "dot(phi)=0",
            "--at",
            "dot(psi)=w",
            "--solve",
            "w",
            "--guess",
            "w=1",
        ],
    );
    let omega = value(&header, &row, "w");
    let spin = disk_spin(0.4, omega);
    assert!((spin + 6.0).abs() <= 1e-9 * 6.0, "w = {omega}: spin {spin}");
}

/// The bicycle's hands-free steady turn at lean 0.001: its speed is the
/// linear benchmark's capsize speed (where `det(g K0 + v^2 K2)` vanishes)
/// to 1e-4 m/s.
#[test]
fn the_bicycles_hands_free_turn_runs_at_the_capsize_speed() {
    let (stdout, header, row) = steady(
        "steady-bicycle-capsize",
        "bicycle",
        &bicycle_turn("phi=0.001", &HANDS_FREE_FROM_6),
    );
    let capsize = BenchmarkParameters::benchmark().capsize_speeds()[0];
    let speed = value(&header, &row, "v");
    assert!(
        (speed - capsize).abs() < 1e-4,
        "{speed} vs {capsize}\n{stdout}"
    );
    assert_eq!(value(&header, &row, "phi"), 0.001);
    assert_eq!(value(&header, &row, "steer_torque"), 0.0);
}

/// A coordinate that a configuration constraint ties, named an unknown,
/// is solved with the constraint a condition of its own. The bicycle's
/// pitch solved so in a steady turn is the pitch that completing the point
/// from its constraint gives, with the same speed and steer, to 1e-10. The
/// Ackermann car's right steer angle at rest is the linkage's closed form
/// `cot(delta_r) = cot(delta_l) + 2 b / l`. A constraint that neither the
/// unknowns nor the coordinates left unset change fails in one line
/// naming it and its residual.
#[test]
fn a_coordinate_a_configuration_constraint_ties_is_solved_from_it() {
    let (_, header, completed) = steady(
        "steady-pitch-completed",
        "bicycle",
        &bicycle_turn("phi=0.2", &HANDS_FREE_FROM_6),
    );
    let (_, solved_header, solved) = steady(
        "steady-pitch-solved",
        "bicycle",
        &bicycle_turn(
            "phi=0.2",
            &[
                "--input",
                "steer_torque=0",
                "--solve",
                "delta,v,theta_b",
                "--guess",
                "v=6",
            ],
        ),
    );
    for name in ["theta_b", "delta", "v"] {
        let (a, b) = (
            value(&header, &completed, name),
            value(&solved_header, &solved, name),
        );
        assert!(
            (a - b).abs() <= 1e-10 * a.abs().max(1.0),
            "{name}: {a} vs {b}"
        );
    }
    assert!(
        value(&header, &completed, "theta_b").abs() > 1e-4,
        "the pitch moves"
    );

    let car = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/models/ackermann_car.model"
    );
    let at_rest = [
        "--at",
        "dot(x)=0",
        "--at",
        "dot(delta_l)=0",
        "--at",
        "dot(delta_r)=0",
    ];
    let mut arguments = vec![
        "--at",
        "delta_l=0.3",
        "--solve",
        "delta_r",
        "--guess",
        "delta_r=0.2",
    ];
    arguments.extend(at_rest);
    let (_, header, row) = steady("steady-ackermann", car, &arguments);
    let linkage = (1.0 / (1.0 / 0.3f64.tan() + 2.0 * 0.4 / 1.0)).atan();
    let right = value(&header, &row, "delta_r");
    assert!((right - linkage).abs() < 1e-12, "{right} vs {linkage}");

    let mut all = vec![
        "steady",
        car,
        "--at",
        "delta_l=0.3",
        "--at",
        "delta_r=0.1",
        "--solve",
        "x",
    ];
    all.extend(at_rest);
    let output = chaplygin(&all);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && stderr.lines().count() == 1,
        "{stderr}"
    );
    let residual: f64 = stderr
        .split("the condition ackermann = 0 still fails by ")
        .nth(1)
        .and_then(|rest| rest.split(',').next())
        .and_then(|number| number.parse().ok())
        .unwrap_or_else(|| panic!("a residual in {stderr}"));
    let expected = 0.2f64.sin() - 2.0 * 0.4 * 0.3f64.sin() * 0.1f64.sin();
    assert!(
        (residual - expected).abs() < 1e-12,
        "{residual} vs {expected}"
    );
}

/// The circumradius of the triangle of three points.
fn circumradius(a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> f64 {
    let side = |p: (f64, f64), q: (f64, f64)| (p.0 - q.0).hypot(p.1 - q.1);
    let area = ((b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1)).abs() / 2.0;
    side(a, b) * side(b, c) * side(c, a) / (4.0 * area)
}

/// A hands-free turn at lean 0.05, simulated for 3 s from the point found:
/// lean and steer stay where they were to 1e-10, and the rear contact's
/// track is a circle of the radius printed (to 1e-6 relative).
#[test]
fn a_found_turn_simulated_stays_steady() {
    let (_, header, row) = steady(
        "steady-bicycle-turn",
        "bicycle",
        &bicycle_turn("phi=0.05", &["--solve", "delta,v", "--guess", "v=6"]),
    );
    let initial: Vec<String> = [
        "phi",
        "delta",
        "theta_b",
        "dot(theta_r)",
        "dot(phi)",
        "dot(delta)",
    ]
    .iter()
    .map(|name| format!("{name}={}", value(&header, &row, name)))
    .collect();
    let (run_header, rows) = bicycle_run("3", &initial);
    for shape in ["phi", "delta"] {
        let start = value(&header, &row, shape);
        let drift = (column(&run_header, &rows, shape).iter())
            .map(|v| (v - start).abs())
            .fold(0.0, f64::max);
        assert!(drift < 1e-10, "{shape} drifts by {drift:e}");
    }
    let (x, y) = (
        column(&run_header, &rows, "x_p"),
        column(&run_header, &rows, "y_p"),
    );
    let last = rows.len() - 1;
    let track = circumradius((x[0], y[0]), (x[last / 2], y[last / 2]), (x[last], y[last]));
    let radius = value(&header, &row, "radius");
    assert!(
        (track - radius).abs() < 1e-6 * radius,
        "{track} vs {radius}"
    );
}

/// The spread (largest less smallest) of a column over `t` in `[a, b]`.
fn spread(header: &[String], rows: &[Vec<f64>], name: &str, (a, b): (f64, f64)) -> f64 {
    let time = column(header, rows, "t");
    let values: Vec<f64> = (time.iter().zip(column(header, rows, name)))
        .filter(|(t, _)| (a..=b).contains(*t))
        .map(|(_, v)| v)
        .collect();
    let high = values.iter().copied().fold(f64::MIN, f64::max);
    let low = values.iter().copied().fold(f64::MAX, f64::min);
    high - low
}

/// The bicycle's hands-free turn at lean `lean` near the guess of speed
/// and steer: its verdict, its weave (the eigenvalue of largest real part,
/// `(re, im)`, `im > 0`), and the rate at which the lean's oscillation
/// grows in a simulation of 15 s from it with `dot(phi)` kicked by 1e-5
/// rad/s. The rate compares the lean's spread over a weave period from
/// second 5 with that over the period `n` periods later (as late as 15 s):
/// with the other modes decayed the oscillation repeats scaled by
/// `exp(re n T)`, and the family's zero only shifts it.
fn kicked_turn(lean: f64, guess: (f64, f64)) -> (bool, (f64, f64), f64) {
    let (phi, v, delta) = (
        format!("phi={lean}"),
        format!("v={}", guess.0),
        format!("delta={}", guess.1),
    );
    let (stdout, header, row) = steady(
        "steady-bicycle-kicked",
        "bicycle",
        &bicycle_turn(
            &phi,
            &["--solve", "delta,v", "--guess", &v, "--guess", &delta],
        ),
    );
    assert!(
        (value(&header, &row, "v") - guess.0).abs() < 0.1,
        "not the turn meant:\n{stdout}"
    );
    let weave = (eigenvalues(&header, &row).into_iter())
        .filter(|(_, im)| *im > 0.0)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .expect("a weave");
    let mut initial: Vec<String> = ["phi", "delta", "theta_b", "dot(theta_r)", "dot(delta)"]
        .iter()
        .map(|name| format!("{name}={}", value(&header, &row, name)))
        .collect();
    initial.push("dot(phi)=1e-5".into());
    let (run_header, rows) = bicycle_run("15", &initial);
    let period = std::f64::consts::TAU / weave.1;
    let periods = (9.0 / period).floor();
    let (first, last) = (5.0, 5.0 + periods * period);
    let (early, late) = (
        spread(&run_header, &rows, "phi", (first, first + period)),
        spread(&run_header, &rows, "phi", (last, last + period)),
    );
    let stable = value(&header, &row, "stable") == 1.0;
    (stable, weave, (late / early).ln() / (periods * period))
}

/// The verdicts on the handlebar-reversed family of hands-free turns
/// (docs/guide/stability.md), checked by simulation: at lean 0.72 on its
/// slow branch (marked stable) a kick in lean rate dies out, and at lean
/// 0.9 (marked unstable) it grows, each at the rate of the weave's real
/// part to 1%: the weave is the mode of largest real part at both.
#[test]
fn the_reversed_handlebars_turns_are_stable_where_marked() {
    for (lean, guess, marked) in [(0.72, (5.3, 3.45), true), (0.9, (6.9, 3.36), false)] {
        let (stable, weave, measured) = kicked_turn(lean, guess);
        assert_eq!(stable, marked, "lean {lean}");
        assert_eq!(measured < 0.0, marked, "lean {lean}: rate {measured}");
        assert!(
            (measured - weave.0).abs() < 0.01 * weave.0.abs(),
            "lean {lean}: simulated rate {measured} vs eigenvalue {weave:?}"
        );
    }
}

/// The handlebar-reversed family (docs/guide/stability.md), traced over
/// lean 0.55 to 0.91 from its fast branch, folds twice;
/// it becomes stable at its second fold, where the capsize mode's real
/// eigenvalue passes through zero, so the change is printed at the fold's
/// lean; the rows marked stable are those between it and the weave's
/// crossing, in the family's order.
#[test]
fn the_reversed_handlebars_family_is_stable_from_its_second_fold() {
    let (stdout, header, rows) = traced(
        "steady-bicycle-reversed",
        "bicycle",
        &bicycle_turn(
            "phi=lean",
            &[
                "--input",
                "steer_torque=0",
                "--solve",
                "delta,v",
                "--guess",
                "v=7.9",
                "--guess",
                "delta=3.23",
                "--trace",
                "lean=0.55:0.91:0.02",
            ],
        ),
    );
    let folds: Vec<f64> = (stdout.lines())
        .filter_map(|line| line.strip_prefix("fold at lean = "))
        .filter_map(|rest| rest.split_whitespace().next()?.parse().ok())
        .collect();
    assert_eq!(folds.len(), 2, "{stdout}");
    let stable_from = printed_value(&stdout, "stable from lean = ");
    let unstable_from = printed_value(&stdout, "unstable from lean = ");
    assert!((stable_from - folds[1]).abs() < 1e-9, "{stdout}");
    let (lean, stable) = (
        column(&header, &rows, "lean"),
        column(&header, &rows, "stable"),
    );
    let second_fold = (lean.windows(3))
        .rposition(|w| w[1] < w[0] && w[1] <= w[2])
        .expect("the second fold's row")
        + 1;
    for (i, (phi, marked)) in lean.iter().zip(&stable).enumerate() {
        let between = i > second_fold && *phi < unstable_from;
        assert_eq!(*marked == 1.0, between, "row {i}, lean {phi}\n{stdout}");
    }
}

/// The rolling disk's turns at turning rate 1.5 over its lean, traced
/// from 0.1: each row's spin meets the Newton-Euler condition to 1e-9, and
/// the family ends short of lean `pi/2` (by less than 0.01), where the
/// disk lies flat and the spin the condition asks, `-m g r / ((C + m r^2)
/// W cos(phi))` to leading order, grows without bound: the spin printed
/// there is the condition's at the lean printed.
#[test]
fn the_disks_family_ends_where_it_lies_flat() {
    let (stdout, header, rows) = traced(
        "steady-disk-flat",
        "rolling-disk-3d",
        &[
            "--at",
            "phi=lean",
            "--at",
            "dot(psi)=1.5",
            "--at",
            "dot(phi)=0",
            "--at",
            "dot(theta)=s",
            "--solve",
            "s",
            "--guess",
            "s=-1",
            "--trace",
            "lean=0.1:2:0.1",
        ],
    );
    let (lean, spin) = (column(&header, &rows, "lean"), column(&header, &rows, "s"));
    assert_eq!(lean.len(), 15, "{stdout}");
    for (phi, s) in lean.iter().zip(&spin) {
        let expected = disk_spin(*phi, 1.5);
        assert!(
            (s - expected).abs() <= 1e-9 * expected.abs().max(1.0),
            "{phi}: {s} vs {expected}"
        );
    }
    let end = printed_value(&stdout, "the family ends near lean = ");
    let short = std::f64::consts::FRAC_PI_2 - end;
    assert!((0.0..1e-2).contains(&short), "{stdout}");
    let last: f64 = (stdout.split("s grows without bound (s = ").nth(1))
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|text| text.parse().ok())
        .unwrap_or_else(|| panic!("the spin reached in\n{stdout}"));
    let expected = disk_spin(end, 1.5);
    assert!(
        (last - expected).abs() < 1e-3 * expected.abs(),
        "{last} vs {expected}: the lean printed to 1e-6, the spin's relative slope tan(lean) = {}",
        end.tan()
    );
}

/// The sleigh (built-in `sleigh`, `models/sleigh.model`: m = 1, inertia = 0.1, a = 0.5) moves
/// steadily only straight: from a turning guess the turning rate goes to
/// 0, the radius is infinite, and the eigenvalue besides the speed's zero
/// is `-m a v / (I + m a^2)` (MATH.md section 6.3): stable forwards,
/// unstable backwards.
#[test]
fn the_sleighs_steady_motions_are_straight() {
    for speed in [1.0, -2.0] {
        let forward = format!("dot(x)={speed}");
        let (stdout, header, row) = steady(
            "steady-sleigh",
            "sleigh",
            &[
                "--at",
                &forward,
                "--at",
                "dot(theta)=w",
                "--solve",
                "w",
                "--guess",
                "w=0.3",
            ],
        );
        assert!(value(&header, &row, "w").abs() < 1e-12, "{stdout}");
        assert_eq!(value(&header, &row, "radius"), f64::INFINITY);
        let rate = -0.5 * speed / (0.1 + 0.25);
        let nonzero: Vec<f64> = (header.iter().zip(&row))
            .filter(|(name, _)| name.starts_with("re_"))
            .map(|(_, re)| *re)
            .filter(|re| re.abs() > 1e-9)
            .collect();
        assert_eq!(nonzero.len(), 1, "{stdout}");
        assert!((nonzero[0] - rate).abs() < 1e-12, "{nonzero:?} vs {rate}");
        assert_eq!(
            value(&header, &row, "stable"),
            f64::from(u8::from(speed > 0.0))
        );
    }
}

/// Each mistake is one line on standard error and a failing status.
#[test]
fn bad_requests_fail_in_one_line() {
    let disk = "rolling-disk-3d";
    let turn = [
        "--at",
        "phi=0.3",
        "--at",
        "dot(psi)=0",
        "--at",
        "dot(phi)=0",
    ];
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["--at", "dot(theta)=s", "--solve", "s,z"],
            "--solve z: is neither a coordinate",
        ),
        (
            vec!["--at", "dot(theta)=q", "--solve", "s"],
            "unknown name `q`",
        ),
        (
            vec!["--at", "dot(theta)=s", "--solve", "r"],
            "--solve r: is a parameter",
        ),
        (
            vec!["--at", "dot(theta)=s", "--solve", "s,phi"],
            "--solve phi: is given by --at",
        ),
        (
            vec!["--at", "dot(theta)=s", "--solve", "s", "--guess", "k=1"],
            "--guess k: not an unknown",
        ),
        (
            vec!["--at", "dot(theta)=s", "--solve", "s", "--input", "steer=t"],
            "a steady motion's inputs are constants",
        ),
        (
            vec!["--at", "dot(theta)=s", "--solve", "s", "--guess", "s=2"],
            "no steady motion near the guess",
        ),
        (
            vec![
                "--at",
                "dot(theta)=s",
                "--solve",
                "s",
                "--trace",
                "s=0:1:0.5",
            ],
            "--trace s: is an unknown of --solve",
        ),
        (
            vec![
                "--at",
                "dot(theta)=s",
                "--solve",
                "s",
                "--trace",
                "m=0:1:0.5",
            ],
            "--trace m: is a parameter",
        ),
        (
            vec![
                "--at",
                "dot(theta)=s",
                "--solve",
                "s",
                "--trace",
                "k=0:1:0.5",
            ],
            "--trace k: no --at or --input expression reads it",
        ),
        (
            vec![
                "--at",
                "dot(theta)=s",
                "--solve",
                "s",
                "--trace",
                "k=1:0:0.5",
            ],
            "--trace k: empty range",
        ),
    ];
    for (arguments, says) in cases {
        let mut all = vec!["steady", disk];
        all.extend(turn);
        all.extend(&arguments);
        let output = chaplygin(&all);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{arguments:?} succeeds");
        assert_eq!(stderr.lines().count(), 1, "{arguments:?}: {stderr}");
        assert!(stderr.contains(says), "{arguments:?}: {stderr}");
    }
}

/// A disk leaning 0.3 rad but not turning has no steady motion at any
/// spin: its lean accelerates at `m g r sin(phi) / (A + m r^2)` whatever
/// the spin (MATH.md section 6.2, `W = 0`). Solving for the spin, alone and
/// as the first point of a trace over the turning rate from 0, fails in
/// one line naming that condition, the residual reached (the closed form,
/// to 1e-9) and every unknown by its name, the traced one too.
#[test]
fn no_steady_motion_names_the_condition_and_its_residual() {
    let lean_acceleration =
        MASS * GRAVITY * RADIUS * 0.3f64.sin() / (MASS * RADIUS * RADIUS * (0.25 + 1.0));
    let alone: &[&str] = &["--at", "dot(psi)=0"];
    let traced: &[&str] = &["--at", "dot(psi)=w", "--trace", "w=0:1:0.5"];
    for (turning, names) in [(alone, "(at s="), (traced, ", w=0)")] {
        let mut all = vec![
            "steady",
            "rolling-disk-3d",
            "--at",
            "phi=0.3",
            "--at",
            "dot(phi)=0",
            "--at",
            "dot(theta)=s",
            "--solve",
            "s",
        ];
        all.extend(turning.iter());
        let output = chaplygin(&all);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.contains(names), "{stderr}");
        let residual: f64 = (stderr
            .split("the condition d/dt dot(phi) = 0 still fails by ")
            .nth(1))
        .and_then(|rest| rest.split(',').next())
        .and_then(|text| text.parse().ok())
        .unwrap_or_else(|| panic!("the condition and its residual in {stderr}"));
        assert!(
            (residual.abs() - lean_acceleration).abs() < 1e-9 * lean_acceleration,
            "{residual} vs {lean_acceleration}"
        );
    }
}

/// More unknowns than the conditions fix: four on the sleigh's three rates,
/// and on the bicycle the lean with the speed and steer of a turn (a family
/// along the lean), named.
#[test]
fn unknowns_the_conditions_do_not_fix_are_refused() {
    let sleigh = chaplygin(&[
        "steady",
        "sleigh",
        "--at",
        "dot(x)=a1",
        "--at",
        "dot(y)=a2",
        "--at",
        "dot(theta)=a3",
        "--at",
        "theta=a4",
        "--solve",
        "a1,a2,a3,a4",
    ]);
    let stderr = String::from_utf8_lossy(&sleigh.stderr);
    assert!(
        stderr.contains("4 unknowns but only 3 conditions"),
        "{stderr}"
    );
    let mut arguments = vec!["steady", "bicycle"];
    arguments.extend(bicycle_turn(
        "phi=lean",
        &[
            "--solve",
            "delta,v,lean",
            "--guess",
            "v=6",
            "--guess",
            "lean=0.05",
        ],
    ));
    let bicycle = chaplygin(&arguments);
    let stderr = String::from_utf8_lossy(&bicycle.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("the conditions do not fix"), "{stderr}");
    assert!(stderr.contains("lean"), "{stderr}");
}

/// `chaplygin steady ... --trace ... --out DIR`: its standard output and
/// the rows of `steady.csv`, with `steady.png` written.
fn traced(name: &str, model: &str, arguments: &[&str]) -> (String, Vec<String>, Vec<Vec<f64>>) {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&out);
    let mut all = vec!["steady", model, "--out", out.to_str().expect("UTF-8")];
    all.extend_from_slice(arguments);
    let output = chaplygin(&all);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(out.join("steady.png").is_file());
    let (header, rows) = read_csv(&out.join("steady.csv"));
    (
        String::from_utf8(output.stdout).expect("UTF-8"),
        header,
        rows,
    )
}

/// The number printed after `prefix` at the start of a line of `stdout`.
fn printed_value(stdout: &str, prefix: &str) -> f64 {
    (stdout.lines())
        .find_map(|line| line.strip_prefix(prefix))
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|value| value.parse::<f64>().ok())
        .unwrap_or_else(|| panic!("`{prefix}` in\n{stdout}"))
}

/// The bicycle's hands-free turns over lean (INTERFACE.md section 14's
/// example): the family folds near lean 0.42 and comes back on a slower
/// branch, the rows in the family's order. The fold is the same, to 1e-9,
/// traced on a finer grid from lean 0.3. A row on each branch equals the
/// point solved alone, from its values rounded to 0.1, to 1e-9.
#[test]
fn the_bicycles_turns_fold_near_lean_0_42() {
    let turn = bicycle_turn("phi=lean", &HANDS_FREE_FROM_6[..4]);
    let mut arguments = turn.clone();
    arguments.extend(["--guess", "v=6", "--trace", "lean=0.01:0.5:0.01"]);
    let (stdout, header, rows) = traced("steady-bicycle-trace", "bicycle", &arguments);
    let lean = column(&header, &rows, "lean");
    let speed = column(&header, &rows, "v");
    let top = lean.iter().copied().fold(f64::MIN, f64::max);
    assert!((top - 0.42).abs() < 1e-12, "{lean:?}");
    let fold = printed_value(&stdout, "fold at lean = ");
    assert!((0.42..0.43).contains(&fold), "{stdout}");
    let mut finer = turn.to_vec();
    finer.extend(["--guess", "v=5.5", "--trace", "lean=0.3:0.5:0.005"]);
    let (again, _, _) = traced("steady-bicycle-trace-finer", "bicycle", &finer);
    let other = printed_value(&again, "fold at lean = ");
    assert!((fold - other).abs() < 1e-9, "{fold} vs {other}");
    let turning = lean.iter().position(|&l| l == top).expect("the top");
    assert!(lean[..=turning].windows(2).all(|w| w[1] > w[0]));
    assert!(lean[turning + 1..].windows(2).all(|w| w[1] < w[0]));
    assert!(
        stdout.contains("the family leaves the range at lean = 0.01"),
        "{stdout}"
    );
    let steer = column(&header, &rows, "delta");
    for index in [9, rows.len() - 10] {
        let phi = format!("phi={}", lean[index]);
        let (guess_v, guess_delta) = (
            format!("v={:.1}", speed[index]),
            format!("delta={:.1}", steer[index]),
        );
        let single: Vec<&str> = ["--at", phi.as_str()]
            .into_iter()
            .chain(turn[2..].iter().copied())
            .chain(["--guess", &guess_v, "--guess", &guess_delta])
            .collect();
        let (_, single_header, row) = steady("steady-bicycle-alone", "bicycle", &single);
        let v = value(&single_header, &row, "v");
        assert!(
            (v - speed[index]).abs() < 1e-9,
            "{phi}: {v} vs {}",
            speed[index]
        );
    }
}

/// The sleigh's straight motions over the speed: straight at every speed,
/// unstable backwards and stable forwards, the change located at 0 (where
/// `-m a v / (I + m a^2)` crosses zero) to 1e-9.
#[test]
fn the_sleigh_becomes_stable_at_zero_speed() {
    let (stdout, header, rows) = traced(
        "steady-sleigh-trace",
        "sleigh",
        &[
            "--at",
            "dot(x)=v",
            "--at",
            "dot(theta)=w",
            "--solve",
            "w",
            "--guess",
            "w=0.1",
            "--trace",
            "v=-1.1:1:0.3",
        ],
    );
    assert_eq!(column(&header, &rows, "v").len(), 8);
    assert!(column(&header, &rows, "w").iter().all(|w| w.abs() < 1e-12));
    let change = printed_value(&stdout, "stable from v = ");
    assert!(change.abs() < 1e-9, "{stdout}");
}
