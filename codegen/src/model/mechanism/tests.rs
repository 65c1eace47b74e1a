//! Norms and unit vectors: exact roots of squares, and square roots of
//! other polynomials carried exactly through products, quotients and
//! derivatives (`sqrt(u)^2 = u`).

use super::vector::{self, Vector};
use crate::sym::Context;
use crate::sym::{ExprId, Function, SymbolId, SymbolKind};

/// A context with a coordinate `q` and a parameter `p`, and their expressions.
fn context() -> (Context, [SymbolId; 2], [ExprId; 2]) {
    let mut cx = Context::new();
    let q = cx.declare("q", SymbolKind::Coordinate);
    let p = cx.declare("p", SymbolKind::Parameter);
    let (qe, pe) = (cx.symbol(q), cx.symbol(p));
    (cx, [q, p], [qe, pe])
}

fn is_zero(cx: &mut Context, id: ExprId) -> bool {
    cx.normal(id).expect("normal form").is_zero()
}

/// `(cos q, 2 sin q, p)`: `|a|^2 = 1 + 3 sin^2 q + p^2`, not a square.
fn skew_vector(cx: &mut Context, [q, p]: [ExprId; 2]) -> Vector {
    let cos = cx.apply(Function::Cos, q).expect("cos");
    let sin = cx.apply(Function::Sin, q).expect("sin");
    let two = cx.integer(2);
    [cos, cx.mul2(two, sin), p]
}

#[test]
fn a_square_root_squared_is_its_radicand_exactly() {
    let (mut cx, [q_symbol, _], symbols) = context();
    let a = skew_vector(&mut cx, symbols);
    let square = vector::inner(&mut cx, &a, &a);
    let root = cx.sqrt(square).expect("sqrt");
    let root_squared = cx.mul2(root, root);
    let difference = cx.sub(root_squared, square);
    assert!(is_zero(&mut cx, difference));
    // 1/sqrt(u)^2 = 1/u: denominators are cleared of roots.
    let one = cx.integer(1);
    let reciprocal = cx.div(one, root).expect("division");
    let reciprocal_squared = cx.mul2(reciprocal, reciprocal);
    let inverse = cx.div(one, square).expect("division");
    let difference = cx.sub(reciprocal_squared, inverse);
    assert!(is_zero(&mut cx, difference));
    // d sqrt(u)/dq * 2 sqrt(u) = du/dq.
    let d_root = cx.derivative(root, q_symbol);
    let d_square = cx.derivative(square, q_symbol);
    let two = cx.integer(2);
    let product = cx.mul(&[two, root, d_root]);
    let difference = cx.sub(product, d_square);
    assert!(is_zero(&mut cx, difference));
    // Not everything is zero: sqrt(u) - u is not.
    let difference = cx.sub(root, square);
    assert!(!is_zero(&mut cx, difference));
}

#[test]
fn a_norm_that_is_no_square_has_its_length_and_unit_vectors_have_norm_one() {
    let (mut cx, [q, p], symbols) = context();
    let a = skew_vector(&mut cx, symbols);
    let reference = |_| 0.0;
    let length = vector::norm(&mut cx, &a, &reference).expect("norm");
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
    assert!((cx.evaluate(length, &value_of) - expected).abs() < 1e-15);
    let direction = vector::unit(&mut cx, &a, &reference).expect("unit");
    let square = vector::inner(&mut cx, &direction, &direction);
    let one = cx.integer(1);
    let difference = cx.sub(square, one);
    assert!(is_zero(&mut cx, difference));
}

#[test]
fn a_square_norm_is_taken_without_a_root_on_the_reference_branch() {
    let (mut cx, [_, p], [qe, pe]) = context();
    let cos = cx.apply(Function::Cos, qe).expect("cos");
    let zero = cx.integer(0);
    let minus_p = cx.neg(pe);
    // |(cos q, 0, 0)| = cos q near q = 0; |(0, -p, 0)| = p for p > 0.
    let defaults = move |s| if s == p { 2.0 } else { 0.0 };
    let tilted = vector::norm(&mut cx, &[cos, zero, zero], &defaults).expect("norm");
    let difference = cx.sub(tilted, cos);
    assert!(is_zero(&mut cx, difference));
    let scaled = vector::norm(&mut cx, &[zero, minus_p, zero], &defaults).expect("norm");
    let difference = cx.sub(scaled, pe);
    assert!(is_zero(&mut cx, difference));
    let form = cx.normal(tilted).expect("normal");
    assert!(
        cx.in_exact_class(&form),
        "no kernel: the root was taken exactly"
    );
}

#[test]
fn a_written_out_square_of_a_polynomial_is_rooted_exactly() {
    let (mut cx, [_, p], [qe, pe]) = context();
    let cos = cx.apply(Function::Cos, qe).expect("cos");
    let sin = cx.apply(Function::Sin, qe).expect("sin");
    let one = cx.integer(1);
    let zero = cx.integer(0);
    let defaults = move |s| if s == p { 2.0 } else { 0.0 };
    // (1 + cos q)(cos q, sin q, 0): |a|^2 = (1 + cos q)^2 written out as
    // 1 + 2 cos q + cos^2 q once sin^2 q = 1 - cos^2 q.
    let one_plus_cos = cx.add2(one, cos);
    let turning = [cos, sin, zero].map(|c| cx.mul2(one_plus_cos, c));
    let length = vector::norm(&mut cx, &turning, &defaults).expect("norm");
    let difference = cx.sub(length, one_plus_cos);
    assert!(is_zero(&mut cx, difference));
    let form = cx.normal(length).expect("normal");
    assert!(cx.in_exact_class(&form), "no root kernel");
    // (q - p cos q, 0, 0) with p = 2: the root is p cos q - q, positive at q = 0.
    let p_cos = cx.mul2(pe, cos);
    let skew = cx.sub(qe, p_cos);
    let length = vector::norm(&mut cx, &[skew, zero, zero], &defaults).expect("norm");
    let expected = cx.sub(p_cos, qe);
    let difference = cx.sub(length, expected);
    assert!(is_zero(&mut cx, difference));
    // 1 + 2 cos q + 2 cos^2 q is no square: it stays a root.
    let not_square = [one_plus_cos, cos, zero];
    let length = vector::norm(&mut cx, &not_square, &defaults).expect("norm");
    let form = cx.normal(length).expect("normal");
    assert!(!cx.in_exact_class(&form), "a root kernel remains");
    let at_zero = cx.evaluate(length, &defaults);
    assert!((at_zero - 5.0_f64.sqrt()).abs() < 1e-15, "{at_zero}");
}
