//! Bodies with a known frame and centre, a scalar mass and a symmetric
//! inertia; particles; the gravity field; the bodies' energies.

use super::super::context::Context;
use super::super::items::{check_unique_in_section, item_expression, named_item};
use super::frames::check_frame_name;
use super::values::{check_configuration_only, evaluator};
use crate::model::Declared;
use crate::model::mechanism::bodies::{Body, BodyMotion};
use crate::model::mechanism::evaluate::Reference;
use crate::model::mechanism::space::{self, GROUND, Space};
use crate::model::mechanism::vector::{self, Vector};
use crate::sym::{ExprId, RationalFunction, SymbolId};
use crate::syntax::{self, Expr, Item, Value};

/// The bodies' `T` and `V` in normal form, the expressions they were
/// derived as, and the bodies' motions.
pub(super) struct BodyEnergies {
    pub(super) kinetic: RationalFunction,
    pub(super) potential: RationalFunction,
    pub(super) derived_as: (ExprId, ExprId),
    pub(super) motions: Vec<BodyMotion>,
}

/// `name = body(frame, center, mass, inertia)` or `name = particle(point, mass)`.
pub(super) fn bodies(
    cx: &mut Context,
    section: Option<&syntax::Section>,
    space: &mut Space,
    reference: &Reference,
) -> Vec<(Declared, Body)> {
    let Some(list) = section.and_then(|s| cx.list(s)) else {
        return Vec::new();
    };
    let mut bodies: Vec<(Declared, Body)> = Vec::new();
    for item in &list.items {
        let Some((declared, value)) = named_item(cx, item, "a body") else {
            continue;
        };
        let names: Vec<Declared> = bodies.iter().map(|(d, _)| d.clone()).collect();
        let unique = check_unique_in_section(cx, &names, &declared.name, declared.span);
        match (unique, body(cx, value, space, reference)) {
            (true, Some(body)) => bodies.push((declared, body)),
            _ => space.mark_broken(&declared.name),
        }
    }
    bodies
}

/// One body or particle, its parts each checked.
fn body(cx: &mut Context, value: &Value, space: &Space, reference: &Reference) -> Option<Body> {
    let (kind, arguments) = match value {
        Value::Expr(Expr::Call {
            function,
            arguments,
            ..
        }) => (function.to_string(), arguments.as_slice()),
        _ => (String::new(), &[][..]),
    };
    match (kind.as_str(), arguments) {
        ("body", [frame, center_value, mass, inertia_value]) => {
            let frame = check_frame_known(cx, frame, space);
            let center = center(cx, center_value, space, reference);
            let mass = configuration_scalar(cx, mass, space, reference, "a mass");
            let inertia = inertia(cx, inertia_value, space, reference);
            let (frame_name, frame) = frame?;
            Some(Body {
                frame,
                frame_name,
                center: center?,
                mass: mass?,
                inertia: inertia?,
                particle: false,
            })
        }
        ("particle", [point, mass]) => {
            let center = center(cx, point, space, reference);
            let mass = configuration_scalar(cx, mass, space, reference, "a mass");
            let zero = cx.sym.integer(0);
            Some(Body {
                frame: space.frame(GROUND)?.clone(),
                frame_name: GROUND.to_string(),
                center: center?,
                mass: mass?,
                inertia: [zero; 9],
                particle: true,
            })
        }
        _ => {
            cx.diagnostics.error(
                value.span(),
                "a body is `body(frame, center, mass, inertia)` or `particle(point, mass)`",
            );
            None
        }
    }
}

/// A body's frame is `ground` or a declared frame: its name and state.
fn check_frame_known(
    cx: &mut Context,
    value: &Value,
    space: &Space,
) -> Option<(String, space::FrameState)> {
    let ident = check_frame_name(cx, value)?;
    let frame = space.frame(&ident.to_string()).cloned();
    if frame.is_none() && !space.is_broken(&ident.to_string()) {
        cx.diagnostics.error(
            ident.span(),
            format!(
                "unknown frame `{ident}`: a body is fixed in `ground` or in a frame declared \
                 in `frames`"
            ),
        );
    }
    Some((ident.to_string(), frame?))
}

/// A body's centre (or a contact's point) is a known point.
pub(super) fn center(
    cx: &mut Context,
    value: &Value,
    space: &Space,
    reference: &Reference,
) -> Option<Vector> {
    let expr = item_expression(cx, value)?;
    if let Expr::Name(ident) = expr {
        let name = ident.to_string();
        let known = space.point(&name).is_some() || space.frame(&name).is_some();
        if !known && !space.is_broken(&name) {
            cx.diagnostics.error(
                ident.span(),
                format!(
                    "unknown point `{name}`: a centre is `origin` or a point declared in `points`"
                ),
            );
            return None;
        }
    }
    evaluator(cx, space, reference).point(expr)
}

