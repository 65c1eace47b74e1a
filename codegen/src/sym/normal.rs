//! The normal form: expressions as rational functions of atoms.
//!
//! [`Context::normal`](crate::sym::Context::normal) turns an expression into a [`RationalFunction`]
//! `N / (f_1^k_1 ... f_m^k_m)`:
//!
//! - trigonometric functions of integer combinations of symbols are expanded,
//!   `sin(a + 2b) = sin a cos 2b + cos a sin 2b`, `cos 2b = cos^2 b - sin^2 b`,
//!   down to products of `sin q_i`, `cos q_i`; `tan u = sin u / cos u`;
//! - products are reduced by `sin^2 q -> 1 - cos^2 q` ([`super::poly`]);
//! - the denominator is kept factored, each factor monic and free of sines
//!   and square roots (a divisor `a + b sin q` is cleared by its conjugate
//!   `a - b sin q`, as the norm of the quadratic extension, and `a + b sqrt(u)`
//!   by `a - b sqrt(u)`), so the numerator decides zero-ness:
//!   on the exact class (atoms are symbols and `sin`/`cos` of symbols) an
//!   expression is zero exactly when its numerator has no terms;
//! - common factors are cancelled: the monomial content, and every
//!   denominator factor that divides the numerator exactly (factors equal as
//!   normal forms are recognised, a full multivariate gcd is not computed);
//! - the square root of a polynomial is an atom `r` reduced by `r^2 = u`
//!   ([`super::poly`]), so `sqrt(u)^2 - u` and `(1/sqrt(u))^2 - 1/u` are zero
//!   by the normal form; zero tests of other expressions with roots fall
//!   back to the numeric test, as for kernels;
//! - anything else (`exp`, `ln`, other fractional powers, trigonometric functions of
//!   other arguments) becomes an opaque kernel atom whose argument is itself in
//!   normal form, so equal kernels are recognised; zero tests involving kernels
//!   fall back to the randomized numeric test ([`super::zero`]).

/// The most terms (numerator and denominator factors together) a normal
/// form may have to be computed written out
/// ([`Context::compact_expression`](crate::sym::Context::compact_expression)).
pub const EXPANDED_TERMS: usize = 64;

use super::number::Rational;
use super::poly::{AtomId, Atoms, Poly};

/// A quotient of polynomials with a factored, sine-free denominator.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct RationalFunction {
    numerator: Poly,
    /// Monic, sine-free, non-constant, pairwise distinct factors, sorted.
    denominator: Vec<(Poly, u32)>,
}

impl RationalFunction {
    /// A polynomial.
    pub fn from_poly(numerator: Poly) -> RationalFunction {
        RationalFunction {
            numerator,
            denominator: Vec::new(),
        }
    }

    /// A constant.
    pub fn constant(value: Rational) -> RationalFunction {
        RationalFunction::from_poly(Poly::constant(value))
    }

    /// Zero.
    pub fn zero() -> RationalFunction {
        RationalFunction::from_poly(Poly::zero())
    }

    /// One.
    pub fn one() -> RationalFunction {
        RationalFunction::constant(Rational::ONE)
    }

    /// The numerator.
    pub fn numerator(&self) -> &Poly {
        &self.numerator
    }

    /// The denominator factors with their multiplicities.
    pub fn denominator(&self) -> &[(Poly, u32)] {
        &self.denominator
    }

    /// The denominator multiplied out.
    pub fn denominator_product(&self, atoms: &Atoms) -> Poly {
        product_of(&self.denominator, atoms)
    }

    /// `1 / (f_1^k_1 ... f_m^k_m)`: one over the denominator, factors kept.
    pub fn reciprocal_of_denominator(&self) -> RationalFunction {
        RationalFunction {
            numerator: Poly::constant(Rational::ONE),
            denominator: self.denominator.clone(),
        }
    }

    /// True when the function is exactly zero (the numerator has no terms).
    pub fn is_zero(&self) -> bool {
        self.numerator.is_zero()
    }

