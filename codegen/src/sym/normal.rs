//! The normal form: expressions as rational functions of atoms.
//!
//! [`Store::normal`] turns an expression into a [`RationalFunction`]
//! `N / (f_1^k_1 ... f_m^k_m)`:
//!
//! - trigonometric functions of integer combinations of symbols are expanded,
//!   `sin(a + 2b) = sin a cos 2b + cos a sin 2b`, `cos 2b = cos^2 b - sin^2 b`,
//!   down to products of `sin q_i`, `cos q_i`; `tan u = sin u / cos u`;
//! - products are reduced by `sin^2 q -> 1 - cos^2 q` ([`super::poly`]);
//! - the denominator is kept factored, each factor monic and free of sines
//!   and square roots (a divisor `a + b sin q` is cleared by its conjugate
//!   `a - b sin q`, as the norm of the quadratic extension, and `a + b sqrt(u)`
//!   by `a - b sqrt(u)`), so the numerator decides zero-ness:
//!   on the exact class (atoms are symbols and `sin`/`cos` of symbols) an
//!   expression is zero exactly when its numerator has no terms;
//! - common factors are cancelled: the monomial content, and every
//!   denominator factor that divides the numerator exactly (factors equal as
//!   normal forms are recognised, a full multivariate gcd is not computed);
//! - the square root of a polynomial is an atom `r` reduced by `r^2 = u`
//!   ([`super::poly`]), so `sqrt(u)^2 - u` and `(1/sqrt(u))^2 - 1/u` are zero
//!   by the normal form; zero tests of other expressions with roots fall
//!   back to the numeric test, as for kernels;
//! - anything else (`exp`, `ln`, other fractional powers, trigonometric functions of
//!   other arguments) becomes an opaque kernel atom whose argument is itself in
//!   normal form, so equal kernels are recognised; zero tests involving kernels
//!   fall back to the randomized numeric test ([`super::zero`]).

use super::expr::{ExprId, Function, Node, Store, SymError, SymbolId};
use super::number::Rational;
use super::poly::{Atom, AtomId, Atoms, Poly};

/// A quotient of polynomials with a factored, sine-free denominator.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct RationalFunction {
    numerator: Poly,
    /// Monic, sine-free, non-constant, pairwise distinct factors, sorted.
    denominator: Vec<(Poly, u32)>,
}

/// The largest multiple angle expanded; larger ones stay opaque atoms.
const MAX_MULTIPLE_ANGLE: i64 = 64;

impl RationalFunction {
    /// A polynomial.
    pub fn from_poly(numerator: Poly) -> RationalFunction {
        RationalFunction {
            numerator,
            denominator: Vec::new(),
        }
    }

    /// A constant.
    pub fn constant(value: Rational) -> RationalFunction {
        RationalFunction::from_poly(Poly::constant(value))
    }

    /// Zero.
    pub fn zero() -> RationalFunction {
        RationalFunction::from_poly(Poly::zero())
    }

    /// One.
    pub fn one() -> RationalFunction {
        RationalFunction::constant(Rational::ONE)
    }

    /// The numerator.
    pub fn numerator(&self) -> &Poly {
        &self.numerator
    }

    /// The denominator factors with their multiplicities.
    pub fn denominator(&self) -> &[(Poly, u32)] {
        &self.denominator
    }

    /// The denominator multiplied out.
    pub fn denominator_product(&self, atoms: &Atoms) -> Poly {
        product_of(&self.denominator, atoms)
    }

    /// `1 / (f_1^k_1 ... f_m^k_m)`: one over the denominator, factors kept.
    pub fn reciprocal_of_denominator(&self) -> RationalFunction {
        RationalFunction {
            numerator: Poly::constant(Rational::ONE),
            denominator: self.denominator.clone(),
        }
    }

    /// True when the function is exactly zero (the numerator has no terms).
    pub fn is_zero(&self) -> bool {
        self.numerator.is_zero()
    }

    /// The value when the function is a constant.
    pub fn as_constant(&self) -> Option<Rational> {
        if self.denominator.is_empty() {
            self.numerator.as_constant()
        } else {
            None
        }
    }

