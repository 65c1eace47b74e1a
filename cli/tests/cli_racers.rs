//! Roller racers through the command line, in every formulation and with
//! every integrator: `tests/models/roller_racer.model` (the joint ahead of
//! the first platform's axle) and `tests/models/trailing_racer.model` (the
//! second platform trailing behind a joint behind it, whose basis of D
//! chosen in the body frame degenerates where `d1 cos(phi) + d2 = 0` while
//! the constraint rows stay independent).
//!
//! Each run's energy is checked against the joint torque's work
//! `int u1 dphi`, computed by parts, `[u1 phi] - int phi u1'(t) dt`, with
//! Simpson's rule on the recorded joint angle (error of order `h^4` in the
//! recording interval, below the integrators' own): the difference is the
//! integrator's error alone. It is within Dormand-Prince's tolerance, and
//! for the fixed-step methods of order `p` (the midpoint rule and the
//! discrete gradient 2, RK4 4) it falls by at least `2^p / 2` when the step
//! halves (or is round-off at both steps): the error the method's order
//! implies at the step used, whatever its constant. The discrete gradient
//! also keeps its own discrete power balance,
//! `H(X) - H(x) = u1(t + h/2) (phi(X) - phi(x))` per step, to round-off.
//!
//! The balances take some 20 runs of one model each: they run in this
//! process ([`Model`]), the racer derived and compiled once per test, the
//! options read as the binary reads them; the swing through `phi = 0`, the
//! derivation report and the refused parameters run the binary.

use crate::support::in_process::Model;
use crate::support::{chaplygin, read_csv};
use std::path::PathBuf;

/// The roller racer with the joint ahead.
const RACER: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/models/roller_racer.model"
);

/// The racer whose second platform trails.
const TRAILING: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/models/trailing_racer.model"
);

/// Every formulation with every integrator it runs with.
const PAIRINGS: [(&str, &str); 10] = [
    ("reduced", "discrete-gradient"),
    ("reduced", "midpoint"),
    ("reduced", "rk4"),
    ("reduced", "dopri5"),
    ("lagrange", "midpoint"),
    ("lagrange", "rk4"),
    ("lagrange", "dopri5"),
    ("momentum", "midpoint"),
    ("momentum", "rk4"),
    ("momentum", "dopri5"),
];

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

    /// The energy gained minus the discrete gradient's work
    /// `sum u1(t + h/2) (phi(t + h) - phi(t))` over the recorded steps: its
    /// discrete power balance, exact for any input law.
    fn discrete_balance(&self, u1: impl Fn(f64) -> f64) -> f64 {
        let (t, phi, energy) = (self.column("t"), self.column("phi"), self.column("energy"));
        let work: f64 = (1..t.len())
            .map(|i| u1((t[i - 1] + t[i]) / 2.0) * (phi[i] - phi[i - 1]))
            .sum();
        energy[energy.len() - 1] - energy[0] - work
    }

    /// The energy gained minus the torque's work for the input law `u1`
    /// of derivative `rate` (see the module documentation).
    fn balance(&self, u1: impl Fn(f64) -> f64, rate: impl Fn(f64) -> f64) -> f64 {
        let (t, phi, energy) = (self.column("t"), self.column("phi"), self.column("energy"));
        let last = t.len() - 1;
        assert!(
            last % 2 == 0,
            "Simpson's rule needs an even number of intervals"
        );
        let h = t[1] - t[0];
        let simpson: f64 = (0..=last)
            .map(|i| {
                let weight = match i {
                    0 => 1.0,
                    i if i == last => 1.0,
                    i if i % 2 == 1 => 4.0,
                    _ => 2.0,
                };
                weight * phi[i] * rate(t[i])
            })
            .sum::<f64>()
            * h
            / 3.0;
        let work = u1(t[last]) * phi[last] - u1(t[0]) * phi[0] - simpson;
        energy[last] - energy[0] - work
    }
}

/// `simulate model` in `formulation` with `integrator`, step `dt`, and
/// `arguments`, through the binary.
fn simulate(
    model: &str,
    (formulation, integrator): (&str, &str),
    dt: &str,
    arguments: &[&str],
) -> Run {
    let mut hasher = std::hash::DefaultHasher::new();
    std::hash::Hash::hash(&(model, arguments), &mut hasher);
    let tag = std::hash::Hasher::finish(&hasher);
    let name = format!("racer-{tag:x}-{formulation}-{integrator}-{dt}");
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&out);
    let mut all = vec![
        "simulate",
        model,
        "--out",
        out.to_str().expect("a UTF-8 path"),
    ];
    all.extend(options((formulation, integrator), dt, arguments));
    let output = chaplygin(&all);
    let context = format!("{formulation} {integrator} {arguments:?}");
    assert!(
        output.status.success(),
        "{context}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let summary = String::from_utf8_lossy(&output.stdout)
        .lines()
        .next()
        .expect("a summary line")
        .to_string();
    let (header, rows) = read_csv(&out.join("trajectory.csv"));
    checked(
        Run {
            summary,
            header,
            rows,
        },
        &context,
    )
}