    /// The value when the function is a constant.
    pub fn as_constant(&self) -> Option<Rational> {
        if self.denominator.is_empty() {
            self.numerator.as_constant()
        } else {
            None
        }
    }

    /// The atoms of the numerator and of the denominator.
    pub fn atoms(&self) -> Vec<AtomId> {
        let mut atoms = self.numerator.atoms();
        for (factor, _) in &self.denominator {
            atoms.extend(factor.atoms());
        }
        atoms.sort_unstable();
        atoms.dedup();
        atoms
    }

    /// A size measure: terms in the numerator and denominator factors.
    pub fn size(&self) -> usize {
        self.numerator.len() + self.denominator.iter().map(|(f, _)| f.len()).sum::<usize>()
    }

    /// True when the form is written out as an expression
    /// ([`super::Context::compact_expression`]: at most [`EXPANDED_TERMS`]
    /// terms). Exact derivations on larger forms (a rolling wheel's contact
    /// rows, a mechanism's energy) are not attempted: they exceed their
    /// budgets after spending them.
    pub fn is_written_out(&self) -> bool {
        self.size() <= EXPANDED_TERMS
    }

    /// `-self`.
    pub fn neg(&self) -> RationalFunction {
        RationalFunction {
            numerator: self.numerator.neg(),
            denominator: self.denominator.clone(),
        }
    }

    /// `c * self`.
    pub fn scale(&self, c: &Rational) -> RationalFunction {
        if c.is_zero() {
            return RationalFunction::zero();
        }
        RationalFunction {
            numerator: self.numerator.scale(c),
            denominator: self.denominator.clone(),
        }
    }

    /// `self + other` over the least common multiple of the factored denominators.
    ///
    /// Charges the budget of `atoms` the terms of both numerators (a sum of
    /// many terms, folded, is quadratic in their count).
    pub fn add(&self, other: &RationalFunction, atoms: &Atoms) -> RationalFunction {
        let merged = self.numerator.len() + other.numerator.len();
        if !atoms.budget().charge(merged as u64) {
            return RationalFunction::zero();
        }
        if other.is_zero() {
            return self.clone();
        }
        if self.is_zero() {
            return other.clone();
        }
        if self.denominator == other.denominator {
            return RationalFunction {
                numerator: self.numerator.add(&other.numerator),
                denominator: self.denominator.clone(),
            }
            .cancelled(atoms);
        }
        let common = lcm(&self.denominator, &other.denominator);
        let left = self
            .numerator
            .mul(&cofactor(&common, &self.denominator, atoms), atoms);
        let right = other
            .numerator
            .mul(&cofactor(&common, &other.denominator, atoms), atoms);
        RationalFunction {
            numerator: left.add(&right),
            denominator: common,
        }
        .cancelled(atoms)
    }

    /// `self - other`.
    pub fn sub(&self, other: &RationalFunction, atoms: &Atoms) -> RationalFunction {
        self.add(&other.neg(), atoms)
    }

    /// `self * other`, cancelling each numerator against the other denominator first.
    pub fn mul(&self, other: &RationalFunction, atoms: &Atoms) -> RationalFunction {
        if self.is_zero() || other.is_zero() {
            return RationalFunction::zero();
        }
        let (left, other_denominator) = cancel(&self.numerator, &other.denominator, atoms);
        let (right, own_denominator) = cancel(&other.numerator, &self.denominator, atoms);
        let multiplicity = highest_multiplicity(&own_denominator)
            .saturating_add(highest_multiplicity(&other_denominator));
        if !atoms.budget().admits_degree(multiplicity) {
            return RationalFunction::zero();
        }
        RationalFunction {
            numerator: left.mul(&right, atoms),
            denominator: merge(&own_denominator, &other_denominator),
        }
        .cancelled(atoms)
    }

