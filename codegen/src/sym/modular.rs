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
//! ([`normal_form`] evaluates normal forms, their root atoms from their
//! radicands).
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
//! Points are drawn from a seed, so every build decides the same way.
//! Expressions outside the class (`exp`, `ln`, fractional powers, `sin` of a
//! non-linear argument) are not evaluated: [`ModularError`].

mod normal_form;

use super::expr::{ExprId, Function, Node, Store, SymbolId};
use rustc_hash::FxHashMap as HashMap;

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

    /// The residue of a symbol.
    fn value(&self, symbol: SymbolId) -> u64 {
        draw(self.seed, 2 * symbol.index() as u64)
    }

    /// The point on the circle of a symbol: `(cos, sin)`.
    fn unit(&self, symbol: SymbolId) -> Unit {
        let t = draw(self.seed, 2 * symbol.index() as u64 + 1);
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

/// The values at one point of the nodes evaluated so far, so that
/// evaluating more expressions evaluates only their new nodes.
#[derive(Clone, Debug)]
pub struct Values {
    point: Point,
    values: HashMap<ExprId, u64>,
}

impl Values {
    /// No values yet, at `point`.
    pub fn at(point: Point) -> Values {
        Values {
            point,
            values: HashMap::default(),
        }
    }

    /// The values of `roots` modulo [`PRIME`].
    pub fn of(&mut self, store: &Store, roots: &[ExprId]) -> Result<Vec<u64>, ModularError> {
        for id in store.reachable_where(roots, |id| self.values.contains_key(&id)) {
            let value = store.modular_node(id, &self.values, &self.point)?;
            self.values.insert(id, value);
        }
        Ok(roots.iter().map(|root| self.values[root]).collect())
    }
}

impl Store {
    /// The values of `roots` modulo [`PRIME`] at `point`.
    pub fn evaluate_modular(
        &self,
        roots: &[ExprId],
        point: &Point,
    ) -> Result<Vec<u64>, ModularError> {
        Values::at(*point).of(self, roots)
    }

    fn modular_node(
        &self,
        id: ExprId,
        values: &HashMap<ExprId, u64>,
        point: &Point,
    ) -> Result<u64, ModularError> {
        let not_in_class = || ModularError::NotInClass {
            expr: self.display(id).to_string(),
        };
        let undefined = || ModularError::Undefined {
            expr: self.display(id).to_string(),
        };
        Ok(match self.node(id) {
            Node::Number(value) => value.residue(PRIME).ok_or_else(undefined)?,
            Node::Symbol(symbol) => point.value(*symbol),
            Node::Add(terms) => terms.iter().fold(0, |sum, t| add(sum, values[t])),
            Node::Mul(factors) => factors
                .iter()
                .fold(1, |product, f| multiply(product, values[f], PRIME)),
            Node::Pow(base, exponent) => match exponent.to_small() {
                Some((n, 1)) => power(values[base], n).ok_or_else(undefined)?,
                Some((n, 2)) => {
                    let root = square_root(values[base]).ok_or_else(undefined)?;
                    power(root, n).ok_or_else(undefined)?
                }
                _ => return Err(not_in_class()),
            },
            Node::Call(function, argument) => {
                let combination = self.angle_combination(*argument).ok_or_else(not_in_class)?;
                let unit = combination
                    .iter()
                    .fold(Unit { cosine: 1, sine: 0 }, |product, &(symbol, a)| {
                        rotate(product, unit_power(point.unit(symbol), a))
                    });
                match function {
                    Function::Sin => unit.sine,
                    Function::Cos => unit.cosine,
                    Function::Tan => {
                        let secant = inverse(unit.cosine, PRIME).ok_or_else(undefined)?;
                        multiply(unit.sine, secant, PRIME)
                    }
                    Function::Exp | Function::Ln => return Err(not_in_class()),
                }
            }
        })
    }

    /// `argument` as `sum a_i q_i` with integers `a_i`, if it is one.
    fn angle_combination(&self, argument: ExprId) -> Option<Vec<(SymbolId, i64)>> {
        let term = |id: ExprId| -> Option<(SymbolId, i64)> {
            match self.node(id) {
                Node::Symbol(symbol) => Some((*symbol, 1)),
                Node::Mul(factors) if factors.len() == 2 => {
                    let coefficient = self.as_number(factors[0])?.to_i64()?;
                    match self.node(factors[1]) {
                        Node::Symbol(symbol) => Some((*symbol, coefficient)),
                        _ => None,
                    }
                }
                _ => None,
            }
        };
        match self.node(argument) {
            Node::Add(terms) => terms.iter().map(|&t| term(t)).collect(),
            _ => term(argument).map(|t| vec![t]),
        }
    }
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
pub fn rank(mut values: Vec<u64>, rows: usize, columns: usize) -> usize {
    let mut rank = 0;
    for column in 0..columns {
        let Some(pivot) = (rank..rows).find(|&r| values[r * columns + column] != 0) else {
            continue;
        };
        for j in 0..columns {
            values.swap(pivot * columns + j, rank * columns + j);
        }
        let scale = inverse(values[rank * columns + column], PRIME).unwrap_or(0);
        for i in rank + 1..rows {
            let factor = multiply(values[i * columns + column], scale, PRIME);
            if factor == 0 {
                continue;
            }
            for j in column..columns {
                let reduction = multiply(factor, values[rank * columns + j], PRIME);
                values[i * columns + j] = subtract(values[i * columns + j], reduction);
            }
        }
        rank += 1;
        if rank == rows {
            break;
        }
    }
    rank
}

#[cfg(test)]
mod tests {
    use super::{ModularError, PRIME, Point, rank};
    use crate::sym::{Function, Rational, Store, SymbolKind};

    fn store_with_angles() -> (Store, crate::sym::ExprId, crate::sym::ExprId) {
        let mut store = Store::new();
        let x = store.declare("x", SymbolKind::Coordinate);
        let y = store.declare("y", SymbolKind::Coordinate);
        let (x, y) = (store.symbol(x), store.symbol(y));
        (store, x, y)
    }

    #[test]
    fn trigonometric_identities_vanish_and_their_perturbations_do_not() {
        let (mut store, x, y) = store_with_angles();
        let sum = store.add2(x, y);
        let two = store.integer(2);
        let twice = store.mul2(two, x);
        let [sin_x, cos_x, sin_y, cos_y] = [
            (Function::Sin, x),
            (Function::Cos, x),
            (Function::Sin, y),
            (Function::Cos, y),
        ]
        .map(|(f, a)| store.apply(f, a).expect("applies"));
        let sin_sum = store.apply(Function::Sin, sum).expect("applies");
        let cos_twice = store.apply(Function::Cos, twice).expect("applies");
        // sin(x + y) - sin x cos y - cos x sin y
        let a = store.mul2(sin_x, cos_y);
        let b = store.mul2(cos_x, sin_y);
        let expansion = store.add2(a, b);
        let addition = store.sub(sin_sum, expansion);
        // cos 2x - (cos^2 x - sin^2 x)
        let c2 = store.pow(cos_x, Rational::integer(2)).expect("power");
        let s2 = store.pow(sin_x, Rational::integer(2)).expect("power");
        let double = store.sub(c2, s2);
        let double_angle = store.sub(cos_twice, double);
        // tan x cos x - sin x
        let tan_x = store.apply(Function::Tan, x).expect("applies");
        let t = store.mul2(tan_x, cos_x);
        let tangent = store.sub(t, sin_x);
        // sin^2 + cos^2 - 1, and the same plus x y (not an identity)
        let pythagoras_sum = store.add2(c2, s2);
        let one = store.integer(1);
        let pythagoras = store.sub(pythagoras_sum, one);
        let xy = store.mul2(x, y);
        let perturbed = store.add2(pythagoras, xy);
        for seed in 0..5 {
            let values = store
                .evaluate_modular(
                    &[addition, double_angle, tangent, pythagoras, perturbed],
                    &Point::new(seed),
                )
                .expect("in the class");
            assert_eq!(&values[..4], [0, 0, 0, 0], "seed {seed}");
            assert_ne!(values[4], 0, "seed {seed}");
        }
    }

    #[test]
    fn values_are_residues_of_the_rational_values() {
        let (mut store, x, _) = store_with_angles();
        let third = store.number(Rational::new(1, 3).expect("non-zero"));
        let expression = store.mul2(third, x);
        let point = Point::new(7);
        let [value, x_value] = store
            .evaluate_modular(&[expression, x], &point)
            .expect("in the class")[..]
        else {
            panic!("two values");
        };
        // 3 * (x / 3) = x
        assert_eq!(super::multiply(3, value, PRIME), x_value);
    }

    #[test]
    fn expressions_outside_the_class_are_refused() {
        let (mut store, x, y) = store_with_angles();
        let product = store.mul2(x, y);
        let sin_product = store.apply(Function::Sin, product).expect("applies");
        let cube_root = store
            .pow(x, Rational::new(1, 3).expect("non-zero denominator"))
            .expect("applies");
        let exponential = store.apply(Function::Exp, x).expect("applies");
        for expression in [sin_product, cube_root, exponential] {
            assert!(matches!(
                store.evaluate_modular(&[expression], &Point::new(1)),
                Err(ModularError::NotInClass { .. })
            ));
        }
    }

    #[test]
    fn square_roots_square_to_their_radicands_where_those_are_squares() {
        let (mut store, x, y) = store_with_angles();
        let radicand = store.add2(x, y);
        let root = store.sqrt(radicand).expect("applies");
        let (mut defined, mut undefined) = (0, 0);
        for point in super::points() {
            match store.evaluate_modular(&[root, radicand], &point) {
                Ok(values) => {
                    let square = super::multiply(values[0], values[0], PRIME);
                    assert_eq!(square, values[1], "sqrt(u)^2 = u");
                    defined += 1;
                }
                Err(ModularError::Undefined { .. }) => undefined += 1,
                Err(other) => panic!("in the class: {other}"),
            }
        }
        // About half the residues are squares modulo a prime.
        assert!(
            defined > 16 && undefined > 16,
            "{defined} defined, {undefined} not"
        );
        let values = super::at_defined_points(2, |point| store.evaluate_modular(&[root], &point))
            .expect("two points where x + y is a square");
        assert_eq!(values.len(), 2);
    }

    #[test]
    fn division_by_a_vanishing_value_is_undefined() {
        let (mut store, x, _) = store_with_angles();
        let zero = store.sub(x, x);
        assert_eq!(store.as_number(zero).map(|z| z.is_zero()), Some(true));
        let sin_x = store.apply(Function::Sin, x).expect("applies");
        let c2 = store.pow(sin_x, Rational::integer(2)).expect("power");
        let cos_x = store.apply(Function::Cos, x).expect("applies");
        let s2 = store.pow(cos_x, Rational::integer(2)).expect("power");
        let one = store.integer(1);
        let sum = store.add2(c2, s2);
        let hidden_zero = store.sub(sum, one);
        let quotient = store.div(x, hidden_zero).expect("not a constant zero");
        assert!(matches!(
            store.evaluate_modular(&[quotient], &Point::new(3)),
            Err(ModularError::Undefined { .. })
        ));
    }

    #[test]
    fn ranks_of_dependent_and_independent_rows() {
        assert_eq!(rank(vec![1, 2, 2, 4], 2, 2), 1);
        assert_eq!(rank(vec![1, 2, 3, 4], 2, 2), 2);
        assert_eq!(rank(vec![0, 0, 0, 0, 0, 5], 3, 2), 1);
        assert_eq!(rank(vec![PRIME - 1, 1, 1, PRIME - 1], 2, 2), 1);
        assert_eq!(rank(Vec::new(), 0, 3), 0);
    }
}
