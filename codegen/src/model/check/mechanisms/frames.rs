//! Frames turned from `ground` about `x`, `y` or `z` without cycles, and
//! points, each `origin` or a point plus or minus vectors.

use super::super::context::Context;
use super::super::items::{item_expression, named_item};
use super::super::names::check_fresh_name;
use super::values::{check_configuration_only, evaluator};
use crate::model::Declared;
use crate::model::mechanism::evaluate::{Reference, axis_index};
use crate::model::mechanism::space::{self, Space};
use crate::sym::SymbolId;
use crate::syntax::{self, Expr, Item, Value};
use proc_macro2::Ident;

/// A frame's declaration: `name = rotate(parent, axis, angle)`.
struct FrameDeclaration<'a> {
    declared: Declared,
    parent: &'a Ident,
    axis: usize,
    angle: &'a Expr,
}

/// The frames, resolved from `ground` in dependency order.
pub(super) fn frames(
    cx: &mut Context,
    section: Option<&syntax::Section>,
    space: &mut Space,
    reference: &Reference,
    q: &[SymbolId],
) -> Vec<Declared> {
    let Some(list) = section.and_then(|s| cx.list(s)) else {
        return Vec::new();
    };
    let mut pending: Vec<FrameDeclaration> = list
        .items
        .iter()
        .filter_map(|item| frame_declaration(cx, item))
        .collect();
    let mut resolved = Vec::new();
    while let Some(ready) = pending
        .iter()
        .position(|f| space.frame(&f.parent.to_string()).is_some())
    {
        let frame = pending.remove(ready);
        if let Some(state) = rotated_frame(cx, &frame, space, reference, q) {
            space.add_frame(&frame.declared.name, state);
            resolved.push(frame.declared);
        } else {
            space.mark_broken(&frame.declared.name);
        }
    }
    let written: Vec<String> = list
        .items
        .iter()
        .filter_map(|item| item.name().map(ToString::to_string))
        .collect();
    for (index, frame) in pending.iter().enumerate() {
        check_frame_parent_known(cx, index, frame, &pending, &written);
    }
    for name in &written {
        if space.frame(name).is_none() {
            space.mark_broken(name);
        }
    }
    resolved
}

/// `name = rotate(parent, x|y|z, angle)` with a fresh name.
fn frame_declaration<'a>(cx: &mut Context, item: &'a Item) -> Option<FrameDeclaration<'a>> {
    let (declared, value) = named_item(cx, item, "a frame")?;
    let call = match value {
        Value::Expr(Expr::Call {
            function,
            arguments,
            ..
        }) if function == "rotate" && arguments.len() == 3 => Some(arguments),
        _ => None,
    };
    let Some([parent, axis, angle]) = call.map(Vec::as_slice) else {
        cx.diagnostics.error(
            value.span(),
            "a frame is `name = rotate(parent, x|y|z, angle)`",
        );
        return None;
    };
    let fresh = check_fresh_name(cx, &declared.name, declared.span, "frame");
    let parent = check_frame_name(cx, parent);
    let axis = check_axis(cx, axis);
    let angle = angle.as_expr();
    Some(FrameDeclaration {
        declared,
        parent: parent?,
        axis: axis?,
        angle: angle.filter(|_| fresh)?,
    })
}

/// A frame is named by an identifier.
pub(in crate::model::check) fn check_frame_name<'a>(
    cx: &mut Context,
    value: &'a Value,
) -> Option<&'a Ident> {
    match value {
        Value::Expr(Expr::Name(ident)) => Some(ident),
        _ => {
            cx.diagnostics
                .error(value.span(), "expected a frame's name, e.g. `ground`");
            None
        }
    }
}

/// A rotation is about the parent's `x`, `y` or `z` axis.
pub(in crate::model::check) fn check_axis(cx: &mut Context, value: &Value) -> Option<usize> {
    let axis = match value {
        Value::Expr(Expr::Name(ident)) => axis_index(ident),
        _ => None,
    };
    if axis.is_none() {
        cx.diagnostics.error(
            value.span(),
            "a frame turns about its parent's `x`, `y` or `z` axis",
        );
    }
    axis
}

