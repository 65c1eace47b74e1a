//! The build-script door: a `.model` file becomes Rust source, and a broken
//! file is reported with its path, line and column.

use crate::support::scratch;
use chaplygin_codegen::{BuildError, Builder};

const SLEIGH: &str = include_str!("../models/sleigh.model");

#[test]
fn a_model_file_becomes_rust_source() {
    let directory = scratch("door-good");
    let file = directory.path().join("sleigh.model");
    std::fs::write(&file, SLEIGH).expect("write");
    let written = Builder::new()
        .model_file(&file)
        .out_dir(directory.path())
        .write_to_out_dir()
        .expect("generates");
    assert_eq!(written, [directory.path().join("sleigh.rs")]);
    let source = std::fs::read_to_string(&written[0]).expect("read");
    assert!(source.contains("pub struct Sleigh"));
    assert!(source.contains("fn constraint_residual"));
    assert!(source.contains("fn acceleration"));
}

#[test]
fn a_broken_model_file_is_reported_with_file_line_and_column() {
    let directory = scratch("door-broken");
    let file = directory.path().join("sleigh.model");
    // Line 9: the blade constraint, with a velocity squared (not linear).
    let broken = SLEIGH.replace("cos(theta)*dot(y)]", "cos(theta)*dot(y)^2]");
    assert_ne!(broken, SLEIGH);
    std::fs::write(&file, &broken).expect("write");
    let error = Builder::new()
        .model_file(&file)
        .out_dir(directory.path())
        .write_to_out_dir()
        .expect_err("rejected");
    let BuildError::Model { path, rendered } = &error else {
        panic!("{error}")
    };
    assert_eq!(path, &file);
    let line = broken
        .lines()
        .position(|l| l.contains("dot(y)^2"))
        .expect("line")
        + 1;
    let column = broken
        .lines()
        .nth(line - 1)
        .and_then(|l| l.find("cos(theta)*dot(y)^2"))
        .expect("column")
        + 1;
    let expected = format!(
        "{}:{line}:{column}: error: a constraint must be linear and homogeneous",
        file.display()
    );
    assert!(
        rendered.starts_with(&expected),
        "{rendered}\nexpected to start with {expected}"
    );
    // two mistakes in one file are both reported
    let twice = broken.replace("inertia = 0.1", "inertia = x");
    std::fs::write(&file, &twice).expect("write");
    let error = Builder::new()
        .model_file(&file)
        .out_dir(directory.path())
        .write_to_out_dir()
        .expect_err("rejected");
    assert_eq!(error.to_string().lines().count(), 2, "{error}");
}