    /// `1 / self`, or an error when `self` is exactly zero.
    pub fn inverse(&self, atoms: &Atoms) -> Option<RationalFunction> {
        if self.is_zero() {
            return None;
        }
        let (cleared, conjugates) = clear_sines(&self.numerator, atoms);
        let numerator = conjugates.mul(&self.denominator_product(atoms), atoms);
        let (coefficient, factors) = factorize(&cleared, &self.denominator, atoms);
        Some(
            RationalFunction {
                numerator: numerator.scale(&coefficient.recip()?),
                denominator: factors,
            }
            .cancelled(atoms),
        )
    }

    /// `self / other`, or `None` when `other` is exactly zero.
    pub fn div(&self, other: &RationalFunction, atoms: &Atoms) -> Option<RationalFunction> {
        Some(self.mul(&other.inverse(atoms)?, atoms))
    }

    /// `self^n` for an integer `n`, or `None` for a negative power of zero.
    pub fn powi(&self, n: i64, atoms: &Atoms) -> Option<RationalFunction> {
        let base = if n < 0 {
            self.inverse(atoms)?
        } else {
            self.clone()
        };
        let mut result = RationalFunction::one();
        let mut square = base;
        let mut remaining = n.unsigned_abs();
        while remaining > 0 {
            if remaining & 1 == 1 {
                result = result.mul(&square, atoms);
            }
            remaining >>= 1;
            if remaining > 0 {
                square = square.mul(&square, atoms);
            }
        }
        Some(result)
    }

    /// Removes every denominator factor that divides the numerator.
    fn cancelled(self, atoms: &Atoms) -> RationalFunction {
        if self.numerator.is_zero() {
            return RationalFunction::zero();
        }
        let (numerator, denominator) = cancel(&self.numerator, &self.denominator, atoms);
        RationalFunction {
            numerator,
            denominator,
        }
    }

    /// The value at the given atom values.
    pub fn evaluate(&self, value_of: &dyn Fn(AtomId) -> f64) -> f64 {
        let denominator: f64 = self
            .denominator
            .iter()
            .map(|(f, k)| f.evaluate(value_of).powi(*k as i32))
            .product();
        self.numerator.evaluate(value_of) / denominator
    }
}

/// Cancels denominator factors that divide `numerator` exactly.
fn cancel(
    numerator: &Poly,
    denominator: &[(Poly, u32)],
    atoms: &Atoms,
) -> (Poly, Vec<(Poly, u32)>) {
    let mut numerator = numerator.clone();
    let mut kept = Vec::with_capacity(denominator.len());
    for (factor, multiplicity) in denominator {
        let mut remaining = *multiplicity;
        while remaining > 0 && might_divide(factor, &numerator) {
            match numerator.div_exact(factor, atoms.budget()) {
                Some(quotient) => {
                    numerator = quotient;
                    remaining -= 1;
                }
                None => break,
            }
        }
        if remaining > 0 {
            kept.push((factor.clone(), remaining));
        }
    }
    (numerator, kept)
}

/// A cheap necessary condition for `factor | p`: the leading monomials divide.
fn might_divide(factor: &Poly, p: &Poly) -> bool {
    match (factor.leading(), p.leading()) {
        (Some((f, _)), Some((m, _))) => m.div(f).is_some() && factor.len() <= p.len(),
        _ => false,
    }
}

/// The highest multiplicity in a factor list (0 for none).
fn highest_multiplicity(factors: &[(Poly, u32)]) -> u64 {
    factors
        .iter()
        .map(|&(_, k)| u64::from(k))
        .max()
        .unwrap_or(0)
}

/// Factor lists multiplied: exponents of equal factors add.
fn merge(a: &[(Poly, u32)], b: &[(Poly, u32)]) -> Vec<(Poly, u32)> {
    combine(a, b, |x, y| x + y)
}

/// The least common multiple of two factor lists: the larger exponent wins.
fn lcm(a: &[(Poly, u32)], b: &[(Poly, u32)]) -> Vec<(Poly, u32)> {
    combine(a, b, u32::max)
}

