//! Norms and unit vectors: exact roots of squares, and square roots of
//! other polynomials carried exactly through products, quotients and
//! derivatives (`sqrt(u)^2 = u`).

use super::vector::{self, Vector};
use crate::sym::{ExprId, Function, Store, SymbolId, SymbolKind};

/// A store with a coordinate `q` and a parameter `p`, and their expressions.
fn store() -> (Store, [SymbolId; 2], [ExprId; 2]) {
    let mut store = Store::new();
    let q = store.declare("q", SymbolKind::Coordinate);
    let p = store.declare("p", SymbolKind::Parameter);
    let (qe, pe) = (store.symbol(q), store.symbol(p));
    (store, [q, p], [qe, pe])
}

fn is_zero(store: &mut Store, id: ExprId) -> bool {
    store.normal(id).expect("normal form").is_zero()
}

/// `(cos q, 2 sin q, p)`: `|a|^2 = 1 + 3 sin^2 q + p^2`, not a square.
fn skew_vector(store: &mut Store, [q, p]: [ExprId; 2]) -> Vector {
    let cos = store.apply(Function::Cos, q).expect("cos");
    let sin = store.apply(Function::Sin, q).expect("sin");
    let two = store.integer(2);
    [cos, store.mul2(two, sin), p]
}

#[test]
fn a_square_root_squared_is_its_radicand_exactly() {
    let (mut store, [q_symbol, _], symbols) = store();
    let a = skew_vector(&mut store, symbols);
    let square = vector::inner(&mut store, &a, &a);
    let root = store.sqrt(square).expect("sqrt");
    let root_squared = store.mul2(root, root);
    let difference = store.sub(root_squared, square);
    assert!(is_zero(&mut store, difference));
    // 1/sqrt(u)^2 = 1/u: denominators are cleared of roots.
    let one = store.integer(1);
    let reciprocal = store.div(one, root).expect("division");
    let reciprocal_squared = store.mul2(reciprocal, reciprocal);
    let inverse = store.div(one, square).expect("division");
    let difference = store.sub(reciprocal_squared, inverse);
    assert!(is_zero(&mut store, difference));
    // d sqrt(u)/dq * 2 sqrt(u) = du/dq.
    let d_root = store.derivative(root, q_symbol);
    let d_square = store.derivative(square, q_symbol);
    let two = store.integer(2);
    let product = store.mul(&[two, root, d_root]);
    let difference = store.sub(product, d_square);
    assert!(is_zero(&mut store, difference));
    // Not everything is zero: sqrt(u) - u is not.
    let difference = store.sub(root, square);
    assert!(!is_zero(&mut store, difference));
}

#[test]
fn a_norm_that_is_no_square_has_its_length_and_unit_vectors_have_norm_one() {
    let (mut store, [q, p], symbols) = store();
    let a = skew_vector(&mut store, symbols);
    let reference = |_| 0.0;
    let length = vector::norm(&mut store, &a, &reference).expect("norm");
    let (at_q, at_p) = (0.7_f64, -1.3_f64);
    let value_of = |s| {
        if s == q {
            at_q
        } else if s == p {
            at_p
        } else {
            0.0
        }
    };
    let expected = (1.0 + 3.0 * at_q.sin().powi(2) + at_p * at_p).sqrt();
    assert!((store.evaluate(length, &value_of) - expected).abs() < 1e-15);
    let direction = vector::unit(&mut store, &a, &reference).expect("unit");
    let square = vector::inner(&mut store, &direction, &direction);
    let one = store.integer(1);
    let difference = store.sub(square, one);
    assert!(is_zero(&mut store, difference));
}

#[test]
fn a_square_norm_is_taken_without_a_root_on_the_reference_branch() {
    let (mut store, [_, p], [qe, pe]) = store();
    let cos = store.apply(Function::Cos, qe).expect("cos");
    let zero = store.integer(0);
    let minus_p = store.neg(pe);
    // |(cos q, 0, 0)| = cos q near q = 0; |(0, -p, 0)| = p for p > 0.
    let defaults = move |s| if s == p { 2.0 } else { 0.0 };
    let tilted = vector::norm(&mut store, &[cos, zero, zero], &defaults).expect("norm");
    let difference = store.sub(tilted, cos);
    assert!(is_zero(&mut store, difference));
    let scaled = vector::norm(&mut store, &[zero, minus_p, zero], &defaults).expect("norm");
    let difference = store.sub(scaled, pe);
    assert!(is_zero(&mut store, difference));
    let form = store.normal(tilted).expect("normal");
    assert!(
        store.in_exact_class(&form),
        "no kernel: the root was taken exactly"
    );
}

#[test]
fn a_written_out_square_of_a_polynomial_is_rooted_exactly() {
    let (mut store, [_, p], [qe, pe]) = store();
    let cos = store.apply(Function::Cos, qe).expect("cos");
    let sin = store.apply(Function::Sin, qe).expect("sin");
    let one = store.integer(1);
    let zero = store.integer(0);
    let defaults = move |s| if s == p { 2.0 } else { 0.0 };
    // (1 + cos q)(cos q, sin q, 0): |a|^2 = (1 + cos q)^2 written out as
    // 1 + 2 cos q + cos^2 q once sin^2 q = 1 - cos^2 q.
    let one_plus_cos = store.add2(one, cos);
    let turning = [cos, sin, zero].map(|c| store.mul2(one_plus_cos, c));
    let length = vector::norm(&mut store, &turning, &defaults).expect("norm");
    let difference = store.sub(length, one_plus_cos);
    assert!(is_zero(&mut store, difference));
    let form = store.normal(length).expect("normal");
    assert!(store.in_exact_class(&form), "no root kernel");
    // (q - p cos q, 0, 0) with p = 2: the root is p cos q - q, positive at q = 0.
    let p_cos = store.mul2(pe, cos);
    let skew = store.sub(qe, p_cos);
    let length = vector::norm(&mut store, &[skew, zero, zero], &defaults).expect("norm");
    let expected = store.sub(p_cos, qe);
    let difference = store.sub(length, expected);
    assert!(is_zero(&mut store, difference));
    // 1 + 2 cos q + 2 cos^2 q is no square: it stays a root.
    let not_square = [one_plus_cos, cos, zero];
    let length = vector::norm(&mut store, &not_square, &defaults).expect("norm");
    let form = store.normal(length).expect("normal");
    assert!(!store.in_exact_class(&form), "a root kernel remains");
    let at_zero = store.evaluate(length, &defaults);
    assert!((at_zero - 5.0_f64.sqrt()).abs() < 1e-15, "{at_zero}");
}
