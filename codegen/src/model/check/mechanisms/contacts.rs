//! Rolling contacts on a declared body with at least one direction, and
//! holonomic constraints free of velocities.

use super::super::context::Context;
use super::super::items::{check_unique_in_section, item_expression, named_item};
use super::bodies::center;
use super::values::{
    Row, check_configuration_only, evaluator, gradient_coefficients, linear_coefficients,
};
use crate::model::Declared;
use crate::model::mechanism::DrawnContact;
use crate::model::mechanism::bodies::Body;
use crate::model::mechanism::evaluate::Reference;
use crate::model::mechanism::space::{self, Space};
use crate::model::mechanism::vector::{self, Vector};
use crate::sym::{ExprId, SymError, SymbolId};
use crate::syntax::{self, Expr, Value};
use proc_macro2::Span;

/// The rolling contacts: each row's name and linear form, and each
/// contact once as drawing it needs.
pub(super) struct Contacts {
    pub(super) names: Vec<Declared>,
    pub(super) rows: Vec<Row>,
    pub(super) drawn: Vec<DrawnContact>,
}

/// `name = no_slip(body, point, [d_1, ...])`: one row `d_i . v_P` each.
pub(super) fn contacts(
    cx: &mut Context,
    section: Option<&syntax::Section>,
    space: &Space,
    reference: &Reference,
    bodies: &[(Declared, Body)],
    q: &[SymbolId],
) -> Contacts {
    let mut names = Vec::new();
    let mut rows = Vec::new();
    let mut drawn = Vec::new();
    let Some(list) = section.and_then(|s| cx.list(s)) else {
        return Contacts { names, rows, drawn };
    };
    for item in &list.items {
        let Some((declared, value)) = named_item(cx, item, "a rolling contact") else {
            continue;
        };
        let Some((slips, body, point)) = contact(cx, value, space, reference, bodies, q) else {
            continue;
        };
        drawn.push(DrawnContact {
            name: declared.name.clone(),
            body,
            point,
        });
        let count = slips.len();
        for (i, slip) in slips.into_iter().enumerate() {
            let name = if count == 1 {
                declared.name.clone()
            } else {
                format!("{}_{}", declared.name, i + 1)
            };
            names.push(Declared {
                name,
                span: declared.span,
            });
            rows.push(slip);
        }
    }
    Contacts { names, rows, drawn }
}

/// The slip velocities `d_i . v_P` of one contact, in normal form and
/// as the expression they were derived as; its body's index and its point.
fn contact(
    cx: &mut Context,
    value: &Value,
    space: &Space,
    reference: &Reference,
    bodies: &[(Declared, Body)],
    q: &[SymbolId],
) -> Option<(Vec<Row>, usize, Vector)> {
    let Value::Expr(Expr::Call {
        function,
        arguments,
        ..
    }) = value
    else {
        return report_contact_form(cx, value.span());
    };
    let [body, point, directions_value] = arguments.as_slice() else {
        return report_contact_form(cx, function.span());
    };
    if function != "no_slip" {
        return report_contact_form(cx, function.span());
    }
    let body = check_body_known(cx, body, bodies, space);
    let point = center(cx, point, space, reference);
    let directions = directions(cx, directions_value, space, reference);
    let ((index, body), point, directions) = (body?, point?, directions?);
    let v = body.material_velocity(&mut cx.sym, &point, q).ok()?;
    let rows = directions
        .iter()
        .map(|d| {
            let slip = vector::inner(&mut cx.sym, d, &v);
            linear_coefficients(cx, slip, q).ok().map(|row| (row, slip))
        })
        .collect::<Option<Vec<Row>>>()?;
    Some((rows, index, point))
}

/// Reports at `span` that a rolling contact is
/// `name = no_slip(body, point, [direction, ...])`.
fn report_contact_form<T>(cx: &mut Context, span: Span) -> Option<T> {
    cx.diagnostics.error(
        span,
        "a rolling contact is `name = no_slip(body, point, [direction, ...])`",
    );
    None
}

/// A contact names a declared body: its index and the body.
fn check_body_known<'b>(
    cx: &mut Context,
    value: &Value,
    bodies: &'b [(Declared, Body)],
    space: &Space,
) -> Option<(usize, &'b Body)> {
    let (found, broken) = match value {
        Value::Expr(Expr::Name(ident)) => (
            bodies.iter().position(|(d, _)| *ident == d.name),
            space.is_broken(&ident.to_string()),
        ),
        _ => (None, false),
    };
    if found.is_none() && !broken {
        cx.diagnostics.error(
            value.span(),
            "unknown body: a rolling contact names a body declared in `bodies`",
        );
    }
    found.map(|index| (index, &bodies[index].1))
}

/// At least one direction, each a vector.
fn directions(
    cx: &mut Context,
    value: &Value,
    space: &Space,
    reference: &Reference,
) -> Option<Vec<Vector>> {
    let Some(list) = value.as_list().filter(|l| !l.items.is_empty()) else {
        cx.diagnostics.error(
            value.span(),
            "a rolling contact needs at least one direction: `[d_1, ...]`, e.g. `[ground.x, ground.y]`",
        );
        return None;
    };
    let mut directions = Vec::new();
    for item in &list.items {
        let expr = item_expression(cx, item.value())?;
        let direction = evaluator(cx, space, reference).vector(expr)?;
        check_configuration_only(cx, &direction, expr, "a direction").then_some(())?;
        directions.push(direction);
    }
    Some(directions)
}

/// `name = f(q)`: the residuals and their velocity forms `(df/dq) qdot`.
pub(super) fn holonomic(
    cx: &mut Context,
    section: Option<&syntax::Section>,
    space: &Space,
    reference: &Reference,
    q: &[SymbolId],
) -> (Vec<Declared>, Vec<ExprId>, Vec<Row>) {
    let (mut names, mut residuals, mut forms) = (Vec::new(), Vec::new(), Vec::new());
    let Some(list) = section.and_then(|s| cx.list(s)) else {
        return (names, residuals, forms);
    };
    for item in &list.items {
        let Some((declared, value)) = named_item(cx, item, "a holonomic constraint") else {
            continue;
        };
        let Some(expr) = item_expression(cx, value) else {
            continue;
        };
        let unique = check_unique_in_section(cx, &names, &declared.name, declared.span);
        let Some(f) = evaluator(cx, space, reference).scalar(expr) else {
            continue;
        };
        if !check_configuration_only(cx, &[f], expr, "a holonomic constraint f(q) = 0") || !unique {
            continue;
        }
        match velocity_form(cx, f, q) {
            Ok(form) => forms.push(form),
            Err(error) => {
                cx.diagnostics.error(expr.first_span(), error.to_string());
                continue;
            }
        }
        names.push(declared);
        residuals.push(f);
    }
    (names, residuals, forms)
}

/// The velocity form `(df/dq) qdot` of a holonomic constraint `f(q) = 0`.
pub(super) fn velocity_form(cx: &mut Context, f: ExprId, q: &[SymbolId]) -> Result<Row, SymError> {
    let rate = space::time_derivative(&mut cx.sym, f, q)?;
    Ok((gradient_coefficients(cx, f, q)?, rate))
}
