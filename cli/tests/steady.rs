//! `chaplygin steady` (docs/INTERFACE.md section 14): steady motions found
//! from unknowns of their point, checked against sources independent of
//! the tool. The rolling disk's steady turns against the Newton-Euler
//! condition of MATH.md section 6.2 and the radius `r |dot(theta)| /
//! |dot(psi)|` of its contact's circle; the benchmark bicycle's hands-free
//! turn at a small lean against the capsize speed of the linear benchmark
//! (Meijaard et al. 2007, closed form in `tests/support/benchmark_bicycle.rs`);
//! a turn simulated from the point found keeps its lean and steer, and its
//! rear contact follows a circle of the radius printed; the sleigh's
//! straight motions and their eigenvalue `-m a v / (I + m a^2)`; and bad
//! input, failing in one line.

use crate::support::benchmark_bicycle::BenchmarkParameters;
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

/// The value of the column `name` of a row.
fn value(header: &[String], row: &[f64], name: &str) -> f64 {
    column(header, &[row.to_vec()], name)[0]
}

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
        &[
            "--at",
            "phi=0.001",
            "--at",
            "dot(theta_r)=-v/rR",
            "--at",
            "dot(phi)=0",
            "--at",
            "dot(delta)=0",
            "--input",
            "steer_torque=0",
            "--solve",
            "delta,v",
            "--guess",
            "v=6",
        ],
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
        &[
            "--at",
            "phi=0.05",
            "--at",
            "dot(theta_r)=-v/rR",
            "--at",
            "dot(phi)=0",
            "--at",
            "dot(delta)=0",
            "--solve",
            "delta,v",
            "--guess",
            "v=6",
        ],
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
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("steady-bicycle-run");
    let mut arguments = vec!["simulate", "bicycle", "--t-end", "3", "--out"];
    arguments.push(out.to_str().expect("UTF-8"));
    for assignment in &initial {
        arguments.extend(["--initial", assignment]);
    }
    let output = chaplygin(&arguments);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let (run_header, rows) = read_csv(&out.join("trajectory.csv"));
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
    let bicycle = chaplygin(&[
        "steady",
        "bicycle",
        "--at",
        "phi=lean",
        "--at",
        "dot(theta_r)=-v/rR",
        "--at",
        "dot(phi)=0",
        "--at",
        "dot(delta)=0",
        "--solve",
        "delta,v,lean",
        "--guess",
        "v=6",
        "--guess",
        "lean=0.05",
    ]);
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
    let turn = [
        "--at",
        "phi=lean",
        "--at",
        "dot(theta_r)=-v/rR",
        "--at",
        "dot(phi)=0",
        "--at",
        "dot(delta)=0",
        "--input",
        "steer_torque=0",
        "--solve",
        "delta,v",
    ];
    let mut arguments = turn.to_vec();
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
