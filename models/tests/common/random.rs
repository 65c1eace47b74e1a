//! Reproducible pseudo-random values for tests: xorshift64*.

/// xorshift64*: reproducible values in [-1, 1).
pub struct Random(pub u64);

impl Random {
    /// The next value, in [-1, 1).
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let bits = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        2.0 * (bits as f64 / (1u64 << 53) as f64) - 1.0
    }

    /// `L` values in [-1, 1).
    pub fn array<const L: usize>(&mut self) -> [f64; L] {
        std::array::from_fn(|_| self.next())
    }

    /// `L` values in [-scale, scale).
    pub fn scaled<const L: usize>(&mut self, scale: f64) -> [f64; L] {
        std::array::from_fn(|_| scale * self.next())
    }
}
