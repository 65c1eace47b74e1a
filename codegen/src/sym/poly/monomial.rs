//! Monomials: power products of atoms, sorted by atom, and their
//! lexicographic order, the order of a [`super::Poly`]'s terms.

use super::AtomId;
use std::cmp::Ordering;

/// A power product of atoms, sorted by atom, exponents positive.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Default)]
pub struct Monomial(pub(super) Vec<(AtomId, u32)>);

impl Monomial {
    /// The monomial 1.
    pub fn one() -> Monomial {
        Monomial(Vec::new())
    }

    /// `atom^exponent`.
    pub fn power(atom: AtomId, exponent: u32) -> Monomial {
        if exponent == 0 {
            Monomial::one()
        } else {
            Monomial(vec![(atom, exponent)])
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
        let mut out = Vec::with_capacity(a.len() + b.len());
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
        out.extend_from_slice(&a[i..]);
        out.extend_from_slice(&b[j..]);
        Monomial(out)
    }

    /// `self / other` when `other` divides `self`.
    pub fn div(&self, other: &Monomial) -> Option<Monomial> {
        let mut out = Vec::with_capacity(self.0.len());
        let mut j = 0;
        for &(atom, exponent) in &self.0 {
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
    pub(super) fn without(&self, atom: AtomId) -> (u32, Monomial) {
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
