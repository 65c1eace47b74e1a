//! The README's first model as a user builds it: a crate of its own, in a
//! scratch directory, whose `Cargo.toml` has the README's dependency line
//! (its path this repository) and whose `main` is the README's first
//! example, built and run, offline (with the versions of the workspace's
//! `Cargo.lock`, whose crates the workspace's own build fetched). What it
//! pulls in is the library alone: none of the crates of the JIT, the
//! command line, the plots or gait design.
//!
//! It builds where and as the compile-fail cases' project builds
//! (`codegen/macros/compile-fail`, trybuild's): in `target/tests/trybuild`,
//! for the host named as `--target`, without debug information and not
//! incrementally. So the macro, its engine and their dependencies, built
//! for the host, are built once for both tests, and kept from one run to
//! the next. From nothing, built in release in a folder of its own, this
//! test took 107 s of CPU and the compile-fail cases 60 s; built this way,
//! 79 s and then 4 s (BENCHMARKS.md, "Test time: less work").

use crate::support::markdown::{blocks, root};
use crate::support::scratch;
use std::path::Path;
use std::process::{Command, Output};

/// The crates of the tools a dependency on `chaplygin` leaves out (as
/// their names start): the JIT's code generator, the command line's
/// parser, the plots and the gait optimizer.
const TOOLS: [&str; 4] = ["cranelift", "clap", "plotters", "argmin"];

/// The README's text between `<!-- ANCHOR: first_model -->` and its end.
fn first_model_section() -> String {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README.md");
    let start = readme
        .find("<!-- ANCHOR: first_model -->")
        .expect("the first model's anchor");
    let end = readme
        .find("<!-- ANCHOR_END: first_model -->")
        .expect("the first model's anchor's end");
    readme[start..end].to_string()
}

/// Cargo run with `arguments` in the crate `directory`, offline, with the
/// settings of trybuild's project (the module's documentation).
fn cargo(directory: &Path, arguments: &[&str]) -> Output {
    Command::new(env!("CARGO"))
        .args(arguments)
        .arg("--offline")
        .current_dir(directory)
        .env("CARGO_TARGET_DIR", root().join("target/tests/trybuild"))
        .env("CARGO_PROFILE_DEV_DEBUG", "false")
        .env("CARGO_INCREMENTAL", "0")
        .env_remove("RUSTFLAGS")
        .output()
        .expect("cargo runs")
}

/// The host's target tuple, as the toolchain's `rustc` prints it.
fn host() -> String {
    let rustc =
        Path::new(env!("CARGO")).with_file_name(format!("rustc{}", std::env::consts::EXE_SUFFIX));
    let printed = Command::new(rustc)
        .args(["--print", "host-tuple"])
        .output()
        .expect("rustc runs");
    assert!(printed.status.success(), "{printed:?}");
    String::from_utf8(printed.stdout)
        .expect("UTF-8")
        .trim()
        .to_string()
}

#[test]
fn the_readme_s_first_model_builds_and_runs_in_a_crate_of_its_own() {
    let section = first_model_section();
    let found = blocks(&section);
    let manifest = (found.iter())
        .find(|block| block.info == "toml")
        .expect("the README's dependency line, a `toml` block opening the first model");
    let example = (found.iter())
        .find(|block| block.info == "rust")
        .expect("the README's first model, a `rust` block");
    assert!(
        section.find("```toml") < section.find("```rust"),
        "the dependency line comes first"
    );
    let [table, line] = &manifest.lines[..] else {
        panic!("`[dependencies]` and one line: {:?}", manifest.lines)
    };
    assert_eq!(table, "[dependencies]");
    let (before, after) = line
        .split_once("path = \"")
        .and_then(|(before, rest)| Some((before, rest.split_once('"')?.1)))
        .unwrap_or_else(|| panic!("a path dependency: {line}"));
    assert!(before.starts_with("chaplygin = {"), "{line}");
    let here = root().display().to_string();

    let directory = scratch("user-crate");
    let crate_dir = directory.path();
    std::fs::create_dir(crate_dir.join("src")).expect("src/");
    std::fs::write(
        crate_dir.join("Cargo.toml"),
        format!(
            "[package]\nname = \"first-model\"\nversion = \"0.1.0\"\nedition = \"2024\"\n\n\
             {table}\n{before}path = {here:?}{after}\n"
        ),
    )
    .expect("Cargo.toml");
    std::fs::copy(root().join("Cargo.lock"), crate_dir.join("Cargo.lock")).expect("Cargo.lock");
    // As rustdoc runs the README's example: its lines in `main`.
    std::fs::write(
        crate_dir.join("src/main.rs"),
        format!("fn main() {{\n{}\n}}\n", example.lines.join("\n")),
    )
    .expect("main.rs");

    let tree = cargo(crate_dir, &["tree", "--prefix", "none"]);
    let tree_text = String::from_utf8_lossy(&tree.stdout);
    assert!(
        tree.status.success(),
        "{}",
        String::from_utf8_lossy(&tree.stderr)
    );
    assert!(tree_text.contains("chaplygin-macros"), "{tree_text}");
    for line in tree_text.lines() {
        assert!(
            !TOOLS.iter().any(|tool| line.starts_with(tool)),
            "a tool's crate in the library's tree: {line}\n{tree_text}"
        );
    }

    let run = cargo(crate_dir, &["run", "--quiet", "--target", &host()]);
    assert!(
        run.status.success(),
        "{}{}",
        String::from_utf8_lossy(&run.stdout),
        String::from_utf8_lossy(&run.stderr)
    );
}
