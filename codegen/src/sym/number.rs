//! Exact rational numbers: the only numbers inside the symbolic engine.
//!
//! A [`Rational`] is kept reduced with a positive denominator. Small values live
//! in two `i64`s and every operation is done in `i128` and checked; a result
//! that does not fit is promoted to a big rational (`num_rational::BigRational`),
//! and a big result that fits again is demoted. Overflow therefore never wraps
//! and equal values always have equal representations (so hashing is sound).
//!
//! Equality, order and hashing therefore work on the numerator and the
//! denominator themselves, in time and stack linear in their size: the
//! `BigRational` implementations go through the value's continued
//! fraction, recursively, one stack frame a partial quotient, and a product
//! of a few constant powers (some 10^5 bits) overflowed the stack.

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Pow, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;
use std::fmt;
use std::hash::{Hash, Hasher};

/// An exact rational number, reduced, with a positive denominator.
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Rational(Repr);

#[derive(Clone)]
enum Repr {
    /// numerator, denominator > 0, gcd = 1
    Small(i64, i64),
    /// only values that do not fit `Small`
    Big(BigRational),
}

impl Rational {
    /// Zero.
    pub const ZERO: Rational = Rational(Repr::Small(0, 1));
    /// One.
    pub const ONE: Rational = Rational(Repr::Small(1, 1));
    /// One half.
    pub const HALF: Rational = Rational(Repr::Small(1, 2));

    /// The integer `n`.
    pub fn integer(n: i64) -> Rational {
        Rational(Repr::Small(n, 1))
    }

    /// `numerator / denominator`, or `None` when the denominator is zero.
    pub fn new(numerator: i64, denominator: i64) -> Option<Rational> {
        (denominator != 0).then(|| from_i128(numerator as i128, denominator as i128))
    }

    /// Parses a decimal literal exactly: `"2"`, `"0.05"`, `"1e-3"`, `"1.5E2"`.
    pub fn from_decimal(text: &str) -> Option<Rational> {
        let (mantissa, exponent) = match text.find(['e', 'E']) {
            Some(at) => (&text[..at], text[at + 1..].parse::<i32>().ok()?),
            None => (text, 0),
        };
        let (whole, fraction) = mantissa.split_once('.').unwrap_or((mantissa, ""));
        let digits = format!("{whole}{fraction}").replace('_', "");
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        let scale = exponent.checked_sub(i32::try_from(fraction.len()).ok()?)?;
        if scale.unsigned_abs() > 4096 {
            return None;
        }
        let value = BigRational::from_integer(digits.parse::<BigInt>().ok()?);
        let ten = BigRational::from_integer(BigInt::from(10));
        let power = num_traits::pow(ten, scale.unsigned_abs() as usize);
        Some(from_big(if scale >= 0 {
            value * power
        } else {
            value / power
        }))
    }

    /// True for zero.
    pub fn is_zero(&self) -> bool {
        matches!(self.0, Repr::Small(0, _))
    }

    /// True for one.
    pub fn is_one(&self) -> bool {
        matches!(self.0, Repr::Small(1, 1))
    }

    /// True for a negative value.
    pub fn is_negative(&self) -> bool {
        match &self.0 {
            Repr::Small(n, _) => *n < 0,
            Repr::Big(b) => b.is_negative(),
        }
    }

    /// True when the denominator is 1.
    pub fn is_integer(&self) -> bool {
        match &self.0 {
            Repr::Small(_, d) => *d == 1,
            Repr::Big(b) => b.is_integer(),
        }
    }

    /// The value as an `i64` when it is an integer that fits.
    pub fn to_i64(&self) -> Option<i64> {
        match &self.0 {
            Repr::Small(n, 1) => Some(*n),
            _ => None,
        }
    }

    /// Numerator and denominator when both fit in `i64`.
    pub fn to_small(&self) -> Option<(i64, i64)> {
        match &self.0 {
            Repr::Small(n, d) => Some((*n, *d)),
            Repr::Big(_) => None,
        }
    }

