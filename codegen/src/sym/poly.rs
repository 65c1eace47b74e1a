//! Sparse multivariate polynomials over *atoms*, reduced modulo `sin^2 + cos^2 = 1`
//! and `s^2 = u` for a square root `s = sqrt(u)` of a polynomial `u`.
//!
//! An atom is a symbol, the sine or cosine of an argument (always interned as a
//! pair), or an opaque kernel (`exp(u)`, `ln(u)`, `u^(p/q)` with `u` already in
//! normal form). A [`Poly`] is a list of terms with exact rational coefficients,
//! sorted by the lexicographic monomial order, leading term first. Every
//! product is reduced by `sin^2 a -> 1 - cos^2 a`, so each sine has degree at
//! most one; on this representation two polynomials are equal as functions of
//! independent symbols exactly when their term lists are equal (the monomials
//! `s^e * c^k * ...` with `e <= 1` form a basis of `Q[s, c]/(s^2 + c^2 - 1)`).
//! A square root of a polynomial, `r = sqrt(u)` (a kernel whose radicand is
//! recorded), is likewise reduced by `r^2 -> u` to degree at most one, so
//! `a + b r` with `a`, `b` free of `r` is its representation; it is
//! canonical when `u` is not a square, the case of the norms of vectors
//! whose square the mechanism stage could not take exactly.

mod atoms;
mod factors;
#[cfg(test)]
mod tests;

pub use atoms::{Atom, AtomId, Atoms};
use factors::Factors;

use super::budget::Budget;
use super::number::Rational;
use rustc_hash::FxHashMap as HashMap;
use std::cmp::Ordering;

/// A power product of atoms, sorted by atom, exponents positive.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Default)]
pub struct Monomial(Factors);

impl Monomial {
    /// The monomial 1.
    pub fn one() -> Monomial {
        Monomial(Factors::new())
    }

    /// `atom^exponent`.
    pub fn power(atom: AtomId, exponent: u32) -> Monomial {
        if exponent == 0 {
            Monomial::one()
        } else {
            Monomial([(atom, exponent)].into_iter().collect())
        }
    }

    /// The `(atom, exponent)` pairs, sorted by atom.
    pub fn factors(&self) -> &[(AtomId, u32)] {
        &self.0
    }

    /// The exponent of `atom` (0 when absent).
    pub fn exponent(&self, atom: AtomId) -> u32 {
        self.0
            .binary_search_by_key(&atom, |&(a, _)| a)
            .map_or(0, |at| self.0[at].1)
    }

    /// True for the monomial 1.
    pub fn is_one(&self) -> bool {
        self.0.is_empty()
    }

    /// `self * other`.
    pub fn mul(&self, other: &Monomial) -> Monomial {
        let (a, b) = (&self.0, &other.0);
        let mut out = Factors::new();
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                Ordering::Less => {
                    out.push(a[i]);
                    i += 1;
                }
                Ordering::Greater => {
                    out.push(b[j]);
                    j += 1;
                }
                Ordering::Equal => {
                    out.push((a[i].0, a[i].1 + b[j].1));
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend(a[i..].iter().copied());
        out.extend(b[j..].iter().copied());
        Monomial(out)
    }

    /// `self / other` when `other` divides `self`.
    pub fn div(&self, other: &Monomial) -> Option<Monomial> {
        let mut out = Factors::new();
        let mut j = 0;
        for &(atom, exponent) in self.0.iter() {
            let divisor = match other.0.get(j) {
                Some(&(a, e)) if a == atom => {
                    j += 1;
                    e
                }
                Some(&(a, _)) if a < atom => return None,
                _ => 0,
            };
            match exponent.cmp(&divisor) {
                Ordering::Less => return None,
                Ordering::Equal => {}
                Ordering::Greater => out.push((atom, exponent - divisor)),
            }
        }
        (j == other.0.len()).then_some(Monomial(out))
    }

    /// The greatest common divisor of two monomials.
    pub fn gcd(&self, other: &Monomial) -> Monomial {
        Monomial(
            self.0
                .iter()
                .filter_map(|&(atom, e)| {
                    let f = other.exponent(atom);
                    (f > 0).then_some((atom, e.min(f)))
                })
                .collect(),
        )
    }

    /// Total degree.
    pub fn degree(&self) -> u32 {
        self.0.iter().map(|&(_, e)| e).sum()
    }

    /// Removes `atom` entirely, returning its exponent and the rest.
    fn without(&self, atom: AtomId) -> (u32, Monomial) {
        let exponent = self.exponent(atom);
        let rest = self.0.iter().copied().filter(|&(a, _)| a != atom).collect();
        (exponent, Monomial(rest))
    }
}

/// The lexicographic monomial order (lower atom ids most significant).
/// It is a monomial order: total, and `a > b` implies `t a > t b`.
impl Ord for Monomial {
    fn cmp(&self, other: &Self) -> Ordering {
        let (a, b) = (&self.0, &other.0);
        for k in 0.. {
            return match (a.get(k), b.get(k)) {
                (None, None) => Ordering::Equal,
                (Some(_), None) => Ordering::Greater,
                (None, Some(_)) => Ordering::Less,
                (Some(&(x, e)), Some(&(y, f))) => match x.cmp(&y) {
                    Ordering::Less => Ordering::Greater,
                    Ordering::Greater => Ordering::Less,
                    Ordering::Equal if e == f => continue,
                    Ordering::Equal => e.cmp(&f),
                },
            };
        }
        Ordering::Equal
    }
}

impl PartialOrd for Monomial {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// A polynomial: terms sorted by decreasing monomial, no zero coefficients.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
pub struct Poly {
    terms: Vec<(Monomial, Rational)>,
}

impl Poly {
    /// The zero polynomial.
    pub fn zero() -> Poly {
        Poly { terms: Vec::new() }
    }

