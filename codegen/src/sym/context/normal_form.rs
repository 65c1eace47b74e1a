//! [`Context::normal`]: an expression to its normal form (memoized), with
//! trigonometric functions of integer combinations of symbols expanded into
//! products of `sin q_i`, `cos q_i`; and a normal form back to an expression.

use super::Context;
use crate::sym::expr::{ExprId, Function, Node, SymError, SymbolId};
use crate::sym::normal::RationalFunction;
use crate::sym::number::Rational;
use crate::sym::poly::{Atom, AtomId, Atoms, Poly};

/// The largest multiple angle expanded; larger ones stay opaque atoms.
const MAX_MULTIPLE_ANGLE: i64 = 64;

impl Context {
    /// The normal form of an expression (memoized).
    ///
    /// Fails with [`SymError::BudgetExceeded`] (or
    /// [`SymError::DegreeTooLarge`]) once the store's derivation budget is
    /// spent, here or in an earlier computation.
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

    /// The budget's error ([`SymError::BudgetExceeded`] or
    /// [`SymError::DegreeTooLarge`]) once the derivation budget is spent.
    fn within_budget(&self) -> Result<(), SymError> {
        self.atoms.budget().error().map_or(Ok(()), Err)
    }

    /// The expression rebuilt from its normal form.
    pub fn simplify(&mut self, id: ExprId) -> Result<ExprId, SymError> {
        let form = self.normal(id)?;
        Ok(self.expression_of(&form))
    }

    fn normal_of_node(&mut self, id: ExprId) -> Result<RationalFunction, SymError> {
        let form = |cx: &Context, child: &ExprId| cx.normal_forms[child].clone();
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
            Node::Atan2(y, x) => {
                let y = self.expression_of(&form(self, &y));
                let x = self.expression_of(&form(self, &x));
                let applied = self.atan2(y, x)?;
                self.kernel_form(applied)
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
        let is_square_root = fraction == Rational::HALF;
        let canonical_base = self.expression_of(base_form);
        let root = self.pow(canonical_base, fraction)?;
        let root_form = match self.node(root) {
            Node::Number(value) => RationalFunction::constant(value.clone()),
            _ if is_square_root && base_form.denominator().is_empty() => {
                let radicand = base_form.numerator().clone();
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
            Function::Exp | Function::Ln | Function::Asin | Function::Acos | Function::Atan => {
                let canonical = self.expression_of(argument);
                let applied = self.apply(function, canonical)?;
                Ok(self.kernel_form(applied))
            }
        }
    }

    /// A function applied to canonical arguments as a normal form: its
    /// value where it folded to a constant, else an opaque kernel atom.
    fn kernel_form(&mut self, applied: ExprId) -> RationalFunction {
        match self.node(applied) {
            Node::Number(value) => RationalFunction::constant(value.clone()),
            _ => RationalFunction::from_poly(Poly::atom(self.atoms.kernel(applied))),
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
        if !argument.denominator().is_empty() {
            return None;
        }
        argument
            .numerator()
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
        let numerator = self.expression_of_poly(form.numerator());
        let mut factors = vec![numerator];
        for (factor, multiplicity) in form.denominator() {
            let base = self.expression_of_poly(factor);
            factors.push(self.pow_of_expression(base, Rational::integer(-(*multiplicity as i64))));
        }
        self.mul(&factors)
    }

    /// The expression to compute a normal form by: the form written out
    /// when it has at most [`EXPANDED_TERMS`](crate::sym::normal::EXPANDED_TERMS) terms, else `derived_as`, the
    /// expression it was derived from (a mechanism's rotation chain, whose
    /// expanded products are far larger than the chain).
    pub fn compact_expression(&mut self, form: &RationalFunction, derived_as: ExprId) -> ExprId {
        if form.is_written_out() {
            self.expression_of(form)
        } else {
            derived_as
        }
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

    /// The atom of a symbol used polynomially.
    pub fn symbol_atom(&mut self, symbol: SymbolId) -> AtomId {
        self.atoms.symbol(symbol)
    }

    /// True when every atom of the numerator is a symbol, or the sine or
    /// cosine of a symbol: then a non-zero numerator proves a non-zero function.
    pub fn in_exact_class(&self, form: &RationalFunction) -> bool {
        form.numerator()
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
