//! Building sums, products, powers and calls with the store's cheap,
//! always-valid rewrites: flattening, constant folding, collecting
//! `c*x + d*x` and `x^a * x^b`, sorting operands.

use super::{ExprId, Function, MAX_CONSTANT_BITS, Node, Store, SymError};
use crate::sym::number::Rational;
use rustc_hash::FxHashMap as HashMap;

impl Store {
    // ----- sums ----------------------------------------------------------

    /// `a + b`.
    pub fn add2(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.add(&[a, b])
    }

    /// `a - b`.
    pub fn sub(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let minus_b = self.neg(b);
        self.add(&[a, minus_b])
    }

    /// `-a`.
    pub fn neg(&mut self, a: ExprId) -> ExprId {
        let minus_one = self.integer(-1);
        self.mul(&[minus_one, a])
    }

    /// The sum of `terms`, flattened, with like terms `c*x + d*x` collected.
    /// A scaled sum `c*(a + b)` stays one term unless each of its terms is
    /// a term of the sum already and one of them cancels: then it is
    /// distributed, so that `(a + b) - (a + b)` is 0 and
    /// `(a + b + c) - (a + b)` is `c`.
    pub fn add(&mut self, terms: &[ExprId]) -> ExprId {
        let mut like = LikeTerms::default();
        let mut scaled_sums = Vec::new();
        let mut pending: Vec<ExprId> = terms.to_vec();
        while let Some(term) = pending.pop() {
            match self.node(term) {
                Node::Number(value) => like.constant = like.constant.add(value),
                Node::Add(children) => pending.extend(children.iter().copied()),
                _ => {
                    let (coefficient, rest) = self.split_coefficient(term);
                    if matches!(self.node(rest), Node::Add(_)) {
                        scaled_sums.push((rest, coefficient));
                    } else {
                        like.collect(rest, coefficient);
                    }
                }
            }
        }
        for (sum, coefficient) in scaled_sums {
            self.add_scaled_sum(&mut like, sum, coefficient);
        }
        let mut children: Vec<ExprId> = like
            .coefficients
            .into_iter()
            .filter(|(_, c)| !c.is_zero())
            .map(|(rest, c)| self.scale(rest, c))
            .collect();
        children.sort_unstable();
        if !like.constant.is_zero() {
            children.insert(0, self.number(like.constant));
        }
        match children.len() {
            0 => self.integer(0),
            1 => children[0],
            _ => self.intern(Node::Add(children.into_boxed_slice())),
        }
    }

    /// Adds `coefficient * sum` to `like`: distributed when each term of
    /// `sum` is already a term there and one cancels, else as one term.
    fn add_scaled_sum(&mut self, like: &mut LikeTerms, sum: ExprId, coefficient: Rational) {
        let Node::Add(children) = self.node(sum).clone() else {
            unreachable!("a scaled sum's rest is a sum");
        };
        let terms: Vec<ExprId> = children
            .iter()
            .copied()
            .filter(|&child| !matches!(self.node(child), Node::Number(_)))
            .collect();
        let split: Vec<(Rational, ExprId)> = terms
            .into_iter()
            .map(|child| self.split_coefficient(child))
            .collect();
        let cancels = |(c, rest): &(Rational, ExprId)| {
            like.positions
                .get(rest)
                .is_some_and(|&at| like.coefficients[at].1.add(&c.mul(&coefficient)).is_zero())
        };
        let present = split
            .iter()
            .all(|(_, rest)| like.positions.contains_key(rest));
        if !(present && split.iter().any(cancels)) {
            like.collect(sum, coefficient);
            return;
        }
        for &child in children.iter() {
            if let Node::Number(value) = self.node(child) {
                like.constant = like.constant.add(&value.mul(&coefficient));
            }
        }
        for (c, rest) in split {
            like.collect(rest, c.mul(&coefficient));
        }
    }

