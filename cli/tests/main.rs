//! The integration tests of the `chaplygin-cli` package, the command line:
//! one test binary that runs the `chaplygin` binary; each file of `tests/`
//! is a module of it, `support/` what they share. `Cargo.toml` sets
//! `autotests = false`, so a new file here runs only once it is declared
//! below; the root package's `every_test_file_is_declared` fails until
//! then.

mod support;

mod animation;
mod bicycle;
mod bicycle_falling;
mod bicycle_simulation;
mod cli;
mod cli_charts;
mod cli_engine;
mod cli_gait;
mod cli_identify;
mod cli_mechanisms;
mod cli_plan;
mod cli_racers;
mod cli_sizes;
mod cli_stop;
mod coordinate_singularities;
mod degenerate_momentum_basis;
mod derive_rust;
mod design_map;
mod energy_controller;
mod energy_drift;
mod euler_parameters;
mod guide_commands;
mod steady;
mod wheeled_robots;
