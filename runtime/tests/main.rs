//! The runtime's integration tests, one test binary: each file of `tests/`
//! is a module of it. `Cargo.toml` sets `autotests = false`: a new file
//! runs only once declared below (the workspace's
//! `every_test_file_is_declared` checks that each is).

mod controlled;
mod discrete_gradient;
mod effort;
mod integrators;
mod linalg;
mod split_steps;
mod state;
mod stop;
