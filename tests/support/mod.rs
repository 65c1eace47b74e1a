//! What the integration tests share: running the binary, scratch
//! directories, reading the CSV files it writes, the canonical form it
//! prints, the snakeboard's hand-derived gait, the benchmark bicycle's
//! closed form (from the models' tests), pages opened in headless Chromium,
//! the guide's Markdown, the numbers of printed lines.

#[allow(dead_code)]
#[path = "../../models/tests/support/benchmark_bicycle.rs"]
pub mod benchmark_bicycle;
pub mod browser;
pub mod canonical_form;
pub mod in_process;
pub mod markdown;
pub mod printed;
pub mod snakeboard_gait;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use tempfile::TempDir;

/// The benchmark bicycle's push, as `simulate bicycle` takes it: upright at
/// 3 m/s (`dot(theta_r) = -10` with `rR = 0.3`), leaning at 0.2 rad/s, steer
/// at rest, fixed steps of 1 ms.
pub const FALL: [&str; 9] = [
    "--initial",
    "dot(theta_r)=-10",
    "--initial",
    "dot(phi)=0.2",
    "--initial",
    "dot(delta)=0",
    "--fixed-step",
    "--dt",
    "0.001",
];

/// The `chaplygin` binary run with `arguments`.
pub fn chaplygin(arguments: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_chaplygin"))
        .args(arguments)
        .output()
        .expect("the binary runs")
}

/// A fresh, empty directory for the test named `name`, under the system's
/// temporary directory as `chaplygin-{name}-XXXXXX`: removed when the
/// returned guard is dropped, so bind it for as long as its path is used.
pub fn scratch(name: &str) -> TempDir {
    tempfile::Builder::new()
        .prefix(&format!("chaplygin-{name}-"))
        .tempdir()
        .expect("a scratch directory under the temporary directory")
}

/// The path of the program `program` on `PATH`, for a test that needs it;
/// `None` after saying the test skipped, where it is not there and the
/// environment variable `variable` is not `require` (as `.ci/run` sets
/// it, after installing the program when missing, as `install` says).
pub fn tool(program: &str, variable: &str, install: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH").unwrap_or_default();
    let found = std::env::split_paths(&path)
        .map(|dir| dir.join(program))
        .find(|candidate| candidate.is_file());
    if found.is_none() {
        assert_ne!(
            std::env::var(variable).as_deref(),
            Ok("require"),
            "{program} is not on PATH: install it ({install})"
        );
        eprintln!(
            "skipped: {program} is not on PATH ({install}); {variable}=require makes this a \
             failure, as in CI"
        );
    }
    found
}

/// The values of the column `name` of `rows` under `header`.
pub fn column(header: &[String], rows: &[Vec<f64>], name: &str) -> Vec<f64> {
    let at = (header.iter())
        .position(|column| column == name)
        .unwrap_or_else(|| panic!("a column `{name}` in {header:?}"));
    rows.iter().map(|row| row[at]).collect()
}

/// The header and the rows of a CSV file the command wrote.
pub fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).expect("the file is written");
    let mut lines = text.lines();
    let header = lines.next().expect("a header");
    let columns = header.split(',').map(String::from).collect();
    let rows = lines
        .map(|line| {
            line.split(',')
                .map(|v| v.parse().expect("a number"))
                .collect()
        })
        .collect();
    (columns, rows)
}

/// Asserts that every `.rs` file in `dir` (relative to `manifest_dir`) but
/// `main.rs` is declared `mod NAME;` in its `main.rs`, the root of that
/// crate's test binary: with `autotests = false`, a file not declared there
/// would not run at all.
pub fn assert_declared(manifest_dir: &str, dir: &str) {
    let dir = Path::new(manifest_dir).join(dir);
    let main = std::fs::read_to_string(dir.join("main.rs")).expect("the tests' main.rs");
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(&dir).expect("the tests' folder") {
        let path = entry.expect("an entry").path();
        let Some(name) = path.file_name().and_then(|name| name.to_str()) else {
            continue;
        };
        let Some(module) = name.strip_suffix(".rs") else {
            continue;
        };
        if module != "main" && !main.lines().any(|line| line == format!("mod {module};")) {
            missing.push(name.to_string());
        }
    }
    assert!(
        missing.is_empty(),
        "not declared in {}: {missing:?}",
        dir.join("main.rs").display()
    );
}
