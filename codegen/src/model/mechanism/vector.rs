//! Vector algebra in ground axes over the model's expressions.
//!
//! A vector is its three components in the axes of `ground`; a point is
//! its position `P - origin` in the same axes. `cross(a, b)`,
//! `inner(a, b) = a_1 b_1 + a_2 b_2 + a_3 b_3`, `norm(a) = sqrt(inner(a, a))`
//! and `unit(a) = a / norm(a)`.
//!
//! A norm is taken exactly when its square's normal form is a perfect
//! square `c m^2` (`c` a square rational, `m` a power product of atoms over
//! a denominator of even multiplicities): the root is `sqrt(c) m`, with the
//! sign that makes it positive at the model's reference configuration
//! (coordinates zero, parameters at their defaults). This is the case of a
//! disk's contact point, `unit(cross(a, cross(a, z)))` with `|a x z| = |cos phi|`
//! for the lean `phi`, taken as `cos phi` on the branch of the upright disk.
//! Any other square stays `sqrt(...)`, a kernel of the normal form that
//! differentiation and emission carry like every other.

use crate::sym::{ExprId, Monomial, Poly, RationalFunction, Store, SymError, SymbolId};

/// Three components in ground axes.
pub(in crate::model) type Vector = [ExprId; 3];

/// `a + b`.
pub(in crate::model) fn add(store: &mut Store, a: &Vector, b: &Vector) -> Vector {
    [0, 1, 2].map(|i| store.add2(a[i], b[i]))
}

/// `a - b`.
pub(in crate::model) fn sub(store: &mut Store, a: &Vector, b: &Vector) -> Vector {
    [0, 1, 2].map(|i| store.sub(a[i], b[i]))
}

/// `-a`.
pub(in crate::model) fn neg(store: &mut Store, a: &Vector) -> Vector {
    [0, 1, 2].map(|i| store.neg(a[i]))
}

/// `s a`.
pub(in crate::model) fn scale(store: &mut Store, s: ExprId, a: &Vector) -> Vector {
    [0, 1, 2].map(|i| store.mul2(s, a[i]))
}

/// `a x b`.
pub(in crate::model) fn cross(store: &mut Store, a: &Vector, b: &Vector) -> Vector {
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let forward = store.mul2(a[j], b[k]);
        let backward = store.mul2(a[k], b[j]);
        store.sub(forward, backward)
    })
}

/// `a . b`.
pub(in crate::model) fn inner(store: &mut Store, a: &Vector, b: &Vector) -> ExprId {
    let products: Vec<ExprId> = (0..3).map(|i| store.mul2(a[i], b[i])).collect();
    store.add(&products)
}

/// The zero vector.
pub(in crate::model) fn zero(store: &mut Store) -> Vector {
    let zero = store.integer(0);
    [zero; 3]
}

/// `|a|`: exact when `a . a` is a perfect square (see the module's doc).
pub(in crate::model) fn norm(
    store: &mut Store,
    a: &Vector,
    reference: &dyn Fn(SymbolId) -> f64,
) -> Result<ExprId, SymError> {
    let square = inner(store, a, a);
    let form = store.normal(square)?;
    match exact_root(store, &form) {
        Some(root) => {
            let root = store.expression_of(&root);
            if store.evaluate(root, reference) < 0.0 {
                Ok(store.neg(root))
            } else {
                Ok(root)
            }
        }
        None => {
            let canonical = store.expression_of(&form);
            store.sqrt(canonical)
        }
    }
}

/// `a / |a|`.
pub(in crate::model) fn unit(
    store: &mut Store,
    a: &Vector,
    reference: &dyn Fn(SymbolId) -> f64,
) -> Result<Vector, SymError> {
    let length = norm(store, a, reference)?;
    let mut components = *a;
    for component in &mut components {
        *component = store.div(*component, length)?;
    }
    Ok(components)
}

/// `sqrt(form)` when the form is `c m^2 / (f_1^2k_1 ...)` with `c` a square
/// rational and `m` a power product: a monomial over the halved denominator.
fn exact_root(store: &Store, form: &RationalFunction) -> Option<RationalFunction> {
    let [(monomial, coefficient)] = form.numerator().terms() else {
        return None;
    };
    let root_coefficient = coefficient.exact_root(2)?;
    let mut root = Poly::term(Monomial::one(), root_coefficient);
    for &(atom, exponent) in monomial.factors() {
        if exponent % 2 != 0 {
            return None;
        }
        root = root.mul_term(
            &Monomial::power(atom, exponent / 2),
            &crate::sym::Rational::ONE,
        );
    }
    let mut result = RationalFunction::from_poly(root);
    for (factor, multiplicity) in form.denominator() {
        if multiplicity % 2 != 0 {
            return None;
        }
        let half = RationalFunction::from_poly(factor.pow(multiplicity / 2, store.atoms()));
        result = result.div(&half, store.atoms())?;
    }
    Some(result)
}
