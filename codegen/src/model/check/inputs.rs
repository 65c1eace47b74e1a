//! Inputs: a force on a coordinate or a column of B(q).

use super::context::Context;
use super::items::{check_unique_in_section, named_item, row_of_expressions};
use super::velocities::velocity_free;
use crate::model::{Declared, Variable};
use crate::sym::{Matrix, RationalFunction};
use crate::syntax::{self, Expr, Item, Value};

/// `(names, B)`: each input a force on a coordinate or a column of B.
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

/// An input names a coordinate, or gives a column of n velocity-free entries.
fn input_column(
    cx: &mut Context,
    item: &Item,
    value: &Value,
    coordinates: &[Variable],
) -> Option<Vec<RationalFunction>> {
    let n = coordinates.len();
    if let Value::Expr(Expr::Name(ident)) = value {
        let name = ident.to_string();
        let Some(index) = coordinates.iter().position(|c| c.declared.name == name) else {
            cx.diagnostics.error(
                ident.span(),
                format!(
                    "an input acts on a coordinate, and `{name}` is not a coordinate (or give a \
                     column `[b_1, ..., b_n]`)"
                ),
            );
            return None;
        };
        return Some(
            (0..n)
                .map(|i| {
                    if i == index {
                        RationalFunction::one()
                    } else {
                        RationalFunction::zero()
                    }
                })
                .collect(),
        );
    }
    if value.as_list().is_none() {
        cx.diagnostics.error(
            value.span(),
            "an input is a coordinate's name or a column `[b_1, ..., b_n]`",
        );
        return None;
    }
    let row = row_of_expressions(cx, item, n, "an input column")?;
    row.into_iter()
        .map(|expr| {
            velocity_free(
                cx,
                expr,
                "an input column depends on the configuration only: no velocities",
            )
        })
        .collect()
}
