//! What the integration tests share, here and in the command line's tests
//! (`cli/tests`, whose support adds running the binary): scratch
//! directories, the snakeboard's hand-derived gait, the benchmark
//! bicycle's closed form (from the models' tests), pages opened in
//! headless Chromium, the guide's Markdown, the numbers of printed lines.

#[allow(dead_code)]
#[path = "../../models/tests/support/benchmark_bicycle.rs"]
pub mod benchmark_bicycle;
// Parts of these only the command line's tests use.
#[allow(dead_code)]
pub mod browser;
#[allow(dead_code)]
pub mod markdown;
pub mod printed;
#[allow(dead_code)]
pub mod snakeboard_gait;

use std::path::{Path, PathBuf};
use tempfile::TempDir;

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
