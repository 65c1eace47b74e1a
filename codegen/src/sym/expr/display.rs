//! Printing expressions in the model language's syntax (`m*r^2 - sin(phi)`),
//! with the fewest parentheses the grammar needs.

use super::{ExprId, Node, Store};
use crate::sym::number::Rational;
use std::fmt;

impl Store {
    /// A printable view of an expression (`m*r^2 - sin(phi)`).
    pub fn display(&self, id: ExprId) -> Displayed<'_> {
        Displayed { store: self, id }
    }
}

/// Prints an expression with the fewest parentheses the grammar needs.
pub struct Displayed<'a> {
    store: &'a Store,
    id: ExprId,
}

/// Binding strength used by the printer: sum < product < power < atom.
const SUM: u8 = 1;
const PRODUCT: u8 = 2;
const POWER: u8 = 3;

impl Displayed<'_> {
    fn write(&self, f: &mut fmt::Formatter<'_>, id: ExprId, context: u8) -> fmt::Result {
        let strength = self.strength(id);
        if strength < context {
            write!(f, "(")?;
            self.write_node(f, id)?;
            write!(f, ")")
        } else {
            self.write_node(f, id)
        }
    }

    fn strength(&self, id: ExprId) -> u8 {
        match self.store.node(id) {
            Node::Add(_) => SUM,
            Node::Mul(_) => PRODUCT,
            Node::Number(v) if v.is_negative() => SUM,
            Node::Number(v) if !v.is_integer() => PRODUCT,
            Node::Pow(_, exponent) if exponent.is_negative() => PRODUCT,
            Node::Pow(..) => POWER,
            _ => POWER + 1,
        }
    }

    fn write_node(&self, f: &mut fmt::Formatter<'_>, id: ExprId) -> fmt::Result {
        let store = self.store;
        match store.node(id) {
            Node::Number(value) => write!(f, "{value}"),
            Node::Symbol(symbol) => write!(f, "{}", store.symbol_info(*symbol).name),
            Node::Add(terms) => self.write_sum(f, terms),
            Node::Mul(factors) => self.write_product(f, factors),
            Node::Pow(_, exponent) if exponent.is_negative() => {
                write!(f, "1/")?;
                self.write_reciprocal(f, id, POWER)
            }
            Node::Pow(base, exponent) => {
                self.write(f, *base, POWER + 1)?;
                if exponent.is_integer() && !exponent.is_negative() {
                    write!(f, "^{exponent}")
                } else {
                    write!(f, "^({exponent})")
                }
            }
            Node::Call(function, argument) => {
                write!(f, "{}(", function.name())?;
                self.write(f, *argument, 0)?;
                write!(f, ")")
            }
            Node::Atan2(y, x) => {
                write!(f, "atan2(")?;
                self.write(f, *y, 0)?;
                write!(f, ", ")?;
                self.write(f, *x, 0)?;
                write!(f, ")")
            }
        }
    }

    fn write_sum(&self, f: &mut fmt::Formatter<'_>, terms: &[ExprId]) -> fmt::Result {
        for (i, &term) in terms.iter().enumerate() {
            let negated = self.negated_term(term);
            match (i, negated.is_some()) {
                (0, true) => write!(f, "-")?,
                (0, false) => {}
                (_, true) => write!(f, " - ")?,
                (_, false) => write!(f, " + ")?,
            }
            match negated {
                Some(NegatedTerm::Number(value)) => write!(f, "{value}")?,
                Some(NegatedTerm::Product(coefficient, rest)) => {
                    if !coefficient.is_one() {
                        write!(f, "{coefficient}*")?;
                    }
                    self.write_factors(f, rest)?;
                }
                None => self.write(f, term, SUM)?,
            }
        }
        Ok(())
    }

    fn negated_term<'s>(&'s self, term: ExprId) -> Option<NegatedTerm<'s>> {
        match self.store.node(term) {
            Node::Number(v) if v.is_negative() => Some(NegatedTerm::Number(v.neg())),
            Node::Mul(factors) => match self.store.node(factors[0]) {
                Node::Number(v) if v.is_negative() => {
                    Some(NegatedTerm::Product(v.neg(), &factors[1..]))
                }
                _ => None,
            },
            _ => None,
        }
    }

    fn write_product(&self, f: &mut fmt::Formatter<'_>, factors: &[ExprId]) -> fmt::Result {
        if let Node::Number(v) = self.store.node(factors[0])
            && v == &Rational::integer(-1)
        {
            write!(f, "-")?;
            return self.write_factors(f, &factors[1..]);
        }
        self.write_factors(f, factors)
    }

    /// `a*b/(c*d^2)`: factors with negative exponents form the denominator.
    fn write_factors(&self, f: &mut fmt::Formatter<'_>, factors: &[ExprId]) -> fmt::Result {
        let (denominator, numerator): (Vec<ExprId>, Vec<ExprId>) = factors.iter().partition(
            |&&factor| matches!(self.store.node(factor), Node::Pow(_, e) if e.is_negative()),
        );
        if numerator.is_empty() {
            write!(f, "1")?;
        }
        self.write_joined(f, &numerator, PRODUCT + 1, |display, f, factor, context| {
            display.write(f, factor, context)
        })?;
        match denominator.as_slice() {
            [] => Ok(()),
            [single] => {
                write!(f, "/")?;
                self.write_reciprocal(f, *single, POWER)
            }
            _ => {
                write!(f, "/(")?;
                self.write_joined(f, &denominator, PRODUCT + 1, Displayed::write_reciprocal)?;
                write!(f, ")")
            }
        }
    }

    fn write_joined(
        &self,
        f: &mut fmt::Formatter<'_>,
        factors: &[ExprId],
        context: u8,
        write_one: fn(&Self, &mut fmt::Formatter<'_>, ExprId, u8) -> fmt::Result,
    ) -> fmt::Result {
        for (i, &factor) in factors.iter().enumerate() {
            if i > 0 {
                write!(f, "*")?;
            }
            write_one(self, f, factor, context)?;
        }
        Ok(())
    }

    /// `base^(-e)` written as `base^e`, for use after a `/`.
    fn write_reciprocal(
        &self,
        f: &mut fmt::Formatter<'_>,
        factor: ExprId,
        context: u8,
    ) -> fmt::Result {
        let Node::Pow(base, exponent) = self.store.node(factor) else {
            return self.write(f, factor, context);
        };
        let positive = exponent.neg();
        if positive.is_one() {
            return self.write(f, *base, context.max(PRODUCT + 1));
        }
        self.write(f, *base, POWER + 1)?;
        if positive.is_integer() {
            write!(f, "^{positive}")
        } else {
            write!(f, "^({positive})")
        }
    }
}

enum NegatedTerm<'a> {
    Number(Rational),
    Product(Rational, &'a [ExprId]),
}

impl fmt::Display for Displayed<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write(f, self.id, 0)
    }
}