/// [`simulate`] of the loaded `model`, in this process.
fn simulated(
    model: &Model,
    (formulation, integrator): (&str, &str),
    dt: &str,
    arguments: &[&str],
) -> Run {
    let all = options((formulation, integrator), dt, arguments);
    let context = format!("{formulation} {integrator} {arguments:?}");
    let run = model
        .simulate(&all)
        .unwrap_or_else(|error| panic!("{context}: {error}"));
    let summary = run
        .outcome
        .unwrap_or_else(|error| panic!("{context}: {error}"));
    checked(
        Run {
            summary,
            header: run.header,
            rows: run.rows,
        },
        &context,
    )
}

/// The options of a run in `formulation` with `integrator`, step `dt`
/// (fixed, but for dopri5), and `arguments`.
fn options<'a>(
    (formulation, integrator): (&'a str, &'a str),
    dt: &'a str,
    arguments: &[&'a str],
) -> Vec<&'a str> {
    let mut all = vec![
        "--formulation",
        formulation,
        "--integrator",
        integrator,
        "--dt",
        dt,
    ];
    if order(integrator).is_some() {
        all.push("--fixed-step");
    }
    all.extend(arguments);
    all
}

/// `run`, which ended at 40 s with its constraints kept to 1e-9.
fn checked(run: Run, context: &str) -> Run {
    assert_eq!(*run.rows.last().expect("rows").first().expect("t"), 40.0);
    assert!(
        run.column("constraint_residual").iter().all(|r| *r < 1e-9),
        "{context}"
    );
    run
}

/// The order of a fixed-step integrator.
fn order(integrator: &str) -> Option<i32> {
    match integrator {
        "midpoint" | "discrete-gradient" => Some(2),
        "rk4" => Some(4),
        _ => None,
    }
}

/// Asserts the energy balance of `pairing`'s run `standard` at the step
/// 0.01 (and of `run` at 0.005 for the fixed-step methods) is the
/// integrator's error (see the module documentation): `balance` computes
/// it from a run, `u1` is the
/// input law (for the discrete gradient's own power balance, exact), and
/// `scale` the energy exchanged.
fn assert_balanced(
    pairing: (&str, &str),
    (standard, run): (&Run, impl Fn(&str) -> Run),
    (balance, u1): (impl Fn(&Run) -> f64, impl Fn(f64) -> f64),
    scale: f64,
) {
    let context = format!("{} {}", pairing.0, pairing.1);
    if pairing.1 == "discrete-gradient" {
        let discrete = standard.discrete_balance(&u1).abs();
        assert!(discrete < 1e-10 * scale.max(1.0), "{context}: {discrete:e}");
    }
    let coarse = balance(standard).abs();
    match (pairing.1, order(pairing.1)) {
        ("dopri5", _) => assert!(
            coarse < 40.0 * 1e-8 * scale.max(1.0),
            "{context}: {coarse:e}"
        ),
        (_, Some(p)) => {
            let fine = balance(&run("0.005")).abs();
            let floor = 1e-11 * scale.max(1.0);
            assert!(
                coarse < 1e-9 * scale.max(1.0) && fine < floor
                    || coarse >= 2f64.powi(p) / 2.0 * fine,
                "{context}: {coarse:e} at 0.01, {fine:e} at 0.005"
            );
            assert!(coarse < 1e-3 * scale.max(1.0), "{context}: {coarse:e}");
        }
        _ => unreachable!("{context}"),
    }
}

