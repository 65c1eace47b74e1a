//! Independent references shared by the models' tests.

pub mod benchmark_bicycle;
