//! The engine's integration tests, one test binary: each file of `tests/`
//! is a module of it, `support/` what they share (with the fuzz targets).
//! `Cargo.toml` sets `autotests = false`: a new file runs only once
//! declared below (the workspace's `every_test_file_is_declared` checks
//! that each is).

mod support;

mod budget;
mod fuzz_properties;
mod fuzz_regressions;