    /// A constant.
    pub fn constant(value: Rational) -> Poly {
        Poly::term(Monomial::one(), value)
    }

    /// `coefficient * monomial`.
    pub fn term(monomial: Monomial, coefficient: Rational) -> Poly {
        if coefficient.is_zero() {
            return Poly::zero();
        }
        Poly {
            terms: vec![(monomial, coefficient)],
        }
    }

    /// The atom itself.
    pub fn atom(atom: AtomId) -> Poly {
        Poly::term(Monomial::power(atom, 1), Rational::ONE)
    }

    /// Builds a polynomial from terms in any order, merging equal monomials.
    pub fn from_terms(terms: impl IntoIterator<Item = (Monomial, Rational)>) -> Poly {
        let mut collected: HashMap<Monomial, Rational> = HashMap::default();
        for (monomial, coefficient) in terms {
            let entry = collected.entry(monomial).or_insert(Rational::ZERO);
            *entry = entry.add(&coefficient);
        }
        let mut terms: Vec<(Monomial, Rational)> = collected
            .into_iter()
            .filter(|(_, c)| !c.is_zero())
            .collect();
        terms.sort_unstable_by(|a, b| b.0.cmp(&a.0));
        Poly { terms }
    }

    /// The terms, leading term first.
    pub fn terms(&self) -> &[(Monomial, Rational)] {
        &self.terms
    }

    /// True for zero.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// The value when the polynomial is a constant.
    pub fn as_constant(&self) -> Option<Rational> {
        match self.terms.as_slice() {
            [] => Some(Rational::ZERO),
            [(m, c)] if m.is_one() => Some(c.clone()),
            _ => None,
        }
    }

    /// The leading term.
    pub fn leading(&self) -> Option<&(Monomial, Rational)> {
        self.terms.first()
    }

    /// The atoms the polynomial mentions.
    pub fn atoms(&self) -> Vec<AtomId> {
        let mut atoms: Vec<AtomId> = self
            .terms
            .iter()
            .flat_map(|(m, _)| m.0.iter().map(|&(a, _)| a))
            .collect();
        atoms.sort_unstable();
        atoms.dedup();
        atoms
    }

    /// `-self`.
    pub fn neg(&self) -> Poly {
        self.scale(&Rational::integer(-1))
    }

    /// `c * self`.
    pub fn scale(&self, c: &Rational) -> Poly {
        if c.is_zero() {
            return Poly::zero();
        }
        Poly {
            terms: self
                .terms
                .iter()
                .map(|(m, k)| (m.clone(), k.mul(c)))
                .collect(),
        }
    }

    /// `self + other`.
    pub fn add(&self, other: &Poly) -> Poly {
        self.merge(other, false)
    }

    /// `self - other`.
    pub fn sub(&self, other: &Poly) -> Poly {
        self.merge(other, true)
    }

    /// `self + other`, or `self - other` when `negate_other`, by merging
    /// the sorted term lists (no negated copy of `other`).
    fn merge(&self, other: &Poly, negate_other: bool) -> Poly {
        Poly::merged(
            self.terms.iter().cloned(),
            other.terms.iter().cloned(),
            negate_other,
        )
    }

