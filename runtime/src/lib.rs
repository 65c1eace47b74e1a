//! The Chaplygin runtime: what generated models plug into.

pub mod linalg;
pub mod phase;
