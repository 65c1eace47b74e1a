//! The integration tests of the `chaplygin` package, one test binary: each
//! file of `tests/` is a module of it (linked once against the engine, the
//! JIT and the runtime, not once per file), `support/` what they share
//! (with the command line's tests, `cli/tests`, which run its binary).
//! `Cargo.toml` sets `autotests = false`, so a new file here runs only once
//! it is declared below; [`every_test_file_is_declared`] fails until then
//! (here and in the other crates' `tests/main.rs`).

mod support;

mod animate;
mod build_script_door;
mod chart_cover;
mod charts;
mod euler_parameters;
mod examples;
mod gait_design;
mod guide;
mod guide_book;
mod holonomic;
mod hygiene;
mod import_circles;
mod plot;
mod user_crate;

/// In every crate whose integration tests are one binary, every `.rs` file
/// of `tests/` is declared a module of its `tests/main.rs`.
#[test]
fn every_test_file_is_declared() {
    for dir in [
        "tests",
        "cli/tests",
        "codegen/tests",
        "runtime/tests",
        "models/tests",
        "jit/tests",
    ] {
        support::assert_declared(env!("CARGO_MANIFEST_DIR"), dir);
    }
}
