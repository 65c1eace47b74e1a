//! The `jit` fuzz target's property as a property test with a fixed seed:
//! random straight-line programs give the interpreter's bits in native
//! code (`support/random_programs.rs`).

use crate::support::random_programs::native_matches_interpreter;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

proptest! {
    #![proptest_config(Config {
        cases: 256,
        rng_seed: RngSeed::Fixed(0x11_7d1f),
        failure_persistence: None,
        ..Config::default()
    })]

    #[test]
    fn random_programs_give_the_interpreters_bits(data in proptest::collection::vec(any::<u8>(), 0..400)) {
        native_matches_interpreter(&data);
    }
}
