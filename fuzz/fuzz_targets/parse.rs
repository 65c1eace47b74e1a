//! Arbitrary bytes as model text through the parser: a syntax tree or
//! diagnostics, never a panic.

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Err(diagnostics) = chaplygin_codegen::syntax::parse_str(&text) {
        assert!(!diagnostics.is_empty(), "a rejected text has a diagnostic");
    }
});
