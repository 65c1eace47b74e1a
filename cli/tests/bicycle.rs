//! The benchmark bicycle of Meijaard, Papadopoulos, Ruina and Schwab (2007)
//! from its declaration (`models/bicycle.model`: four bodies, two rolling
//! wheels, the front contact's height as a holonomic constraint), through
//! `chaplygin linearize bicycle`: its eigenvalues against the paper's closed
//! form, written out independently from the 25 parameters in
//! `models/tests/support/benchmark_bicycle.rs`, its stable speed range, and
//! its canonical form `M qddot + v C1 qdot + (g K0 + v^2 K2) q = f` in lean
//! `phi` and steer `delta` (the paper's equation (2.2)) against the matrices
//! the paper publishes for table 1 (quoted in MATH.md section 6) and against
//! the closed form of its appendix A, every entry to 1e-12 relative (1e-12
//! absolute where it is 0). Each command derives the bicycle once.

use crate::steady::ROLLING_AT_V;
use crate::support::benchmark_bicycle::{BenchmarkParameters, CanonicalMatrices};
use crate::support::canonical_form::{assert_entries, printed_matrix};
use nalgebra::{Complex, Matrix2};
use std::path::PathBuf;
use std::process::Command;

/// Upright straight running at speed `v` (a sweep variable), with
/// [`ROLLING_AT_V`].
const UPRIGHT: [&str; 4] = ["--at", "phi=0", "--at", "delta=0"];

/// The standard output of a successful `chaplygin linearize bicycle` about
/// upright running with `arguments` added.
fn upright(arguments: &[&str]) -> String {
    let output = Command::new(env!("CARGO_BIN_EXE_chaplygin"))
        .args(["linearize", "bicycle"])
        .args(ROLLING_AT_V)
        .args(UPRIGHT)
        .args(arguments)
        .output()
        .expect("runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).expect("UTF-8")
}

/// `eigenvalues.csv` of `chaplygin linearize bicycle ... --sweep SWEEP`:
/// per grid speed, the eigenvalues.
fn swept(name: &str, sweep: &str) -> Vec<(f64, Vec<Complex<f64>>)> {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&out);
    upright(&["--sweep", sweep, "--out", out.to_str().expect("UTF-8")]);
    let text = std::fs::read_to_string(out.join("eigenvalues.csv")).expect("written");
    text.lines()
        .skip(1)
        .map(|line| {
            let fields: Vec<f64> = line
                .split(',')
                .map(|f| f.parse().expect("a number"))
                .collect();
            let eigenvalues = fields[1..]
                .chunks(2)
                .map(|pair| Complex::new(pair[0], pair[1]))
                .collect();
            (fields[0], eigenvalues)
        })
        .collect()
}

/// The eigenvalues but the zero of the conserved front-wheel spin.
fn nonzero(eigenvalues: &[Complex<f64>]) -> Vec<Complex<f64>> {
    eigenvalues
        .iter()
        .copied()
        .filter(|s| s.norm() > 1e-9)
        .collect()
}

