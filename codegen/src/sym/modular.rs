//! Evaluation modulo a prime at random points: exact tests of identities and
//! ranks for expressions whose normal forms are too large to form.
//!
//! The expressions of mechanics are rational functions of the symbols
//! (coordinates, parameters, velocities, momenta) and of `sin q`, `cos q` of
//! integer combinations of them. A [`Point`] gives every symbol a residue
//! modulo the prime [`PRIME`] `= 2^61 - 1` and, independently, a point
//! `(c, s)` on the circle `c^2 + s^2 = 1` over the same field, from the
//! rational parametrization
//!
//! ```text
//! c = (1 - t^2) / (1 + t^2),   s = 2 t / (1 + t^2)
//! ```
//!
//! (`1 + t^2` never vanishes: -1 is not a square modulo a prime `3 mod 4`).
//! A square root `sqrt(u)` is the principal root of `u`'s value,
//! `u^((p + 1) / 4)` (a root because `p = 3 mod 4`), where `u`'s value is a
//! square; where it is not, the point is not on the variety `r^2 = u` and the
//! expression is [`ModularError::Undefined`] there, so callers draw the next point
//! ([`points`]). The normal form uses nothing of a root `r` but `r^2 = u`, so
//! either root of `u` gives a point of the variety it works on
//! ([`crate::sym::residues`] evaluates expressions, and normal forms with
//! their root atoms from their radicands).
//! `cos` and `sin` of `a_1 q_1 + ... + a_m q_m` (integers `a_i`) are the real
//! and imaginary parts of the unit `prod (c_i + i s_i)^(a_i)`, the addition
//! formulas. A symbol and its sine and cosine satisfy no algebraic relation
//! but `c^2 + s^2 = 1`, so such a point is a point of the variety the
//! functions live on, and:
//!
//! - a non-zero value proves that the expression is not identically zero
//!   (a rational function that vanishes identically has numerator in the ideal
//!   of `c^2 + s^2 - 1`, which vanishes at the point, while every divisor met
//!   on the way was checked to be non-zero there);
//! - the rank of a matrix of values is a lower bound of its generic rank;
//! - a zero value, or a rank that meets an upper bound, is only probable: by
//!   the Schwartz-Zippel lemma a non-zero numerator of degree `d` in the
//!   parameters `t` and the residues vanishes at a uniformly random point with
//!   probability at most `d / PRIME` (about `4.3e-19 d`).
//!
//! Points are drawn from a seed, so every build decides the same way. This
//! module is the arithmetic and the points alone: a symbol is named by its
//! index.
//! Expressions outside the class (`exp`, `ln`, fractional powers, `sin` of a
//! non-linear argument, the inverse functions `asin acos atan atan2`) are not
//! evaluated: [`ModularError`]. An inverse function is not a free value
//! either: it is tied to its argument by identities no residue keeps
//! (`atan(tan q) = q` near `q = 0`, `asin u + acos u = pi/2`), so a random
//! residue for it could prove an expression that vanishes non-zero.

/// The Mersenne prime `2^61 - 1`.
pub const PRIME: u64 = (1 << 61) - 1;

/// The seeds of the points at which the derivations decide by evaluation.
pub const SEEDS: [u64; 2] = [0x00c4_a91f_9e37_79b9, 0x5eed_0fd1_5c0f_fe00];

/// How many points [`points`] draws: a square root's radicand is a square
/// at half the points, so 64 draws miss a point where every one of a few
/// roots is defined with probability far below `1e-6`.
pub const POINT_DRAWS: u64 = 64;

/// The points derivations evaluate at, in order: first [`SEEDS`], then
/// further points from them, for callers that skip the points where an
/// expression is [`ModularError::Undefined`].
pub fn points() -> impl Iterator<Item = Point> {
    (0..POINT_DRAWS).map(|draw_index| {
        let seed = SEEDS[(draw_index % 2) as usize];
        Point::new(seed.wrapping_add((draw_index / 2).wrapping_mul(0x9E37_79B9_7F4A_7C15)))
    })
}

/// `evaluate` at the first `count` points of [`points`] where it is
/// defined (skipping those where it is [`ModularError::Undefined`]); an
/// expression outside the class is an error at once, and so is finding
/// fewer than `count` defined points.
pub fn at_defined_points<T>(
    count: usize,
    mut evaluate: impl FnMut(Point) -> Result<T, ModularError>,
) -> Result<Vec<T>, ModularError> {
    let mut results = Vec::with_capacity(count);
    let mut undefined = None;
    for point in points() {
        match evaluate(point) {
            Ok(result) => results.push(result),
            Err(error @ ModularError::Undefined { .. }) => undefined = Some(error),
            Err(error) => return Err(error),
        }
        if results.len() == count {
            return Ok(results);
        }
    }
    Err(undefined.unwrap_or(ModularError::Undefined {
        expr: "every point drawn".to_string(),
    }))
}

