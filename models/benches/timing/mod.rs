//! A timing loop for ratios measured in one run: each function is called on
//! the same cycled inputs in batches, and the best batch of several counts,
//! which removes most of the noise of a shared machine.

use std::hint::black_box;
use std::time::Instant;

/// Batches timed per function; the fastest one is kept.
const BATCHES: usize = 9;

/// Nanoseconds per call of `function` over `inputs` (cycled, `calls` calls
/// per batch), the best of [`BATCHES`] batches.
pub fn best_nanoseconds<I, O>(inputs: &[I], calls: usize, function: impl Fn(&I) -> O) -> f64 {
    (0..BATCHES)
        .map(|_| {
            let start = Instant::now();
            for call in 0..calls {
                black_box(function(black_box(&inputs[call % inputs.len()])));
            }
            start.elapsed().as_nanos() as f64 / calls as f64
        })
        .fold(f64::INFINITY, f64::min)
}

/// Prints `name: generated / hand-written = ratio` with both times.
pub fn print_ratio(name: &str, generated: f64, hand_written: f64) {
    println!(
        "RATIO {name}: generated {generated:.2} ns / hand-written {hand_written:.2} ns = {:.3}",
        generated / hand_written
    );
}

/// Deterministic pseudo-random numbers (SplitMix64), uniform in `[low, high)`.
pub struct Random(u64);

impl Random {
    /// A generator from its seed.
    pub fn new(seed: u64) -> Random {
        Random(seed)
    }

    /// The next number, uniform in `[low, high)`.
    pub fn uniform(&mut self, low: f64, high: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        low + (high - low) * (z >> 11) as f64 / (1u64 << 53) as f64
    }

    /// An array of numbers uniform in `[low, high)`.
    pub fn array<const D: usize>(&mut self, low: f64, high: f64) -> [f64; D] {
        std::array::from_fn(|_| self.uniform(low, high))
    }
}