    /// The sum of two term lists sorted by decreasing monomial, the second
    /// negated when `negate_other`, by merging them; terms that cancel are
    /// left out. The terms are taken, not copied, so a long remainder that
    /// changes in few terms is not copied whole.
    fn merged(
        a: impl Iterator<Item = (Monomial, Rational)>,
        b: impl Iterator<Item = (Monomial, Rational)>,
        negate_other: bool,
    ) -> Poly {
        let signed = |c: Rational| if negate_other { c.neg() } else { c };
        let (mut a, mut b) = (a.peekable(), b.peekable());
        let mut terms = Vec::with_capacity(a.size_hint().0 + b.size_hint().0);
        while let (Some((m, _)), Some((n, _))) = (a.peek(), b.peek()) {
            match m.cmp(n) {
                Ordering::Greater => terms.extend(a.next()),
                Ordering::Less => terms.extend(b.next().map(|(n, d)| (n, signed(d)))),
                Ordering::Equal => {
                    let ((m, c), (_, d)) = (a.next().expect("peeked"), b.next().expect("peeked"));
                    let sum = c.add(&signed(d));
                    if !sum.is_zero() {
                        terms.push((m, sum));
                    }
                }
            }
        }
        terms.extend(a);
        terms.extend(b.map(|(n, d)| (n, signed(d))));
        Poly { terms }
    }

    /// `coefficient * monomial * self`; the order is kept, so no sorting.
    pub fn mul_term(&self, monomial: &Monomial, coefficient: &Rational) -> Poly {
        if coefficient.is_zero() {
            return Poly::zero();
        }
        Poly {
            terms: self
                .terms
                .iter()
                .map(|(m, c)| (m.mul(monomial), c.mul(coefficient)))
                .collect(),
        }
    }

    /// `self * other` without trigonometric reduction.
    fn mul_unreduced(&self, other: &Poly) -> Poly {
        if self.is_zero() || other.is_zero() {
            return Poly::zero();
        }
        if let Some(c) = other.as_constant() {
            return self.scale(&c);
        }
        if let Some(c) = self.as_constant() {
            return other.scale(&c);
        }
        Poly::from_terms(
            self.terms
                .iter()
                .flat_map(|(m, c)| other.terms.iter().map(move |(n, d)| (m.mul(n), c.mul(d)))),
        )
    }

    /// `self * other`, reduced by `sin^2 = 1 - cos^2`; zero once the budget
    /// of `atoms` is spent. The product is charged `self.len() * other.len()`
    /// term products, each weighted by the sizes in words of the largest
    /// coefficients (big coefficients make each product slower), and is
    /// not computed where an exponent could pass the budget's degree limit.
    pub fn mul(&self, other: &Poly, atoms: &Atoms) -> Poly {
        let products = (self.len() as u64)
            .saturating_mul(other.len() as u64)
            .saturating_mul(self.coefficient_words())
            .saturating_mul(other.coefficient_words());
        let degree = u64::from(self.highest_exponent()) + u64::from(other.highest_exponent());
        if !atoms.budget().admits_degree(degree) || !atoms.budget().charge(products) {
            return Poly::zero();
        }
        self.mul_unreduced(other).reduce_trig(atoms)
    }

    /// The highest exponent of any atom in any term.
    fn highest_exponent(&self) -> u32 {
        self.terms
            .iter()
            .flat_map(|(m, _)| m.0.iter().map(|&(_, e)| e))
            .max()
            .unwrap_or(0)
    }

    /// The size in words of the largest coefficient (1 for zero).
    fn coefficient_words(&self) -> u64 {
        self.terms.iter().map(|(_, c)| c.words()).max().unwrap_or(1)
    }

    /// `self^n`.
    pub fn pow(&self, n: u32, atoms: &Atoms) -> Poly {
        let mut result = Poly::constant(Rational::ONE);
        for _ in 0..n {
            result = result.mul(self, atoms);
        }
        result
    }

    /// Replaces every `sin^e` with `e >= 2` by `sin^(e mod 2) (1 - cos^2)^(e div 2)`,
    /// and every `r^e` of a square root `r = sqrt(u)` by `r^(e mod 2) u^(e div 2)`,
    /// charging the terms each expansion step creates to the budget of `atoms`
    /// (zero once it is spent).
    pub fn reduce_trig(self, atoms: &Atoms) -> Poly {
        let needs_reduction =
            |m: &Monomial| m.0.iter().any(|&(a, e)| e >= 2 && atoms.is_reducible(a));
        if !self.terms.iter().any(|(m, _)| needs_reduction(m)) {
            return self;
        }
        let mut reduced = Vec::new();
        let mut roots_expanded = false;
        for (monomial, coefficient) in self.terms {
            let mut expansion = Poly::term(Monomial::one(), coefficient);
            let mut kept = Factors::new();
            for &(atom, exponent) in monomial.0.iter() {
                let square = match (atoms.cosine_of(atom), atoms.radicand_of(atom)) {
                    _ if exponent < 2 => None,
                    (Some(cosine), _) => Some(
                        Poly::constant(Rational::ONE)
                            .sub(&Poly::term(Monomial::power(cosine, 2), Rational::ONE)),
                    ),
                    (None, Some(radicand)) => {
                        roots_expanded = true;
                        Some(radicand.clone())
                    }
                    (None, None) => None,
                };
                let Some(square) = square else {
                    kept.push((atom, exponent));
                    continue;
                };
                for _ in 0..exponent / 2 {
                    if !atoms
                        .budget()
                        .charge(square.len() as u64 * expansion.len() as u64)
                    {
                        return Poly::zero();
                    }
                    expansion = expansion.mul_unreduced(&square);
                }
                if exponent % 2 == 1 {
                    kept.push((atom, 1));
                }
            }
            let kept = Monomial(kept);
            reduced.extend(expansion.terms.into_iter().map(|(m, c)| (m.mul(&kept), c)));
        }
        let reduced = Poly::from_terms(reduced);
        // A radicand may bring sines (or roots) that meet the kept ones.
        if roots_expanded {
            reduced.reduce_trig(atoms)
        } else {
            reduced
        }
    }

