//! The `chaplygin` binary run as a user runs it: `list`, `derive`,
//! `simulate` (the CSV's header and energy, a `.model` file on the
//! interpreter against the built-in model on the JIT, determinism, the plots), and bad input (one line
//! on standard error, a non-zero exit, the CSV written so far kept valid),
//! `linearize` (eigenvalues, sweeps, and `--canonical`: the snakeboard's
//! canonical form against a hand derivation, the benchmark bicycle's against
//! the paper in `cli/tests/bicycle.rs`).

use crate::support::canonical_form::{assert_entries, printed_matrix};
use crate::support::scratch;
use std::path::Path;
use std::process::{Command, Output};

fn chaplygin(arguments: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_chaplygin"))
        .args(arguments)
        .output()
        .expect("the binary runs")
}

fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// A CSV's header and rows.
type Csv = (Vec<String>, Vec<Vec<f64>>);

/// The header and the rows of a CSV file, each row as long as the header.
fn read_csv(path: &Path) -> Csv {
    let text = std::fs::read_to_string(path).expect("the CSV exists");
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .expect("a header")
        .split(',')
        .map(String::from)
        .collect();
    let rows: Vec<Vec<f64>> = lines
        .map(|line| {
            line.split(',')
                .map(|v| v.parse().expect("a number"))
                .collect()
        })
        .collect();
    assert!(
        rows.iter().all(|row| row.len() == header.len()),
        "ragged CSV"
    );
    (header, rows)
}

/// Asserts a failed run with exactly one line on standard error containing
/// every one of `needles`.
fn assert_one_line_error(output: &Output, needles: &[&str]) {
    assert!(!output.status.success(), "succeeded: {}", stdout(output));
    let message = stderr(output);
    assert_eq!(message.trim_end().lines().count(), 1, "{message}");
    for needle in needles {
        assert!(message.contains(needle), "`{needle}` not in {message}");
    }
}

/// The snakeboard rolling with its wheels turned: at `theta = 0`,
/// `y' = 0` and `theta' = x' tan(phi) / r` satisfy both wheel constraints.
const SNAKEBOARD_ROLLING: [&str; 10] = [
    "--initial",
    "phi=0.4",
    "--initial",
    "dot(x)=1",
    "--initial",
    "dot(theta)=0.8455864374763236",
    "--initial",
    "dot(psi)=0.3",
    "--initial",
    "dot(phi)=0",
];

/// The CSV of a successful `chaplygin simulate` with `arguments`, written
/// into a scratch directory named after `name`.
fn simulated(name: &str, arguments: &[&str]) -> Csv {
    let out = scratch(&format!("cli-{name}"));
    let mut all = vec!["simulate"];
    all.extend(arguments);
    all.extend(["--out", out.path().to_str().unwrap()]);
    let output = chaplygin(&all);
    assert!(
        output.status.success(),
        "{arguments:?}: {}",
        stderr(&output)
    );
    read_csv(&out.path().join("trajectory.csv"))
}

#[test]
fn list_names_the_built_in_models() {
    let output = chaplygin(&["list"]);
    assert!(output.status.success());
    let text = stdout(&output);
    for model in ["snakeboard", "sleigh", "rolling-disk", "differential-drive"] {
        assert!(text.contains(model), "{model} missing from {text}");
    }
    assert!(text.contains("completely nonholonomic"), "{text}");
}

