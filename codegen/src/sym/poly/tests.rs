//! Tests of the polynomials: trigonometric reduction, arithmetic, ordering.

use super::*;
use crate::sym::{Store, SymbolKind};

fn setup() -> (Atoms, AtomId, AtomId, AtomId) {
    let mut store = Store::new();
    let x = store.declare("x", SymbolKind::Coordinate);
    let arg = store.symbol(x);
    let mut atoms = Atoms::default();
    let m = atoms.symbol(store.declare("m", SymbolKind::Parameter));
    let (s, c) = atoms.trig_pair(arg);
    (atoms, m, s, c)
}

#[test]
fn sine_squared_reduces_to_one_minus_cosine_squared() {
    let (atoms, _, s, c) = setup();
    let sine = Poly::atom(s);
    let cosine = Poly::atom(c);
    let pythagoras = sine.mul(&sine, &atoms).add(&cosine.mul(&cosine, &atoms));
    assert_eq!(pythagoras, Poly::constant(Rational::ONE));
    let cube = sine.pow(3, &atoms);
    assert_eq!(cube.degree_in(s), 1);
}

#[test]
fn exact_division_recovers_the_factor_and_rejects_non_factors() {
    let (atoms, m, s, c) = setup();
    let a = Poly::atom(m).add(&Poly::atom(c));
    let b = Poly::atom(s).add(&Poly::constant(Rational::integer(3)));
    let product = a.mul(&b, &atoms);
    assert_eq!(product.div_exact(&a, atoms.budget()), Some(b.clone()));
    assert_eq!(b.div_exact(&a, atoms.budget()), None);
    assert_eq!(
        Poly::atom(m).mul(&Poly::atom(m), &atoms).monomial_content(),
        Monomial::power(m, 2)
    );
}

#[test]
fn lexicographic_order_is_multiplicative() {
    let (_, m, s, c) = setup();
    let a = Monomial::power(m, 1);
    let b = Monomial::power(s, 3).mul(&Monomial::power(c, 1));
    assert_eq!(a.cmp(&b), Ordering::Greater);
    let t = Monomial::power(c, 2);
    assert_eq!(a.mul(&t).cmp(&b.mul(&t)), Ordering::Greater);
}
