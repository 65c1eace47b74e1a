//! `chaplygin derive MODEL --format rust` prints exactly the Rust the build
//! script writes for the model (docs/INTERFACE.md section 3), for a model
//! file and for a built-in by name.

use crate::support::scratch;
use std::path::Path;
use std::process::Command;

/// What the build-script door (`chaplygin_codegen::Builder`) writes for
/// the model file `models/{stem}.model`.
fn written_by_the_build_script(stem: &str) -> String {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../models/{stem}.model"));
    let out_dir = scratch(&format!("derive-rust-{stem}"));
    let written = chaplygin_codegen::Builder::new()
        .model_file(&file)
        .out_dir(out_dir.path())
        .write_to_out_dir()
        .expect("the model generates");
    std::fs::read_to_string(&written[0]).expect("the file is written")
}

/// The command's standard output, which must succeed.
fn printed(arguments: &[&str]) -> String {
    let output = Command::new(env!("CARGO_BIN_EXE_chaplygin"))
        .args(arguments)
        .output()
        .expect("the binary runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).expect("UTF-8")
}

#[test]
fn a_model_file_prints_what_the_build_script_writes() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/sleigh.model");
    let code = printed(&["derive", file, "--format", "rust"]);
    assert_eq!(code, written_by_the_build_script("sleigh"));
    assert!(code.contains("pub fn reduced_rhs("), "{code}");
}

#[test]
fn a_built_in_prints_what_the_build_script_writes_for_its_file() {
    let code = printed(&["derive", "snakeboard", "--format", "rust"]);
    assert_eq!(code, written_by_the_build_script("snakeboard"));
    assert!(
        code.lines()
            .any(|line| line.starts_with("    pub fn reduced_rhs(")),
        "formatted, one item a line: {code}"
    );
}

/// The model text `source` without its `drawing:` section, the last one.
fn without_drawing(source: &str) -> String {
    let (before, _) = source
        .split_once("    drawing: [")
        .expect("a drawing section");
    format!("{before}}}")
}

/// The drawing section is read by the interpreter alone (docs/INTERFACE.md
/// section 10): the Rust of a model declared by its energy and of a
/// mechanism is the same with and without it.
#[test]
fn the_drawing_section_leaves_the_emitted_rust_as_it_is() {
    for source in [
        include_str!("../../models/snakeboard.model"),
        include_str!("../../models/sleigh_bodies.model"),
    ] {
        let drawn = chaplygin_codegen::generate(source).expect("generates");
        let plain = chaplygin_codegen::generate(&without_drawing(source)).expect("generates");
        assert!(drawn == plain, "the drawing changed the Rust of\n{source}");
    }
}