/// A scalar of the configuration, e.g. a mass or an inertia entry.
fn configuration_scalar(
    cx: &mut Context,
    value: &Value,
    space: &Space,
    reference: &Reference,
    what: &str,
) -> Option<ExprId> {
    let expr = item_expression(cx, value)?;
    let scalar = evaluator(cx, space, reference).scalar(expr)?;
    check_configuration_only(cx, &[scalar], expr, what).then_some(scalar)
}

/// `diag(a, b, c)` or a symmetric `[[..], [..], [..]]`.
fn inertia(
    cx: &mut Context,
    value: &Value,
    space: &Space,
    reference: &Reference,
) -> Option<[ExprId; 9]> {
    let what = "an inertia entry";
    if let Value::Expr(Expr::Call {
        function,
        arguments,
        ..
    }) = value
        && function == "diag"
        && arguments.len() == 3
    {
        let zero = cx.sym.integer(0);
        let mut entries = [zero; 9];
        for (i, argument) in arguments.iter().enumerate() {
            entries[4 * i] = configuration_scalar(cx, argument, space, reference, what)?;
        }
        return Some(entries);
    }
    let rows = value.as_list().filter(|list| {
        list.items.len() == 3
            && list
                .items
                .iter()
                .all(|row| row.value().as_list().is_some_and(|r| r.items.len() == 3))
    });
    let Some(rows) = rows else {
        cx.diagnostics.error(
            value.span(),
            "an inertia is `diag(a, b, c)` or a symmetric 3 x 3 list `[[..], [..], [..]]` \
             in the body's axes",
        );
        return None;
    };
    let entries: Vec<&Value> = rows
        .items
        .iter()
        .filter_map(|row| row.value().as_list())
        .flat_map(|row| row.items.iter().map(Item::value))
        .collect();
    let mut values = Vec::with_capacity(9);
    for entry in &entries {
        values.push(configuration_scalar(cx, entry, space, reference, what));
    }
    let values: Vec<ExprId> = values.into_iter().collect::<Option<_>>()?;
    let values: [ExprId; 9] = values.try_into().ok()?;
    check_symmetric_inertia(cx, &values, &entries).then_some(values)
}

/// An inertia matrix equals its transpose.
fn check_symmetric_inertia(cx: &mut Context, values: &[ExprId; 9], entries: &[&Value]) -> bool {
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        let difference = cx.sym.sub(values[3 * i + j], values[3 * j + i]);
        if cx.sym.normal(difference).is_ok_and(|d| d.is_zero()) {
            continue;
        }
        cx.diagnostics.error(
            entries[3 * i + j].span(),
            format!(
                "an inertia matrix is symmetric: entry ({}, {}) differs from entry ({}, {})",
                i + 1,
                j + 1,
                j + 1,
                i + 1
            ),
        );
        return false;
    }
    true
}

/// The uniform gravity field (zero when not given).
pub(super) fn gravity(
    cx: &mut Context,
    section: Option<&syntax::Section>,
    space: &Space,
    reference: &Reference,
) -> Vector {
    let zero = vector::zero(&mut cx.sym);
    let Some(expr) = section.and_then(|s| cx.expression(s)) else {
        return zero;
    };
    match evaluator(cx, space, reference).vector(expr) {
        Some(field) if check_configuration_only(cx, &field, expr, "gravity") => field,
        _ => zero,
    }
}

/// `T` and `V` of the bodies and of the `extra` motions (kinetic energy
/// alone): the expressions they were derived as, their normal forms, and
/// each body's motion, then the extra ones.
pub(super) fn body_energies(
    cx: &mut Context,
    bodies: &[(Declared, Body)],
    extra: Vec<BodyMotion>,
    gravity: &Vector,
    q: &[SymbolId],
) -> Option<BodyEnergies> {
    let mut motions = Vec::new();
    let mut potential = Vec::new();
    for (_, body) in bodies {
        motions.push(body.motion(&mut cx.sym, q).ok()?);
        potential.push(body.potential_energy(&mut cx.sym, gravity));
    }
    motions.extend(extra);
    let kinetic: Vec<ExprId> = (motions.iter())
        .map(|motion| motion.kinetic_energy(&mut cx.sym))
        .collect();
    let kinetic = cx.sym.add(&kinetic);
    let potential = cx.sym.add(&potential);
    Some(BodyEnergies {
        kinetic: cx.sym.normal(kinetic).ok()?,
        potential: cx.sym.normal(potential).ok()?,
        derived_as: (kinetic, potential),
        motions,
    })
}
