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

/// The kind of input on which the `jit` target's process died of a stack
/// overflow (FUZZING.md): five constants raised to the 7776th power, summed,
/// and the sum squared, a constant of 82,767 and 71,306 bits whose
/// continued fraction has 41,614 partial quotients, which the store's hash
/// of a big rational used to walk one stack frame each (the target's input
/// squared twice; once overflows a test's thread).
#[test]
fn a_sum_of_large_constant_powers_squared_compiles() {
    let constant = |n: u8, d: u8| [1, 17 * (d - 1) + n + 8];
    let sixth_power = [8, 11];
    let mut program = Vec::new();
    for (i, (n, d)) in [(3, 4), (2, 3), (5, 4), (7, 8), (5, 3)]
        .into_iter()
        .enumerate()
    {
        program.extend(constant(n, d));
        (0..5).for_each(|_| program.extend(sixth_power));
        if i > 0 {
            program.extend([3, 0]);
        }
    }
    let square = [15, 0, 5, 0];
    program.extend(square);
    program.extend([0.3_f64, 0.5, 0.7].iter().flat_map(|x| x.to_le_bytes()));
    native_matches_interpreter(&program);
}