/// Why an expression was not evaluated at a point.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ModularError {
    /// The expression leaves the class of rational trigonometric functions.
    #[error("{expr} is not a rational function of sines and cosines of integer combinations")]
    NotInClass {
        /// The offending sub-expression, printed.
        expr: String,
    },
    /// A divisor vanishes at the point.
    #[error("{expr} divides by zero at the point")]
    Undefined {
        /// The division, printed.
        expr: String,
    },
}

/// A random point: a residue and a point on the circle for every symbol,
/// derived from a seed and the symbol's index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Point {
    seed: u64,
}

/// `c + i s` on the unit circle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Unit {
    cosine: u64,
    sine: u64,
}

impl Point {
    /// The point drawn from `seed`.
    pub fn new(seed: u64) -> Point {
        Point { seed }
    }

    /// The residue of the symbol of index `symbol`.
    pub fn value(&self, symbol: usize) -> u64 {
        draw(self.seed, 2 * symbol as u64)
    }

    /// `(cos, sin)` of `a_1 q_1 + ... + a_m q_m`, given as the pairs
    /// `(index of q_i, a_i)`: the unit `prod (c_i + i s_i)^(a_i)`.
    pub fn cos_sin(&self, combination: &[(usize, i64)]) -> (u64, u64) {
        let unit = combination
            .iter()
            .fold(Unit { cosine: 1, sine: 0 }, |product, &(symbol, a)| {
                rotate(product, unit_power(self.unit(symbol), a))
            });
        (unit.cosine, unit.sine)
    }

    /// The point on the circle of the symbol of index `symbol`.
    fn unit(&self, symbol: usize) -> Unit {
        let t = draw(self.seed, 2 * symbol as u64 + 1);
        let t2 = multiply(t, t, PRIME);
        let denominator = inverse(add(1, t2), PRIME).unwrap_or(1);
        Unit {
            cosine: multiply(subtract(1, t2), denominator, PRIME),
            sine: multiply(add(t, t), denominator, PRIME),
        }
    }
}

/// A residue drawn from `(seed, index)` (splitmix64, reduced).
fn draw(seed: u64, index: u64) -> u64 {
    let mut z = seed
        .wrapping_add(index.wrapping_mul(0x9E37_79B9_7F4A_7C15))
        .wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    (z ^ (z >> 31)) % PRIME
}

/// `a * b` on the unit circle (the addition formulas).
fn rotate(a: Unit, b: Unit) -> Unit {
    Unit {
        cosine: subtract(
            multiply(a.cosine, b.cosine, PRIME),
            multiply(a.sine, b.sine, PRIME),
        ),
        sine: add(
            multiply(a.cosine, b.sine, PRIME),
            multiply(a.sine, b.cosine, PRIME),
        ),
    }
}

/// `unit^exponent`; a negative exponent is the conjugate's power.
fn unit_power(unit: Unit, exponent: i64) -> Unit {
    let mut base = if exponent < 0 {
        Unit {
            cosine: unit.cosine,
            sine: subtract(0, unit.sine),
        }
    } else {
        unit
    };
    let mut result = Unit { cosine: 1, sine: 0 };
    let mut remaining = exponent.unsigned_abs();
    while remaining > 0 {
        if remaining & 1 == 1 {
            result = rotate(result, base);
        }
        base = rotate(base, base);
        remaining >>= 1;
    }
    result
}

/// `a + b` modulo [`PRIME`].
pub fn add(a: u64, b: u64) -> u64 {
    (a + b) % PRIME
}

/// `a - b` modulo [`PRIME`].
pub fn subtract(a: u64, b: u64) -> u64 {
    (a + PRIME - b) % PRIME
}

/// `a * b` modulo `modulus`.
pub fn multiply(a: u64, b: u64, modulus: u64) -> u64 {
    ((a as u128 * b as u128) % modulus as u128) as u64
}

/// `a^-1` modulo the prime `modulus` (Fermat), `None` for `a = 0`.
pub fn inverse(a: u64, modulus: u64) -> Option<u64> {
    let a = a % modulus;
    (a != 0).then(|| unsigned_power(a, modulus - 2, modulus))
}

/// `a^exponent` modulo [`PRIME`]; `None` for a negative power of zero.
pub fn power(a: u64, exponent: i64) -> Option<u64> {
    let base = if exponent < 0 { inverse(a, PRIME)? } else { a };
    Some(unsigned_power(base, exponent.unsigned_abs(), PRIME))
}

/// The principal square root `a^((p + 1) / 4)` of `a` modulo [`PRIME`],
/// `None` when `a` is not a square (Euler's criterion).
pub fn square_root(a: u64) -> Option<u64> {
    let a = a % PRIME;
    if a == 0 {
        return Some(0);
    }
    (unsigned_power(a, (PRIME - 1) / 2, PRIME) == 1)
        .then(|| unsigned_power(a, (PRIME + 1) / 4, PRIME))
}

fn unsigned_power(mut base: u64, mut exponent: u64, modulus: u64) -> u64 {
    let mut result = 1 % modulus;
    while exponent > 0 {
        if exponent & 1 == 1 {
            result = multiply(result, base, modulus);
        }
        base = multiply(base, base, modulus);
        exponent >>= 1;
    }
    result
}