    /// The atoms of the numerator and of the denominator.
    pub fn atoms(&self) -> Vec<AtomId> {
        let mut atoms = self.numerator.atoms();
        for (factor, _) in &self.denominator {
            atoms.extend(factor.atoms());
        }
        atoms.sort_unstable();
        atoms.dedup();
        atoms
    }

    /// A size measure: terms in the numerator and denominator factors.
    pub fn size(&self) -> usize {
        self.numerator.len() + self.denominator.iter().map(|(f, _)| f.len()).sum::<usize>()
    }

    /// `-self`.
    pub fn neg(&self) -> RationalFunction {
        RationalFunction {
            numerator: self.numerator.neg(),
            denominator: self.denominator.clone(),
        }
    }

    /// `c * self`.
    pub fn scale(&self, c: &Rational) -> RationalFunction {
        if c.is_zero() {
            return RationalFunction::zero();
        }
        RationalFunction {
            numerator: self.numerator.scale(c),
            denominator: self.denominator.clone(),
        }
    }

    /// `self + other` over the least common multiple of the factored denominators.
    ///
    /// Charges the budget of `atoms` the terms of both numerators (a sum of
    /// many terms, folded, is quadratic in their count).
    pub fn add(&self, other: &RationalFunction, atoms: &Atoms) -> RationalFunction {
        let merged = self.numerator.len() + other.numerator.len();
        if !atoms.budget().charge(merged as u64) {
            return RationalFunction::zero();
        }
        if other.is_zero() {
            return self.clone();
        }
        if self.is_zero() {
            return other.clone();
        }
        if self.denominator == other.denominator {
            return RationalFunction {
                numerator: self.numerator.add(&other.numerator),
                denominator: self.denominator.clone(),
            }
            .cancelled(atoms);
        }
        let common = lcm(&self.denominator, &other.denominator);
        let left = self
            .numerator
            .mul(&cofactor(&common, &self.denominator, atoms), atoms);
        let right = other
            .numerator
            .mul(&cofactor(&common, &other.denominator, atoms), atoms);
        RationalFunction {
            numerator: left.add(&right),
            denominator: common,
        }
        .cancelled(atoms)
    }

    /// `self - other`.
    pub fn sub(&self, other: &RationalFunction, atoms: &Atoms) -> RationalFunction {
        self.add(&other.neg(), atoms)
    }

    /// `self * other`, cancelling each numerator against the other denominator first.
    pub fn mul(&self, other: &RationalFunction, atoms: &Atoms) -> RationalFunction {
        if self.is_zero() || other.is_zero() {
            return RationalFunction::zero();
        }
        let (left, other_denominator) = cancel(&self.numerator, &other.denominator, atoms);
        let (right, own_denominator) = cancel(&other.numerator, &self.denominator, atoms);
        RationalFunction {
            numerator: left.mul(&right, atoms),
            denominator: merge(&own_denominator, &other_denominator),
        }
        .cancelled(atoms)
    }

    /// `1 / self`, or an error when `self` is exactly zero.
    pub fn inverse(&self, atoms: &Atoms) -> Option<RationalFunction> {
        if self.is_zero() {
            return None;
        }
        let (cleared, conjugates) = clear_sines(&self.numerator, atoms);
        let numerator = conjugates.mul(&self.denominator_product(atoms), atoms);
        let (coefficient, factors) = factorize(&cleared, &self.denominator, atoms);
        Some(
            RationalFunction {
                numerator: numerator.scale(&coefficient.recip()?),
                denominator: factors,
            }
            .cancelled(atoms),
        )
    }

    /// `self / other`, or `None` when `other` is exactly zero.
    pub fn div(&self, other: &RationalFunction, atoms: &Atoms) -> Option<RationalFunction> {
        Some(self.mul(&other.inverse(atoms)?, atoms))
    }

    /// `self^n` for an integer `n`, or `None` for a negative power of zero.
    pub fn powi(&self, n: i64, atoms: &Atoms) -> Option<RationalFunction> {
        let base = if n < 0 {
            self.inverse(atoms)?
        } else {
            self.clone()
        };
        let mut result = RationalFunction::one();
        let mut square = base;
        let mut remaining = n.unsigned_abs();
        while remaining > 0 {
            if remaining & 1 == 1 {
                result = result.mul(&square, atoms);
            }
            remaining >>= 1;
            if remaining > 0 {
                square = square.mul(&square, atoms);
            }
        }
        Some(result)
    }

