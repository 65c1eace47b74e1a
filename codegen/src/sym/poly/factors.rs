//! The `(atom, exponent)` pairs of a monomial, kept inline up to
//! [`INLINE`] pairs: most monomials of a mechanism have a handful of
//! factors, and a product of polynomials builds one monomial per pair of
//! terms, so keeping them off the heap removes an allocation per term
//! product.

use super::AtomId;
use std::hash::{Hash, Hasher};
use std::ops::Deref;

/// Pairs kept without allocating.
const INLINE: usize = 6;

/// A short list of `(atom, exponent)` pairs, on the stack up to [`INLINE`].
#[derive(Clone)]
pub enum Factors {
    /// The first `len` pairs are the list.
    Inline {
        len: u8,
        pairs: [(AtomId, u32); INLINE],
    },
    /// More than [`INLINE`] pairs.
    Spilled(Vec<(AtomId, u32)>),
}

impl Factors {
    /// The empty list.
    pub const fn new() -> Factors {
        Factors::Inline {
            len: 0,
            pairs: [(AtomId::FIRST, 0); INLINE],
        }
    }

    /// Appends a pair.
    pub fn push(&mut self, pair: (AtomId, u32)) {
        match self {
            Factors::Inline { len, pairs } if usize::from(*len) < INLINE => {
                pairs[usize::from(*len)] = pair;
                *len += 1;
            }
            Factors::Inline { pairs, .. } => {
                let mut spilled = pairs.to_vec();
                spilled.push(pair);
                *self = Factors::Spilled(spilled);
            }
            Factors::Spilled(pairs) => pairs.push(pair),
        }
    }
}

impl Default for Factors {
    fn default() -> Self {
        Factors::new()
    }
}

impl Deref for Factors {
    type Target = [(AtomId, u32)];

    fn deref(&self) -> &Self::Target {
        match self {
            Factors::Inline { len, pairs } => &pairs[..usize::from(*len)],
            Factors::Spilled(pairs) => pairs,
        }
    }
}

impl Extend<(AtomId, u32)> for Factors {
    fn extend<I: IntoIterator<Item = (AtomId, u32)>>(&mut self, pairs: I) {
        for pair in pairs {
            self.push(pair);
        }
    }
}

impl FromIterator<(AtomId, u32)> for Factors {
    fn from_iter<I: IntoIterator<Item = (AtomId, u32)>>(pairs: I) -> Self {
        let mut factors = Factors::new();
        factors.extend(pairs);
        factors
    }
}

impl PartialEq for Factors {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl Eq for Factors {}

impl Hash for Factors {
    fn hash<H: Hasher>(&self, state: &mut H) {
        (**self).hash(state);
    }
}

impl std::fmt::Debug for Factors {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}