/// A frame that never resolved has an unknown parent, or is part of a
/// cycle (reported once, at the cycle's first frame); a frame below a
/// broken declaration is not reported again.
fn check_frame_parent_known(
    cx: &mut Context,
    index: usize,
    frame: &FrameDeclaration,
    pending: &[FrameDeclaration],
    written: &[String],
) {
    let position = |name: &str| pending.iter().position(|f| f.declared.name == name);
    let parent = frame.parent.to_string();
    if position(&parent).is_none() {
        if !written.contains(&parent) {
            cx.diagnostics.error(
                frame.parent.span(),
                format!(
                    "unknown frame `{parent}`: a frame is turned from `ground` or from a \
                     frame declared in `frames`"
                ),
            );
        }
        return;
    }
    let mut cycle = vec![index];
    let mut next = position(&parent);
    while let Some(member) = next.filter(|m| !cycle.contains(m)) {
        cycle.push(member);
        next = position(&pending[member].parent.to_string());
    }
    if next == Some(index) && cycle.iter().all(|&member| member >= index) {
        let names: Vec<&str> = cycle
            .iter()
            .chain([&index])
            .map(|&member| pending[member].declared.name.as_str())
            .collect();
        cx.diagnostics.error(
            frame.parent.span(),
            format!(
                "the frames form a cycle ({}): each frame is turned from a parent on a \
                 chain that must start at `ground`",
                names.join(" <- ")
            ),
        );
    }
}

/// The frame's orientation: its parent's turned by its angle.
fn rotated_frame(
    cx: &mut Context,
    frame: &FrameDeclaration,
    space: &Space,
    reference: &Reference,
    q: &[SymbolId],
) -> Option<space::FrameState> {
    let parent = space.frame(&frame.parent.to_string())?;
    turned(cx, parent, frame.axis, frame.angle, space, reference, q)
}

/// `parent` turned by `angle`, which depends on the configuration only,
/// about its axis `axis` (0, 1, 2 for x, y, z); its angular velocity from
/// the rates of `q` (none with `q` empty).
pub(in crate::model::check) fn turned(
    cx: &mut Context,
    parent: &space::FrameState,
    axis: usize,
    angle: &Expr,
    space: &Space,
    reference: &Reference,
    q: &[SymbolId],
) -> Option<space::FrameState> {
    let value = evaluator(cx, space, reference).scalar(angle)?;
    if !check_configuration_only(cx, &[value], angle, "a frame's angle") {
        return None;
    }
    match space::rotated(&mut cx.sym, parent, axis, value, q) {
        Ok(state) => Some(state),
        Err(error) => {
            cx.diagnostics.error(angle.first_span(), error.to_string());
            None
        }
    }
}

/// The points, each `origin` or a point plus or minus vectors.
pub(super) fn points(
    cx: &mut Context,
    section: Option<&syntax::Section>,
    space: &mut Space,
    reference: &Reference,
) -> Vec<Declared> {
    let Some(list) = section.and_then(|s| cx.list(s)) else {
        return Vec::new();
    };
    let mut declared_points = Vec::new();
    for item in &list.items {
        let Some((declared, value)) = named_item(cx, item, "a point") else {
            continue;
        };
        let Some(expr) = item_expression(cx, value) else {
            continue;
        };
        let position = evaluator(cx, space, reference).point(expr);
        if !check_fresh_name(cx, &declared.name, declared.span, "point") {
            continue;
        }
        match position {
            Some(position) if check_configuration_only(cx, &position, expr, "a point") => {
                space.add_point(&declared.name, position);
                declared_points.push(declared);
            }
            _ => space.mark_broken(&declared.name),
        }
    }
    declared_points
}
