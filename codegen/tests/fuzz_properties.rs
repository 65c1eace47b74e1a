//! The properties of the `parse` and `expand` fuzz targets (`fuzz/`), as
//! property tests with few cases and a fixed seed: any text parses to a
//! syntax tree or to diagnostics, and any mutation of a built-in model
//! compiles to code or to diagnostics, never a panic. (The third target's
//! property, the normal form keeps the value, is in `src/sym/proptests.rs`.)

use chaplygin_codegen::generate_within;
use chaplygin_codegen::sym::Budget;
use chaplygin_codegen::syntax::parse_str;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

fn config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(0x5eed_c4a9),
        failure_persistence: None,
        ..Config::default()
    }
}

proptest! {
    #![proptest_config(config(64))]

    #[test]
    fn any_text_parses_or_is_diagnosed(text in "(.|\n){0,200}") {
        if let Err(diagnostics) = parse_str(&text) {
            prop_assert!(!diagnostics.is_empty());
        }
    }
}

proptest! {
    #![proptest_config(config(12))]

    #[test]
    fn any_mutated_model_compiles_or_is_diagnosed(
        pick in any::<u8>(),
        mutations in proptest::collection::vec(any::<u8>(), 0..24),
    ) {
        let text = crate::support::mutate::mutated_model(pick, &mutations);
        if let Err(diagnostics) = generate_within(&text, Budget::new(200_000)) {
            prop_assert!(!diagnostics.is_empty());
        }
    }
}