#[test]
fn derive_prints_the_reduced_equations_in_latex() {
    let output = chaplygin(&["derive", "snakeboard", "--format", "latex"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let latex = stdout(&output);
    // MATH.md 3.1: alpha1dot = -(sin(phi)/r) u1, alpha2dot = u1, alpha3dot = u2
    for equation in [
        r"\dot{\mathrm{group}} &= -\frac{u_{\mathrm{torso}} \sin\phi}{r}",
        r"\dot{\mathrm{torso}} &= u_{\mathrm{torso}}",
        r"\dot{\mathrm{wheels}} &= u_{\mathrm{wheels}}",
    ] {
        assert!(latex.contains(equation), "{equation} not in the document");
    }
    let json = stdout(&chaplygin(&["derive", "sleigh", "--format", "json"]));
    assert!(json.trim_start().starts_with('{') && json.contains("\"constraints\""));
}

/// The text document states MATH.md 3.1 line for line and the constraint
/// analysis with how it was decided.
#[test]
fn derive_prints_the_reduced_equations_as_text() {
    let output = chaplygin(&["derive", "snakeboard", "--format", "text"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    for line in [
        "dot(x) = cos(phi)*cos(theta)*group/m",
        "dot(theta) = sin(phi)*group/(m*r)",
        "dot(group) = -sin(phi)*u_torso/r",
        "dot(torso) = u_torso",
        "dot(wheels) = u_wheels",
        "growth vector: (3, 4, 5)",
        "integrability decided: exactly, on normal forms",
        "classification: completely nonholonomic",
    ] {
        assert!(text.contains(line), "`{line}` not in\n{text}");
    }
}

#[test]
fn the_controlled_snakeboard_keeps_its_energy_in_the_csv() {
    let out = scratch("cli-energy");
    let output = chaplygin(&[
        "simulate",
        "snakeboard",
        "--controller",
        "energy",
        "--integrator",
        "midpoint",
        "--t-end",
        "20",
        "--out",
        out.path().to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let (header, rows) = read_csv(&out.path().join("trajectory.csv"));
    assert_eq!(
        header.join(","),
        "t,x,y,theta,psi,phi,group,torso,wheels,xt,xw,u_torso,u_wheels,energy,constraint_residual"
    );
    assert_eq!(rows.len(), 2001);
    let energy0 = rows[0][13];
    for row in &rows {
        assert!(
            (row[13] - energy0).abs() <= 1e-10 * energy0,
            "{} vs {energy0}",
            row[13]
        );
    }
    // alpha1 grows from rest (MATH.md 3.2)
    assert_eq!(rows[0][6], 0.0);
    assert!(rows.iter().any(|row| row[6] > 0.1));
    let summary = stdout(&output);
    assert!(summary.contains("energy drift") && summary.contains("max constraint residual"));
    for plot in [
        "path.png",
        "energy.png",
        "constraint_residual.png",
        "figure4.png",
    ] {
        let bytes = std::fs::read(out.path().join(plot)).expect("the plot exists");
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{plot}");
    }
}

/// Asserts that two runs wrote the same columns and rows, to 1e-12
/// relative.
fn assert_same_run((header, rows): &Csv, (other_header, other_rows): &Csv) {
    assert_eq!(header, other_header);
    assert_eq!(rows.len(), other_rows.len());
    for (row, other) in rows.iter().zip(other_rows) {
        for (a, b) in row.iter().zip(other) {
            assert!(
                (a - b).abs() <= 1e-12 * a.abs().max(1.0),
                "{a} vs {b} at t = {}",
                row[0]
            );
        }
    }
}

#[test]
fn a_model_file_on_the_interpreter_runs_the_built_ins_trajectory_on_the_jit() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/snakeboard.model");
    let run = |model: &str, engine: &str| {
        let mut arguments = vec![model, "--initial", "dot(phi)=0.2", "--engine", engine];
        arguments.extend(["--input", "u_torso=0.05", "--t-end", "5"]);
        arguments.extend(SNAKEBOARD_ROLLING);
        simulated(&format!("snakeboard-{engine}"), &arguments)
    };
    assert_same_run(&run("snakeboard", "jit"), &run(file, "interpret"));
}

#[test]
fn the_same_command_writes_the_same_bytes() {
    let csv = |name: &str| {
        let out = scratch(&format!("cli-{name}"));
        let output = chaplygin(&[
            "simulate",
            "sleigh",
            "--integrator",
            "dopri5",
            "--t-end",
            "3",
            "--out",
            out.path().to_str().unwrap(),
        ]);
        assert!(output.status.success(), "{}", stderr(&output));
        std::fs::read(out.path().join("trajectory.csv")).unwrap()
    };
    assert_eq!(csv("first"), csv("second"));
}

#[test]
fn bad_input_is_one_line_and_a_failure() {
    assert_one_line_error(
        &chaplygin(&["simulate", "unicycle"]),
        &["unknown model `unicycle`", "snakeboard"],
    );
    assert_one_line_error(
        &chaplygin(&["simulate", "snakeboard", "--param", "mass=2"]),
        &["unknown parameter `mass`", "jw"],
    );
    assert_one_line_error(
        &chaplygin(&[
            "simulate",
            "sleigh",
            "--initial",
            "theta=0",
            "--initial",
            "dot(y)=1",
        ]),
        &["violates constraint `blade`", "1e0"],
    );
    assert_one_line_error(
        &chaplygin(&["simulate", "sleigh", "--initial", "speed=1"]),
        &["--initial: unknown name `speed`", "dot(theta)"],
    );
    assert_one_line_error(
        &chaplygin(&["simulate", "sleigh", "--controller", "energy"]),
        &["energy controller needs", "has no coordinate `phi`"],
    );
    assert!(
        !chaplygin(&["simulate", "snakeboard", "--integrator", "euler"])
            .status
            .success()
    );
}

/// The snakeboard `model` from `phi = 1.2` with the wheels driven
/// (`u_wheels = 0.05`, RK4), writing into `out`.
fn driven_into_phi_pi_2(model: &str, out: &Path) -> Output {
    chaplygin(&[
        "simulate",
        model,
        "--initial",
        "phi=1.2",
        "--input",
        "u_wheels=0.05",
        "--integrator",
        "rk4",
        "--out",
        out.to_str().unwrap(),
    ])
}

#[test]
fn a_singular_configuration_stops_the_run_with_a_valid_partial_csv() {
    let out = scratch("cli-singular");
    // phi'' = u_wheels / jw = 1 from phi = 1.2, phidot = 0.5: phi reaches pi/2 near t = 0.5
    let output = driven_into_phi_pi_2("snakeboard", out.path());
    assert_one_line_error(
        &output,
        &[
            "singular configuration at t = 0.",
            "the constraint rows front, back are dependent",
            "phi = 1.57",
            "det[A; V^T]",
        ],
    );
    let (header, rows) = read_csv(&out.path().join("trajectory.csv"));
    // t, the state, the inputs, energy, constraint_residual and chart
    assert_eq!(header.len(), 1 + 8 + 2 + 2 + 1);
    assert!(rows.len() > 10 && rows.iter().flatten().all(|v| v.is_finite()));
    assert!(rows.last().unwrap()[0] < 0.6);
}

/// A `.model` file's regularity measures (computed on run-time-sized
/// matrices) stop the run where the snakeboard's wheel constraints become
/// parallel, `phi = pi/2` (Duindam & Stramigioli 2004, section 3), in both
/// formulations.
#[test]
fn a_model_file_stops_at_the_singular_configuration_too() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/snakeboard.model");
    let out = scratch("cli-singular-file");
    // From rest at phi = 1.2, phi'' = u_wheels / jw = 1: phi = pi/2 at t = 0.86.
    let output = driven_into_phi_pi_2(file, out.path());
    assert_one_line_error(
        &output,
        &[
            "singular configuration at t = 0.8",
            "phi = 1.57",
            "det[A; V^T]",
        ],
    );
    // Started on the singular configuration, the Lagrange-d'Alembert form's
    // Gram matrix A g^-1 A^T is singular at once.
    let output = chaplygin(&[
        "simulate",
        file,
        "--formulation",
        "lagrange",
        "--initial",
        "phi=1.5707963267948966",
        "--out",
        out.path().to_str().unwrap(),
    ]);
    assert_one_line_error(
        &output,
        &["singular configuration at t = 0:", "Gram matrix A g^-1 A^T"],
    );
}

/// The snakeboard's coordinates from the momentum formulation (an ODE in
/// `(q, rdot, p)`) follow the Lagrange-d'Alembert run (in `(q, qdot)`) to
/// dopri5's accuracy.
#[test]
fn the_momentum_formulation_follows_the_lagrange_run() {
    let run = |formulation: &str| {
        let mut arguments = vec!["snakeboard", "--formulation", formulation];
        arguments.extend(["--integrator", "dopri5", "--input", "u_torso=0.05"]);
        arguments.extend(SNAKEBOARD_ROLLING);
        arguments.extend(["--t-end", "5"]);
        simulated(&format!("formulation-{formulation}"), &arguments)
    };
    let (lagrange_header, lagrange) = run("lagrange");
    let (momentum_header, momentum) = run("momentum");
    assert!(momentum_header.iter().any(|name| name == "dot(phi)"));
    assert!(momentum_header.iter().any(|name| name == "p1"));
    assert_eq!(lagrange.len(), momentum.len());
    for coordinate in ["t", "x", "y", "theta", "psi", "phi"] {
        let column = |header: &[String]| header.iter().position(|name| name == coordinate).unwrap();
        let (a, b) = (column(&lagrange_header), column(&momentum_header));
        for (row, other) in lagrange.iter().zip(&momentum) {
            assert!(
                (row[a] - other[b]).abs() <= 1e-6,
                "{coordinate}: {} vs {} at t = {}",
                row[a],
                other[b],
                row[0]
            );
        }
    }
}

/// The momentum formulation of a `.model` file through the interpreter runs
/// the trajectory of the built-in on the JIT; a file without a symmetry is
/// refused in one line.
#[test]
fn the_momentum_formulation_of_a_model_file_follows_the_built_in() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/snakeboard.model");
    let run = |model: &str, engine: &str| {
        let mut arguments = vec![model, "--formulation", "momentum", "--integrator", "rk4"];
        arguments.extend(["--input", "u_torso=0.05*sin(3*t)", "--t-end", "3"]);
        arguments.extend(["--engine", engine]);
        arguments.extend(SNAKEBOARD_ROLLING);
        simulated(&format!("momentum-{engine}"), &arguments)
    };
    assert_same_run(&run("snakeboard", "jit"), &run(file, "interpret"));
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/sleigh.model");
    let source = std::fs::read_to_string(file).unwrap();
    let without_symmetry: String = source
        .lines()
        .filter(|line| !line.trim_start().starts_with("symmetry:"))
        .map(|line| format!("{line}\n"))
        .collect();
    let directory = scratch("cli-no-symmetry");
    let path = directory.path().join("sleigh.model");
    std::fs::write(&path, without_symmetry).unwrap();
    assert_one_line_error(
        &chaplygin(&[
            "simulate",
            path.to_str().unwrap(),
            "--formulation",
            "momentum",
        ]),
        &["declares no symmetry"],
    );
}

/// The roller racer (`tests/models/roller_racer.model`; its runs in
/// every formulation: `cli/tests/cli_racers.rs`).
const RACER: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/models/roller_racer.model"
);

/// The racer's run in `formulation` with `integrator` and `arguments`: the
/// output, and the CSV when one was written.
fn racer(
    name: &str,
    formulation: &str,
    integrator: &str,
    arguments: &[&str],
) -> (Output, Option<Csv>) {
    let out = scratch(&format!("cli-racer-{name}-{formulation}-{integrator}"));
    let mut all = vec![
        "simulate",
        RACER,
        "--formulation",
        formulation,
        "--integrator",
        integrator,
        "--out",
        out.path().to_str().unwrap(),
    ];
    all.extend(arguments);
    let output = chaplygin(&all);
    let csv = out.path().join("trajectory.csv");
    let table = csv.exists().then(|| read_csv(&csv));
    (output, table)
}

/// The values of column `name`.
fn column_of(table: &Csv, name: &str) -> Vec<f64> {
    crate::support::column(&table.0, &table.1, name)
}

/// `--input NAME=EXPRESSION`: the model language's expressions of `t` and
/// the parameters, recorded as applied; a name that is neither, nor a
/// coordinate, is refused (feedback laws of the state: `cli/tests/cli_stop.rs`).
#[test]
fn inputs_are_expressions_of_time_and_the_parameters() {
    for (law, expected) in [
        (
            "u1=0.2*cos(2*t)",
            (|t: f64| 0.2 * (2.0 * t).cos()) as fn(f64) -> f64,
        ),
        ("u1=-d1^2*exp(-t)", |t: f64| -0.25 * (-t).exp()),
    ] {
        let (output, table) = racer(
            "law",
            "lagrange",
            "rk4",
            &[
                "--input",
                law,
                "--initial",
                "dot(x)=1",
                "--initial",
                "dot(phi)=0",
                "--t-end",
                "1",
            ],
        );
        assert!(output.status.success(), "{law}: {}", stderr(&output));
        let table = table.unwrap();
        for (t, u) in column_of(&table, "t").iter().zip(column_of(&table, "u1")) {
            assert!((u - expected(*t)).abs() <= 1e-15, "{law} at {t}: {u}");
        }
    }
    assert_one_line_error(
        &racer("law", "lagrange", "rk4", &["--input", "u1=0.2*cos(2*s)"]).0,
        &[
            "--input u1=0.2*cos(2*s)",
            "`s` is not `t`, a parameter or a coordinate",
        ],
    );
}

/// The default integrator is the discrete gradient for the reduced form,
/// which keeps the sleigh's energy (not quadratic in its state: the
/// metric turns with the heading) to round-off, and the midpoint rule for
/// the Lagrange-d'Alembert form; the summary names it.
#[test]
fn the_default_integrator_keeps_the_sleighs_energy_and_is_named() {
    let energy_drift = |summary: &str| -> f64 {
        let after = summary.split("energy drift ").nth(1).expect(summary);
        after.split(' ').next().unwrap().parse().unwrap()
    };
    let out = scratch("cli-default-integrator");
    let output = chaplygin(&[
        "simulate",
        "sleigh",
        "--t-end",
        "20",
        "--out",
        out.path().to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let summary = stdout(&output);
    assert!(
        summary.contains("2000 steps of discrete-gradient"),
        "{summary}"
    );
    assert!(energy_drift(&summary) <= 1e-12, "{summary}");
    let output = chaplygin(&[
        "simulate",
        "sleigh",
        "--formulation",
        "lagrange",
        "--t-end",
        "1",
        "--out",
        out.path().to_str().unwrap(),
    ]);
    assert!(
        stdout(&output).contains("steps of midpoint"),
        "{}",
        stdout(&output)
    );
}

/// `--initial` fixes the velocities given and solves the others from the
/// constraints: the sleigh's blade gives `dot(y) = tan(theta) dot(x)`.
#[test]
fn initial_velocities_not_given_are_solved_from_the_constraints() {
    let out = scratch("cli-solved-initial");
    let output = chaplygin(&[
        "simulate",
        "sleigh",
        "--formulation",
        "lagrange",
        "--initial",
        "theta=0.5",
        "--initial",
        "dot(x)=1",
        "--initial",
        "dot(theta)=0.2",
        "--t-end",
        "0.1",
        "--out",
        out.path().to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let (header, rows) = read_csv(&out.path().join("trajectory.csv"));
    let column = |name: &str| header.iter().position(|h| h == name).expect(name);
    assert!((rows[0][column("dot(y)")] - 0.5f64.tan()).abs() < 1e-15);
    assert_eq!(rows[0][column("dot(theta)")], 0.2);
    assert_one_line_error(
        &chaplygin(&["simulate", "sleigh", "--initial", "dot(theta)=1"]),
        &[
            "leave 1 direction free among dot(x), dot(y), which the constraints tie: give 1 of them too",
        ],
    );
}

/// The sleigh's straight motion at `dot(x) = 1`: the yaw rate decays like
/// `exp(-m a v t / (I + m a^2))` (`m = 1`, `I = 0.1`, `a = 0.5`: rate
/// -10/7), the forward speed is conserved (a zero); the built-in model and
/// its `.model` file through the interpreter print the same.
#[test]
fn linearize_prints_the_sleighs_eigenvalues() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/sleigh.model");
    let mut printed = Vec::new();
    for model in ["sleigh", file] {
        let output = chaplygin(&[
            "linearize",
            model,
            "--at",
            "dot(x)=1",
            "--at",
            "dot(theta)=0",
        ]);
        assert!(output.status.success(), "{}", stderr(&output));
        let text = stdout(&output);
        assert!(text.contains("-1.428571429e0 + 0.000000000e0 i"), "{text}");
        assert!(text.contains("(zero)"), "{text}");
        assert!(text.contains("(1 zeros counted as conserved"), "{text}");
        assert!(text.contains("asymptotically stable: yes"), "{text}");
        printed.push(text);
    }
    assert_eq!(printed[0], printed[1]);
}

/// The intervals printed under the line starting with `kind` (the
/// asymptotically or the neutrally stable ones): each `(refined, grid)`.
fn printed_intervals(text: &str, kind: &str) -> Vec<((f64, f64), (f64, f64))> {
    let pair = |text: &str| {
        let (a, b) = text.split_once(", ").expect("two ends");
        (a.parse().expect("a number"), b.parse().expect("a number"))
    };
    text.lines()
        .skip_while(|line| !line.starts_with(kind))
        .skip(1)
        .take_while(|line| line.starts_with("  ["))
        .map(|line| {
            let (refined, grid) = line
                .trim()
                .strip_prefix('[')
                .and_then(|rest| rest.split_once("] (grid points ["))
                .expect("an interval");
            (pair(refined), pair(grid.trim_end_matches("])")))
        })
        .collect()
}

/// `--sweep` over the sleigh's speed: one CSV row per grid point (STOP
/// included) with the hand eigenvalues `0` and `-m a v / (I + m a^2)`,
/// the plot, the stable interval `v > 0` on the grid with its start refined
/// to 0, and the neutral point `v = 0`.
#[test]
fn linearize_sweeps_write_the_eigenvalues_and_the_stable_intervals() {
    let out = scratch("cli-sweep");
    let output = chaplygin(&[
        "linearize",
        "sleigh",
        "--at",
        "dot(x)=v*cos(0.3)",
        "--at",
        "theta=0.3",
        "--at",
        "dot(theta)=0",
        "--sweep",
        "v=-1:1:0.25",
        "--param",
        "a=0.4",
        "--out",
        out.path().to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let (header, rows) = read_csv(&out.path().join("eigenvalues.csv"));
    assert_eq!(header, ["v", "re_1", "im_1", "re_2", "im_2"]);
    assert_eq!(rows.len(), 9);
    for row in &rows {
        let yaw = -0.4 * row[0] / (0.1 + 0.16);
        let (first, second) = if yaw > 0.0 { (yaw, 0.0) } else { (0.0, yaw) };
        assert!((row[1] - first).abs() < 1e-10, "{row:?}");
        assert!((row[3] - second).abs() < 1e-10, "{row:?}");
        assert_eq!((row[2], row[4]), (0.0, 0.0));
    }
    let bytes = std::fs::read(out.path().join("eigenvalues.png")).expect("the plot exists");
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let text = stdout(&output);
    let stable = printed_intervals(&text, "asymptotically stable");
    assert_eq!(stable.len(), 1, "{text}");
    let ((start, end), grid) = stable[0];
    assert_eq!((end, grid), (1.0, (0.25, 1.0)), "{text}");
    assert!((0.0..1e-9).contains(&start), "{text}");
    let neutral = printed_intervals(&text, "neutrally stable");
    assert_eq!(neutral.len(), 1, "{text}");
    let ((from, to), grid) = neutral[0];
    assert_eq!(grid, (0.0, 0.0), "{text}");
    assert!(from.abs() < 1e-9 && to.abs() < 1e-9, "{text}");
}

/// The leaning disk rolling upright at the spin rate `w`: its lean and
/// heading oscillate without decay (every eigenvalue but the conserved
/// quantities' zeros on the imaginary axis) exactly where `w^2 > g / (3 r)`
/// (a uniform disk, Bloch 2003, section 1.4), `w > 2.5573` at the defaults
/// `g = 9.81`, `r = 0.5`; the grid's end is refined to that closed form.
/// Nowhere is it asymptotically stable: rolling conserves energy.
#[test]
fn the_upright_disk_is_neutrally_stable_above_its_critical_spin() {
    let out = scratch("cli-disk-sweep");
    let output = chaplygin(&[
        "linearize",
        "rolling-disk-3d",
        "--at",
        "dot(theta)=w",
        "--at",
        "phi=0",
        "--at",
        "dot(phi)=0",
        "--at",
        "dot(psi)=0",
        "--sweep",
        "w=1:4:0.5",
        "--out",
        out.path().to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(text.contains("asymptotically stable for no w"), "{text}");
    let neutral = printed_intervals(&text, "neutrally stable");
    assert_eq!(neutral.len(), 1, "{text}");
    let ((from, to), grid) = neutral[0];
    assert_eq!((to, grid), (4.0, (3.0, 4.0)), "{text}");
    let critical = (9.81f64 / (3.0 * 0.5)).sqrt();
    assert!((from - critical).abs() < 1e-7, "{from} vs {critical}");
}

#[test]
fn linearize_bad_input_is_one_line_and_a_failure() {
    let sleigh = |extra: &[&str]| {
        let mut arguments = vec!["linearize", "sleigh", "--at", "dot(x)=1"];
        arguments.extend(extra);
        chaplygin(&arguments)
    };
    assert_one_line_error(
        &sleigh(&["--at", "dot(theta)=0.5"]),
        &["not a steady motion", "d/dt dot(theta)"],
    );
    assert_one_line_error(&sleigh(&[]), &["leave dot(theta) free: give it too"]);
    assert_one_line_error(
        &sleigh(&["--at", "dot(y)=1"]),
        &["violates constraint `blade`"],
    );
    assert_one_line_error(
        &sleigh(&[
            "--at",
            "dot(theta)=0",
            "--param",
            "m=0",
            "--param",
            "inertia=0",
        ]),
        &["mass matrix", "not positive definite"],
    );
    assert_one_line_error(
        &sleigh(&["--at", "dot(theta)=0", "--sweep", "v=0:1:0"]),
        &["STEP must be positive"],
    );
    assert_one_line_error(
        &sleigh(&["--at", "dot(theta)=0", "--sweep", "v=1:0:0.1"]),
        &["empty range"],
    );
    assert_one_line_error(
        &sleigh(&["--at", "dot(theta)=w"]),
        &["unknown name `w`", "inertia"],
    );
    assert_one_line_error(&sleigh(&["--at", "speed=1"]), &["unknown name `speed`"]);
    assert_one_line_error(
        &sleigh(&["--at", "dot(theta)=0", "--sweep", "m=1:2:1"]),
        &["`m` is a parameter"],
    );
    // A sweep stops at the first point that is no steady motion, naming it.
    assert_one_line_error(
        &sleigh(&["--at", "dot(theta)=w", "--sweep", "w=0:1:0.5"]),
        &["at w = 0.5:", "not a steady motion"],
    );
}

/// The thin disk declared in `models/tests/linearization.rs`: the body of
/// its `chaplygin::model!` invocation, the same text a `.model` file holds.
fn tilting_disk_text() -> String {
    let file = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../models/tests/linearization.rs"
    );
    let text = std::fs::read_to_string(file).expect("readable");
    let open =
        text.find("chaplygin::model! {").expect("the disk's macro") + "chaplygin::model! ".len();
    let mut depth = 0;
    for (offset, character) in text[open..].char_indices() {
        depth += match character {
            '{' => 1,
            '}' => -1,
            _ => 0,
        };
        if depth == 0 {
            return text[open + 1..open + offset].to_string();
        }
    }
    panic!("unbalanced braces in {file}");
}

/// A `.model` file with an `se2 * rotation` symmetry linearizes through the
/// interpreter: a thin disk (radius 0.5, g = 9.81) rolling upright at
/// `v = 0.5` (spin `Omega = 1`) is below the critical speed `sqrt(g r / 3)`,
/// and its lean grows at `sqrt(4/5 g/r - 12/5 Omega^2) = sqrt(13.296)`
/// (the classical lean equation, quoted in `models/tests/linearization.rs`).
#[test]
fn linearize_runs_a_model_file_with_a_rotation_symmetry() {
    let directory = scratch("cli-tilting-disk");
    let path = directory.path().join("disk.model");
    std::fs::write(&path, tilting_disk_text()).unwrap();
    let output = chaplygin(&[
        "linearize",
        path.to_str().unwrap(),
        "--at",
        "dot(psi)=0",
        "--at",
        "dot(phi)=0",
        "--at",
        "dot(theta)=1",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    let growth = format!("{:.9e}", 13.296f64.sqrt());
    assert!(text.contains(&growth), "{growth} not in {text}");
    assert!(text.contains("asymptotically stable: no"), "{text}");
}

/// The planar pendulum of `tests/models/planar_pendulum.model`: a bob at
/// `(x, z)` held at length `l = 1` by `x^2 + z^2 - l^2 = 0`.
const PLANAR_PENDULUM: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/models/planar_pendulum.model"
);

/// A bead in the tilted trough `z = 2 y^2 - 0.2 x` of
/// `tests/models/tilted_trough.model`, symmetric under translations along `x`.
const TILTED_TROUGH: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/models/tilted_trough.model"
);

/// Runs `simulate` on `model` with `arguments` and checks that it kept its
/// configuration constraint: the summary names the largest holonomic
/// residual, the CSV's last column is `holonomic_residual` (before `chart`
/// with several charts), and it and
/// `constraint(row)` recomputed from the coordinates stay within 1e-10 at
/// every row; the energy's relative drift stays within `energy_bound`.
/// Returns the CSV.
fn assert_kept_run(
    model: &str,
    arguments: &[&str],
    constraint: impl Fn(&Csv, usize) -> f64,
    energy_bound: f64,
) -> Csv {
    let context = format!("{model} {arguments:?}");
    let out = scratch(&format!(
        "cli-kept-{}",
        arguments.join("-").replace(['(', ')', '='], "")
    ));
    let mut all = vec!["simulate", model];
    all.extend(arguments);
    all.extend(["--out", out.path().to_str().unwrap()]);
    let output = chaplygin(&all);
    assert!(output.status.success(), "{context}: {}", stderr(&output));
    assert!(
        stdout(&output).contains("max holonomic residual"),
        "{context}: {}",
        stdout(&output)
    );
    let table = read_csv(&out.path().join("trajectory.csv"));
    let columns: Vec<&str> = table.0.iter().map(String::as_str).collect();
    let ending = match columns[..] {
        [.., last, "chart"] => last,
        [.., last] => last,
        [] => "",
    };
    assert_eq!(ending, "holonomic_residual", "{context}");
    for (row, recorded) in column_of(&table, "holonomic_residual").iter().enumerate() {
        let recomputed = constraint(&table, row);
        assert!(
            *recorded <= 1e-10 && recomputed.abs() <= 1e-10,
            "{context}: row {row}: {recorded:e}, {recomputed:e}"
        );
    }
    let energy = column_of(&table, "energy");
    let drift = energy
        .iter()
        .map(|e| ((e - energy[0]) / energy[0]).abs())
        .fold(0.0, f64::max);
    assert!(drift <= energy_bound, "{context}: energy drift {drift:e}");
    table
}

/// `name`'s value in `row`.
fn at(table: &Csv, name: &str, row: usize) -> f64 {
    column_of(table, name)[row]
}

/// From rest at `x = 0.6` (`z = 0.8` solved from the length), the
/// interpreted pendulum is kept on its circle after every step. Without
/// the projection the length drifted over these 20 s by 4.3e-7 (RK4),
/// 8.8e-4 (midpoint), 2.3e-9 (Dormand-Prince). The reduced form runs until
/// just before the bob passes under the pivot, where the tool's momentum
/// basis (solved for `dot(x)`) degenerates.
#[test]
fn a_model_file_with_a_holonomic_constraint_stays_on_it_in_every_run() {
    let length = |table: &Csv, row| at(table, "x", row).powi(2) + at(table, "z", row).powi(2) - 1.0;
    for (formulation, integrator, t_end, energy_bound) in [
        ("lagrange", "rk4", "20", 1e-5),
        ("lagrange", "midpoint", "20", 2e-3),
        ("lagrange", "dopri5", "20", 1e-7),
        ("reduced", "rk4", "0.7", 1e-6),
        ("reduced", "dopri5", "0.7", 1e-7),
    ] {
        let arguments = [
            "--formulation",
            formulation,
            "--integrator",
            integrator,
            "--initial",
            "x=0.6",
            "--t-end",
            t_end,
        ];
        let table = assert_kept_run(PLANAR_PENDULUM, &arguments, length, energy_bound);
        assert_eq!(at(&table, "z", 0), 0.8);
    }
}

/// The trough's height `z = 2 y^2 - 0.2 x` is solved at the start and kept
/// in every formulation, the momentum form's `(q, rdot)` rebuilt from the
/// projected configuration and velocity (measured energy drifts with RK4
/// over 10 s: 7.8e-7, 6.1e-6, 1.8e-4). Without the projection the momentum
/// form's height drifted by 3.6e-8.
#[test]
fn a_model_file_with_a_symmetry_stays_in_its_trough_in_the_momentum_form() {
    let trough = |table: &Csv, row| {
        at(table, "z", row) - 2.0 * at(table, "y", row).powi(2) + 0.2 * at(table, "x", row)
    };
    for (formulation, energy_bound) in [("lagrange", 1e-5), ("reduced", 1e-4), ("momentum", 1e-3)] {
        let arguments = [
            "--formulation",
            formulation,
            "--integrator",
            "rk4",
            "--initial",
            "y=0.3",
            "--initial",
            "dot(x)=-2",
            "--initial",
            "dot(y)=0",
            "--t-end",
            "10",
        ];
        let table = assert_kept_run(TILTED_TROUGH, &arguments, trough, energy_bound);
        assert!((at(&table, "z", 0) - 0.18).abs() <= 1e-15);
    }
}

/// The snakeboard (`models/snakeboard.model`: `T = m/2 (xdot^2 + ydot^2) +
/// j/2 thetadot^2 + jt thetadot psidot + jt/2 psidot^2 + jw/2 phidot^2`)
/// running straight at `dot(x) = v`, torso `psi` and wheels `phi` at 0 and at
/// rest. By hand: the constraints' difference gives `thetadot = v tan(phi) /
/// r`, so to first order `thetaddot = v phidot / r` (`vdot` is of second
/// order); neither constraint involves `psidot` or `phidot`, so the torso's
/// and the wheels' equations are `jt (thetaddot + psiddot) = u_torso` and
/// `jw phiddot = u_wheels`: `M = diag(jt, jw)`, `C1 = [[0, jt/r], [0, 0]]`,
/// no stiffness. Without a potential there is no gravity: `m` stands in for
/// it, and `K0` is 0 whatever it is.
#[test]
fn the_snakeboards_canonical_form_is_the_hand_derivation_on_both_engines() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/snakeboard.model");
    let (jt, jw, r) = (0.3, 0.05, 0.5);
    let expected = [
        ("M", [[jt, 0.0], [0.0, jw]]),
        ("C1", [[0.0, jt / r], [0.0, 0.0]]),
        ("K0", [[0.0; 2]; 2]),
        ("K2", [[0.0; 2]; 2]),
    ];
    let mut printed = Vec::new();
    for (model, engine) in [("snakeboard", "jit"), (file, "interpret")] {
        let output = chaplygin(&[
            "linearize",
            model,
            "--engine",
            engine,
            "--at",
            "dot(x)=v",
            "--at",
            "dot(psi)=0",
            "--at",
            "dot(phi)=0",
            "--canonical",
            "psi,phi",
            "--canonical-speed",
            "v=0.5,3",
            "--canonical-gravity",
            "m",
        ]);
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        let text = String::from_utf8(output.stdout).expect("UTF-8");
        assert!(
            text.contains("at v = 0.5 and v = 3") && text.contains("divided by m = 1"),
            "{text}"
        );
        for (name, matrix) in &expected {
            let found = printed_matrix(&text, name, ["psi", "phi"]);
            assert_entries(&found, matrix, &format!("{model}: {name}"));
        }
        printed.push(text);
    }
    assert_eq!(printed[0], printed[1]);
}

#[test]
fn canonical_requests_without_a_canonical_form_are_one_line_errors() {
    let snakeboard = |extra: &[&str]| {
        let mut arguments = vec!["linearize", "snakeboard", "--at", "dot(psi)=0"];
        arguments.extend(["--at", "dot(phi)=0", "--canonical-gravity", "m"]);
        arguments.extend(extra);
        chaplygin(&arguments)
    };
    let straight = ["--at", "dot(x)=v", "--canonical-speed", "v"];
    assert_one_line_error(
        &snakeboard(&[&straight[..], &["--canonical", "psi,steer"]].concat()),
        &["unknown coordinate `steer`", "x, y, theta, psi, phi"],
    );
    assert_one_line_error(
        &snakeboard(&[
            "--at",
            "dot(x)=1",
            "--canonical",
            "psi,phi",
            "--canonical-speed",
            "v",
        ]),
        &["--canonical-speed", "v", "no --at expression uses `v`"],
    );
    assert_one_line_error(
        &snakeboard(&[
            "--at",
            "dot(x)=jw",
            "--canonical",
            "psi,phi",
            "--canonical-speed",
            "jw",
        ]),
        &["`jw` is a parameter"],
    );
    assert_one_line_error(
        &snakeboard(&[&straight[..], &["--canonical", "psi,phi", "--param", "m=0"]].concat()),
        &["--canonical-gravity", "`m` is 0"],
    );
    // The torso alone: the wheels' rate enters its equation (C1's jt/r).
    assert_one_line_error(
        &snakeboard(&[&straight[..], &["--canonical", "psi"]].concat()),
        &["`dot(phi)` enters the equation of `dot(psi)`", "decouple"],
    );
    // The sleigh has no parameter `g`, and yawing at a constant rate is no
    // steady motion of it.
    let sleigh = |extra: &[&str]| {
        let mut arguments = vec!["linearize", "sleigh", "--at", "dot(x)=v"];
        arguments.extend(["--canonical", "theta", "--canonical-speed", "v"]);
        arguments.extend(extra);
        chaplygin(&arguments)
    };
    assert_one_line_error(
        &sleigh(&["--at", "dot(theta)=0"]),
        &["--canonical-gravity", "`g` is no parameter of the model"],
    );
    assert_one_line_error(
        &sleigh(&["--at", "dot(theta)=0.5", "--canonical-gravity", "m"]),
        &["at v = 1:", "not a steady motion", "d/dt dot(theta)"],
    );
}

/// Standard output closed by its reader before the command writes (as
/// `| head` does) ends the command quietly: no panic, no message.
#[test]
fn a_closed_output_ends_the_command_quietly() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_chaplygin"))
        .args(["derive", "sleigh"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the binary runs");
    drop(child.stdout.take());
    let output = child.wait_with_output().expect("the binary ends");
    assert!(output.status.success(), "{}", stderr(&output));
    assert_eq!(stderr(&output), "");
}

/// A tolerance that is negative, not finite, or zero with the other, and
/// `--fixed-step` with dopri5, are refused before the run, naming the
/// option.
#[test]
fn tolerances_that_cannot_be_met_are_refused_naming_the_option() {
    let sleigh = crate::support::in_process::Model::load("sleigh", "jit");
    for (options, expected) in [
        (
            &["--rtol=-1"][..],
            "--rtol -1: a tolerance is a finite number, not negative",
        ),
        (
            &["--atol", "inf"][..],
            "--atol inf: a tolerance is a finite number",
        ),
        (
            &["--rtol", "0", "--atol", "0"][..],
            "--rtol and --atol are both 0",
        ),
        (
            &["--integrator", "dopri5", "--fixed-step"][..],
            "--fixed-step takes rk4, midpoint",
        ),
    ] {
        let error = sleigh
            .simulate(options)
            .err()
            .unwrap_or_else(|| panic!("{options:?}"));
        assert!(error.contains(expected), "{options:?}: {error}");
    }
}
