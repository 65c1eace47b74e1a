//! Expressions and normal forms evaluated modulo a prime at a random
//! point: the store's nodes each once, a normal form's atoms each once,
//! with the arithmetic, the points and what a value decides in
//! [`super::modular`].

mod normal_form;

use super::expr::{ExprId, Function, Node, Store};
use super::modular::{ModularError, PRIME, Point, add, inverse, multiply, power, square_root};
use rustc_hash::FxHashMap as HashMap;

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
            Node::Symbol(symbol) => point.value(symbol.index()),
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
            Node::Call(function @ (Function::Sin | Function::Cos | Function::Tan), argument) => {
                let combination = self.angle_combination(*argument).ok_or_else(not_in_class)?;
                let (cosine, sine) = point.cos_sin(&combination);
                match function {
                    Function::Sin => sine,
                    Function::Cos => cosine,
                    _ => {
                        let secant = inverse(cosine, PRIME).ok_or_else(undefined)?;
                        multiply(sine, secant, PRIME)
                    }
                }
            }
            Node::Call(..) | Node::Atan2(..) => return Err(not_in_class()),
        })
    }

    /// `argument` as `sum a_i q_i` with integers `a_i`, if it is one: the
    /// pairs `(index of q_i, a_i)`.
    fn angle_combination(&self, argument: ExprId) -> Option<Vec<(usize, i64)>> {
        let term = |id: ExprId| -> Option<(usize, i64)> {
            match self.node(id) {
                Node::Symbol(symbol) => Some((symbol.index(), 1)),
                Node::Mul(factors) if factors.len() == 2 => {
                    let coefficient = self.as_number(factors[0])?.to_i64()?;
                    match self.node(factors[1]) {
                        Node::Symbol(symbol) => Some((symbol.index(), coefficient)),
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

#[cfg(test)]
mod tests {
    use crate::sym::modular::{self, ModularError, PRIME, Point};
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
        assert_eq!(modular::multiply(3, value, PRIME), x_value);
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
        for point in modular::points() {
            match store.evaluate_modular(&[root, radicand], &point) {
                Ok(values) => {
                    let square = modular::multiply(values[0], values[0], PRIME);
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
        let values = modular::at_defined_points(2, |point| store.evaluate_modular(&[root], &point))
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
}
