//! The handles of expressions and symbols in a store
//! ([`crate::sym::Store`]), which the atoms of polynomials name too.

/// Handle of an expression in a [`Store`](crate::sym::Store).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ExprId(pub(crate) u32);

impl ExprId {
    /// Position of the node in its store (children come before parents).
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Handle of a symbol in a [`Store`](crate::sym::Store).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SymbolId(pub(crate) u32);

impl SymbolId {
    /// Position of the symbol in its store, in declaration order.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}
