//! Differentiation and substitution.
//!
//! On expressions ([`Context::derivative`]) by the usual rules, memoized over
//! the DAG so a shared sub-expression is differentiated once; on normal forms
//! ([`Context::derivative_of_normal`]) term by term, with
//! `d sin u = cos u du`, `d cos u = -sin u du`, `d u^(p/q) = (p/q) u^(p/q) du / u`,
//! `d exp u = exp u du`, `d ln u = du / u`, `d asin u = du / sqrt(1 - u^2)`,
//! `d acos u = -du / sqrt(1 - u^2)`, `d atan u = du / (1 + u^2)`,
//! `d atan2(y, x) = (x dy - y dx) / (x^2 + y^2)`, and the quotient rule on the
//! factored denominator `d(N/F) = (dN - N sum_i k_i df_i / f_i) / F`.

use super::context::Context;
use super::expr::{ExprId, Function, Node, Store, SymError, SymbolId};
use super::normal::RationalFunction;
use super::number::Rational;
use super::poly::{Atom, AtomId, Monomial, Poly};
use rustc_hash::FxHashMap;
use std::collections::HashMap;

impl Context {
    /// `d root / d symbol` as an expression.
    pub fn derivative(&mut self, root: ExprId, symbol: SymbolId) -> ExprId {
        self.derivatives(&[root], symbol)[0]
    }

    /// `d root / d symbol` for several roots, a shared sub-expression
    /// differentiated once for all of them.
    /// Derivatives are remembered per symbol, so a later call differentiates
    /// only the nodes no earlier call reached.
    pub fn derivatives(&mut self, roots: &[ExprId], symbol: SymbolId) -> Vec<ExprId> {
        let mut derivatives = self.derivative_memo.remove(&symbol).unwrap_or_default();
        for id in self.reachable_where(roots, |id| derivatives.contains_key(&id)) {
            let derivative = self.derivative_of_node(id, symbol, &derivatives);
            derivatives.insert(id, derivative);
        }
        let found = roots.iter().map(|root| derivatives[root]).collect();
        self.derivative_memo.insert(symbol, derivatives);
        found
    }

    fn derivative_of_node(
        &mut self,
        id: ExprId,
        symbol: SymbolId,
        derivatives: &FxHashMap<ExprId, ExprId>,
    ) -> ExprId {
        let zero = self.integer(0);
        let d = |child: &ExprId| derivatives[child];
        match self.node(id).clone() {
            Node::Number(_) => zero,
            Node::Symbol(s) => self.integer(i64::from(s == symbol)),
            Node::Add(terms) => {
                let parts: Vec<ExprId> = terms.iter().map(d).collect();
                self.add(&parts)
            }
            Node::Mul(factors) => {
                let mut parts = Vec::with_capacity(factors.len());
                for (i, factor) in factors.iter().enumerate() {
                    if d(factor) == zero {
                        continue;
                    }
                    let mut product = factors.to_vec();
                    product[i] = d(factor);
                    parts.push(self.mul(&product));
                }
                self.add(&parts)
            }
            Node::Pow(base, exponent) if d(&base) != zero => {
                let lowered = self.pow_of_expression(base, exponent.sub(&Rational::ONE));
                let coefficient = self.number(exponent);
                self.mul(&[coefficient, lowered, d(&base)])
            }
            Node::Call(function, argument) if d(&argument) != zero => {
                let outer = self.derivative_of_function(function, argument);
                self.mul(&[outer, d(&argument)])
            }
            Node::Atan2(y, x) if d(&y) != zero || d(&x) != zero => {
                let (dy, dx) = (d(&y), d(&x));
                self.derivative_of_atan2(y, x, dy, dx)
            }
            Node::Pow(..) | Node::Call(..) | Node::Atan2(..) => zero,
        }
    }

    /// `f'(u)` for a non-constant argument `u`.
    fn derivative_of_function(&mut self, function: Function, argument: ExprId) -> ExprId {
        match function {
            Function::Sin => self.apply_to_expression(Function::Cos, argument),
            Function::Cos => {
                let sine = self.apply_to_expression(Function::Sin, argument);
                self.neg(sine)
            }
            Function::Tan => {
                let cosine = self.apply_to_expression(Function::Cos, argument);
                self.pow_of_expression(cosine, Rational::integer(-2))
            }
            Function::Exp => self.apply_to_expression(Function::Exp, argument),
            Function::Ln => self.pow_of_expression(argument, Rational::integer(-1)),
            Function::Asin => self.inverse_root_of_one_minus_square(argument),
            Function::Acos => {
                let slope = self.inverse_root_of_one_minus_square(argument);
                self.neg(slope)
            }
            Function::Atan => {
                let one = self.integer(1);
                let square = self.pow_of_expression(argument, Rational::integer(2));
                let sum = self.add2(one, square);
                self.pow_of_expression(sum, Rational::integer(-1))
            }
        }
    }

