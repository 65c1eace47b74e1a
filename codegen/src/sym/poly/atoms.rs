//! The atoms of polynomials: symbols, sine and cosine pairs of one argument,
//! square roots with their radicands, and opaque kernels, interned in a
//! table that also carries the derivation budget products are charged to.

use super::Poly;
use crate::sym::budget::Budget;
use crate::sym::ids::{ExprId, SymbolId};
use rustc_hash::FxHashMap as HashMap;

/// Handle of an atom in an [`Atoms`] table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct AtomId(u32);

impl AtomId {
    /// The first atom interned (a filler for unused inline slots).
    pub(super) const FIRST: AtomId = AtomId(0);
}

/// An indivisible factor of a polynomial.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Atom {
    /// A symbol used polynomially.
    Symbol(SymbolId),
    /// `sin(arg)`; `arg` is a symbol, or an argument the expansion leaves whole.
    Sin(ExprId),
    /// `cos(arg)`.
    Cos(ExprId),
    /// An opaque function of normal-form arguments (`exp`, `ln`, fractional
    /// powers, `asin acos atan atan2`).
    Kernel(ExprId),
}

/// The interned atoms, each sine paired with the cosine of the same argument,
/// and the derivation budget that products over them are charged to.
#[derive(Clone, Default, Debug)]
pub struct Atoms {
    list: Vec<Atom>,
    index: HashMap<Atom, AtomId>,
    cosine_partner: HashMap<AtomId, AtomId>,
    radicands: HashMap<AtomId, Poly>,
    budget: Budget,
}

impl Atoms {
    /// An empty table charging its products to `budget`.
    pub fn with_budget(budget: Budget) -> Atoms {
        Atoms {
            budget,
            ..Atoms::default()
        }
    }

    /// The budget products are charged to (shared by every copy of the table).
    pub fn budget(&self) -> &Budget {
        &self.budget
    }

    /// Charges this table's products to `budget` from now on; returns the
    /// budget charged so far.
    pub fn replace_budget(&mut self, budget: Budget) -> Budget {
        std::mem::replace(&mut self.budget, budget)
    }

    /// The atom behind a handle.
    pub fn get(&self, id: AtomId) -> &Atom {
        &self.list[id.0 as usize]
    }

    /// Interns a symbol atom.
    pub fn symbol(&mut self, symbol: SymbolId) -> AtomId {
        self.intern(Atom::Symbol(symbol))
    }

    /// Interns an opaque kernel.
    pub fn kernel(&mut self, expression: ExprId) -> AtomId {
        self.intern(Atom::Kernel(expression))
    }

    /// Interns the kernel `expression = sqrt(radicand)`, reduced by
    /// `sqrt(radicand)^2 = radicand` from now on.
    pub fn square_root(&mut self, expression: ExprId, radicand: Poly) -> AtomId {
        let root = self.intern(Atom::Kernel(expression));
        self.radicands.insert(root, radicand);
        root
    }

    /// The radicand of a square-root atom (`None` for any other atom).
    pub fn radicand_of(&self, root: AtomId) -> Option<&Poly> {
        self.radicands.get(&root)
    }

    /// True for the atoms whose square reduces: sines and square roots.
    pub fn is_reducible(&self, atom: AtomId) -> bool {
        self.cosine_partner.contains_key(&atom) || self.radicands.contains_key(&atom)
    }

    /// Interns `(sin(arg), cos(arg))` together.
    pub fn trig_pair(&mut self, argument: ExprId) -> (AtomId, AtomId) {
        let sine = self.intern(Atom::Sin(argument));
        let cosine = self.intern(Atom::Cos(argument));
        self.cosine_partner.insert(sine, cosine);
        (sine, cosine)
    }

    /// The cosine paired with a sine atom (`None` for any other atom).
    pub fn cosine_of(&self, sine: AtomId) -> Option<AtomId> {
        self.cosine_partner.get(&sine).copied()
    }

    fn intern(&mut self, atom: Atom) -> AtomId {
        if let Some(&id) = self.index.get(&atom) {
            return id;
        }
        let id = AtomId(self.list.len() as u32);
        self.list.push(atom.clone());
        self.index.insert(atom, id);
        id
    }
}