    /// The size in 64-bit words: the scale of the cost of arithmetic on it.
    pub fn words(&self) -> u64 {
        self.bits() / 64 + 1
    }

    /// The bits of the numerator and the denominator together.
    pub fn bits(&self) -> u64 {
        match &self.0 {
            Repr::Small(n, d) => {
                u64::from(64 - n.unsigned_abs().leading_zeros())
                    + u64::from(64 - d.unsigned_abs().leading_zeros())
            }
            Repr::Big(value) => value.numer().bits() + value.denom().bits(),
        }
    }

    /// The nearest `f64`.
    pub fn to_f64(&self) -> f64 {
        match &self.0 {
            Repr::Small(n, d) => *n as f64 / *d as f64,
            Repr::Big(b) => b.to_f64().unwrap_or(f64::NAN),
        }
    }

    fn to_big(&self) -> BigRational {
        match &self.0 {
            Repr::Small(n, d) => BigRational::new_raw(BigInt::from(*n), BigInt::from(*d)),
            Repr::Big(b) => b.clone(),
        }
    }

    /// `-self`.
    pub fn neg(&self) -> Rational {
        match &self.0 {
            Repr::Small(n, d) => match n.checked_neg() {
                Some(n) => Rational(Repr::Small(n, *d)),
                None => from_i128(-(*n as i128), *d as i128),
            },
            Repr::Big(b) => from_big(-b.clone()),
        }
    }

    /// `|self|`.
    pub fn abs(&self) -> Rational {
        if self.is_negative() {
            self.neg()
        } else {
            self.clone()
        }
    }

    /// `self + other`.
    pub fn add(&self, other: &Rational) -> Rational {
        match (&self.0, &other.0) {
            (Repr::Small(a, b), Repr::Small(c, d)) => {
                add_in_i64(*a, *b, *c, *d).unwrap_or_else(|| {
                    let (a, b, c, d) = (*a as i128, *b as i128, *c as i128, *d as i128);
                    from_i128(a * d + c * b, b * d)
                })
            }
            _ => big_sum(&self.to_big(), &other.to_big()),
        }
    }

    /// `self - other`.
    pub fn sub(&self, other: &Rational) -> Rational {
        self.add(&other.neg())
    }

    /// `self * other`.
    pub fn mul(&self, other: &Rational) -> Rational {
        match (&self.0, &other.0) {
            (Repr::Small(a, b), Repr::Small(c, d)) => mul_in_i64(*a, *b, *c, *d)
                .unwrap_or_else(|| from_i128(*a as i128 * *c as i128, *b as i128 * *d as i128)),
            _ => big_product(&self.to_big(), &other.to_big()),
        }
    }

    /// `1 / self`, or `None` for zero.
    pub fn recip(&self) -> Option<Rational> {
        if self.is_zero() {
            return None;
        }
        Some(match &self.0 {
            Repr::Small(n, d) => from_i128(*d as i128, *n as i128),
            Repr::Big(b) => from_big(b.recip()),
        })
    }

    /// `self / other`, or `None` when `other` is zero.
    pub fn div(&self, other: &Rational) -> Option<Rational> {
        Some(self.mul(&other.recip()?))
    }

    /// `self^exponent` for an integer exponent, or `None` for `0^negative`:
    /// the powers of the numerator and the denominator, coprime as they are.
    pub fn powi(&self, exponent: i64) -> Option<Rational> {
        let base = if exponent < 0 {
            self.recip()?
        } else {
            self.clone()
        };
        let exponent = exponent.unsigned_abs();
        Some(match base.0 {
            Repr::Small(n, d) => {
                let small = u32::try_from(exponent)
                    .ok()
                    .and_then(|k| Some((n.checked_pow(k)?, d.checked_pow(k)?)));
                match small {
                    Some((n, d)) => Rational(Repr::Small(n, d)),
                    None => big_power(BigInt::from(n), BigInt::from(d), exponent),
                }
            }
            Repr::Big(b) => {
                let (n, d) = b.into_raw();
                big_power(n, d, exponent)
            }
        })
    }