/// The racer's gait: the joint driven by `u1 = 0.2 cos(2 t)` from a straight
/// roll (`phi = 0`, `dot(x) = 1`, `dot(phi) = 0`) swings `phi` by +-0.06 and
/// keeps the heading within 0.4 rad, for 40 s, in every formulation.
#[test]
fn the_roller_racer_gait_swings_the_joint_and_balances_its_energy() {
    let gait = [
        "--input",
        "u1=0.2*cos(2*t)",
        "--initial",
        "dot(x)=1",
        "--initial",
        "dot(phi)=0",
        "--t-end",
        "40",
    ];
    let u1 = |t: f64| 0.2 * (2.0 * t).cos();
    let rate = |t: f64| -0.4 * (2.0 * t).sin();
    let model = Model::load(RACER, "jit");
    for pairing in PAIRINGS {
        let run = |dt: &str| simulated(model, pairing, dt, &gait);
        let standard = run("0.01");
        let phi = standard.column("phi");
        let swing = phi.iter().fold(0.0_f64, |m, p| m.max(p.abs()));
        assert!((0.05..0.06).contains(&swing), "{pairing:?}: {swing}");
        let heading = standard.column("theta");
        assert!(
            heading.iter().all(|h| (0.0..0.4).contains(h)),
            "{pairing:?}"
        );
        assert_balanced(
            pairing,
            (&standard, run),
            (|run: &Run| run.balance(u1, rate), u1),
            0.2 * swing,
        );
    }
}

/// The racer circling under a constant torque `u1 = 0.02` from
/// `phi = 0.3`: the joint stays within `[0.3, 1.4]` while the heading
/// turns through `+-pi/2` again and again (where a basis of D chosen in
/// the coordinates would degenerate; the tool's is chosen in the body
/// frame), in every formulation, for 40 s.
#[test]
fn the_roller_racer_circling_runs_40_s_in_every_form() {
    let circling = [
        "--input",
        "u1=0.02",
        "--initial",
        "phi=0.3",
        "--initial",
        "dot(x)=1",
        // the front axle's no-slip row: dot(theta) = sin(phi) / (d1 cos(phi) - d2)
        "--initial",
        "dot(theta)=1.6633259780808927",
        "--t-end",
        "40",
    ];
    let model = Model::load(RACER, "jit");
    for pairing in PAIRINGS {
        let run = |dt: &str| simulated(model, pairing, dt, &circling);
        let standard = run("0.01");
        let phi = standard.column("phi");
        assert!(phi.iter().all(|p| (0.3..=1.4).contains(p)), "{pairing:?}");
        let headings = standard.column("theta");
        let crossings = headings
            .windows(2)
            .filter(|w| {
                ((w[0] / std::f64::consts::PI - 0.5).floor())
                    != ((w[1] / std::f64::consts::PI - 0.5).floor())
            })
            .count();
        assert!(
            crossings >= 4,
            "{pairing:?}: {crossings} crossings of +-pi/2"
        );
        let turn = phi.last().expect("rows") - phi[0];
        let constant = |_: f64| 0.02;
        let balance = |run: &Run| run.balance(constant, |_| 0.0);
        assert_balanced(pairing, (&standard, run), (balance, constant), 0.02 * turn);
    }
}

/// The joint swinging through `phi = 0`: the derived momentum basis has
/// its factor `sin(phi)` divided out, so the momentum form's reconstruction
/// stays regular there, and the run ends where the Lagrange-d'Alembert
/// form's does.
#[test]
fn the_racer_swings_through_phi_0_in_the_momentum_form() {
    let swing = [
        "--initial",
        "phi=0.1",
        "--initial",
        "dot(x)=1",
        "--initial",
        "dot(phi)=-0.5",
        "--t-end",
        "40",
    ];
    let momentum = simulate(RACER, ("momentum", "rk4"), "0.01", &swing);
    let lagrange = simulate(RACER, ("lagrange", "rk4"), "0.01", &swing);
    let phi = momentum.column("phi");
    assert!(phi.iter().any(|v| *v < -0.01), "the joint swings through 0");
    for name in ["x", "y", "theta", "phi"] {
        let (a, b) = (momentum.column(name), lagrange.column(name));
        let (a, b) = (a.last().expect("rows"), b.last().expect("rows"));
        assert!((a - b).abs() < 1e-6, "{name}: {a} vs {b}");
    }
}