    /// `(1 - u^2)^(-1/2)`, the slope of `asin u`.
    fn inverse_root_of_one_minus_square(&mut self, argument: ExprId) -> ExprId {
        let one = self.integer(1);
        let square = self.pow_of_expression(argument, Rational::integer(2));
        let difference = self.sub(one, square);
        self.pow_of_expression(difference, Rational::HALF.neg())
    }

    /// `(x dy - y dx) / (x^2 + y^2)`, the differential of `atan2(y, x)`.
    fn derivative_of_atan2(&mut self, y: ExprId, x: ExprId, dy: ExprId, dx: ExprId) -> ExprId {
        let along = self.mul2(x, dy);
        let across = self.mul2(y, dx);
        let numerator = self.sub(along, across);
        let x_square = self.pow_of_expression(x, Rational::integer(2));
        let y_square = self.pow_of_expression(y, Rational::integer(2));
        let radius_square = self.add2(x_square, y_square);
        let inverse = self.pow_of_expression(radius_square, Rational::integer(-1));
        self.mul2(numerator, inverse)
    }

    /// `d form / d symbol`, in normal form.
    pub fn derivative_of_normal(
        &mut self,
        form: &RationalFunction,
        symbol: SymbolId,
    ) -> Result<RationalFunction, SymError> {
        let numerator = self.derivative_of_poly(form.numerator(), symbol)?;
        let mut logarithmic = RationalFunction::zero();
        for (factor, multiplicity) in form.denominator() {
            let d_factor = self.derivative_of_poly(factor, symbol)?;
            if d_factor.is_zero() {
                continue;
            }
            let ratio = d_factor
                .div(&RationalFunction::from_poly(factor.clone()), &self.atoms)
                .ok_or_else(|| SymError::DivisionByZero {
                    expr: "a denominator factor".to_string(),
                })?;
            logarithmic = logarithmic.add(
                &ratio.scale(&Rational::integer(*multiplicity as i64)),
                &self.atoms,
            );
        }
        let quotient_part = numerator.mul(&form.reciprocal_of_denominator(), &self.atoms);
        Ok(quotient_part.sub(&form.mul(&logarithmic, &self.atoms), &self.atoms))
    }

    /// `d poly / d symbol`: a polynomial unless a kernel's derivative divides.
    fn derivative_of_poly(
        &mut self,
        poly: &Poly,
        symbol: SymbolId,
    ) -> Result<RationalFunction, SymError> {
        let mut atom_derivatives: Vec<(AtomId, RationalFunction)> = Vec::new();
        for atom in poly.atoms() {
            let d = self.derivative_of_atom(atom, symbol)?;
            if !d.is_zero() {
                atom_derivatives.push((atom, d));
            }
        }
        let mut polynomial_terms = Vec::new();
        let mut rational = RationalFunction::zero();
        for (atom, d_atom) in &atom_derivatives {
            for (monomial, coefficient) in poly.terms() {
                let exponent = monomial.exponent(*atom);
                if exponent == 0 {
                    continue;
                }
                let rest = monomial.div(&Monomial::power(*atom, 1)).unwrap_or_default();
                let c = coefficient.mul(&Rational::integer(exponent as i64));
                match d_atom.as_polynomial() {
                    Some(d) => polynomial_terms.push(d.mul_term(&rest, &c)),
                    None => {
                        let term = RationalFunction::from_poly(Poly::term(rest, c));
                        rational = rational.add(&term.mul(d_atom, &self.atoms), &self.atoms);
                    }
                }
            }
        }
        let polynomial = Poly::from_terms(
            polynomial_terms
                .iter()
                .flat_map(|p| p.terms().iter().cloned()),
        )
        .reduce_trig(&self.atoms);
        Ok(RationalFunction::from_poly(polynomial).add(&rational, &self.atoms))
    }

    /// `d atom / d symbol`.
    fn derivative_of_atom(
        &mut self,
        atom: AtomId,
        symbol: SymbolId,
    ) -> Result<RationalFunction, SymError> {
        match self.atoms.get(atom).clone() {
            Atom::Symbol(s) => Ok(RationalFunction::constant(Rational::integer(i64::from(
                s == symbol,
            )))),
            Atom::Sin(argument) | Atom::Cos(argument) => {
                let inner = self.normal(argument)?;
                let d_inner = self.derivative_of_normal(&inner, symbol)?;
                if d_inner.is_zero() {
                    return Ok(d_inner);
                }
                let (sine, cosine) = self.atoms.trig_pair(argument);
                let outer = if sine == atom {
                    Poly::atom(cosine)
                } else {
                    Poly::atom(sine).neg()
                };
                Ok(RationalFunction::from_poly(outer).mul(&d_inner, &self.atoms))
            }
            Atom::Kernel(kernel) => self.derivative_of_kernel(atom, kernel, symbol),
        }
    }

