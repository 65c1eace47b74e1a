//! `chaplygin gait`: the net displacement per cycle of a prescribed shape
//! loop against the snakeboard's hand-derived momentum equation and
//! reconstruction (MATH.md section 4.1) and the three-link snake's
//! hand-derived connection (MATH.md section 4.3), integrated here
//! independently; the cycle's CSV, the path plot and the snake's
//! curvature plot; the models a gait cannot move.

use crate::support::snakeboard_gait::{GAIT, hand_derived_cycle, rk4_from_zero};

use crate::support::{chaplygin, read_csv, scratch};
use std::f64::consts::PI;

/// The three-link snake's loop `a1 = 0.8 + 0.35 cos t`, `a2 = -0.3 +
/// 0.35 sin t` by its hand-derived connection (l = 1): with `s_i = sin a_i`,
/// `c_i = cos a_i`, `d = (l/2) (s1 (1 + c2) - s2 (1 + c1))`,
/// `v1 = -(l/2)^2 ((1 + c2) a1dot + (1 + c1) a2dot) / d`, `v2 = 0`,
/// `omega = -(l/2) (s2 a1dot + s1 a2dot) / d`; RK4 over one period.
fn hand_derived_snake_cycle(steps: usize) -> [f64; 3] {
    let h_l = 0.5;
    let rate = |t: f64, s: [f64; 3]| {
        let (a1, a2) = (0.8 + 0.35 * t.cos(), -0.3 + 0.35 * t.sin());
        let (a1dot, a2dot) = (-0.35 * t.sin(), 0.35 * t.cos());
        let ((s1, c1), (s2, c2)) = (a1.sin_cos(), a2.sin_cos());
        let d = h_l * (s1 * (1.0 + c2) - s2 * (1.0 + c1));
        let v1 = -h_l * h_l * ((1.0 + c2) * a1dot + (1.0 + c1) * a2dot) / d;
        let omega = -h_l * (s2 * a1dot + s1 * a2dot) / d;
        [s[2].cos() * v1, s[2].sin() * v1, omega]
    };
    rk4_from_zero(rate, steps)
}

/// Runs `chaplygin` with `arguments`, which must succeed; its standard
/// output.
fn succeeded(arguments: &[&str]) -> String {
    let output = chaplygin(arguments);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// The numbers of the line `net displacement per cycle: x = X, y = Y, theta = TH`.
fn displacement(stdout: &str) -> [f64; 3] {
    let line = stdout
        .lines()
        .find_map(|line| line.strip_prefix("net displacement per cycle: "))
        .unwrap_or_else(|| panic!("no displacement line in {stdout}"));
    let values: Vec<f64> = line
        .split(", ")
        .map(|part| part.split(" = ").nth(1).unwrap().parse().unwrap())
        .collect();
    [values[0], values[1], values[2]]
}

#[test]
fn the_snakeboards_cycle_moves_it_as_the_hand_derived_equations_do() {
    let out = scratch("gait");
    assert_eq!(GAIT[8], format!("{}", 2.0 * PI));
    let arguments = [
        &["gait"],
        &GAIT[..],
        &["--cycles", "2", "--out", out.path().to_str().unwrap()],
    ];
    let stdout = succeeded(&arguments.concat());
    let moved = displacement(&stdout);
    let expected = hand_derived_cycle(20_000);
    assert!(
        expected[0].abs() > 0.5,
        "the gait moves the board: {expected:?}"
    );
    for (ours, theirs) in moved.iter().zip(&expected) {
        assert!((ours - theirs).abs() < 1e-8, "{moved:?} vs {expected:?}");
    }
    // From rest the board ends the cycle at rest: the second cycle repeats
    // the first in its own frame.
    assert!(stdout.contains("cycle 2: x = -0.80702920679"), "{stdout}");
    let (header, rows) = read_csv(&out.path().join("cycle.csv"));
    assert_eq!(header, ["t", "x", "y", "theta", "psi", "phi", "p1"]);
    assert_eq!(rows.len(), 2 * 2000 + 1);
    let last = rows.last().unwrap();
    assert!((last[0] - 4.0 * PI).abs() < 1e-12 && (last[5] - 0.5).abs() < 1e-12);
    let gait_path = std::fs::metadata(out.path().join("gait_path.png")).unwrap();
    assert!(gait_path.len() > 10_000);
    assert!(
        !out.path().join("curvature.png").exists(),
        "the snakeboard carries momentum"
    );
}

#[test]
fn the_snakes_cycle_moves_it_as_its_hand_derived_connection_does() {
    let out = scratch("gait-snake");
    let period = format!("{}", 2.0 * PI);
    let stdout = succeeded(&[
        "gait",
        "three-link-snake",
        "--shape",
        "a1,a2",
        "--cycle",
        "a1=0.8+0.35*cos(t)",
        "--cycle",
        "a2=-0.3+0.35*sin(t)",
        "--period",
        &period,
        "--out",
        out.path().to_str().unwrap(),
    ]);
    let moved = displacement(&stdout);
    let expected = hand_derived_snake_cycle(20_000);
    assert!(expected[0] > 0.3, "the loop moves the snake: {expected:?}");
    for (ours, theirs) in moved.iter().zip(&expected) {
        assert!((ours - theirs).abs() < 1e-8, "{moved:?} vs {expected:?}");
    }
    let plot = std::fs::read(out.path().join("curvature.png")).expect("curvature.png");
    assert_eq!(&plot[1..4], b"PNG");
    let (width, height) = (&plot[16..20], &plot[20..24]);
    assert_eq!(
        (width, height),
        (&1800u32.to_be_bytes()[..], &680u32.to_be_bytes()[..])
    );
    assert!(
        stdout.contains("wrote") && stdout.contains("curvature.png"),
        "{stdout}"
    );
}

#[test]
fn a_gait_needs_a_shape_that_determines_the_motion() {
    let refused = |arguments: &[&str], says: &str| {
        let output = chaplygin(arguments);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            !output.status.success() && stderr.contains(says),
            "{stderr}"
        );
    };
    let gait = |model: &'static str, shape: &'static str, law: &'static str| {
        vec![
            "gait", model, "--shape", shape, "--cycle", law, "--period", "1",
        ]
    };
    refused(&gait("sleigh", "a", "a=t"), "there is no shape for a gait");
    refused(
        &gait("rolling-disk-3d", "phi", "phi=0.1*sin(t)"),
        "the inputs enter the momentum equation",
    );
    refused(
        &gait("snakeboard", "psi", "psi=sin(t)"),
        "no law for phi (the shape coordinates of `snakeboard.model`: psi, phi)",
    );
    let mut unknown_name = gait("snakeboard", "psi,phi", "psi=sin(x)");
    unknown_name.extend(["--cycle", "phi=0"]);
    refused(
        &unknown_name,
        "--cycle psi=sin(x): `x` is neither `t` nor a parameter",
    );
    refused(
        &gait("snakeboard", "psi,phi", "psi=0"),
        "--shape names psi, phi but --cycle gives laws for psi",
    );
}
