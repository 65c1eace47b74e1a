//! Inputs the fuzz targets (`fuzz/`, see `FUZZING.md`) found to hang or
//! crash the engine, each kept as a test of its fix.

use chaplygin_codegen::generate;
use chaplygin_codegen::sym::{Rational, Store, SymError};

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
