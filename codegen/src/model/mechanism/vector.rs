//! Vector algebra in ground axes over the model's expressions.
//!
//! A vector is its three components in the axes of `ground`; a point is
//! its position `P - origin` in the same axes. `cross(a, b)`,
//! `inner(a, b) = a_1 b_1 + a_2 b_2 + a_3 b_3`, `norm(a) = sqrt(inner(a, a))`
//! and `unit(a) = a / norm(a)`.
//!
//! A norm is taken exactly when its square's normal form is a perfect
//! square `s^2` over a denominator of even multiplicities: `s` a monomial
//! `sqrt(c) m` (`c` a square rational, `m` a power product of atoms) or a
//! polynomial without sines, found term by term from the leading one
//! ([`polynomial_root`]: `(1 + cos q)^2` written out is `1 + cos q` again).
//! The root takes the sign that makes it positive at the model's reference
//! configuration
//! (coordinates zero, parameters at their defaults). This is the case of a
//! disk's contact point, `unit(cross(a, cross(a, z)))` with `|a x z| = |cos phi|`
//! for the lean `phi`, taken as `cos phi` on the branch of the upright disk.
//! Any other square stays `sqrt(...)`, a kernel of the normal form that
//! differentiation and emission carry like every other.

use crate::sym::{Atoms, Context, ExprId, Monomial, Poly, RationalFunction, SymError, SymbolId};

/// Three components in ground axes.
pub(in crate::model) type Vector = [ExprId; 3];

/// `a + b`.
pub(in crate::model) fn add(cx: &mut Context, a: &Vector, b: &Vector) -> Vector {
    [0, 1, 2].map(|i| cx.add2(a[i], b[i]))
}

/// `a - b`.
pub(in crate::model) fn sub(cx: &mut Context, a: &Vector, b: &Vector) -> Vector {
    [0, 1, 2].map(|i| cx.sub(a[i], b[i]))
}

/// `-a`.
pub(in crate::model) fn neg(cx: &mut Context, a: &Vector) -> Vector {
    [0, 1, 2].map(|i| cx.neg(a[i]))
}

/// `s a`.
pub(in crate::model) fn scale(cx: &mut Context, s: ExprId, a: &Vector) -> Vector {
    [0, 1, 2].map(|i| cx.mul2(s, a[i]))
}

/// `a x b`.
pub(in crate::model) fn cross(cx: &mut Context, a: &Vector, b: &Vector) -> Vector {
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let forward = cx.mul2(a[j], b[k]);
        let backward = cx.mul2(a[k], b[j]);
        cx.sub(forward, backward)
    })
}

/// `a . b`.
pub(in crate::model) fn inner(cx: &mut Context, a: &Vector, b: &Vector) -> ExprId {
    let products: Vec<ExprId> = (0..3).map(|i| cx.mul2(a[i], b[i])).collect();
    cx.add(&products)
}

/// The zero vector.
pub(in crate::model) fn zero(cx: &mut Context) -> Vector {
    let zero = cx.integer(0);
    [zero; 3]
}

/// `|a|`: exact when `a . a` is a perfect square (see the module's doc).
pub(in crate::model) fn norm(
    cx: &mut Context,
    a: &Vector,
    reference: &dyn Fn(SymbolId) -> f64,
) -> Result<ExprId, SymError> {
    let square = inner(cx, a, a);
    let form = cx.normal(square)?;
    match exact_root(cx, &form) {
        Some(root) => {
            let root = cx.expression_of(&root);
            if cx.evaluate(root, reference) < 0.0 {
                Ok(cx.neg(root))
            } else {
                Ok(root)
            }
        }
        None => {
            let canonical = cx.expression_of(&form);
            cx.sqrt(canonical)
        }
    }
}

/// `a / |a|`.
pub(in crate::model) fn unit(
    cx: &mut Context,
    a: &Vector,
    reference: &dyn Fn(SymbolId) -> f64,
) -> Result<Vector, SymError> {
    let length = norm(cx, a, reference)?;
    let mut components = *a;
    for component in &mut components {
        *component = cx.div(*component, length)?;
    }
    Ok(components)
}

/// `sqrt(form)` when the form is `s^2 / (f_1^2k_1 ...)`: `s` (see
/// [`polynomial_root`]) over the halved denominator.
fn exact_root(cx: &Context, form: &RationalFunction) -> Option<RationalFunction> {
    let root = polynomial_root(form.numerator(), cx.atoms())?;
    let mut result = RationalFunction::from_poly(root);
    for (factor, multiplicity) in form.denominator() {
        if multiplicity % 2 != 0 {
            return None;
        }
        let half = RationalFunction::from_poly(factor.pow(multiplicity / 2, cx.atoms()));
        result = result.div(&half, cx.atoms())?;
    }
    Some(result)
}

/// `s` with `s^2 = p` and a positive leading coefficient, when there is
/// one: the leading term of `p` is that of `s` squared, and each next term
/// of `s` is the leading term of the remainder `p - s_k^2` over twice the
/// leading term of `s` (the lexicographic order is a monomial order). A
/// polynomial with a sine is not tried: its square would have been reduced
/// by `sin^2 = 1 - cos^2`, so the remainders do not cancel term by term.
fn polynomial_root(p: &Poly, atoms: &Atoms) -> Option<Poly> {
    if p.has_sine(atoms) {
        return None;
    }
    let (lead_monomial, lead_coefficient) = p.leading()?;
    let root_monomial = half(lead_monomial)?;
    let root_coefficient = lead_coefficient.exact_root(2)?;
    let twice = root_coefficient.add(&root_coefficient);
    let mut root = Poly::term(root_monomial.clone(), root_coefficient);
    for _ in 0..p.len() {
        let remainder = p.sub(&root.mul(&root, atoms));
        let Some((monomial, coefficient)) = remainder.leading() else {
            return Some(root);
        };
        let next = monomial.div(&root_monomial)?;
        if next >= root_monomial {
            return None;
        }
        root = root.add(&Poly::term(next, coefficient.div(&twice)?));
    }
    p.sub(&root.mul(&root, atoms)).is_zero().then_some(root)
}

/// `m` with `m^2 = monomial`, when every exponent is even.
fn half(monomial: &Monomial) -> Option<Monomial> {
    monomial
        .factors()
        .iter()
        .try_fold(Monomial::one(), |half, &(atom, exponent)| {
            (exponent % 2 == 0).then(|| half.mul(&Monomial::power(atom, exponent / 2)))
        })
}