/// The trailing racer under a constant joint torque `u1 = 0.1` from rest:
/// the trailing platform swings round, through `cos(phi) = -d2/d1` (where
/// the basis chosen in the body frame degenerates) five times in 40 s, in
/// every formulation; the reduced form changes charts there and back, and
/// every run gains the torque's work `0.1 (phi(40) - phi(0))`.
#[test]
fn the_trailing_racer_turns_through_its_basis_singularity_in_every_form() {
    let (d1, d2) = (0.5, 0.3);
    let singular = |phi: f64| d1 * phi.cos() + d2;
    let torque = ["--input", "u1=0.1", "--t-end", "40"];
    let model = Model::load(TRAILING, "jit");
    for pairing in PAIRINGS {
        let run = |dt: &str| simulated(model, pairing, dt, &torque);
        let standard = run("0.01");
        let phi = standard.column("phi");
        let crossings = phi
            .windows(2)
            .filter(|w| singular(w[0]).signum() != singular(w[1]).signum())
            .count();
        assert!(crossings >= 5, "{pairing:?}: {crossings}");
        if pairing.0 == "reduced" {
            let charts = standard.column("chart");
            let switches = charts.windows(2).filter(|w| w[0] != w[1]).count();
            assert!(switches >= crossings, "{pairing:?}: {}", standard.summary);
        }
        let turn = phi.last().expect("rows") - phi[0];
        let constant = |_: f64| 0.1;
        let balance = |run: &Run| run.balance(constant, |_| 0.0);
        assert_balanced(pairing, (&standard, run), (balance, constant), 0.1 * turn);
    }
}

/// `derive` names the trailing racer's singular set, the minor's
/// determinant, and the chart that covers it.
#[test]
fn derive_reports_the_trailing_racers_singular_set_and_its_cover() {
    let output = chaplygin(&["derive", TRAILING]);
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        text.contains(
            "chart 0 (dependent v_y_body, omega_theta): degenerates where -d1*cos(phi) - d2 = 0"
        ),
        "{text}"
    );
    assert!(text.contains("e.g. phi = 2.2143"), "{text}");
    assert!(text.contains("covered by chart 1"), "{text}");
}

/// With `d1 = d2` the racer's derived momentum basis, normalized by its
/// value `d1 - d2` at the defaults, degenerates at every configuration:
/// the momentum formulation refuses to start, naming the divisor, while
/// the reduced form runs.
#[test]
fn parameters_that_make_the_momentum_basis_degenerate_are_refused_before_the_run() {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("racer-d1-d2");
    let arguments = |formulation: &'static str| {
        [
            "simulate",
            RACER,
            "--formulation",
            formulation,
            "--param",
            "d1=0.3",
            "--initial",
            "phi=0.3",
            "--initial",
            "dot(x)=1",
            "--initial",
            "dot(phi)=0",
            "--t-end",
            "1",
        ]
    };
    let mut momentum = arguments("momentum").to_vec();
    momentum.extend(["--out", out.to_str().expect("a UTF-8 path")]);
    let output = chaplygin(&momentum);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("degenerates at every configuration")
            && stderr.contains("a division in the momentum basis e(r): d1 - d2 must not vanish"),
        "{stderr}"
    );
    let mut reduced = arguments("reduced").to_vec();
    reduced.extend(["--out", out.to_str().expect("a UTF-8 path")]);
    assert!(chaplygin(&reduced).status.success());
}

/// The trailing racer under the constant torque, its steps following the
/// tolerance: at 1e-5 and at 1e-8, in every formulation with every
/// integrator, the configuration after 10 s (through the basis
/// singularity once) is within 100 times the tolerance of Dormand-Prince
/// at 1e-12, and no run warns (docs/INTERFACE.md section 12).
#[test]
fn the_trailing_racer_follows_the_tolerance_in_every_form() {
    let model = Model::load(TRAILING, "jit");
    let span = ["--input", "u1=0.1", "--t-end", "10"];
    let end = |options: &[&str]| {
        let run = model
            .simulate(&[&span[..], options].concat())
            .expect("the run starts");
        let summary = run.outcome.as_ref().expect("the run ends").clone();
        assert!(run.warnings.is_empty(), "{options:?}: {:?}", run.warnings);
        let last = ["x", "y", "theta", "phi"].map(|name| *run.column(name).last().expect("rows"));
        (summary, last)
    };
    let tight = [
        "--integrator",
        "dopri5",
        "--rtol",
        "1e-12",
        "--atol",
        "1e-12",
    ];
    let (_, reference) = end(&tight);
    for tolerance in ["1e-5", "1e-8"] {
        for (formulation, integrator) in PAIRINGS {
            let pairing = ["--formulation", formulation, "--integrator", integrator];
            let (summary, reached) =
                end(&[&pairing[..], &["--rtol", tolerance, "--atol", tolerance]].concat());
            let context = format!("{formulation} {integrator} at {tolerance}: {summary}");
            assert!(
                !summary.contains("chart switches 0") || formulation != "reduced",
                "{context}"
            );
            let error = (0..4)
                .map(|i| (reached[i] - reference[i]).abs())
                .fold(0.0, f64::max);
            let allowed = 100.0 * tolerance.parse::<f64>().expect("a number");
            assert!(error < allowed, "{context}: error {error:e}");
        }
    }
}
