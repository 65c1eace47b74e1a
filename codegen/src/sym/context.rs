//! The context above the expression [`Store`]: what the engine computes
//! from expressions and keeps.
//!
//! The store is a plain arena (interned nodes and the symbol table): what
//! an expression *is*. The [`Context`] owns a store and adds what is
//! known about its expressions: the polynomial [`Atoms`] their normal forms
//! are written over (with the derivation [`Budget`] those normal forms are
//! charged to), each expression's normal form (`context/normal_form.rs`),
//! and the derivatives taken so far ([`super::diff`]). It dereferences to
//! its store, so building and reading expressions reads the same through
//! either; a model's derivations take the model by shared reference and
//! one `&mut Context`.

mod normal_form;

use super::budget::Budget;
use super::expr::{ExprId, Store, SymbolId};
use super::normal::RationalFunction;
use super::poly::Atoms;
use rustc_hash::FxHashMap as HashMap;
use std::ops::{Deref, DerefMut};

/// An expression store with its atoms, normal forms and derivatives.
#[derive(Default, Clone)]
pub struct Context {
    store: Store,
    pub(super) atoms: Atoms,
    normal_forms: HashMap<ExprId, RationalFunction>,
    /// `d node / d symbol` of the nodes differentiated so far, per symbol.
    pub(super) derivative_memo: HashMap<SymbolId, HashMap<ExprId, ExprId>>,
}

/// A nested budget being charged instead of the context's own.
struct Attempt {
    trial: Budget,
    outer: Budget,
}

impl Context {
    /// An empty context.
    pub fn new() -> Context {
        Context::default()
    }

    /// An empty context whose normal forms are charged to `budget`.
    pub fn with_budget(budget: Budget) -> Context {
        Context {
            atoms: Atoms::with_budget(budget),
            ..Context::default()
        }
    }

    /// The atoms the normal forms are written over.
    pub fn atoms(&self) -> &Atoms {
        &self.atoms
    }

    /// The derivation budget the normal forms are charged to.
    pub fn budget(&self) -> &Budget {
        self.atoms.budget()
    }

    /// Runs `work` on a budget of `limit` term products nested in this
    /// context's ([`Budget::nested`]): its result, or `None` when the
    /// nested budget ran out (the result is then truncated and dropped).
    /// The limit is cut to what this context's budget has left, so an
    /// attempt never spends it.
    pub fn attempt<T>(&mut self, limit: u64, work: impl FnOnce(&mut Context) -> T) -> Option<T> {
        let trial = self.enter_attempt(limit);
        let result = work(self);
        self.leave_attempt(trial).then_some(result)
    }

    /// Starts charging a nested budget of `limit` (see [`Context::attempt`]).
    fn enter_attempt(&mut self, limit: u64) -> Attempt {
        let budget = self.budget();
        let left = budget.limit().saturating_sub(budget.used());
        let trial = budget.nested(limit.min(left.saturating_sub(1)));
        let outer = self.atoms.replace_budget(trial.clone());
        Attempt { trial, outer }
    }

    /// Ends an attempt: true when it stayed within its nested budget.
    fn leave_attempt(&mut self, attempt: Attempt) -> bool {
        self.atoms.replace_budget(attempt.outer);
        !attempt.trial.is_exhausted()
    }
}

impl Deref for Context {
    type Target = Store;

    fn deref(&self) -> &Store {
        &self.store
    }
}

impl DerefMut for Context {
    fn deref_mut(&mut self) -> &mut Store {
        &mut self.store
    }
}
