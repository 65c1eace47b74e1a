//! The engines of the command line (docs/guide/simulating.md, "The command line"): a model
//! from its text runs on native code compiled at run time (`--engine jit`,
//! the default) or on the IR interpreter (`--engine interpret`), with the
//! same numbers, since both run the same programs with the same operations;
//! the summary names the engine. The built-ins run from their text too.

use crate::support::in_process::Model;
use crate::support::{chaplygin, scratch};

const BICYCLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/bicycle.model");
const CASTER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/caster_robot.model");

/// Runs `chaplygin` with `arguments` and `--out` a scratch directory named
/// after `name`: its standard output.
fn run(name: &str, arguments: &[&str]) -> String {
    let out = scratch(&format!("engine-{name}"));
    let mut all = arguments.to_vec();
    all.extend(["--out", out.path().to_str().expect("path")]);
    let output = chaplygin(&all);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{arguments:?}: {stderr}");
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// The summary line without its wall time.
fn summary_without_time(stdout: &str) -> String {
    let line = stdout.lines().next().expect("a summary line");
    let (steps, rest) = line.split_once(" in ").expect("a time");
    let (_, after) = rest.split_once(" s, ").expect("an engine");
    format!("{steps} {after}")
}

/// The bicycle's file through the lean's push and the chart it runs in,
/// in the reduced form and in the Lagrange-d'Alembert form: the JIT's
/// trajectory is the interpreter's, digit for digit (bit for bit), and the
/// summaries differ only in the engine they name. In this process, the
/// file loaded once on each engine ([`Model`]); the tests below run the
/// binary on both.
#[test]
fn the_jit_runs_the_bicycle_file_as_the_interpreter_does() {
    let (jit, interpreter) = (
        Model::load(BICYCLE, "jit"),
        Model::load(BICYCLE, "interpret"),
    );
    for formulation in ["reduced", "lagrange"] {
        let options = [
            "--formulation",
            formulation,
            "--initial",
            "dot(theta_r)=-10",
            "--initial",
            "dot(phi)=0.5",
            "--initial",
            "dot(delta)=0",
            "--t-end",
            "0.5",
            "--dt",
            "0.005",
        ];
        let on = |model: &Model| {
            let run = model.simulate(&options).expect("the run starts");
            let summary = run.outcome.expect("the run ends");
            (summary, run.header, run.rows)
        };
        let (jit_summary, header, rows) = on(jit);
        let (interpreted_summary, interpreted_header, interpreted_rows) = on(interpreter);
        assert!(jit_summary.contains("engine jit"), "{jit_summary}");
        assert!(
            interpreted_summary.contains("engine interpret"),
            "{interpreted_summary}"
        );
        assert_eq!(rows.len(), 101, "{formulation}");
        let phi = header.iter().position(|h| h == "phi").expect("a column");
        assert!(rows[100][phi] > 0.05, "the lean moved: {}", rows[100][phi]);
        let bits = |rows: &[Vec<f64>]| -> Vec<Vec<u64>> {
            (rows.iter())
                .map(|row| row.iter().map(|value| value.to_bits()).collect())
                .collect()
        };
        assert_eq!(header, interpreted_header, "{formulation}");
        assert_eq!(bits(&rows), bits(&interpreted_rows), "{formulation}");
        assert_eq!(
            summary_without_time(&jit_summary).replace("jit", "interpret"),
            summary_without_time(&interpreted_summary)
        );
    }
}

/// The bicycle's linearization at 5 m/s from its file: the eigenvalues
/// printed are the same on both engines.
#[test]
fn the_jit_linearizes_as_the_interpreter_does() {
    let arguments = |engine| {
        [
            "linearize",
            BICYCLE,
            "--at",
            "dot(theta_r)=-5/rR",
            "--at",
            "dot(psi)=0",
            "--at",
            "dot(phi)=0",
            "--at",
            "dot(delta)=0",
            "--engine",
            engine,
        ]
    };
    let jit = run("linearize-jit", &arguments("jit"));
    let interpreted = run("linearize-interpret", &arguments("interpret"));
    assert!(jit.contains("asymptotically stable: yes"), "{jit}");
    assert_eq!(jit, interpreted);
}

/// Every built-in runs from its text on the JIT by default, as files do,
/// and on the interpreter when asked.
#[test]
fn the_summary_names_the_engine_of_each_built_in() {
    let engine_of = |model: &str| {
        let stdout = run(
            &format!("built-in-{model}"),
            &["simulate", model, "--t-end", "0.05"],
        );
        summary_without_time(&stdout)
    };
    let caster = engine_of("caster-robot");
    assert!(caster.contains("engine jit"), "{caster}");
    assert!(engine_of("bicycle").contains("engine jit"));
    assert!(engine_of("snakeboard").contains("engine jit"));
    let interpreted = run(
        "built-in-interpreted",
        &[
            "simulate",
            "sleigh",
            "--t-end",
            "0.05",
            "--engine",
            "interpret",
        ],
    );
    assert!(summary_without_time(&interpreted).contains("engine interpret"));
    let file = run(
        "caster-file",
        &[
            "simulate",
            CASTER,
            "--initial",
            "dot(phi_l)=1",
            "--initial",
            "dot(phi_r)=2",
            "--t-end",
            "0.05",
        ],
    );
    assert!(file.contains("engine jit"), "{file}");
}