    /// Splits `c * rest` into its constant coefficient and the rest.
    fn split_coefficient(&mut self, term: ExprId) -> (Rational, ExprId) {
        if let Node::Mul(factors) = self.node(term)
            && let Node::Number(c) = self.node(factors[0])
        {
            let c = c.clone();
            let rest = factors[1..].to_vec();
            let rest = if rest.len() == 1 {
                rest[0]
            } else {
                self.intern(Node::Mul(rest.into_boxed_slice()))
            };
            return (c, rest);
        }
        (Rational::ONE, term)
    }

    /// `c * rest` where `rest` carries no constant factor.
    fn scale(&mut self, rest: ExprId, c: Rational) -> ExprId {
        if c.is_one() {
            return rest;
        }
        let c = self.number(c);
        self.mul(&[c, rest])
    }

    // ----- products ------------------------------------------------------

    /// `a * b`.
    pub fn mul2(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.mul(&[a, b])
    }

    /// The product of `factors`, flattened, with `x^a * x^b = x^(a+b)` collected.
    pub fn mul(&mut self, factors: &[ExprId]) -> ExprId {
        let mut constant = Rational::ONE;
        let mut exponents: Vec<(ExprId, Rational)> = Vec::new();
        let mut positions: HashMap<ExprId, usize> = HashMap::default();
        let mut pending: Vec<ExprId> = factors.to_vec();
        while let Some(factor) = pending.pop() {
            let (base, exponent) = match self.node(factor) {
                Node::Number(value) => {
                    constant = constant.mul(value);
                    continue;
                }
                Node::Mul(children) => {
                    pending.extend(children.iter().copied());
                    continue;
                }
                Node::Pow(base, exponent) => (*base, exponent.clone()),
                _ => (factor, Rational::ONE),
            };
            match positions.get(&base) {
                Some(&at) => exponents[at].1 = exponents[at].1.add(&exponent),
                None => {
                    positions.insert(base, exponents.len());
                    exponents.push((base, exponent));
                }
            }
        }
        if constant.is_zero() {
            return self.integer(0);
        }
        let mut children = Vec::with_capacity(exponents.len() + 1);
        let mut distributed = false;
        for (base, exponent) in exponents {
            let power = self.pow_of_collected(base, exponent);
            match self.node(power) {
                Node::Number(value) => constant = constant.mul(value),
                Node::Mul(_) => {
                    distributed = true;
                    children.push(power);
                }
                _ => children.push(power),
            }
        }
        if distributed {
            // An integer power of a product, e.g. sqrt(2x)^2 = 2x, was
            // distributed: collect its factors with the others once more.
            children.push(self.number(constant));
            return self.mul(&children);
        }
        if constant.is_zero() {
            return self.integer(0);
        }
        children.sort_unstable();
        if !constant.is_one() {
            children.insert(0, self.number(constant));
        }
        match children.len() {
            0 => self.integer(1),
            1 => children[0],
            _ => self.intern(Node::Mul(children.into_boxed_slice())),
        }
    }

    /// Rebuilds a collected power; a constant base that cannot be folded exactly
    /// (e.g. `2^(1/2)`) is kept as a power node, which is always valid here
    /// because constructors never produce a negative base with a fractional exponent.
    fn pow_of_collected(&mut self, base: ExprId, exponent: Rational) -> ExprId {
        match self.pow(base, exponent.clone()) {
            Ok(power) => power,
            Err(_) => self.intern(Node::Pow(base, exponent)),
        }
    }

    /// `a / b`. Fails when `b` is the constant zero; a divisor that is zero only
    /// after simplification is caught by the normal form.
    pub fn div(&mut self, a: ExprId, b: ExprId) -> Result<ExprId, SymError> {
        let inverse = self.pow(b, Rational::integer(-1))?;
        Ok(self.mul(&[a, inverse]))
    }

    // ----- powers --------------------------------------------------------

    /// `base ^ exponent` for a rational exponent.
    pub fn pow(&mut self, base: ExprId, exponent: Rational) -> Result<ExprId, SymError> {
        if exponent.is_zero() {
            return Ok(self.integer(1));
        }
        if exponent.is_one() {
            return Ok(base);
        }
        match self.node(base).clone() {
            Node::Number(value) => self.pow_of_number(&value, exponent),
            _ => Ok(self.pow_of_expression(base, exponent)),
        }
    }