    /// True when some sine atom occurs.
    pub fn has_sine(&self, atoms: &Atoms) -> bool {
        self.atoms().iter().any(|&a| atoms.cosine_of(a).is_some())
    }

    /// `p(-s)` for a sine atom `s`: the conjugate used to clear sines from a denominator.
    pub fn conjugate(&self, sine: AtomId) -> Poly {
        Poly {
            terms: self
                .terms
                .iter()
                .map(|(m, c)| {
                    if m.exponent(sine) % 2 == 1 {
                        (m.clone(), c.neg())
                    } else {
                        (m.clone(), c.clone())
                    }
                })
                .collect(),
        }
    }

    /// `self / divisor` when the division is exact. The divisor must contain no
    /// sine (then no reduction can occur and polynomial division is division in
    /// the trigonometric ring). Each step charges `budget` the terms of the
    /// remainder it rewrites, weighted as products are by the sizes in words
    /// of the largest coefficients (each step multiplies the divisor by a
    /// coefficient of the remainder's size and reduces the sums); `None` once
    /// the budget is spent.
    pub fn div_exact(&self, divisor: &Poly, budget: &Budget) -> Option<Poly> {
        let (lead_monomial, lead_coefficient) = divisor.leading()?;
        if let Some(c) = divisor.as_constant() {
            return Some(self.scale(&c.recip()?));
        }
        let mut remainder = self.clone();
        let mut quotient = Vec::new();
        while let Some((monomial, coefficient)) = remainder.leading() {
            let rewritten = ((remainder.len() + divisor.len()) as u64)
                .saturating_mul(remainder.coefficient_words())
                .saturating_mul(divisor.coefficient_words());
            if !budget.charge(rewritten) {
                return None;
            }
            let factor = monomial.div(lead_monomial)?;
            let c = coefficient.div(lead_coefficient)?;
            let product = divisor.mul_term(&factor, &c);
            remainder = Poly::merged(remainder.terms.into_iter(), product.terms.into_iter(), true);
            quotient.push((factor, c));
        }
        Some(Poly { terms: quotient })
    }

    /// The largest monomial dividing every term (1 for zero).
    pub fn monomial_content(&self) -> Monomial {
        let mut terms = self.terms.iter();
        let Some((first, _)) = terms.next() else {
            return Monomial::one();
        };
        terms.fold(first.clone(), |g, (m, _)| g.gcd(m))
    }

    /// Divides every term by a monomial that divides all of them.
    pub fn div_monomial(&self, monomial: &Monomial) -> Poly {
        Poly {
            terms: self
                .terms
                .iter()
                .filter_map(|(m, c)| Some((m.div(monomial)?, c.clone())))
                .collect(),
        }
    }

    /// Highest exponent of `atom`.
    pub fn degree_in(&self, atom: AtomId) -> u32 {
        self.terms
            .iter()
            .map(|(m, _)| m.exponent(atom))
            .max()
            .unwrap_or(0)
    }

    /// Coefficients of `atom^0, atom^1, ...`, as polynomials in the other atoms.
    pub fn coefficients_in(&self, atom: AtomId) -> Vec<Poly> {
        let mut by_power = vec![Vec::new(); self.degree_in(atom) as usize + 1];
        for (monomial, coefficient) in &self.terms {
            let (exponent, rest) = monomial.without(atom);
            by_power[exponent as usize].push((rest, coefficient.clone()));
        }
        by_power.into_iter().map(Poly::from_terms).collect()
    }

    /// The value at the given atom values.
    pub fn evaluate(&self, value_of: &dyn Fn(AtomId) -> f64) -> f64 {
        self.terms
            .iter()
            .map(|(m, c)| {
                m.0.iter()
                    .fold(c.to_f64(), |acc, &(a, e)| acc * value_of(a).powi(e as i32))
            })
            .sum()
    }

    /// Number of terms.
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// True for zero (no terms).
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }
}