    /// The exact `n`-th root of a non-negative value when it is rational.
    pub fn exact_root(&self, n: u32) -> Option<Rational> {
        if self.is_negative() || n == 0 {
            return None;
        }
        let big = self.to_big();
        let numerator = big.numer().nth_root(n);
        let denominator = big.denom().nth_root(n);
        let root = from_big(BigRational::new(numerator, denominator));
        (root.powi(n as i64).as_ref() == Some(self)).then_some(root)
    }

    /// The residue `numerator * denominator^-1` modulo the prime `modulus`
    /// (below 2^63), or `None` when the denominator is a multiple of it.
    pub fn residue(&self, modulus: u64) -> Option<u64> {
        let reduce = |value: &BigInt| -> u64 {
            let residue = value.mod_floor(&BigInt::from(modulus));
            residue.to_u64().unwrap_or(0)
        };
        let big = self.to_big();
        let (numerator, denominator) = (reduce(big.numer()), reduce(big.denom()));
        super::modular::inverse(denominator, modulus)
            .map(|inverse| super::modular::multiply(numerator, inverse, modulus))
    }

    /// The numerator as a rational (an integer).
    pub fn numerator(&self) -> Rational {
        match &self.0 {
            Repr::Small(n, _) => Rational::integer(*n),
            Repr::Big(b) => from_big(BigRational::from_integer(b.numer().clone())),
        }
    }

    /// The denominator as a rational (a positive integer).
    pub fn denominator(&self) -> Rational {
        match &self.0 {
            Repr::Small(_, d) => Rational::integer(*d),
            Repr::Big(b) => from_big(BigRational::from_integer(b.denom().clone())),
        }
    }
}

/// `(a/b) (c/d)` for reduced operands, `b, d > 0`: cancelling `gcd(a, d)`
/// and `gcd(c, b)` leaves the product reduced, which `BigRational`'s
/// product reduces once more, a third gcd, of the largest numbers.
fn big_product(x: &BigRational, y: &BigRational) -> Rational {
    if x.is_zero() || y.is_zero() {
        return Rational::ZERO;
    }
    let (ad, cb) = (gcd(x.numer(), y.denom()), gcd(y.numer(), x.denom()));
    let numerator = (x.numer() / &ad) * (y.numer() / &cb);
    let denominator = (x.denom() / &cb) * (y.denom() / &ad);
    from_big(BigRational::new_raw(numerator, denominator))
}

/// `a/b + c/d` for reduced operands, `b, d > 0`, by Henrici's algorithm
/// (Knuth, *The Art of Computer Programming* vol. 2, 4.5.1): with
/// `g = gcd(b, d)`, `t = a (d/g) + c (b/g)` and `h = gcd(t, g)`, the sum is
/// `(t/h) / ((b/g) (d/h))`, reduced. Its gcds are of the denominators, 1 for
/// integers, where `BigRational`'s sum reduces by a gcd of the numerator and
/// the denominator, which takes a step for about every two bits of the
/// numerator even when the denominator is 1.
fn big_sum(x: &BigRational, y: &BigRational) -> Rational {
    let (a, b, c, d) = (x.numer(), x.denom(), y.numer(), y.denom());
    let g = gcd(b, d);
    let (numerator, denominator) = if g.is_one() {
        (a * d + c * b, b * d)
    } else {
        let (b_g, d_g) = (b / &g, d / &g);
        let t = a * &d_g + c * &b_g;
        let h = gcd(&t, &g);
        (&t / &h, b_g * (d / &h))
    };
    if numerator.is_zero() {
        return Rational::ZERO;
    }
    from_big(BigRational::new_raw(numerator, denominator))
}

/// `gcd(a, b)`, at once where either is 1 in magnitude: `num-bigint`'s
/// binary gcd takes a step for about every two bits of the other even then.
fn gcd(a: &BigInt, b: &BigInt) -> BigInt {
    if a.magnitude().is_one() || b.magnitude().is_one() {
        BigInt::one()
    } else {
        a.gcd(b)
    }
}

