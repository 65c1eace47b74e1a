//! The `model!` procedural macro.
