//! What the command line's tests share: running the binary, reading the
//! CSV files it writes, the benchmark bicycle's push, the canonical form
//! it prints, runs in the test process as the binary makes them; and the
//! library's test support (`tests/support/`): scratch directories, the
//! snakeboard's hand-derived gait, the benchmark bicycle's closed form,
//! pages opened in headless Chromium, the guide's Markdown, the numbers of
//! printed lines.

pub mod canonical_form;
pub mod in_process;

// The library's tests use the rest of it.
#[allow(dead_code)]
#[path = "../../../tests/support/mod.rs"]
mod library;

pub use library::{benchmark_bicycle, browser, markdown, printed, scratch, snakeboard_gait};

use std::path::Path;
use std::process::{Command, Output};

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

/// The `chaplygin` binary run with `arguments`, sent Ctrl-C (`SIGINT`)
/// three seconds after it starts: its output, once it has failed.
pub fn interrupted(arguments: &[&str]) -> Output {
    let child = Command::new(env!("CARGO_BIN_EXE_chaplygin"))
        .args(arguments)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("starts");
    std::thread::sleep(std::time::Duration::from_secs(3));
    let signal = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(signal.success());
    let output = child.wait_with_output().expect("ends");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "{stderr}");
    output
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