/// `(n/d)^k` for coprime `n` and `d > 0`: coprime again, so not reduced.
fn big_power(n: BigInt, d: BigInt, k: u64) -> Rational {
    from_big(BigRational::new_raw(n.pow(k), d.pow(k)))
}

/// `a/b + c/d` (reduced operands, `b, d > 0`) in checked `i64` arithmetic,
/// or `None` when an intermediate overflows.
fn add_in_i64(a: i64, b: i64, c: i64, d: i64) -> Option<Rational> {
    if b == d {
        return Some(reduced_i64(a.checked_add(c)?, b));
    }
    let numerator = a.checked_mul(d)?.checked_add(c.checked_mul(b)?)?;
    Some(reduced_i64(numerator, b.checked_mul(d)?))
}

/// `(a/b) (c/d)` (reduced operands, `b, d > 0`) in checked `i64` arithmetic,
/// or `None` when the product overflows. Cancelling `gcd(a, d)` and
/// `gcd(c, b)` first leaves the product reduced.
fn mul_in_i64(a: i64, b: i64, c: i64, d: i64) -> Option<Rational> {
    if b == 1 && d == 1 {
        return Some(Rational::integer(a.checked_mul(c)?));
    }
    let (ad, cb) = (gcd_i64(a, d), gcd_i64(c, b));
    let numerator = (a / ad).checked_mul(c / cb)?;
    let denominator = (b / cb).checked_mul(d / ad)?;
    Some(Rational(Repr::Small(numerator, denominator)))
}

/// `gcd(|n|, d)` for `d > 0` (so it fits `i64`).
fn gcd_i64(n: i64, d: i64) -> i64 {
    n.unsigned_abs().gcd(&d.unsigned_abs()) as i64
}

/// `numerator / denominator` reduced, for `denominator > 0`.
fn reduced_i64(numerator: i64, denominator: i64) -> Rational {
    if denominator == 1 {
        return Rational::integer(numerator);
    }
    let divisor = gcd_i64(numerator, denominator);
    Rational(Repr::Small(numerator / divisor, denominator / divisor))
}

fn from_i128(numerator: i128, denominator: i128) -> Rational {
    let divisor = numerator.gcd(&denominator);
    let sign = if denominator < 0 { -1 } else { 1 };
    let (n, d) = (sign * numerator / divisor, sign * denominator / divisor);
    match (i64::try_from(n), i64::try_from(d)) {
        (Ok(n), Ok(d)) => Rational(Repr::Small(n, d)),
        _ => Rational(Repr::Big(BigRational::new(
            BigInt::from(n),
            BigInt::from(d),
        ))),
    }
}

fn from_big(value: BigRational) -> Rational {
    match (value.numer().to_i64(), value.denom().to_i64()) {
        (Some(n), Some(d)) => Rational(Repr::Small(n, d)),
        _ => Rational(Repr::Big(value)),
    }
}

impl Default for Rational {
    fn default() -> Self {
        Rational::ZERO
    }
}

impl From<i64> for Rational {
    fn from(n: i64) -> Self {
        Rational::integer(n)
    }
}

impl PartialOrd for Rational {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Rational {
    fn cmp(&self, other: &Self) -> Ordering {
        match (&self.0, &other.0) {
            (Repr::Small(a, b), Repr::Small(c, d)) => {
                (*a as i128 * *d as i128).cmp(&(*c as i128 * *b as i128))
            }
            _ => {
                let (x, y) = (self.to_big(), other.to_big());
                (x.numer() * y.denom()).cmp(&(y.numer() * x.denom()))
            }
        }
    }
}

impl PartialEq for Repr {
    fn eq(&self, other: &Repr) -> bool {
        match (self, other) {
            (Repr::Small(a, b), Repr::Small(c, d)) => (a, b) == (c, d),
            (Repr::Big(x), Repr::Big(y)) => x.numer() == y.numer() && x.denom() == y.denom(),
            _ => false,
        }
    }
}

impl Eq for Repr {}

impl Hash for Repr {
    fn hash<H: Hasher>(&self, state: &mut H) {
        match self {
            Repr::Small(n, d) => (0_u8, n, d).hash(state),
            Repr::Big(b) => (1_u8, b.numer(), b.denom()).hash(state),
        }
    }
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0 {
            Repr::Small(n, 1) => write!(f, "{n}"),
            Repr::Small(n, d) => write!(f, "{n}/{d}"),
            Repr::Big(b) if b.is_integer() => write!(f, "{}", b.numer()),
            Repr::Big(b) => write!(f, "{}/{}", b.numer(), b.denom()),
        }
    }
}

