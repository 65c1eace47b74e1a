//! Differential: random straight-line programs compiled to native code by
//! the JIT give, bit for bit, what the IR's interpreter gives (see
//! `jit/tests/support/random_programs.rs` for the programs and the points).

#![no_main]

#[path = "../../jit/tests/support/random_programs.rs"]
mod random_programs;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| random_programs::native_matches_interpreter(data));
