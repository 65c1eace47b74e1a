//! Inputs: a force on a coordinate, a linear form of coordinate names, or
//! a column of B(q).

mod linear_form;
#[cfg(test)]
mod tests;

use super::context::Context;
use super::items::{check_unique_in_section, named_item, row_of_expressions};
use super::velocities::velocity_free;
use crate::model::{Declared, Variable};
use crate::sym::{Matrix, RationalFunction};
use crate::syntax::{self, Expr, Item, Value};
use linear_form::linear_form_column;

/// `(names, B)`: each input a force on a coordinate, a linear form of
/// coordinate names, or a column of B.
pub(super) fn inputs(
    cx: &mut Context,
    section: Option<&syntax::Section>,
    coordinates: &[Variable],
) -> Option<(Vec<Declared>, Matrix)> {
    let n = coordinates.len();
    let Some(list) = section.and_then(|s| cx.list(s)) else {
        return (section.is_none()).then(|| (Vec::new(), Matrix::zeros(n, 0)));
    };
    let mut names: Vec<Declared> = Vec::new();
    let mut columns = Vec::new();
    let mut ok = true;
    for item in &list.items {
        let Some((declared, value)) = named_item(cx, item, "an input") else {
            ok = false;
            continue;
        };
        ok &= check_unique_in_section(cx, &names, &declared.name, declared.span);
        match input_column(cx, item, value, coordinates) {
            Some(column) => columns.push(column),
            None => ok = false,
        }
        names.push(declared);
    }
    if !ok {
        return None;
    }
    let p = names.len();
    let mut b = Matrix::zeros(n, p);
    for (j, column) in columns.into_iter().enumerate() {
        for (i, entry) in column.into_iter().enumerate() {
            b.set(i, j, entry);
        }
    }
    Some((names, b))
}

/// An input names a coordinate, gives a linear form of coordinate names
/// ([`linear_form`]), or a column of n velocity-free entries.
fn input_column(
    cx: &mut Context,
    item: &Item,
    value: &Value,
    coordinates: &[Variable],
) -> Option<Vec<RationalFunction>> {
    let n = coordinates.len();
    let expr = match value {
        Value::Expr(Expr::Name(ident)) if !is_coordinate(ident, coordinates) => {
            cx.diagnostics.error(
                ident.span(),
                format!(
                    "an input acts on a coordinate, and `{ident}` is not a coordinate (or give a \
                     column `[b_1, ..., b_n]`)"
                ),
            );
            return None;
        }
        Value::Expr(expr) => expr,
        Value::List(_) => {
            let row = row_of_expressions(cx, item, n, "an input column")?;
            return row
                .into_iter()
                .map(|expr| {
                    velocity_free(
                        cx,
                        expr,
                        "an input column depends on the configuration only: no velocities",
                    )
                })
                .collect();
        }
    };
    linear_form_column(cx, expr, coordinates)
}

/// True when `ident` names one of the coordinates.
fn is_coordinate(ident: &proc_macro2::Ident, coordinates: &[Variable]) -> bool {
    coordinates.iter().any(|c| *ident == c.declared.name)
}