impl fmt::Debug for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arithmetic_stays_reduced_and_exact() {
        let third = Rational::new(1, 3).unwrap();
        let sixth = Rational::new(-1, -6).unwrap();
        assert_eq!(third.add(&sixth), Rational::new(1, 2).unwrap());
        assert_eq!(third.add(&sixth), Rational::HALF);
        assert_eq!(third.mul(&Rational::integer(3)), Rational::ONE);
        assert_eq!(Rational::new(2, -4).unwrap().to_small(), Some((-1, 2)));
        assert!(Rational::new(1, 0).is_none());
        assert!(Rational::ZERO.recip().is_none());
    }

    /// The checked `i64` paths against big rational arithmetic, on values
    /// around the edges of `i64` where they overflow and must promote.
    #[test]
    fn the_i64_paths_agree_with_big_rationals() {
        let edges = [
            0,
            1,
            -1,
            2,
            -3,
            6,
            35,
            i64::MAX,
            i64::MIN,
            i64::MAX / 2,
            -(1 << 40),
        ];
        let denominators = [1, 2, 3, 6, 35, i64::MAX, 1 << 40, (1 << 31) - 1];
        let values: Vec<Rational> = edges
            .iter()
            .flat_map(|&n| {
                denominators
                    .iter()
                    .map(move |&d| from_big(BigRational::new(BigInt::from(n), BigInt::from(d))))
            })
            .collect();
        for x in &values {
            assert_eq!(x.neg().to_big(), -x.to_big());
            for y in &values {
                assert_eq!(x.add(y).to_big(), x.to_big() + y.to_big(), "{x} + {y}");
                assert_eq!(x.mul(y).to_big(), x.to_big() * y.to_big(), "{x} * {y}");
                assert_eq!(x.add(y), from_big(x.to_big() + y.to_big()), "{x} + {y}");
                assert_eq!(x.mul(y), from_big(x.to_big() * y.to_big()), "{x} * {y}");
            }
        }
    }

    /// Products and powers of big values against `BigRational`'s, which
    /// reduce their results: equal values, equal representations.
    #[test]
    fn big_sums_products_and_powers_agree_with_big_rationals() {
        let values: Vec<Rational> = [(i64::MAX, 3), (-(1 << 62), 7), (35, i64::MAX), (6, 35)]
            .iter()
            .map(|&(n, d)| Rational::new(n, d).unwrap())
            .flat_map(|x| [x.clone(), x.powi(3).unwrap(), x.powi(-2).unwrap()])
            .chain([Rational::ZERO, Rational::ONE, Rational::integer(i64::MAX)])
            .flat_map(|x| [x.neg(), x.mul(&x), x])
            .collect();
        for x in &values {
            for k in -3_i64..=5 {
                let expected = (k >= 0 || !x.is_zero()).then(|| {
                    let base = if k < 0 {
                        x.to_big().recip()
                    } else {
                        x.to_big()
                    };
                    num_traits::pow(base, k.unsigned_abs() as usize)
                });
                assert_eq!(x.powi(k).map(|p| p.to_big()), expected, "{x}^{k}");
                assert_eq!(x.powi(k), expected.map(from_big), "{x}^{k}");
            }
            for y in &values {
                assert_eq!(x.add(y).to_big(), x.to_big() + y.to_big(), "{x} + {y}");
                assert_eq!(x.add(y), from_big(x.to_big() + y.to_big()), "{x} + {y}");
                assert_eq!(x.mul(y).to_big(), x.to_big() * y.to_big(), "{x} * {y}");
                assert_eq!(x.mul(y), from_big(x.to_big() * y.to_big()), "{x} * {y}");
            }
        }
    }

    #[test]
    fn overflow_promotes_and_demotes() {
        let big = Rational::integer(i64::MAX);
        let square = big.mul(&big);
        assert!(square.to_small().is_none());
        let expected = BigInt::from(i64::MAX) * BigInt::from(i64::MAX);
        assert_eq!(square.numerator().to_big().numer(), &expected);
        let back = square.div(&big).unwrap();
        assert_eq!(back.to_small(), Some((i64::MAX, 1)));
        let min = Rational::integer(i64::MIN);
        assert_eq!(min.neg().sub(&Rational::ONE), Rational::integer(i64::MAX));
        assert_eq!(
            Rational::integer(2)
                .powi(200)
                .unwrap()
                .powi(-1)
                .unwrap()
                .recip()
                .unwrap(),
            Rational::integer(2).powi(200).unwrap()
        );
    }

    /// `F(n + 1) / F(n)` for the Fibonacci numbers `F`: the continued
    /// fraction `[1; 1, 1, ...]` with `n` partial quotients, the longest for
    /// the size of its terms.
    fn fibonacci_ratio(n: usize) -> Rational {
        let (mut previous, mut current) = (BigInt::from(1), BigInt::from(1));
        for _ in 1..n {
            let next = &previous + &current;
            previous = std::mem::replace(&mut current, next);
        }
        from_big(BigRational::new(current, previous))
    }

    /// 20,000 partial quotients: `BigRational`'s recursive hash and order
    /// need more than a 256 KiB stack for them.
    #[test]
    fn long_continued_fractions_hash_and_compare_in_little_stack() {
        let on_a_small_stack = std::thread::Builder::new()
            .stack_size(256 * 1024)
            .spawn(|| {
                let (a, b) = (fibonacci_ratio(20_000), fibonacci_ratio(20_001));
                let hash = |x: &Rational| {
                    let mut hasher = std::hash::DefaultHasher::new();
                    x.hash(&mut hasher);
                    hasher.finish()
                };
                assert_eq!(hash(&a), hash(&a.mul(&Rational::ONE)));
                assert_ne!(hash(&a), hash(&b));
                assert_eq!(a, a.add(&Rational::ZERO));
                assert_ne!(a, b);
                // Cassini: F(n+1)^2 - F(n) F(n+2) = (-1)^n, so the ratios of
                // consecutive Fibonacci numbers fall and rise by turns:
                // F(20001)/F(20000) > F(20002)/F(20001).
                assert_eq!(a.cmp(&b), Ordering::Greater);
                assert_eq!(b.cmp(&a), Ordering::Less);
                assert_eq!(a.cmp(&a.clone()), Ordering::Equal);
            })
            .expect("a thread starts");
        on_a_small_stack
            .join()
            .expect("no overflow, no failed assertion");
    }

    #[test]
    fn decimal_literals_are_exact() {
        assert_eq!(Rational::from_decimal("0.05"), Rational::new(1, 20));
        assert_eq!(Rational::from_decimal("1e-3"), Rational::new(1, 1000));
        assert_eq!(
            Rational::from_decimal("1.5E2"),
            Some(Rational::integer(150))
        );
        assert_eq!(Rational::from_decimal("2"), Some(Rational::integer(2)));
        assert_eq!(Rational::from_decimal("abc"), None);
        assert_eq!(Rational::from_decimal("1e999999"), None);
    }

    #[test]
    fn roots_and_order() {
        assert_eq!(
            Rational::new(9, 4).unwrap().exact_root(2),
            Rational::new(3, 2)
        );
        assert_eq!(Rational::integer(2).exact_root(2), None);
        assert_eq!(Rational::integer(-8).exact_root(3), None);
        assert!(Rational::new(1, 3).unwrap() < Rational::new(1, 2).unwrap());
        assert_eq!(format!("{}", Rational::new(-3, 6).unwrap()), "-1/2");
    }
}
