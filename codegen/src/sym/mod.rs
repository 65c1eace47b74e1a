//! The symbolic engine.

pub mod budget;
pub mod context;
pub mod diff;
pub mod eval;
pub mod expr;
pub mod ids;
pub mod latex;
pub mod matrix;
pub mod modular;
pub mod normal;
pub mod number;
pub mod poly;
pub mod residues;
pub mod zero;

pub use budget::{Budget, DEFAULT_DERIVATION_BUDGET, MAX_DEGREE};
pub use context::Context;
pub use expr::{ExprId, Function, Node, Store, SymError, Symbol, SymbolId, SymbolKind};
pub use matrix::{Matrix, MatrixError};
pub use normal::RationalFunction;
pub use number::Rational;
pub use poly::{Atom, AtomId, Atoms, Monomial, Poly};
pub use zero::{Decision, NumericZeroTest, ZeroTest};

#[cfg(test)]
mod inverse_tests;
#[cfg(test)]
mod proptests;
#[cfg(test)]
mod tests;
