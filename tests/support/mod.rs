//! What the command-line tests share: running the binary, reading the CSV
//! files it writes.

use std::path::Path;
use std::process::{Command, Output};

/// The `chaplygin` binary run with `arguments`.
pub fn chaplygin(arguments: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_chaplygin"))
        .args(arguments)
        .output()
        .expect("the binary runs")
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
