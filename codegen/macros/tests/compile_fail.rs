//! Every rule of the model language rejects a bad model at compile time, on
//! the offending token: one folder per category under `tests/compile_fail/`,
//! each case with its committed `.stderr` (see that folder's README).

#[test]
fn bad_models_are_compile_errors() {
    let cases = trybuild::TestCases::new();
    cases.compile_fail("tests/compile_fail/*/*.rs");
}