    fn derivative_of_kernel(
        &mut self,
        atom: AtomId,
        kernel: ExprId,
        symbol: SymbolId,
    ) -> Result<RationalFunction, SymError> {
        let itself = RationalFunction::from_poly(Poly::atom(atom));
        match self.node(kernel).clone() {
            Node::Pow(base, exponent) => {
                let base_form = self.normal(base)?;
                let d_base = self.derivative_of_normal(&base_form, symbol)?;
                let ratio = d_base.div(&base_form, &self.atoms).ok_or_else(|| {
                    SymError::DivisionByZero {
                        expr: self.display(base).to_string(),
                    }
                })?;
                Ok(itself.mul(&ratio, &self.atoms).scale(&exponent))
            }
            Node::Call(Function::Exp, argument) => {
                let inner = self.normal(argument)?;
                let d_inner = self.derivative_of_normal(&inner, symbol)?;
                Ok(itself.mul(&d_inner, &self.atoms))
            }
            Node::Call(Function::Ln, argument) => {
                let inner = self.normal(argument)?;
                let d_inner = self.derivative_of_normal(&inner, symbol)?;
                d_inner
                    .div(&inner, &self.atoms)
                    .ok_or_else(|| SymError::DivisionByZero {
                        expr: self.display(argument).to_string(),
                    })
            }
            Node::Call(function @ (Function::Asin | Function::Acos | Function::Atan), argument) => {
                let inner = self.normal(argument)?;
                let d_inner = self.derivative_of_normal(&inner, symbol)?;
                if d_inner.is_zero() {
                    return Ok(d_inner);
                }
                let slope = self.derivative_of_function(function, argument);
                let slope = self.normal(slope)?;
                Ok(slope.mul(&d_inner, &self.atoms))
            }
            Node::Atan2(y, x) => self.derivative_of_atan2_form(y, x, symbol),
            _ => Ok(RationalFunction::zero()),
        }
    }

    /// `d atan2(y, x) / d symbol = (x dy - y dx) / (x^2 + y^2)` in normal form.
    fn derivative_of_atan2_form(
        &mut self,
        y: ExprId,
        x: ExprId,
        symbol: SymbolId,
    ) -> Result<RationalFunction, SymError> {
        let (y_form, x_form) = (self.normal(y)?, self.normal(x)?);
        let dy = self.derivative_of_normal(&y_form, symbol)?;
        let dx = self.derivative_of_normal(&x_form, symbol)?;
        let atoms = &self.atoms;
        let numerator = x_form.mul(&dy, atoms).sub(&y_form.mul(&dx, atoms), atoms);
        if numerator.is_zero() {
            return Ok(numerator);
        }
        let radius_square = x_form
            .mul(&x_form, atoms)
            .add(&y_form.mul(&y_form, atoms), atoms);
        numerator
            .div(&radius_square, atoms)
            .ok_or_else(|| SymError::DivisionByZero {
                expr: format!("{}^2 + {}^2", self.display(x), self.display(y)),
            })
    }
}

impl Store {
    /// Replaces symbols by expressions. Fails when the result divides by an
    /// exact zero or leaves a function's domain at a constant (`ln(0)`).
    pub fn substitute(
        &mut self,
        root: ExprId,
        replacements: &HashMap<SymbolId, ExprId>,
    ) -> Result<ExprId, SymError> {
        let mut rebuilt: FxHashMap<ExprId, ExprId> = FxHashMap::default();
        for id in self.reachable(&[root]) {
            let new = match self.node(id).clone() {
                Node::Symbol(s) => replacements.get(&s).copied().unwrap_or(id),
                Node::Number(_) => id,
                Node::Add(terms) => {
                    let terms: Vec<ExprId> = terms.iter().map(|t| rebuilt[t]).collect();
                    self.add(&terms)
                }
                Node::Mul(factors) => {
                    let factors: Vec<ExprId> = factors.iter().map(|f| rebuilt[f]).collect();
                    self.mul(&factors)
                }
                Node::Pow(base, exponent) => self.pow(rebuilt[&base], exponent)?,
                Node::Call(function, argument) => self.apply(function, rebuilt[&argument])?,
                Node::Atan2(y, x) => self.atan2(rebuilt[&y], rebuilt[&x])?,
            };
            rebuilt.insert(id, new);
        }
        Ok(rebuilt[&root])
    }
}

impl RationalFunction {
    /// The numerator when the denominator is 1.
    pub fn as_polynomial(&self) -> Option<&Poly> {
        self.denominator().is_empty().then(|| self.numerator())
    }
}
