//! Every rule of the model language rejects a bad model at compile time, on
//! the offending token: one folder per category under `tests/compile_fail/`,
//! each case with its committed `.stderr` (see that folder's README).

#[test]
fn bad_models_are_compile_errors() {
    // trybuild's project has no profile of its own: without debug
    // information the macro and the engine it builds compile and load
    // faster, and no diagnostic depends on it. The root package's
    // `tests/user_crate.rs` builds in trybuild's folder with these
    // settings, so the macro and the engine are built once for both.
    // SAFETY: set before trybuild starts cargo, which inherits it; this
    // binary's only test, so no other thread reads the environment.
    unsafe { std::env::set_var("CARGO_PROFILE_DEV_DEBUG", "false") };
    let cases = trybuild::TestCases::new();
    cases.compile_fail("tests/compile_fail/*/*.rs");
}
