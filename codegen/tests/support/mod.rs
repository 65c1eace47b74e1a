//! Shared inputs of the codegen integration tests and fuzz targets. Each test
//! crate uses part of it, hence `dead_code` is allowed here.

#![allow(dead_code)]

pub mod models;
pub mod mutate;