    /// Removes every denominator factor that divides the numerator.
    fn cancelled(self, atoms: &Atoms) -> RationalFunction {
        if self.numerator.is_zero() {
            return RationalFunction::zero();
        }
        let (numerator, denominator) = cancel(&self.numerator, &self.denominator, atoms);
        RationalFunction {
            numerator,
            denominator,
        }
    }

    /// The value at the given atom values.
    pub fn evaluate(&self, value_of: &dyn Fn(AtomId) -> f64) -> f64 {
        let denominator: f64 = self
            .denominator
            .iter()
            .map(|(f, k)| f.evaluate(value_of).powi(*k as i32))
            .product();
        self.numerator.evaluate(value_of) / denominator
    }
}

/// Cancels denominator factors that divide `numerator` exactly.
fn cancel(
    numerator: &Poly,
    denominator: &[(Poly, u32)],
    atoms: &Atoms,
) -> (Poly, Vec<(Poly, u32)>) {
    let mut numerator = numerator.clone();
    let mut kept = Vec::with_capacity(denominator.len());
    for (factor, multiplicity) in denominator {
        let mut remaining = *multiplicity;
        while remaining > 0 && might_divide(factor, &numerator) {
            match numerator.div_exact(factor, atoms.budget()) {
                Some(quotient) => {
                    numerator = quotient;
                    remaining -= 1;
                }
                None => break,
            }
        }
        if remaining > 0 {
            kept.push((factor.clone(), remaining));
        }
    }
    (numerator, kept)
}

/// A cheap necessary condition for `factor | p`: the leading monomials divide.
fn might_divide(factor: &Poly, p: &Poly) -> bool {
    match (factor.leading(), p.leading()) {
        (Some((f, _)), Some((m, _))) => m.div(f).is_some() && factor.len() <= p.len(),
        _ => false,
    }
}

/// Factor lists multiplied: exponents of equal factors add.
fn merge(a: &[(Poly, u32)], b: &[(Poly, u32)]) -> Vec<(Poly, u32)> {
    combine(a, b, |x, y| x + y)
}

/// The least common multiple of two factor lists: the larger exponent wins.
fn lcm(a: &[(Poly, u32)], b: &[(Poly, u32)]) -> Vec<(Poly, u32)> {
    combine(a, b, u32::max)
}

fn combine(a: &[(Poly, u32)], b: &[(Poly, u32)], join: fn(u32, u32) -> u32) -> Vec<(Poly, u32)> {
    let mut out: Vec<(Poly, u32)> = a.to_vec();
    for (factor, k) in b {
        match out.iter_mut().find(|(f, _)| f == factor) {
            Some(entry) => entry.1 = join(entry.1, *k),
            None => out.push((factor.clone(), *k)),
        }
    }
    out.sort_unstable();
    out
}

/// `common / part` multiplied out, where `part` divides `common` factor-wise.
fn cofactor(common: &[(Poly, u32)], part: &[(Poly, u32)], atoms: &Atoms) -> Poly {
    let missing: Vec<(Poly, u32)> = common
        .iter()
        .filter_map(|(factor, k)| {
            let present = part
                .iter()
                .find(|(f, _)| f == factor)
                .map_or(0, |(_, j)| *j);
            (*k > present).then(|| (factor.clone(), *k - present))
        })
        .collect();
    product_of(&missing, atoms)
}

fn product_of(factors: &[(Poly, u32)], atoms: &Atoms) -> Poly {
    factors
        .iter()
        .fold(Poly::constant(Rational::ONE), |acc, (f, k)| {
            acc.mul(&f.pow(*k, atoms), atoms)
        })
}

