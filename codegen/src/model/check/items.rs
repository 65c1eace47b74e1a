//! The shapes of list items every section reads: `name = value`, an
//! expression, a row of `n` expressions; names unique in their section;
//! and calls without keyword arguments, which only a drawing's shapes take.

use super::context::Context;
use crate::model::Declared;
use crate::syntax::{Expr, Item, Value};
use proc_macro2::Span;

/// A list item is `name = value`.
pub(super) fn named_item<'a>(
    cx: &mut Context,
    item: &'a Item,
    what: &str,
) -> Option<(Declared, &'a Value)> {
    match item {
        Item::Named { name, value } => Some((
            Declared {
                name: name.to_string(),
                span: name.span(),
            },
            value,
        )),
        Item::Plain(value) => {
            cx.diagnostics
                .error(value.span(), format!("expected `name = ...` for {what}"));
            None
        }
    }
}

/// An item's value is an expression, not a list.
pub(super) fn item_expression<'a>(cx: &mut Context, value: &'a Value) -> Option<&'a Expr> {
    let expr = value.as_expr();
    if expr.is_none() {
        cx.diagnostics
            .error(value.span(), "expected an expression, found a list");
    }
    expr
}

/// A row `[e_1, ..., e_n]` of exactly `n` expressions.
pub(super) fn row_of_expressions<'a>(
    cx: &mut Context,
    item: &'a Item,
    n: usize,
    what: &str,
) -> Option<Vec<&'a Expr>> {
    let Some(list) = item.value().as_list() else {
        cx.diagnostics.error(
            item.span(),
            format!("{what} is a list `[...]` of {n} expressions"),
        );
        return None;
    };
    if list.items.len() != n {
        cx.diagnostics.error(
            list.span,
            format!(
                "{what} must have {n} entries (one per coordinate), found {}",
                list.items.len()
            ),
        );
        return None;
    }
    list.items
        .iter()
        .map(|entry| match entry.value().as_expr() {
            Some(expr) if entry.name().is_none() => Some(expr),
            _ => {
                cx.diagnostics
                    .error(entry.span(), format!("an entry of {what} is an expression"));
                None
            }
        })
        .collect()
}

/// Names of constraints, inputs, bodies and holonomic constraints are
/// unique in their section.
pub(super) fn check_unique_in_section(
    cx: &mut Context,
    names: &[Declared],
    name: &str,
    span: Span,
) -> bool {
    let unique = !names.iter().any(|d| d.name == name);
    if !unique {
        cx.diagnostics
            .error(span, format!("`{name}` is declared twice in this section"));
    }
    unique
}

/// No call in `value` has keyword arguments (`name = value` inside its
/// parentheses): each is reported at its name.
pub(super) fn check_no_keywords(cx: &mut Context, value: &Value) {
    match value {
        Value::List(list) => {
            for item in &list.items {
                check_no_keywords(cx, item.value());
            }
        }
        Value::Expr(expr) => check_no_keywords_in(cx, expr),
    }
}

fn check_no_keywords_in(cx: &mut Context, expr: &Expr) {
    match expr {
        Expr::Call {
            function,
            arguments,
            keywords,
            ..
        } => {
            for keyword in keywords {
                cx.diagnostics.error(
                    keyword.name.span(),
                    format!(
                        "`{} = ...` is a keyword argument, which `{function}` does not take: \
                         only the shapes of the `drawing` section take keyword arguments",
                        keyword.name
                    ),
                );
            }
            for argument in arguments {
                check_no_keywords(cx, argument);
            }
        }
        Expr::Field { base: inner, .. } | Expr::Negate { operand: inner, .. } => {
            check_no_keywords_in(cx, inner);
        }
        Expr::Binary { left, right, .. } => {
            check_no_keywords_in(cx, left);
            check_no_keywords_in(cx, right);
        }
        Expr::Number { .. } | Expr::Name(_) => {}
    }
}
