//! The inverse functions `asin acos atan atan2`: their derivatives against
//! central differences of `f64`'s own functions, their constant cases, and
//! the identities the engine must not apply.

use super::modular::{ModularError, Point};
use super::{Context, ExprId, Function, SymError, SymbolId, SymbolKind};

/// The coordinates `x`, `y` and the parameter `m`.
fn context() -> (Context, [SymbolId; 3], [ExprId; 3]) {
    let mut cx = Context::new();
    let symbols = [
        cx.declare("x", SymbolKind::Coordinate),
        cx.declare("y", SymbolKind::Coordinate),
        cx.declare("m", SymbolKind::Parameter),
    ];
    let leaves = symbols.map(|s| cx.symbol(s));
    (cx, symbols, leaves)
}

/// The value of `id` at `(x, y, m)`.
fn value(cx: &Context, symbols: &[SymbolId; 3], id: ExprId, at: [f64; 3]) -> f64 {
    cx.evaluate(id, &|s| {
        at[symbols.iter().position(|&t| t == s).unwrap_or(0)]
    })
}

/// `d id / dx` at `at`, by the tree and by the normal form, each within
/// `1e-8` of the central difference of `reference`, `f64`'s own functions.
fn assert_slope_in_x(
    cx: &mut Context,
    symbols: &[SymbolId; 3],
    id: ExprId,
    at: [f64; 3],
    reference: impl Fn(f64, f64, f64) -> f64,
) {
    let [x, y, m] = at;
    let h = 1e-6;
    let difference = (reference(x + h, y, m) - reference(x - h, y, m)) / (2.0 * h);
    assert_eq!(value(cx, symbols, id, at), reference(x, y, m));
    let tree = cx.derivative(id, symbols[0]);
    let form = cx.normal(id).expect("normal form");
    let d_form = cx.derivative_of_normal(&form, symbols[0]).expect("slope");
    let from_form = cx.expression_of(&d_form);
    for slope in [tree, from_form] {
        let slope_value = value(cx, symbols, slope, at);
        assert!(
            (slope_value - difference).abs() < 1e-8,
            "{}: {slope_value} vs {difference}",
            cx.display(slope)
        );
    }
}

#[test]
fn inverse_sine_cosine_and_tangent_differentiate_exactly() {
    let (mut cx, symbols, [x, y, m]) = context();
    let product = cx.mul(&[x, y, m]);
    for (function, reference) in [
        (Function::Asin, f64::asin as fn(f64) -> f64),
        (Function::Acos, f64::acos),
        (Function::Atan, f64::atan),
    ] {
        let applied = cx.apply(function, product).expect("applies");
        for at in [[0.4, 0.9, 1.3], [-0.7, 0.5, 2.1]] {
            assert_slope_in_x(&mut cx, &symbols, applied, at, |x, y, m| {
                reference(x * y * m)
            });
        }
    }
}

/// `atan2(y, x^2 m - 1)` in every quadrant of its point: the slope
/// `(x dy - y dx) / (x^2 + y^2)` with the ordinate first.
#[test]
fn atan2_differentiates_exactly_in_every_quadrant() {
    let (mut cx, symbols, [x, y, m]) = context();
    let square = cx.mul(&[x, x, m]);
    let one = cx.integer(1);
    let abscissa = cx.sub(square, one);
    let ordinate = cx.mul2(x, y);
    let angle = cx.atan2(ordinate, abscissa).expect("applies");
    for at in [
        [1.5, 0.8, 1.0],
        [0.5, 0.8, 1.0],
        [0.5, -0.8, 1.0],
        [1.5, -0.8, 1.0],
    ] {
        assert_slope_in_x(&mut cx, &symbols, angle, at, |x, y, m| {
            (x * y).atan2(x * x * m - 1.0)
        });
    }
}

#[test]
fn constant_arguments_fold_or_fail_outside_the_domain() {
    let (mut cx, _, _) = context();
    let [zero, one, two, minus_one] = [0, 1, 2, -1].map(|n| cx.integer(n));
    assert_eq!(cx.apply(Function::Asin, zero), Ok(zero));
    assert_eq!(cx.apply(Function::Acos, one), Ok(zero));
    assert_eq!(cx.apply(Function::Atan, zero), Ok(zero));
    assert_eq!(cx.atan2(zero, two), Ok(zero));
    for (function, outside) in [(Function::Asin, two), (Function::Acos, minus_one)] {
        let doubled = cx.mul2(outside, two);
        assert!(matches!(
            cx.apply(function, doubled),
            Err(SymError::Undefined { .. })
        ));
    }
    assert!(matches!(
        cx.atan2(zero, zero),
        Err(SymError::Undefined { .. })
    ));
    // atan2(0, -1) = pi and acos(0) = pi/2 are kept: not rational.
    let pi = cx.atan2(zero, minus_one).expect("defined");
    assert_eq!(cx.evaluate(pi, &|_| 0.0), std::f64::consts::PI);
    let quarter_turn = cx.apply(Function::Acos, zero).expect("defined");
    assert_eq!(
        cx.evaluate(quarter_turn, &|_| 0.0),
        std::f64::consts::FRAC_PI_2
    );
}

#[test]
fn the_arity_of_each_function_is_checked() {
    let (mut cx, _, [x, y, _]) = context();
    assert!(matches!(
        cx.apply_named("atan2", &[x]),
        Err(SymError::ArgumentCount {
            expected: 2,
            found: 1,
            ..
        })
    ));
    assert!(matches!(
        cx.apply_named("atan", &[y, x]),
        Err(SymError::ArgumentCount {
            expected: 1,
            found: 2,
            ..
        })
    ));
    let by_name = cx.apply_named("atan2", &[y, x]).expect("applies");
    assert_eq!(Ok(by_name), cx.atan2(y, x));
}

/// `atan(tan x) = x` only for `|x| < pi/2`, and `tan(atan x) = x`, `asin
/// x + acos x = pi/2`, though true, are not in the normal form: each stays
/// a non-zero form (its kernels opaque), and the first is indeed non-zero
/// at `x = 2`.
#[test]
fn branch_identities_are_not_applied() {
    let (mut cx, symbols, [x, _, _]) = context();
    let tangent = cx.apply(Function::Tan, x).expect("applies");
    let round_trip = cx.apply(Function::Atan, tangent).expect("applies");
    let difference = cx.sub(round_trip, x);
    assert!(!cx.normal(difference).expect("normal form").is_zero());
    assert!(value(&cx, &symbols, difference, [2.0, 0.0, 0.0]).abs() > 3.0);
    let inverse = cx.apply(Function::Atan, x).expect("applies");
    let back = cx.apply(Function::Tan, inverse).expect("applies");
    let back_difference = cx.sub(back, x);
    assert!(!cx.normal(back_difference).expect("normal form").is_zero());
}

/// Modular evaluation leaves the inverse functions out of its class: a
/// random residue for `atan(x)` would not keep `tan(atan(x)) = x`.
#[test]
fn modular_evaluation_refuses_inverse_functions() {
    let (mut cx, _, [x, y, _]) = context();
    let inverse = cx.apply(Function::Atan, x).expect("applies");
    let angle = cx.atan2(y, x).expect("applies");
    for id in [inverse, angle] {
        assert!(matches!(
            cx.evaluate_modular(&[id], &Point::new(7)),
            Err(ModularError::NotInClass { .. })
        ));
    }
}