#[test]
fn the_eigenvalues_from_0_to_10_m_s_are_the_papers() {
    let reference = BenchmarkParameters::benchmark();
    let rows = swept("bicycle-eigenvalues", "v=0:10:1");
    assert_eq!(rows.len(), 11);
    for (v, eigenvalues) in rows {
        // Five: lean, steer and their rates, and the front wheel's spin,
        // whose rate is conserved (a zero eigenvalue).
        assert_eq!(eigenvalues.len(), 5, "at v = {v}");
        let declared = nonzero(&eigenvalues);
        let expected = reference.eigenvalues(v);
        assert_eq!(declared.len(), 4, "at v = {v}: {eigenvalues:?}");
        for s in expected {
            let closest = declared
                .iter()
                .map(|d| (d - s).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(
                closest <= 1e-9 * s.norm(),
                "at v = {v}: {s} is {closest:e} from the declared bicycle's {declared:?}"
            );
        }
    }
}

/// The first grid speed of `sweep` where every non-zero eigenvalue has a
/// negative real part changes from `before` to its negation.
fn stability_change(name: &str, sweep: &str, stable_before: bool) -> f64 {
    let rows = swept(name, sweep);
    let stable = |eigenvalues: &[Complex<f64>]| nonzero(eigenvalues).iter().all(|s| s.re < 0.0);
    let (v, _) = rows
        .iter()
        .find(|(_, eigenvalues)| stable(eigenvalues) != stable_before)
        .expect("the change lies in the sweep");
    *v
}

#[test]
fn the_weave_and_capsize_speeds_are_the_papers_to_1e_6() {
    let reference = BenchmarkParameters::benchmark();
    // Meijaard et al. (2007), section 6: 4.292382536341 and 6.024262015388 m/s.
    let weave = reference.weave_speeds()[0];
    let capsize = reference.capsize_speeds()[0];
    let onset = stability_change("bicycle-weave", "v=4.2923:4.2925:0.000001", false);
    let end = stability_change("bicycle-capsize", "v=6.0241:6.0243:0.000001", true);
    // The first stable grid point lies within one step above the weave speed,
    // the first unstable one within one step above the capsize speed.
    assert!(
        onset >= weave && onset - weave <= 1e-6 + 1e-12,
        "{onset} vs {weave}"
    );
    assert!(
        end >= capsize && end - capsize <= 1e-6 + 1e-12,
        "{end} vs {capsize}"
    );
}

/// The stable speed range the command prints, its ends refined between
/// the grid's points by bisection: the paper's weave and capsize speeds.
#[test]
fn the_printed_stable_range_is_the_papers_weave_to_capsize() {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bicycle-range");
    let text = upright(&[
        "--sweep",
        "v=3:7:0.5",
        "--out",
        out.to_str().expect("UTF-8"),
    ]);
    let line = text
        .lines()
        .skip_while(|line| !line.starts_with("asymptotically stable"))
        .nth(1)
        .expect("an interval");
    let reference = BenchmarkParameters::benchmark();
    let expected = format!(
        "  [{:.9}, {:.9}] (grid points [4.5, 6])",
        reference.weave_speeds()[0],
        reference.capsize_speeds()[0]
    );
    let ends = |line: &str| -> Vec<f64> {
        line.trim()[1..line.trim().find(']').expect("an end")]
            .split(", ")
            .map(|end| end.parse().expect("a number"))
            .collect()
    };
    for (found, paper) in ends(line).iter().zip(ends(&expected)) {
        assert!((found - paper).abs() < 1e-8, "{line} vs {expected}");
    }
    assert!(line.ends_with("(grid points [4.5, 6])"), "{line}");
}

/// The matrices of Meijaard et al. (2007), section 5 (MATH.md section 6),
/// rows `(phi, delta)`.
const PUBLISHED: [(&str, [[f64; 2]; 2]); 4] = [
    (
        "M",
        [
            [80.81722, 2.31941332208709],
            [2.31941332208709, 0.29784188199686],
        ],
    ),
    (
        "C1",
        [
            [0.0, 33.86641391492494],
            [-0.85035641456978, 1.68540397397560],
        ],
    ),
    (
        "K0",
        [
            [-80.95, -2.59951685249872],
            [-2.59951685249872, -0.80329488458618],
        ],
    ),
    ("K2", [[0.0, 76.59734589573222], [0.0, 2.65431523794604]]),
];

fn rows(matrix: &Matrix2<f64>) -> [[f64; 2]; 2] {
    [
        [matrix[(0, 0)], matrix[(0, 1)]],
        [matrix[(1, 0)], matrix[(1, 1)]],
    ]
}

#[test]
fn the_declared_bicycles_canonical_form_is_the_papers_to_1e_12() {
    let text = upright(&["--canonical", "phi,delta", "--canonical-speed", "v"]);
    assert!(
        text.contains("at v = 1 and v = 2") && text.contains("divided by g = 9.81"),
        "{text}"
    );
    let CanonicalMatrices { m, c1, k0, k2 } = BenchmarkParameters::benchmark().canonical();
    let closed_form = [("M", m), ("C1", c1), ("K0", k0), ("K2", k2)];
    for ((name, published), (_, closed)) in PUBLISHED.iter().zip(closed_form) {
        let found = printed_matrix(&text, name, ["phi", "delta"]);
        assert_entries(&found, published, &format!("{name} (published)"));
        assert_entries(&found, &rows(&closed), &format!("{name} (appendix A)"));
    }
}