    /// `base ^ exponent` for a non-constant base: never fails.
    pub(crate) fn pow_of_expression(&mut self, base: ExprId, exponent: Rational) -> ExprId {
        if exponent.is_zero() {
            return self.integer(1);
        }
        if exponent.is_one() {
            return base;
        }
        match self.node(base).clone() {
            Node::Pow(inner, inner_exponent) if exponent.is_integer() => {
                self.pow_of_expression(inner, inner_exponent.mul(&exponent))
            }
            Node::Mul(factors) if exponent.is_integer() => {
                let powers: Vec<ExprId> = factors
                    .iter()
                    .map(|&f| self.pow_of_collected(f, exponent.clone()))
                    .collect();
                self.mul(&powers)
            }
            _ => self.intern(Node::Pow(base, exponent)),
        }
    }

    fn pow_of_number(&mut self, value: &Rational, exponent: Rational) -> Result<ExprId, SymError> {
        if value.is_zero() && exponent.is_negative() {
            return Err(SymError::DivisionByZero {
                expr: "0".to_string(),
            });
        }
        if let Some(n) = exponent.to_i64() {
            within_constant_bits(value, n)?;
            if let Some(folded) = value.powi(n) {
                return Ok(self.number(folded));
            }
        }
        if value.is_negative() {
            return Err(SymError::NegativeBase {
                expr: format!("({value})^({exponent})"),
            });
        }
        let (numerator, denominator) = match exponent.to_small() {
            Some(parts) => parts,
            None => {
                let base = self.number(value.clone());
                return Ok(self.intern(Node::Pow(base, exponent)));
            }
        };
        let root = u32::try_from(denominator)
            .ok()
            .and_then(|d| value.exact_root(d));
        if let Some(root) = root {
            within_constant_bits(&root, numerator)?;
            if let Some(power) = root.powi(numerator) {
                return Ok(self.number(power));
            }
        }
        let base = self.number(value.clone());
        Ok(self.intern(Node::Pow(base, exponent)))
    }

    /// `sqrt(x)`, stored as `x^(1/2)`.
    pub fn sqrt(&mut self, x: ExprId) -> Result<ExprId, SymError> {
        self.pow(x, Rational::HALF)
    }

    // ----- functions -----------------------------------------------------

    /// Applies a function by its model-language name to its arguments
    /// (`sin cos tan sqrt exp ln asin acos atan` one, `atan2(y, x)` two).
    pub fn apply_named(&mut self, name: &str, arguments: &[ExprId]) -> Result<ExprId, SymError> {
        let expected = super::arity(name).ok_or_else(|| SymError::UnknownFunction {
            name: name.to_string(),
        })?;
        if arguments.len() != expected {
            return Err(SymError::ArgumentCount {
                name: name.to_string(),
                expected,
                found: arguments.len(),
            });
        }
        let function = match (name, arguments) {
            ("sqrt", &[argument]) => return self.sqrt(argument),
            ("atan2", &[y, x]) => return self.atan2(y, x),
            ("sin", _) => Function::Sin,
            ("cos", _) => Function::Cos,
            ("tan", _) => Function::Tan,
            ("exp", _) => Function::Exp,
            ("ln", _) => Function::Ln,
            ("asin", _) => Function::Asin,
            ("acos", _) => Function::Acos,
            _ => Function::Atan,
        };
        self.apply(function, arguments[0])
    }

