//! The Chaplygin compiler.
//!
//! A model flows one way through typed stages: the symbolic engine [`sym`]
//! holds every expression, and [`ir`] lowers derived expressions to
//! straight-line code with common subexpressions shared, which is interpreted
//! or emitted as allocation-free Rust.

#![warn(missing_docs)]

pub mod diagnostic;
pub mod ir;
pub mod model;
pub mod sym;
pub mod syntax;
