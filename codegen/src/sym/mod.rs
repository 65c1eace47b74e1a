//! The symbolic engine.

pub mod eval;
pub mod expr;
pub mod number;

pub use expr::{ExprId, Function, Node, Store, SymError, Symbol, SymbolId, SymbolKind};
pub use number::Rational;
