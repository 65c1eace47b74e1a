//! Frames turned from `ground` without cycles, each by an angle about `x`,
//! `y` or `z` or by four Euler parameters that are distinct coordinates of
//! no other frame; and points, each `origin` or a point plus or minus
//! vectors.

use super::super::context::Context;
use super::super::items::{item_expression, named_item};
use super::super::names::check_fresh_name;
use super::values::{check_configuration_only, evaluator};
use crate::model::Declared;
use crate::model::lower::Binding;
use crate::model::mechanism::evaluate::{Reference, axis_index};
use crate::model::mechanism::space::{self, Space};
use crate::model::mechanism::{FrameTurn, TurnedBy};
use crate::sym::{ExprId, SymbolId};
use crate::syntax::{self, Expr, Item, Value};
use proc_macro2::Ident;

/// A frame's declaration: `name = rotate(parent, axis, angle)` or
/// `name = orient(parent, e0, e1, e2, e3)`.
struct FrameDeclaration<'a> {
    declared: Declared,
    parent: &'a Ident,
    turn: Turn<'a>,
}

/// What turns a frame from its parent.
enum Turn<'a> {
    /// An angle about the parent's axis (0, 1, 2 for x, y, z).
    Rotate { axis: usize, angle: &'a Expr },
    /// The Euler parameters `e0, e1, e2, e3`, coordinates.
    Orient([SymbolId; 4]),
}

/// The frames, resolved from `ground` in dependency order, each with how
/// it is turned.
pub(super) fn frames(
    cx: &mut Context,
    section: Option<&syntax::Section>,
    space: &mut Space,
    reference: &Reference,
    q: &[SymbolId],
) -> Vec<(Declared, FrameTurn)> {
    let Some(list) = section.and_then(|s| cx.list(s)) else {
        return Vec::new();
    };
    let mut pending: Vec<FrameDeclaration> = list
        .items
        .iter()
        .filter_map(|item| frame_declaration(cx, item))
        .collect();
    check_parameters_unshared(cx, &pending);
    let mut resolved = Vec::new();
    while let Some(ready) = pending
        .iter()
        .position(|f| space.frame(&f.parent.to_string()).is_some())
    {
        let frame = pending.remove(ready);
        if let Some((state, by)) = turned_frame(cx, &frame, space, reference, q) {
            space.add_frame(&frame.declared.name, state);
            let parent = frame.parent.to_string();
            resolved.push((frame.declared, FrameTurn { parent, by }));
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

/// `name = rotate(parent, x|y|z, angle)` or `name = orient(parent, e0, e1,
/// e2, e3)` with a fresh name.
fn frame_declaration<'a>(cx: &mut Context, item: &'a Item) -> Option<FrameDeclaration<'a>> {
    let (declared, value) = named_item(cx, item, "a frame")?;
    let call = match value {
        Value::Expr(Expr::Call {
            function,
            arguments,
            ..
        }) => Some((function.to_string(), arguments.as_slice())),
        _ => None,
    };
    let (parent, turn) = match call {
        Some((function, [parent, axis, angle])) if function == "rotate" => {
            (parent, rotation(cx, axis, angle))
        }
        Some((function, [parent, e @ ..])) if function == "orient" && e.len() == 4 => {
            (parent, euler_parameters(cx, e))
        }
        _ => {
            cx.diagnostics.error(
                value.span(),
                "a frame is `name = rotate(parent, x|y|z, angle)` or \
                 `name = orient(parent, e0, e1, e2, e3)`",
            );
            return None;
        }
    };
    let fresh = check_fresh_name(cx, &declared.name, declared.span, "frame");
    let parent = check_frame_name(cx, parent);
    Some(FrameDeclaration {
        declared,
        parent: parent?,
        turn: turn.filter(|_| fresh)?,
    })
}

/// `x|y|z, angle` of a `rotate` frame.
fn rotation<'a>(cx: &mut Context, axis: &Value, angle: &'a Value) -> Option<Turn<'a>> {
    let axis = check_axis(cx, axis)?;
    let angle = angle.as_expr()?;
    Some(Turn::Rotate { axis, angle })
}

