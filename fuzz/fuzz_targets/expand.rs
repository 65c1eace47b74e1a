//! Mutated built-in models through the whole compiler: generated code or
//! diagnostics, never a panic or a hang.
//!
//! The first byte picks a built-in model (snakeboard, rolling disk,
//! differential drive, sleigh); the rest are mutations of its token list
//! (`codegen/tests/support/mutate.rs`).
//! Each compile runs within a small derivation budget so that inputs stay
//! fast; exceeding it is an accepted outcome (a diagnostic).

#![no_main]

#[path = "../../codegen/tests/support/mod.rs"]
mod support;

use chaplygin_codegen::generate_within;
use chaplygin_codegen::sym::Budget;
use libfuzzer_sys::fuzz_target;

/// A tenth of the default: the built-in models use far less.
const BUDGET: u64 = 2_000_000;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, mutations)) = data.split_first() else {
        return;
    };
    let text = support::mutate::mutated_model(pick, mutations);
    if let Err(diagnostics) = generate_within(&text, Budget::new(BUDGET)) {
        assert!(!diagnostics.is_empty(), "a rejected model has a diagnostic");
    }
});
