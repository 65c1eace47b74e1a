//! The derivation budget: a deterministic bound on the work of one compile.
//!
//! The normal form multiplies polynomials, and a product of polynomials with
//! `a` and `b` terms forms `a * b` term products before like terms are
//! collected. Nested powers of trigonometric sums make these counts grow
//! exponentially: `(sin(x + y) + cos(x - y))^40` expands to products of
//! polynomials with thousands of terms each. Every polynomial product charges
//! its `a * b` term products (weighted by the size in words of the largest
//! coefficients) to a [`Budget`]; exact division (weighted the same way),
//! sums of rational functions and the `sin^2 = 1 - cos^2` reduction charge
//! the terms they rewrite. The count depends only on the model, never on
//! the clock, so a model is accepted or rejected the same way on every
//! machine.
//!
//! The budget is shared by a [`super::Store`] and every copy of its atom
//! table. Once it is spent, products return zero without being computed (so
//! the rest of the derivation finishes quickly), [`super::Context::normal`]
//! reports [`super::SymError::BudgetExceeded`], and the compiler reports that
//! one error instead of whatever the truncated computation concluded.
//!
//! The budget also bounds the degrees: a product whose exponent of an atom,
//! or whose multiplicity of a denominator factor, would pass [`MAX_DEGREE`]
//! is not computed either and spends the budget, and the normal form then
//! reports [`super::SymError::DegreeTooLarge`] (the exponents are `u32`s, so
//! the bound also keeps every sum of two of them exact).
//!
//! A derivation that has a cheaper alternative tries the expensive one on a
//! [`Budget::nested`] budget ([`super::Context::attempt`]): its products count
//! against both, and when the nested limit is reached the attempt is
//! abandoned while the outer budget goes on.

use super::expr::SymError;
use std::cell::Cell;
use std::iter;
use std::rc::Rc;

/// The default limit on polynomial term products per compile.
///
/// The compiled built-in models use under 0.1 % of it; the wheeled snakes
/// of 2 to 12 links up to 14 %, and the benchmark bicycle about 70 %
/// (28 million), mostly on exact forms they attempt and give up for
/// structured ones (`FUZZING.md` lists the measured use of each).
pub const DEFAULT_DERIVATION_BUDGET: u64 = 40_000_000;

/// The highest exponent of an atom in a polynomial, and the highest
/// multiplicity of a denominator factor, that the normal form computes.
pub const MAX_DEGREE: u32 = 1 << 16;

/// A shared counter of polynomial term products with a limit.
#[derive(Clone, Debug)]
pub struct Budget(Rc<Counter>);

#[derive(Debug)]
struct Counter {
    limit: u64,
    used: Cell<u64>,
    /// The budget this one is nested in, charged too.
    outer: Option<Budget>,
    /// True when a degree past [`MAX_DEGREE`] spent this budget.
    passed_degree: Cell<bool>,
}

impl Budget {
    /// A budget of `limit` term products, none used yet.
    pub fn new(limit: u64) -> Budget {
        Budget(Rc::new(Counter {
            limit,
            used: Cell::new(0),
            outer: None,
            passed_degree: Cell::new(false),
        }))
    }

    /// A budget of `limit` term products inside this one: what it is
    /// charged, this one is charged too, and it is spent when either is.
    pub fn nested(&self, limit: u64) -> Budget {
        Budget(Rc::new(Counter {
            limit,
            used: Cell::new(0),
            outer: Some(self.clone()),
            passed_degree: Cell::new(false),
        }))
    }

    /// The limit.
    pub fn limit(&self) -> u64 {
        self.0.limit
    }

    /// Term products charged so far (saturating at just above the limit).
    pub fn used(&self) -> u64 {
        self.0.used.get()
    }

    /// True once a charge has gone beyond the limit (of this budget or of
    /// the one it is nested in).
    pub fn is_exhausted(&self) -> bool {
        self.used() > self.limit() || self.0.outer.as_ref().is_some_and(Budget::is_exhausted)
    }