/// The four Euler parameters of an `orient` frame: distinct coordinates.
fn euler_parameters(cx: &mut Context, values: &[Value]) -> Option<Turn<'static>> {
    let symbols: Vec<Option<SymbolId>> = values.iter().map(|v| coordinate(cx, v)).collect();
    let symbols: Vec<SymbolId> = symbols.into_iter().collect::<Option<_>>()?;
    for (index, value) in values.iter().enumerate() {
        if symbols[..index].contains(&symbols[index]) {
            cx.diagnostics.error(
                value.span(),
                "the four Euler parameters of a frame are four different coordinates",
            );
            return None;
        }
    }
    Some(Turn::Orient([
        symbols[0], symbols[1], symbols[2], symbols[3],
    ]))
}

/// A declared coordinate, named.
fn coordinate(cx: &mut Context, value: &Value) -> Option<SymbolId> {
    let binding = match value {
        Value::Expr(Expr::Name(ident)) => cx.scope.get(&ident.to_string()),
        _ => None,
    };
    match binding {
        Some(Binding::Coordinate(symbol)) => Some(symbol),
        _ => {
            cx.diagnostics.error(
                value.span(),
                "an Euler parameter is a coordinate declared in `coordinates`, e.g. `e0`",
            );
            None
        }
    }
}

/// No coordinate is an Euler parameter of two frames (reported at the
/// second frame's name).
fn check_parameters_unshared(cx: &mut Context, declarations: &[FrameDeclaration]) {
    let mut taken: Vec<(SymbolId, &str)> = Vec::new();
    for declaration in declarations {
        let Turn::Orient(e) = declaration.turn else {
            continue;
        };
        let shared = e.iter().find_map(|s| taken.iter().find(|(t, _)| t == s));
        if let Some(&(symbol, frame)) = shared {
            let name = cx.sym.symbol_info(symbol).name.clone();
            cx.diagnostics.error(
                declaration.declared.span,
                format!(
                    "`{name}` is already an Euler parameter of frame `{frame}`: each \
                     `orient` frame has four coordinates of its own"
                ),
            );
        }
        taken.extend(e.iter().map(|&s| (s, declaration.declared.name.as_str())));
    }
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

/// The frame's orientation, its parent's turned, and what turns it.
fn turned_frame(
    cx: &mut Context,
    frame: &FrameDeclaration,
    space: &Space,
    reference: &Reference,
    q: &[SymbolId],
) -> Option<(space::FrameState, TurnedBy)> {
    let parent = space.frame(&frame.parent.to_string())?;
    let index = |symbol: SymbolId| q.iter().position(|&c| c == symbol);
    match frame.turn {
        Turn::Rotate { axis, angle } => {
            let value = angle_value(cx, angle, space, reference)?;
            let state = rotated(cx, parent, axis, (angle, value), q)?;
            let reads = cx.sym.free_symbols(value).into_iter().filter_map(index);
            Some((state, TurnedBy::Angle(reads.collect())))
        }
        Turn::Orient(e) => {
            let state = space::oriented(&mut cx.sym, parent, e);
            let indices = e.map(|symbol| index(symbol).unwrap_or_default());
            Some((state, TurnedBy::EulerParameters(indices)))
        }
    }
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
    let value = angle_value(cx, angle, space, reference)?;
    rotated(cx, parent, axis, (angle, value), q)
}

/// A frame's angle, which depends on the configuration only.
fn angle_value(
    cx: &mut Context,
    angle: &Expr,
    space: &Space,
    reference: &Reference,
) -> Option<ExprId> {
    let value = evaluator(cx, space, reference).scalar(angle)?;
    check_configuration_only(cx, &[value], angle, "a frame's angle").then_some(value)
}

/// `parent` turned about `axis` by the angle written `angle` of value
/// `value`.
fn rotated(
    cx: &mut Context,
    parent: &space::FrameState,
    axis: usize,
    (angle, value): (&Expr, ExprId),
    q: &[SymbolId],
) -> Option<space::FrameState> {
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
