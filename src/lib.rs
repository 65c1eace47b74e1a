//! Chaplygin: nonholonomic mechanical models compiled into verified simulators.
//!
//! Declare a model with [`model!`]; the macro checks it and emits a parameter
//! struct with its mass matrix, energy, constraint matrix and constraint
//! residual as allocation-free functions.

pub use chaplygin_macros::model;
pub use chaplygin_runtime as runtime;

/// The README's examples, compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