    /// `function(argument)`, folding the exact constant cases
    /// (`sin 0 = 0`, `cos 0 = 1`, `tan 0 = 0`, `exp 0 = 1`, `ln 1 = 0`,
    /// `asin 0 = 0`, `acos 1 = 0`, `atan 0 = 0`) and failing outside the
    /// domain at a constant (`ln` of a constant not above 0, `asin` and
    /// `acos` of one beyond `[-1, 1]`).
    pub fn apply(&mut self, function: Function, argument: ExprId) -> Result<ExprId, SymError> {
        if let Node::Number(value) = self.node(argument) {
            let undefined = || SymError::Undefined {
                expr: format!("{}({value})", function.name()),
            };
            let folded = match function {
                Function::Sin | Function::Tan | Function::Asin | Function::Atan => {
                    value.is_zero().then_some(0)
                }
                Function::Cos | Function::Exp => value.is_zero().then_some(1),
                Function::Ln if value.is_negative() || value.is_zero() => return Err(undefined()),
                Function::Ln | Function::Acos => value.is_one().then_some(0),
            };
            let bounded = matches!(function, Function::Asin | Function::Acos);
            if bounded && value.abs() > Rational::ONE {
                return Err(undefined());
            }
            if let Some(folded) = folded {
                return Ok(self.integer(folded));
            }
        }
        Ok(self.intern(Node::Call(function, argument)))
    }

    /// `atan2(y, x)`, the angle of the point `(x, y)`: 0 for a constant
    /// point on the positive x axis, undefined at the constant origin.
    pub fn atan2(&mut self, y: ExprId, x: ExprId) -> Result<ExprId, SymError> {
        if let (Some(y_value), Some(x_value)) = (self.as_number(y), self.as_number(x))
            && y_value.is_zero()
        {
            if x_value.is_zero() {
                return Err(SymError::Undefined {
                    expr: "atan2(0, 0)".to_string(),
                });
            }
            if !x_value.is_negative() {
                return Ok(self.integer(0));
            }
        }
        Ok(self.intern(Node::Atan2(y, x)))
    }

    /// `function(argument)` for an argument known not to be a constant.
    pub(crate) fn apply_to_expression(&mut self, function: Function, argument: ExprId) -> ExprId {
        self.intern(Node::Call(function, argument))
    }
}

/// The terms of a sum being built: a constant and each distinct term's
/// coefficient, in order of appearance.
#[derive(Default)]
struct LikeTerms {
    constant: Rational,
    coefficients: Vec<(ExprId, Rational)>,
    positions: HashMap<ExprId, usize>,
}

impl LikeTerms {
    /// Adds `coefficient * rest`.
    fn collect(&mut self, rest: ExprId, coefficient: Rational) {
        match self.positions.get(&rest) {
            Some(&at) => self.coefficients[at].1 = self.coefficients[at].1.add(&coefficient),
            None => {
                self.positions.insert(rest, self.coefficients.len());
                self.coefficients.push((rest, coefficient));
            }
        }
    }
}

impl Store {
    /// `expr`, or [`SymError::ConstantTooLarge`] where one of its own
    /// constants has more than [`MAX_CONSTANT_BITS`] bits: its value (a
    /// number), its constant factor (a product), or the constant or a
    /// term's coefficient (a sum). [`Store::add`] and [`Store::mul`] fold
    /// constants without a limit; a sum or product built from operands
    /// that passed this check has at most twice their bits, so checking
    /// each one built from input stops a constant's growth at once.
    pub fn within_constant_limit(&self, expr: ExprId) -> Result<ExprId, SymError> {
        let terms = match self.node(expr) {
            Node::Add(terms) => terms,
            _ => std::slice::from_ref(&expr),
        };
        for &term in terms {
            let constant = match self.node(term) {
                Node::Number(value) => Some(value),
                Node::Mul(factors) => match self.node(factors[0]) {
                    Node::Number(value) => Some(value),
                    _ => None,
                },
                _ => None,
            };
            if let Some(value) = constant {
                within_constant_bits(value, 1)?;
            }
        }
        Ok(expr)
    }
}

/// Fails with [`SymError::ConstantTooLarge`] where `value^n` would have
/// more than [`MAX_CONSTANT_BITS`] bits (estimated from `value`'s), rather
/// than computing it; the powers of 1 and -1 are always small.
fn within_constant_bits(value: &Rational, n: i64) -> Result<(), SymError> {
    let bits = value.bits().saturating_mul(n.unsigned_abs());
    if bits > MAX_CONSTANT_BITS && value.abs() != Rational::ONE {
        return Err(SymError::ConstantTooLarge { bits });
    }
    Ok(())
}
