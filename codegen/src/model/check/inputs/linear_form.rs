//! An input written as a linear form of coordinate names: its column of
//! B(q) read off as the coefficients.
//!
//! The form `drive = phi_l + phi_r` or `push = cos(theta)*x + sin(theta)*y`
//! is read as written, before it is lowered:
//!
//! ```text
//! form  = term (+|- term)*          the top-level sum, `-` and `-(...)` flipping signs
//! term  = factor (*|/ factor)*      the factors of a product; a `/` starts a divisor
//! B_i   = sum over the terms whose direction is q_i of  sign * (other factors) / (divisors)
//! ```
//!
//! The direction of a term is its one factor that is a coordinate's bare
//! name; the other factors and the divisors are its coefficient, an
//! expression of the coordinates (as values) and the parameters. A term
//! with no such factor (`2*(x + y)`, `1`, `m/x`) or with two (`y*x`) is an
//! error on the term; a coefficient proportional to a coordinate gets a
//! name in `define` (`ky = y`, then `ky*x`).

use super::super::context::Context;
use super::super::velocities::velocity_free;
use crate::model::Variable;
use crate::sym::{Rational, RationalFunction};
use crate::syntax::{BinaryOperator, Expr};

/// What each term of a linear form is, for the diagnostics.
const RULE: &str = "each term of an input's linear form is one coordinate name times a \
                    coefficient, e.g. `cos(theta)*x + sin(theta)*y`";

/// One term of the form's top-level sum: `sign * factors / divisors`.
struct Term<'e> {
    negated: bool,
    factors: Vec<&'e Expr>,
    divisors: Vec<&'e Expr>,
    written: &'e Expr,
}

/// The column of B(q) of the linear form `form`, or `None` after
/// reporting each term that breaks the rule.
pub(super) fn linear_form_column(
    cx: &mut Context,
    form: &Expr,
    coordinates: &[Variable],
) -> Option<Vec<RationalFunction>> {
    let mut terms = Vec::new();
    split_sum(form, false, &mut terms);
    let mut column = vec![RationalFunction::zero(); coordinates.len()];
    let mut ok = true;
    for term in &terms {
        match term_in_direction(cx, term, coordinates) {
            Some((index, coefficient)) => {
                column[index] = column[index].add(&coefficient, cx.sym.atoms());
            }
            None => ok = false,
        }
    }
    ok.then_some(column)
}

/// Appends the terms of the sum `expr`, each negated when `negated`.
fn split_sum<'e>(expr: &'e Expr, negated: bool, terms: &mut Vec<Term<'e>>) {
    match expr {
        Expr::Binary {
            operator: BinaryOperator::Add,
            left,
            right,
            ..
        } => {
            split_sum(left, negated, terms);
            split_sum(right, negated, terms);
        }
        Expr::Binary {
            operator: BinaryOperator::Subtract,
            left,
            right,
            ..
        } => {
            split_sum(left, negated, terms);
            split_sum(right, !negated, terms);
        }
        Expr::Negate { operand, .. } => split_sum(operand, !negated, terms),
        _ => {
            let mut term = Term {
                negated,
                factors: Vec::new(),
                divisors: Vec::new(),
                written: expr,
            };
            split_product(expr, &mut term);
            terms.push(term);
        }
    }
}

/// Adds the factors and divisors of the product `expr` to `term`.
fn split_product<'e>(expr: &'e Expr, term: &mut Term<'e>) {
    match expr {
        Expr::Binary {
            operator: BinaryOperator::Multiply,
            left,
            right,
            ..
        } => {
            split_product(left, term);
            split_product(right, term);
        }
        Expr::Binary {
            operator: BinaryOperator::Divide,
            left,
            right,
            ..
        } => {
            split_product(left, term);
            term.divisors.push(right);
        }
        Expr::Negate { operand, .. } => {
            term.negated = !term.negated;
            split_product(operand, term);
        }
        _ => term.factors.push(expr),
    }
}

/// The index of the term's direction and its coefficient, or `None`
/// after reporting why the term has no single direction.
fn term_in_direction(
    cx: &mut Context,
    term: &Term<'_>,
    coordinates: &[Variable],
) -> Option<(usize, RationalFunction)> {
    let directions: Vec<(usize, usize)> = (term.factors.iter().enumerate())
        .filter_map(|(at, factor)| Some((at, coordinate_index(factor, coordinates)?)))
        .collect();
    let (at, index) = match directions.as_slice() {
        [only] => *only,
        [] => {
            let message = format!("{RULE}; this term has no coordinate name as a factor");
            cx.diagnostics.error(term.written.first_span(), message);
            return None;
        }
        [(_, first), (second_at, second), ..] => {
            let message = format!(
                "{RULE}; this term has two, `{}` and `{}`, and either could be the \
                 direction: name the coefficient in `define` (`k = {}`, then `k*{}`)",
                coordinates[*first].declared.name,
                coordinates[*second].declared.name,
                coordinates[*first].declared.name,
                coordinates[*second].declared.name,
            );
            cx.diagnostics
                .error(term.factors[*second_at].first_span(), message);
            return None;
        }
    };
    let coefficient = coefficient(cx, term, at)?;
    Some((index, coefficient))
}

/// The coordinate a factor names bare, if it does.
fn coordinate_index(factor: &Expr, coordinates: &[Variable]) -> Option<usize> {
    let Expr::Name(ident) = factor else {
        return None;
    };
    let name = ident.to_string();
    coordinates.iter().position(|c| c.declared.name == name)
}

/// `sign * (the factors but the direction's) / (the divisors)`, free of
/// velocities.
fn coefficient(cx: &mut Context, term: &Term<'_>, direction: usize) -> Option<RationalFunction> {
    let rule = "an input's coefficients depend on the configuration only: no velocities";
    let sign = if term.negated { -1 } else { 1 };
    let mut product = RationalFunction::constant(Rational::integer(sign));
    let others = (term.factors.iter().enumerate()).filter(|&(at, _)| at != direction);
    for (_, factor) in others {
        let value = velocity_free(cx, factor, rule)?;
        product = product.mul(&value, cx.sym.atoms());
    }
    for divisor in &term.divisors {
        let value = velocity_free(cx, divisor, rule)?;
        let Some(quotient) = product.div(&value, cx.sym.atoms()) else {
            cx.diagnostics.error(
                divisor.first_span(),
                "an input's coefficient divides by an expression that is exactly zero",
            );
            return None;
        };
        product = quotient;
    }
    Some(product)
}