/// Multiplies `p` by conjugates until no square root and no sine is left:
/// `a + b r -> (a + b r)(a - b r) = a^2 - b^2 u` for a root `r = sqrt(u)`,
/// the outermost root first (its radicand may hold inner roots and sines,
/// a sine's conjugate none), then each sine the same way. Returns the
/// product and the product of the conjugates used.
fn clear_sines(p: &Poly, atoms: &Atoms) -> (Poly, Poly) {
    let mut cleared = p.clone();
    let mut conjugates = Poly::constant(Rational::ONE);
    while let Some(sine) = next_to_clear(&cleared, atoms) {
        let conjugate = cleared.conjugate(sine);
        cleared = cleared.mul(&conjugate, atoms);
        conjugates = conjugates.mul(&conjugate, atoms);
    }
    (cleared, conjugates)
}

/// The outermost square root of `p` (the latest interned), else a sine.
fn next_to_clear(p: &Poly, atoms: &Atoms) -> Option<AtomId> {
    let present = p.atoms();
    let root = present
        .iter()
        .copied()
        .filter(|&a| atoms.radicand_of(a).is_some())
        .max();
    root.or_else(|| present.into_iter().find(|&a| atoms.cosine_of(a).is_some()))
}

/// Splits a non-zero, sine-free polynomial into a constant times monic factors:
/// single-atom factors for its monomial content, then known factors (those of
/// `known`) divided out, then the monic remainder.
fn factorize(p: &Poly, known: &[(Poly, u32)], atoms: &Atoms) -> (Rational, Vec<(Poly, u32)>) {
    let content = p.monomial_content();
    let mut rest = p.div_monomial(&content);
    let mut factors: Vec<(Poly, u32)> = content
        .factors()
        .iter()
        .map(|&(atom, e)| (Poly::atom(atom), e))
        .collect();
    for (factor, _) in known {
        let mut found = 0;
        while rest.len() > 1 && might_divide(factor, &rest) {
            match rest.div_exact(factor, atoms.budget()) {
                Some(quotient) => {
                    rest = quotient;
                    found += 1;
                }
                None => break,
            }
        }
        if found > 0 {
            factors.push((factor.clone(), found));
        }
    }
    let coefficient = rest.leading().map_or(Rational::ONE, |(_, c)| c.clone());
    if rest.as_constant().is_none() {
        let monic = rest.scale(&coefficient.recip().unwrap_or(Rational::ONE));
        factors.push((monic, 1));
    }
    (coefficient, merge(&factors, &[]))
}

impl Store {
    /// The normal form of an expression (memoized).
    ///
    /// Fails with [`SymError::BudgetExceeded`] once the store's derivation
    /// budget is spent, here or in an earlier computation.
    pub fn normal(&mut self, id: ExprId) -> Result<RationalFunction, SymError> {
        self.within_budget()?;
        if let Some(found) = self.normal_forms.get(&id) {
            return Ok(found.clone());
        }
        for node in self.reachable(&[id]) {
            if !self.normal_forms.contains_key(&node) {
                let form = self.normal_of_node(node);
                self.within_budget()?;
                self.normal_forms.insert(node, form?);
            }
        }
        Ok(self.normal_forms[&id].clone())
    }

    /// `Err(BudgetExceeded)` once the derivation budget is spent.
    fn within_budget(&self) -> Result<(), SymError> {
        let budget = self.atoms.budget();
        if budget.is_exhausted() {
            Err(SymError::BudgetExceeded {
                limit: budget.limit(),
            })
        } else {
            Ok(())
        }
    }

    /// The expression rebuilt from its normal form.
    pub fn simplify(&mut self, id: ExprId) -> Result<ExprId, SymError> {
        let form = self.normal(id)?;
        Ok(self.expression_of(&form))
    }

    fn normal_of_node(&mut self, id: ExprId) -> Result<RationalFunction, SymError> {
        let form = |store: &Store, child: &ExprId| store.normal_forms[child].clone();
        Ok(match self.node(id).clone() {
            Node::Number(value) => RationalFunction::constant(value),
            Node::Symbol(symbol) => {
                RationalFunction::from_poly(Poly::atom(self.atoms.symbol(symbol)))
            }
            Node::Add(terms) => terms.iter().fold(RationalFunction::zero(), |acc, t| {
                acc.add(&form(self, t), &self.atoms)
            }),
            Node::Mul(factors) => factors.iter().fold(RationalFunction::one(), |acc, f| {
                acc.mul(&form(self, f), &self.atoms)
            }),
            Node::Pow(base, exponent) => {
                let base_form = form(self, &base);
                self.normal_power(base, &base_form, &exponent)?
            }
            Node::Call(function, argument) => {
                let argument_form = form(self, &argument);
                self.normal_call(function, &argument_form)?
            }
        })
    }

