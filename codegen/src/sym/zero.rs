//! Zero tests: exact on the normal form's class, randomized numeric outside it.
//!
//! [`Context::zero_test`] decides `e = 0` by the normal form: a zero numerator
//! proves zero; a non-zero numerator whose atoms are symbols and `sin`/`cos`
//! of symbols proves non-zero (those atoms are algebraically independent but
//! for `sin^2 + cos^2 = 1`, which the normal form has already used). Outside
//! that class (`exp`, `ln`, fractional powers, trigonometric functions of
//! other arguments) the answer falls back to [`Store::numerically_zero`]:
//! evaluation at several pseudo-random points, compared with the size of the
//! terms, which is also the independent cross-check used in tests.

use super::context::Context;
use super::expr::{ExprId, Node, Store, SymError};

/// How a zero test was decided.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Decision {
    /// By the exact normal form.
    NormalForm,
    /// By evaluation at random points (outside the exact class).
    Numeric,
}

/// The answer of a zero test.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ZeroTest {
    /// Whether the expression is zero.
    pub is_zero: bool,
    /// How it was decided.
    pub decided_by: Decision,
}

/// Settings of the randomized numeric zero test.
#[derive(Clone, Copy, Debug)]
pub struct NumericZeroTest {
    /// Points at which the expression must vanish.
    pub points: usize,
    /// `|e| <= tolerance * scale`, `scale` the largest term magnitude (at least 1e-300).
    pub relative_tolerance: f64,
    /// Seed of the point generator (the test is deterministic).
    pub seed: u64,
}

impl Default for NumericZeroTest {
    fn default() -> Self {
        NumericZeroTest {
            points: 8,
            relative_tolerance: 1e-9,
            seed: 0x5eed_c4a9_1791_0001,
        }
    }
}

/// A small deterministic generator (SplitMix64) for sample points.
#[derive(Clone, Debug)]
pub struct SplitMix(u64);

impl SplitMix {
    /// A generator from a seed.
    pub fn new(seed: u64) -> SplitMix {
        SplitMix(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// A uniform number in `[low, high)`.
    pub fn uniform(&mut self, low: f64, high: f64) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        low + (high - low) * unit
    }
}

impl Context {
    /// Decides whether an expression is zero (see the module doc).
    pub fn zero_test(&mut self, id: ExprId) -> Result<ZeroTest, SymError> {
        let form = self.normal(id)?;
        if form.is_zero() {
            return Ok(ZeroTest {
                is_zero: true,
                decided_by: Decision::NormalForm,
            });
        }
        if self.in_exact_class(&form) {
            return Ok(ZeroTest {
                is_zero: false,
                decided_by: Decision::NormalForm,
            });
        }
        Ok(ZeroTest {
            is_zero: self.numerically_zero(id, &NumericZeroTest::default()),
            decided_by: Decision::Numeric,
        })
    }

    /// True when `a - b` is zero (see [`Context::zero_test`]).
    pub fn equal(&mut self, a: ExprId, b: ExprId) -> Result<bool, SymError> {
        let difference = self.sub(a, b);
        Ok(self.zero_test(difference)?.is_zero)
    }
}

impl Store {
    /// Evaluates at random points (symbols uniform in `[0.3, 1.7]`, where the
    /// model's functions are defined); points where the expression is not
    /// finite are skipped. Zero when every finite sample is below the
    /// tolerance and at least half the points were finite.
    pub fn numerically_zero(&self, id: ExprId, settings: &NumericZeroTest) -> bool {
        let mut generator = SplitMix::new(settings.seed);
        let symbols = self.free_symbols(id);
        let terms = match self.node(id) {
            Node::Add(terms) => terms.to_vec(),
            _ => vec![id],
        };
        let mut finite = 0;
        for _ in 0..settings.points {
            let values: Vec<f64> = symbols
                .iter()
                .map(|_| generator.uniform(0.3, 1.7))
                .collect();
            let value_of = |s| symbols.binary_search(&s).map_or(0.0, |at| values[at]);
            let mut samples = self.evaluate_many(&terms, &value_of);
            let scale = samples.iter().fold(1e-300f64, |m, v| m.max(v.abs()));
            samples.push(samples.iter().sum());
            let total = samples[samples.len() - 1];
            if !total.is_finite() || !scale.is_finite() {
                continue;
            }
            finite += 1;
            if total.abs() > settings.relative_tolerance * scale {
                return false;
            }
        }
        2 * finite >= settings.points
    }
}
