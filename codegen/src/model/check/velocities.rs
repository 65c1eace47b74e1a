//! Where velocities may appear: nowhere in a value of the configuration,
//! and in an energy or a constraint to a fixed degree, polynomially; with
//! the token a violation is reported on.

use super::context::Context;
use crate::diagnostic::Diagnostics;
use crate::model::lower::Lowerer;
use crate::sym::{Atom, RationalFunction, SymbolKind};
use crate::syntax::{BinaryOperator, Expr, Value};
use proc_macro2::Span;

/// An expression free of velocities, in normal form.
pub(super) fn velocity_free(cx: &mut Context, expr: &Expr, rule: &str) -> Option<RationalFunction> {
    let id = cx.lower(expr)?;
    let has_velocity = cx
        .sym
        .free_symbols(id)
        .iter()
        .any(|&s| matches!(cx.sym.symbol_info(s).kind, SymbolKind::Velocity(_)));
    if has_velocity {
        let span = first_velocity_span(expr).unwrap_or_else(|| expr.first_span());
        cx.diagnostics.error(span, rule.to_string());
        return None;
    }
    cx.normal(id, expr.first_span())
}

/// Every term of the numerator has velocity degree `degree`, and no
/// velocity sits in a denominator or inside a function.
pub(super) fn check_velocity_degree(
    cx: &mut Context,
    form: &RationalFunction,
    expr: &Expr,
    degree: u32,
    rule: &str,
) -> bool {
    if velocity_degrees(cx, form) == Some(vec![degree]) || (form.is_zero() && degree == 1) {
        return true;
    }
    let span = offending_term(cx, expr, degree).unwrap_or_else(|| expr.first_span());
    cx.diagnostics.error(span, rule.to_string());
    false
}

/// The distinct velocity degrees of the numerator's terms, or `None` when
/// velocities enter non-polynomially.
fn velocity_degrees(cx: &mut Context, form: &RationalFunction) -> Option<Vec<u32>> {
    let denominator_atoms: Vec<_> = form
        .denominator()
        .iter()
        .flat_map(|(f, _)| f.atoms())
        .collect();
    let mut velocity_atoms = Vec::new();
    for atom in form.atoms() {
        match cx.sym.atoms().get(atom).clone() {
            Atom::Symbol(s) if matches!(cx.sym.symbol_info(s).kind, SymbolKind::Velocity(_)) => {
                if denominator_atoms.contains(&atom) {
                    return None;
                }
                velocity_atoms.push(atom);
            }
            _ => {
                let expression = cx.sym.expression_of_atom(atom);
                let inside = cx.sym.free_symbols(expression);
                if inside
                    .iter()
                    .any(|&s| matches!(cx.sym.symbol_info(s).kind, SymbolKind::Velocity(_)))
                {
                    return None;
                }
            }
        }
    }
    let mut degrees: Vec<u32> = form
        .numerator()
        .terms()
        .iter()
        .map(|(m, _)| velocity_atoms.iter().map(|&a| m.exponent(a)).sum())
        .collect();
    degrees.sort_unstable();
    degrees.dedup();
    Some(degrees)
}

/// The first top-level term of `expr` whose velocity degree is wrong.
fn offending_term(cx: &mut Context, expr: &Expr, degree: u32) -> Option<Span> {
    let mut terms = Vec::new();
    top_level_terms(expr, &mut terms);
    for term in terms {
        let mut scratch = Diagnostics::default();
        let id = Lowerer {
            cx: &mut cx.sym,
            scope: &cx.scope,
            diagnostics: &mut scratch,
        }
        .lower(term)?;
        let form = cx.sym.normal(id).ok()?;
        if velocity_degrees(cx, &form) != Some(vec![degree]) {
            return Some(term.first_span());
        }
    }
    None
}

/// The terms of a sum, with the signs dropped.
fn top_level_terms<'a>(expr: &'a Expr, terms: &mut Vec<&'a Expr>) {
    match expr {
        Expr::Binary {
            operator: BinaryOperator::Add | BinaryOperator::Subtract,
            left,
            right,
            ..
        } => {
            top_level_terms(left, terms);
            top_level_terms(right, terms);
        }
        Expr::Negate { operand, .. } => top_level_terms(operand, terms),
        _ => terms.push(expr),
    }
}

/// The span of the first `dot(...)` in an expression.
pub(super) fn first_velocity_span(expr: &Expr) -> Option<Span> {
    match expr {
        Expr::Call { function, .. } if function == "dot" => Some(function.span()),
        Expr::Call { arguments, .. } => arguments.iter().find_map(value_velocity_span),
        Expr::Negate { operand, .. } | Expr::Field { base: operand, .. } => {
            first_velocity_span(operand)
        }
        Expr::Binary { left, right, .. } => {
            first_velocity_span(left).or_else(|| first_velocity_span(right))
        }
        Expr::Number { .. } | Expr::Name(_) => None,
    }
}

/// The span of the first `dot(...)` in an expression or list.
fn value_velocity_span(value: &Value) -> Option<Span> {
    match value {
        Value::Expr(expr) => first_velocity_span(expr),
        Value::List(list) => list
            .items
            .iter()
            .find_map(|item| value_velocity_span(item.value())),
    }
}
