//! The JIT's integration tests, one test binary: each file of `tests/` is a
//! module of it. `allocation` installs a counting global allocator for the
//! whole binary; it counts per thread, so the other modules' tests running
//! beside it do not disturb its counts. `Cargo.toml` sets
//! `autotests = false`: a new file runs only once declared below (the
//! workspace's `every_test_file_is_declared` checks that each is).

mod allocation;
mod api;
mod differential;
mod model;
mod models;
mod ops;
mod support;
