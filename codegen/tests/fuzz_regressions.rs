//! Inputs the fuzz targets (`fuzz/`, see `FUZZING.md`) found to hang or
//! crash the engine, each kept as a test of its fix.

use chaplygin_codegen::generate;
use chaplygin_codegen::sym::{Context, MAX_DEGREE, Rational, Store, SymError, SymbolKind};

/// `normal_form` timeout: `(-6)^4` raised to the 4th power again and again
/// reaches `6^(4^9)`, a 677,000-bit constant whose exact folding took minutes.
/// `6^(4^k)` has `4^k * log2(6)` bits: 42,353 for k = 7 (under the limit of
/// 65,536), 169,413 for k = 8 (over it), so exactly seven folds succeed.
#[test]
fn a_tower_of_constant_powers_is_rejected_not_computed() {
    let mut store = Store::new();
    let mut power = store.integer(6);
    let mut folds = 0;
    let error = loop {
        match store.pow(power, Rational::integer(4)) {
            Ok(next) => {
                power = next;
                folds += 1;
            }
            Err(error) => break error,
        }
    };
    assert_eq!(folds, 7);
    assert!(
        matches!(error, SymError::ConstantTooLarge { .. }),
        "{error:?}"
    );
}

/// The same tower written in a model is one diagnostic.
#[test]
fn a_model_with_a_tower_of_constant_powers_is_diagnosed() {
    let text = "pub struct Tower { coordinates: [x], \
                kinetic_energy: ((((((((((6^4)^4)^4)^4)^4)^4)^4)^4)^4)*dot(x)^2) }";
    let diagnostics = generate(text).expect_err("the constant is too large");
    let rendered = diagnostics.render("tower.model");
    assert!(
        rendered.contains("a constant power with about"),
        "{rendered}"
    );
}

/// `normal_form` wrong value: the normal form of `(x^412316860416 - x)^3`
/// squared `x` on to `x^(2^32)`, past its `u32` exponents, which wrapped to
/// `x^0`, and so expanded `(1 - x)^3`: 0.027 at `x = 0.7` for the tree's
/// -0.343. A degree past `MAX_DEGREE` is now an error.
#[test]
fn a_power_past_the_degree_limit_is_rejected_not_wrapped() {
    let mut cx = Context::new();
    let x = cx.declare("x", SymbolKind::Coordinate);
    let x = cx.symbol(x);
    let power = |cx: &mut Context, base, n: i64| cx.pow(base, Rational::integer(n)).unwrap();
    let high = power(&mut cx, x, 412_316_860_416);
    let difference = cx.sub(high, x);
    let cube = power(&mut cx, difference, 3);
    let degree_too_large = Err(SymError::DegreeTooLarge { limit: MAX_DEGREE });
    assert_eq!(cx.normal(cube), degree_too_large);

    let mut cx = Context::new();
    let x = cx.declare("x", SymbolKind::Coordinate);
    let x = cx.symbol(x);
    let at_the_limit = power(&mut cx, x, i64::from(MAX_DEGREE));
    let form = cx
        .normal(at_the_limit)
        .expect("the limit itself is allowed");
    assert_eq!(cx.evaluate_normal(&form, &|_| 1.0), 1.0);
    assert_eq!(form.numerator().degree_in(form.atoms()[0]), MAX_DEGREE);
}

/// The same bound on a denominator factor's multiplicity: `(x + 1)^-80000`
/// squares the factor's multiplicity up past `MAX_DEGREE`.
#[test]
fn a_denominator_past_the_degree_limit_is_rejected() {
    let mut cx = Context::new();
    let x = cx.declare("x", SymbolKind::Coordinate);
    let x = cx.symbol(x);
    let one = cx.integer(1);
    let sum = cx.add2(x, one);
    let power = cx.pow(sum, Rational::integer(-80_000)).unwrap();
    assert_eq!(
        cx.normal(power),
        Err(SymError::DegreeTooLarge { limit: MAX_DEGREE })
    );
}

/// In a model, the degree past the limit is one diagnostic.
#[test]
fn a_model_with_a_power_past_the_degree_limit_is_diagnosed() {
    let text = "pub struct High { coordinates: [x], \
                kinetic_energy: (1 + (x^412316860416 - x)^2)*dot(x)^2 }";
    let diagnostics = generate(text).expect_err("the degree is too high");
    let rendered = diagnostics.render("high.model");
    assert!(
        rendered.contains("the normal form needs a power of degree above 65536"),
        "{rendered}"
    );
}
