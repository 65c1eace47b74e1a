//! Chaplygin: nonholonomic mechanical models compiled into verified simulators.

pub use chaplygin_runtime as runtime;
