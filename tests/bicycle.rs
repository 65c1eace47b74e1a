//! The benchmark bicycle of Meijaard, Papadopoulos, Ruina and Schwab (2007)
//! from its declaration (`models/bicycle.model`: four bodies, two rolling
//! wheels, the front contact's height as a holonomic constraint), through
//! `chaplygin linearize bicycle`: its eigenvalues against the paper's closed
//! form, written out independently from the 25 parameters in
//! `models/tests/support/benchmark_bicycle.rs`, and its stable speed range.

#[allow(dead_code)]
#[path = "../models/tests/support/benchmark_bicycle.rs"]
mod benchmark_bicycle;

use benchmark_bicycle::BenchmarkParameters;
use nalgebra::Complex;
use std::path::PathBuf;
use std::process::Command;

/// Upright straight running at speed `v` (a sweep variable).
const UPRIGHT: [&str; 10] = [
    "--at",
    "dot(theta_r)=-v/rR",
    "--at",
    "dot(phi)=0",
    "--at",
    "dot(delta)=0",
    "--at",
    "phi=0",
    "--at",
    "delta=0",
];

/// `eigenvalues.csv` of `chaplygin linearize bicycle ... --sweep SWEEP`:
/// per grid speed, the eigenvalues.
fn swept(name: &str, sweep: &str) -> Vec<(f64, Vec<Complex<f64>>)> {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&out);
    let output = Command::new(env!("CARGO_BIN_EXE_chaplygin"))
        .args(["linearize", "bicycle"])
        .args(UPRIGHT)
        .args(["--sweep", sweep, "--out"])
        .arg(&out)
        .output()
        .expect("runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
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