    fn normal_power(
        &mut self,
        base: ExprId,
        base_form: &RationalFunction,
        exponent: &Rational,
    ) -> Result<RationalFunction, SymError> {
        if let Some(n) = exponent.to_i64() {
            return base_form
                .powi(n, &self.atoms)
                .ok_or_else(|| self.division_by_zero(base));
        }
        if base_form.is_zero() {
            return if exponent.is_negative() {
                Err(self.division_by_zero(base))
            } else {
                Ok(RationalFunction::zero())
            };
        }
        let whole = floor(exponent);
        let fraction = exponent.sub(&Rational::integer(whole));
        let is_square_root = fraction == Rational::new(1, 2).unwrap_or(Rational::ONE);
        let canonical_base = self.expression_of(base_form);
        let root = self.pow(canonical_base, fraction)?;
        let root_form = match self.node(root) {
            Node::Number(value) => RationalFunction::constant(value.clone()),
            _ if is_square_root && base_form.denominator.is_empty() => {
                let radicand = base_form.numerator.clone();
                RationalFunction::from_poly(Poly::atom(self.atoms.square_root(root, radicand)))
            }
            _ => RationalFunction::from_poly(Poly::atom(self.atoms.kernel(root))),
        };
        let integer_part = base_form
            .powi(whole, &self.atoms)
            .ok_or_else(|| self.division_by_zero(base))?;
        Ok(root_form.mul(&integer_part, &self.atoms))
    }

    fn division_by_zero(&self, divisor: ExprId) -> SymError {
        SymError::DivisionByZero {
            expr: self.display(divisor).to_string(),
        }
    }

    fn normal_call(
        &mut self,
        function: Function,
        argument: &RationalFunction,
    ) -> Result<RationalFunction, SymError> {
        match function {
            Function::Sin => Ok(RationalFunction::from_poly(self.sine_cosine(argument).0)),
            Function::Cos => Ok(RationalFunction::from_poly(self.sine_cosine(argument).1)),
            Function::Tan => {
                let (sine, cosine) = self.sine_cosine(argument);
                RationalFunction::from_poly(sine)
                    .div(&RationalFunction::from_poly(cosine), &self.atoms)
                    .ok_or_else(|| SymError::DivisionByZero {
                        expr: "cos of the argument of tan".to_string(),
                    })
            }
            Function::Exp | Function::Ln => {
                let canonical = self.expression_of(argument);
                let applied = self.apply(function, canonical)?;
                Ok(match self.node(applied) {
                    Node::Number(value) => RationalFunction::constant(value.clone()),
                    _ => RationalFunction::from_poly(Poly::atom(self.atoms.kernel(applied))),
                })
            }
        }
    }

    /// `(sin u, cos u)` as polynomials: expanded over an integer combination
    /// of symbols, a sine/cosine atom pair of the whole argument otherwise.
    fn sine_cosine(&mut self, argument: &RationalFunction) -> (Poly, Poly) {
        match self.integer_combination(argument) {
            Some(combination) => {
                let mut sine = Poly::zero();
                let mut cosine = Poly::constant(Rational::ONE);
                for (symbol, multiple) in combination {
                    let symbol_expression = self.symbol(symbol);
                    let (s, c) = self.atoms.trig_pair(symbol_expression);
                    let (s, c) =
                        multiple_angle(Poly::atom(s), Poly::atom(c), multiple, &self.atoms);
                    let new_sine = sine.mul(&c, &self.atoms).add(&cosine.mul(&s, &self.atoms));
                    let new_cosine = cosine.mul(&c, &self.atoms).sub(&sine.mul(&s, &self.atoms));
                    sine = new_sine;
                    cosine = new_cosine;
                }
                (sine, cosine)
            }
            None => {
                let canonical = self.expression_of(argument);
                let (s, c) = self.atoms.trig_pair(canonical);
                (Poly::atom(s), Poly::atom(c))
            }
        }
    }