fn combine(a: &[(Poly, u32)], b: &[(Poly, u32)], join: fn(u32, u32) -> u32) -> Vec<(Poly, u32)> {
    let mut out: Vec<(Poly, u32)> = a.to_vec();
    for (factor, k) in b {
        match out.iter_mut().find(|(f, _)| f == factor) {
            Some(entry) => entry.1 = join(entry.1, *k),
            None => out.push((factor.clone(), *k)),
        }
    }
    out.sort_unstable();
    out
}

/// `common / part` multiplied out, where `part` divides `common` factor-wise.
fn cofactor(common: &[(Poly, u32)], part: &[(Poly, u32)], atoms: &Atoms) -> Poly {
    let missing: Vec<(Poly, u32)> = common
        .iter()
        .filter_map(|(factor, k)| {
            let present = part
                .iter()
                .find(|(f, _)| f == factor)
                .map_or(0, |(_, j)| *j);
            (*k > present).then(|| (factor.clone(), *k - present))
        })
        .collect();
    product_of(&missing, atoms)
}

fn product_of(factors: &[(Poly, u32)], atoms: &Atoms) -> Poly {
    factors
        .iter()
        .fold(Poly::constant(Rational::ONE), |acc, (f, k)| {
            acc.mul(&f.pow(*k, atoms), atoms)
        })
}

/// Multiplies `p` by conjugates until no square root and no sine is left:
/// `a + b r -> (a + b r)(a - b r) = a^2 - b^2 u` for a root `r = sqrt(u)`,
/// the outermost root first (its radicand may hold inner roots and sines,
/// a sine's conjugate none), then each sine the same way. Returns the
/// product and the product of the conjugates used.
fn clear_sines(p: &Poly, atoms: &Atoms) -> (Poly, Poly) {
    let mut cleared = p.clone();
    let mut conjugates = Poly::constant(Rational::ONE);
    while let Some(sine) = next_to_clear(&cleared, atoms) {
        let conjugate = cleared.conjugate(sine);
        cleared = cleared.mul(&conjugate, atoms);
        conjugates = conjugates.mul(&conjugate, atoms);
    }
    (cleared, conjugates)
}

/// The outermost square root of `p` (the latest interned), else a sine.
fn next_to_clear(p: &Poly, atoms: &Atoms) -> Option<AtomId> {
    let present = p.atoms();
    let root = present
        .iter()
        .copied()
        .filter(|&a| atoms.radicand_of(a).is_some())
        .max();
    root.or_else(|| present.into_iter().find(|&a| atoms.cosine_of(a).is_some()))
}

/// Splits a non-zero, sine-free polynomial into a constant times monic factors:
/// single-atom factors for its monomial content, then known factors (those of
/// `known`) divided out, then the monic remainder.
fn factorize(p: &Poly, known: &[(Poly, u32)], atoms: &Atoms) -> (Rational, Vec<(Poly, u32)>) {
    let content = p.monomial_content();
    let mut rest = p.div_monomial(&content);
    let mut factors: Vec<(Poly, u32)> = content
        .factors()
        .iter()
        .map(|&(atom, e)| (Poly::atom(atom), e))
        .collect();
    for (factor, _) in known {
        let mut found = 0;
        while rest.len() > 1 && might_divide(factor, &rest) {
            match rest.div_exact(factor, atoms.budget()) {
                Some(quotient) => {
                    rest = quotient;
                    found += 1;
                }
                None => break,
            }
        }
        if found > 0 {
            factors.push((factor.clone(), found));
        }
    }
    let coefficient = rest.leading().map_or(Rational::ONE, |(_, c)| c.clone());
    if rest.as_constant().is_none() {
        let monic = rest.scale(&coefficient.recip().unwrap_or(Rational::ONE));
        factors.push((monic, 1));
    }
    (coefficient, merge(&factors, &[]))
}