/// The rank of a row-major matrix of residues, by Gaussian elimination
/// modulo [`PRIME`].
pub fn rank(values: Vec<u64>, rows: usize, columns: usize) -> usize {
    reduced_echelon(values, rows, columns).1.len()
}

/// A basis of the kernel `{v : M v = 0}` of the row-major matrix `M` of
/// residues, one vector per free column of its reduced echelon form, that
/// column's entry 1.
pub fn kernel(values: Vec<u64>, rows: usize, columns: usize) -> Vec<Vec<u64>> {
    let (reduced, pivots) = reduced_echelon(values, rows, columns);
    (0..columns)
        .filter(|column| !pivots.contains(column))
        .map(|free| {
            let mut vector = vec![0; columns];
            vector[free] = 1;
            for (row, &pivot) in pivots.iter().enumerate() {
                vector[pivot] = subtract(0, reduced[row * columns + free]);
            }
            vector
        })
        .collect()
}

/// The reduced row echelon form modulo [`PRIME`] of a row-major matrix,
/// with its pivot columns in order.
fn reduced_echelon(mut values: Vec<u64>, rows: usize, columns: usize) -> (Vec<u64>, Vec<usize>) {
    let mut pivots = Vec::new();
    for column in 0..columns {
        let rank = pivots.len();
        if rank == rows {
            break;
        }
        let Some(pivot) = (rank..rows).find(|&r| values[r * columns + column] != 0) else {
            continue;
        };
        for j in 0..columns {
            values.swap(pivot * columns + j, rank * columns + j);
        }
        let scale = inverse(values[rank * columns + column], PRIME).unwrap_or(0);
        for j in column..columns {
            values[rank * columns + j] = multiply(values[rank * columns + j], scale, PRIME);
        }
        for i in (0..rows).filter(|&i| i != rank) {
            let factor = values[i * columns + column];
            if factor == 0 {
                continue;
            }
            for j in column..columns {
                let reduction = multiply(factor, values[rank * columns + j], PRIME);
                values[i * columns + j] = subtract(values[i * columns + j], reduction);
            }
        }
        pivots.push(column);
    }
    (values, pivots)
}

/// The rational `numerator / denominator`, both at most `bound` in
/// magnitude, whose residue is `residue`, if there is one (Wang's rational
/// reconstruction by the extended Euclidean algorithm; unique for
/// `2 bound^2 < PRIME`).
pub fn rational(residue: u64, bound: i64) -> Option<(i64, i64)> {
    let (mut r0, mut r1) = (PRIME as i128, (residue % PRIME) as i128);
    let (mut s0, mut s1) = (0i128, 1i128);
    while r1 > bound as i128 {
        let quotient = r0 / r1;
        (r0, r1) = (r1, r0 - quotient * r1);
        (s0, s1) = (s1, s0 - quotient * s1);
    }
    let (numerator, denominator) = if s1 < 0 { (-r1, -s1) } else { (r1, s1) };
    (denominator != 0 && denominator <= bound as i128)
        .then_some((numerator as i64, denominator as i64))
}

#[cfg(test)]
mod tests {
    use super::{PRIME, kernel, rank, rational};

    #[test]
    fn ranks_of_dependent_and_independent_rows() {
        assert_eq!(rank(vec![1, 2, 2, 4], 2, 2), 1);
        assert_eq!(rank(vec![1, 2, 3, 4], 2, 2), 2);
        assert_eq!(rank(vec![0, 0, 0, 0, 0, 5], 3, 2), 1);
        assert_eq!(rank(vec![PRIME - 1, 1, 1, PRIME - 1], 2, 2), 1);
        assert_eq!(rank(Vec::new(), 0, 3), 0);
    }

    #[test]
    fn the_kernel_of_dependent_columns() {
        // Columns 1 and 2 are twice and minus column 0.
        let values = vec![1, 2, PRIME - 1, 3, 6, PRIME - 3];
        let basis = kernel(values.clone(), 2, 3);
        assert_eq!(basis.len(), 2);
        for vector in &basis {
            for row in values.chunks(3) {
                let product = (row.iter().zip(vector)).fold(0, |sum, (&a, &v)| {
                    super::add(sum, super::multiply(a, v, PRIME))
                });
                assert_eq!(product, 0);
            }
        }
        assert_eq!(kernel(vec![1, 0, 0, 1], 2, 2), Vec::<Vec<u64>>::new());
    }

    #[test]
    fn small_rationals_are_reconstructed_from_their_residues() {
        for (numerator, denominator) in [(1, 1), (-1, 1), (3, 7), (-22, 5), (0, 1)] {
            let residue = super::multiply(
                (numerator + PRIME as i64) as u64 % PRIME,
                super::inverse(denominator as u64, PRIME).unwrap(),
                PRIME,
            );
            assert_eq!(rational(residue, 1 << 20), Some((numerator, denominator)));
        }
        // A residue of no small rational (0x0123_4567_89ab_cdef is one:
        // -233/225), checked by running the same algorithm apart.
        assert_eq!(rational(0x0bad_5eed_1234_5679, 1 << 20), None);
    }
}