    /// Charges `products` term products; false when the budget is (now)
    /// spent. Beyond the limit nothing more is charged, to this budget or to
    /// the one it is nested in.
    pub fn charge(&self, products: u64) -> bool {
        if self.is_exhausted() {
            return false;
        }
        let room = self.limit().saturating_add(1) - self.used();
        let charged = products.min(room);
        self.0.used.set(self.used() + charged);
        if let Some(outer) = &self.0.outer {
            outer.charge(charged);
        }
        !self.is_exhausted()
    }

    /// True when a product of this `degree` (the highest exponent of an
    /// atom, or multiplicity of a denominator factor, it would have) may be
    /// computed; otherwise false, and the budget is spent, as is every
    /// budget it is nested in that this spends.
    pub fn admits_degree(&self, degree: u64) -> bool {
        if degree <= u64::from(MAX_DEGREE) {
            return true;
        }
        let lasting: Vec<&Budget> = self.chain().filter(|b| !b.is_spent()).collect();
        self.charge(u64::MAX);
        for budget in lasting.into_iter().filter(|b| b.is_spent()) {
            budget.0.passed_degree.set(true);
        }
        false
    }

    /// The error of a spent budget, `None` while it lasts:
    /// [`SymError::DegreeTooLarge`] when a degree spent it (or the budget it
    /// is nested in), [`SymError::BudgetExceeded`] when term products did.
    pub fn error(&self) -> Option<SymError> {
        if !self.is_exhausted() {
            return None;
        }
        let by_degree = self
            .chain()
            .any(|b| b.is_spent() && b.0.passed_degree.get());
        Some(if by_degree {
            SymError::DegreeTooLarge { limit: MAX_DEGREE }
        } else {
            SymError::BudgetExceeded {
                limit: self.limit(),
            }
        })
    }

    /// This budget and those it is nested in, innermost first.
    fn chain(&self) -> impl Iterator<Item = &Budget> {
        iter::successors(Some(self), |b| b.0.outer.as_ref())
    }

    /// True when this budget's own limit is passed.
    fn is_spent(&self) -> bool {
        self.used() > self.limit()
    }
}

impl Default for Budget {
    /// A budget of [`DEFAULT_DERIVATION_BUDGET`].
    fn default() -> Budget {
        Budget::new(DEFAULT_DERIVATION_BUDGET)
    }
}

#[cfg(test)]
mod tests {
    use super::{Budget, MAX_DEGREE, SymError};

    #[test]
    fn a_nested_budget_charges_its_outer_one_and_runs_out_alone() {
        let outer = Budget::new(100);
        let inner = outer.nested(10);
        assert!(inner.charge(6));
        assert_eq!(outer.used(), 6);
        assert!(!inner.charge(6));
        assert!(inner.is_exhausted());
        assert!(!outer.is_exhausted());
        assert_eq!(outer.used(), 6 + 5, "only what fitted the nested budget");
        assert!(outer.charge(78));
        let second = outer.nested(1000);
        assert!(!second.charge(20), "the outer budget is spent");
        assert!(outer.is_exhausted() && second.is_exhausted());
    }

    #[test]
    fn a_degree_past_the_limit_spends_the_budget_and_names_itself() {
        let outer = Budget::new(100);
        assert!(outer.admits_degree(u64::from(MAX_DEGREE)));
        assert_eq!(outer.error(), None);
        let inner = outer.nested(10);
        assert!(!inner.admits_degree(u64::from(MAX_DEGREE) + 1));
        assert_eq!(
            inner.error(),
            Some(SymError::DegreeTooLarge { limit: MAX_DEGREE })
        );
        assert_eq!(outer.error(), None, "the nested budget ran out alone");
        assert!(outer.charge(80));
        assert!(!outer.charge(20));
        assert_eq!(outer.error(), Some(SymError::BudgetExceeded { limit: 100 }));
        let spent_by_products = Budget::new(5);
        assert!(!spent_by_products.charge(6));
        assert!(!spent_by_products.admits_degree(u64::MAX));
        assert_eq!(
            spent_by_products.error(),
            Some(SymError::BudgetExceeded { limit: 5 }),
            "products spent it first"
        );
    }
}