    /// `argument = sum n_i q_i` with integers `|n_i| <= 64` and no constant term.
    fn integer_combination(&self, argument: &RationalFunction) -> Option<Vec<(SymbolId, i64)>> {
        if !argument.denominator.is_empty() {
            return None;
        }
        argument
            .numerator
            .terms()
            .iter()
            .map(|(monomial, coefficient)| {
                let multiple = coefficient
                    .to_i64()
                    .filter(|n| n.abs() <= MAX_MULTIPLE_ANGLE)?;
                match monomial.factors() {
                    [(atom, 1)] => match self.atoms.get(*atom) {
                        Atom::Symbol(symbol) => Some((*symbol, multiple)),
                        _ => None,
                    },
                    _ => None,
                }
            })
            .collect()
    }

    /// Rebuilds an expression from a normal form.
    pub fn expression_of(&mut self, form: &RationalFunction) -> ExprId {
        let numerator = self.expression_of_poly(&form.numerator);
        let mut factors = vec![numerator];
        for (factor, multiplicity) in &form.denominator {
            let base = self.expression_of_poly(factor);
            factors.push(self.pow_of_expression(base, Rational::integer(-(*multiplicity as i64))));
        }
        self.mul(&factors)
    }

    /// Rebuilds an expression from a polynomial.
    pub fn expression_of_poly(&mut self, poly: &Poly) -> ExprId {
        let terms: Vec<ExprId> = poly
            .terms()
            .iter()
            .map(|(monomial, coefficient)| {
                let mut factors = vec![self.number(coefficient.clone())];
                for &(atom, exponent) in monomial.factors() {
                    let base = self.expression_of_atom(atom);
                    factors.push(self.pow_of_expression(base, Rational::integer(exponent as i64)));
                }
                self.mul(&factors)
            })
            .collect();
        self.add(&terms)
    }

    /// The expression an atom stands for.
    pub fn expression_of_atom(&mut self, atom: AtomId) -> ExprId {
        match self.atoms.get(atom).clone() {
            Atom::Symbol(symbol) => self.symbol(symbol),
            Atom::Sin(argument) => self.apply_to_expression(Function::Sin, argument),
            Atom::Cos(argument) => self.apply_to_expression(Function::Cos, argument),
            Atom::Kernel(expression) => expression,
        }
    }

    /// The atom table of the normal form.
    pub fn atoms(&self) -> &Atoms {
        &self.atoms
    }

    /// The atom of a symbol used polynomially.
    pub fn symbol_atom(&mut self, symbol: SymbolId) -> AtomId {
        self.atoms.symbol(symbol)
    }

    /// True when every atom of the numerator is a symbol, or the sine or
    /// cosine of a symbol: then a non-zero numerator proves a non-zero function.
    pub fn in_exact_class(&self, form: &RationalFunction) -> bool {
        form.numerator
            .atoms()
            .iter()
            .all(|&a| match self.atoms.get(a) {
                Atom::Symbol(_) => true,
                Atom::Sin(argument) | Atom::Cos(argument) => {
                    matches!(self.node(*argument), Node::Symbol(_))
                }
                Atom::Kernel(_) => false,
            })
    }
}

/// `(sin n x, cos n x)` from `(sin x, cos x)` by repeated angle addition.
fn multiple_angle(sine: Poly, cosine: Poly, n: i64, atoms: &Atoms) -> (Poly, Poly) {
    let mut s = Poly::zero();
    let mut c = Poly::constant(Rational::ONE);
    for _ in 0..n.unsigned_abs() {
        let next_s = s.mul(&cosine, atoms).add(&c.mul(&sine, atoms));
        let next_c = c.mul(&cosine, atoms).sub(&s.mul(&sine, atoms));
        s = next_s;
        c = next_c;
    }
    if n < 0 { (s.neg(), c) } else { (s, c) }
}

/// The largest integer not above `r` (for exponents, which are small).
fn floor(r: &Rational) -> i64 {
    let (numerator, denominator) = r.to_small().unwrap_or((0, 1));
    numerator.div_euclid(denominator)
}
