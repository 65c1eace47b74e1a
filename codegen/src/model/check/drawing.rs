//! The `drawing:` section (docs/INTERFACE.md section 10): named shapes,
//! each `box(...)`, `sphere(...)` or `disc(...)` with keyword arguments, or
//! `segment(A, B)` or `trace(P)`, names unique in the section.
//!
//! A position is a list `[x, y, z]` of scalars in ground axes or a point
//! (`center`, `origin + x*ground.x`), a direction a list or a vector
//! (`heading.y`); both depend on the configuration only. An orientation is
//! `frame = F` (a declared frame, `ground`, or `rotate(F, x|y|z, angle)`
//! turned from one, nested as deeply as wanted), `heading = angle` (turned
//! from `ground` about z), or for a disc `axle = v`; without one a shape
//! has ground's axes. A size (`size`, `radius`, `thickness`) depends on the
//! parameters only and is positive at their defaults.
//!
//! The section is checked after every other, so that the symbolic context
//! of the rest of the model, and so the Rust emitted for it, is the same
//! with or without it.

use super::context::Context;
use super::items::{check_no_keywords, check_unique_in_section, item_expression, named_item};
use super::mechanisms::frames::{check_axis, check_frame_name, turned};
use super::mechanisms::values::{check_configuration_only, evaluator};
use crate::model::Declared;
use crate::model::drawing::{DISC_THICKNESS, DrawnItem, Figure, Orientation};
use crate::model::mechanism::evaluate::Reference;
use crate::model::mechanism::space::{FrameState, GROUND, Space};
use crate::sym::{ExprId, Rational, SymbolKind};
use crate::syntax::{self, Expr, Item, Keyword, Value};
use proc_macro2::{Ident, Span};

/// What a drawing item may be, as errors say it.
const SHAPES: &str = "a drawing item is `box(center = P, size = [a, b, c], ...)`, \
                      `sphere(center = P, radius = r, ...)`, `disc(center = P, radius = r, ...)`, \
                      `segment(A, B)` or `trace(P)`";

/// The keywords that orient a shape; at most one is given.
const ORIENTATIONS: [&str; 3] = ["frame", "heading", "axle"];

/// Where the section's expressions are evaluated: the mechanism's frames
/// and points (`ground` and `origin` alone for a model declared by its
/// energy), the parameters at their defaults.
pub(super) struct Place<'a> {
    pub(super) space: &'a Space,
    pub(super) reference: &'a Reference,
}

/// The drawing section's items, in order, or `None` after reporting.
pub(super) fn drawing(
    cx: &mut Context,
    section: &syntax::Section,
    place: &Place,
) -> Option<Vec<DrawnItem<ExprId>>> {
    let list = cx.list(section)?;
    let errors_before = cx.diagnostics.len();
    let mut names: Vec<Declared> = Vec::new();
    let mut items = Vec::new();
    for item in &list.items {
        let Some((declared, value)) = named_item(cx, item, "a drawing item") else {
            continue;
        };
        let unique = check_unique_in_section(cx, &names, &declared.name, declared.span);
        let figure = figure(cx, value, place);
        if let (true, Some(figure)) = (unique, figure) {
            items.push(DrawnItem {
                name: declared.name.clone(),
                figure,
            });
        }
        names.push(declared);
    }
    (cx.diagnostics.len() == errors_before).then_some(items)
}

/// One item's shape, its arguments each checked.
fn figure(cx: &mut Context, value: &Value, place: &Place) -> Option<Figure<ExprId>> {
    let Value::Expr(Expr::Call {
        function,
        arguments,
        keywords,
        ..
    }) = value
    else {
        cx.diagnostics.error(value.span(), SHAPES);
        return None;
    };
    for nested in arguments.iter().chain(keywords.iter().map(|k| &k.value)) {
        check_no_keywords(cx, nested);
    }
    let call = Call {
        function,
        arguments,
        keywords,
    };
    match function.to_string().as_str() {
        "box" | "sphere" | "disc" => solid(cx, &call, place),
        "segment" => {
            let [from, to] = call.positional::<2>(cx, "its two ends, `segment(A, B)`")?;
            let from = position(cx, from, place, "an end of a segment");
            let to = position(cx, to, place, "an end of a segment");
            Some(Figure::Segment {
                from: from?,
                to: to?,
            })
        }
        "trace" => {
            let [point] = call.positional::<1>(cx, "the point it traces, `trace(P)`")?;
            let point = position(cx, point, place, "a traced point")?;
            Some(Figure::Trace { point })
        }
        other => {
            let message = format!("unknown shape `{other}`: {SHAPES}");
            cx.diagnostics.error(function.span(), message);
            None
        }
    }
}

/// A shape's call as written.
struct Call<'a> {
    function: &'a Ident,
    arguments: &'a [Value],
    keywords: &'a [Keyword],
}

impl<'a> Call<'a> {
    /// Exactly `N` positional arguments and no keyword argument.
    fn positional<const N: usize>(&self, cx: &mut Context, what: &str) -> Option<[&'a Value; N]> {
        if let Some(keyword) = self.keywords.first() {
            let message = format!(
                "`{}` takes {what}, not keyword arguments such as `{}`",
                self.function, keyword.name
            );
            cx.diagnostics.error(keyword.name.span(), message);
            return None;
        }
        let found: Option<[&Value; N]> = self.arguments.iter().collect::<Vec<_>>().try_into().ok();
        if found.is_none() {
            let message = format!(
                "`{}` takes {what}: {N} argument(s), found {}",
                self.function,
                self.arguments.len()
            );
            cx.diagnostics.error(self.function.span(), message);
        }
        found
    }

    /// The keyword arguments, each one of `allowed` and given once, after
    /// no positional argument; `None` after reporting.
    fn keywords(&self, cx: &mut Context, allowed: &[&str]) -> Option<Vec<&'a Keyword>> {
        let errors_before = cx.diagnostics.len();
        if let Some(argument) = self.arguments.first() {
            let message = format!(
                "`{}` takes keyword arguments only (`{} = ...`), found a positional argument",
                self.function, allowed[0]
            );
            cx.diagnostics.error(argument.span(), message);
        }
        let mut given: Vec<&Keyword> = Vec::new();
        for keyword in self.keywords {
            let name = keyword.name.to_string();
            if !allowed.contains(&name.as_str()) {
                let message = format!(
                    "unknown keyword argument `{name}` of `{}`: it takes {}",
                    self.function,
                    allowed.join(", ")
                );
                cx.diagnostics.error(keyword.name.span(), message);
            } else if given.iter().any(|k| k.name == name) {
                let message = format!("`{name}` is given twice");
                cx.diagnostics.error(keyword.name.span(), message);
            } else {
                given.push(keyword);
            }
        }
        (cx.diagnostics.len() == errors_before).then_some(given)
    }

    /// The value of the keyword `name`, or `None` after reporting that
    /// the shape needs it (`form` shows it).
    fn required(
        &self,
        cx: &mut Context,
        given: &[&'a Keyword],
        name: &str,
        form: &str,
    ) -> Option<&'a Value> {
        let value = keyword(given, name);
        if value.is_none() {
            let message = format!("`{}` needs `{name} = {form}`", self.function);
            cx.diagnostics.error(self.function.span(), message);
        }
        value
    }
}

/// The value of the keyword `name` among `given`.
fn keyword<'a>(given: &[&'a Keyword], name: &str) -> Option<&'a Value> {
    given.iter().find(|k| k.name == name).map(|k| &k.value)
}

/// `box`, `sphere` or `disc`: a centre, an orientation and sizes.
fn solid(cx: &mut Context, call: &Call, place: &Place) -> Option<Figure<ExprId>> {
    let kind = call.function.to_string();
    let (sizes, form): (&[&str], &str) = match kind.as_str() {
        "box" => (&["size"], "[a, b, c]"),
        "sphere" => (&["radius"], "r"),
        _ => (&["radius", "thickness"], "r"),
    };
    let mut allowed = vec!["center"];
    allowed.extend(sizes);
    allowed.extend(
        ORIENTATIONS
            .iter()
            .filter(|&&o| o != "axle" || kind == "disc"),
    );
    let given = call.keywords(cx, &allowed)?;
    let center = call.required(cx, &given, "center", "P");
    let first_size = call.required(cx, &given, sizes[0], form);
    let orientation = orientation(cx, &given, place);
    let center = position(cx, center?, place, "a centre");
    let (center, orientation, first_size) = (center?, orientation?, first_size?);
    Some(match kind.as_str() {
        "box" => Figure::Box {
            center,
            orientation,
            size: box_size(cx, first_size, place)?,
        },
        "sphere" => Figure::Sphere {
            center,
            orientation,
            radius: size(cx, first_size, place)?,
        },
        _ => {
            let radius = size(cx, first_size, place)?;
            let thickness = match keyword(&given, "thickness") {
                Some(value) => size(cx, value, place)?,
                None => {
                    let (numerator, denominator) = DISC_THICKNESS;
                    let fraction = Rational::new(numerator, denominator)?;
                    let fraction = cx.sym.number(fraction);
                    cx.sym.mul2(fraction, radius)
                }
            };
            Figure::Disc {
                center,
                orientation,
                radius,
                thickness,
            }
        }
    })
}

/// The one orientation keyword given (`frame`, `heading` or `axle`), or
/// ground's axes.
fn orientation(cx: &mut Context, given: &[&Keyword], place: &Place) -> Option<Orientation<ExprId>> {
    let orienting: Vec<&&Keyword> = (given.iter())
        .filter(|k| ORIENTATIONS.iter().any(|o| k.name == o))
        .collect();
    if let [first, second, ..] = orienting.as_slice() {
        let message = format!(
            "`{}` and `{}` both orient the shape: give one of `frame`, `heading` (or a disc's \
             `axle`)",
            first.name, second.name
        );
        cx.diagnostics.error(second.name.span(), message);
        return None;
    }
    let ground = place.space.frame(GROUND)?;
    let Some(keyword) = orienting.first() else {
        return Some(Orientation::Axes(ground.rotation));
    };
    match keyword.name.to_string().as_str() {
        "frame" => frame(cx, &keyword.value, place).map(|f| Orientation::Axes(f.rotation)),
        "heading" => {
            let angle = item_expression(cx, &keyword.value)?;
            turned(cx, ground, 2, angle, place.space, place.reference, &[])
                .map(|f| Orientation::Axes(f.rotation))
        }
        _ => axle(cx, &keyword.value, place).map(Orientation::Axle),
    }
}

/// `F` (a declared frame or `ground`) or `rotate(F, x|y|z, angle)`.
fn frame(cx: &mut Context, value: &Value, place: &Place) -> Option<FrameState> {
    if let Value::Expr(Expr::Call {
        function,
        arguments,
        ..
    }) = value
        && function == "rotate"
        && let [parent, axis, angle] = arguments.as_slice()
    {
        let parent = frame(cx, parent, place);
        let axis = check_axis(cx, axis);
        let angle = item_expression(cx, angle);
        let (parent, axis, angle) = (parent?, axis?, angle?);
        return turned(cx, &parent, axis, angle, place.space, place.reference, &[]);
    }
    if let Value::Expr(Expr::Call { .. }) = value {
        let message = "a frame is a frame's name or `rotate(frame, x|y|z, angle)`";
        cx.diagnostics.error(value.span(), message);
        return None;
    }
    let name = check_frame_name(cx, value)?;
    let found = place.space.frame(&name.to_string()).cloned();
    if found.is_none() && !place.space.is_broken(&name.to_string()) {
        let message = format!(
            "unknown frame `{name}`: a shape is oriented by `ground`, a frame declared in \
             `frames`, or `rotate(frame, x|y|z, angle)`"
        );
        cx.diagnostics.error(name.span(), message);
    }
    found
}

/// A position: `[x, y, z]` in ground axes or a point, of the configuration.
fn position(cx: &mut Context, value: &Value, place: &Place, what: &str) -> Option<[ExprId; 3]> {
    let (values, expr) = match value {
        Value::List(_) => (triple(cx, value, place, what)?, None),
        Value::Expr(expr) => (
            evaluator(cx, place.space, place.reference).point(expr)?,
            Some(expr),
        ),
    };
    configuration_only(cx, &values, value, expr, what).then_some(values)
}

/// A disc's axle: `[a, b, c]` in ground axes or a vector, of the
/// configuration, not zero.
fn axle(cx: &mut Context, value: &Value, place: &Place) -> Option<[ExprId; 3]> {
    let what = "an axle";
    let (values, expr) = match value {
        Value::List(_) => (triple(cx, value, place, what)?, None),
        Value::Expr(expr) => (
            evaluator(cx, place.space, place.reference).vector(expr)?,
            Some(expr),
        ),
    };
    if !configuration_only(cx, &values, value, expr, what) {
        return None;
    }
    let zero = (values.iter()).all(|&id| cx.sym.normal(id).is_ok_and(|form| form.is_zero()));
    if zero {
        cx.diagnostics.error(
            value.span(),
            "an axle is a nonzero vector: this one is zero",
        );
        return None;
    }
    Some(values)
}

/// No velocities in `values`, the value of `value` (an expression `expr`,
/// or a list whose entries were checked).
fn configuration_only(
    cx: &mut Context,
    values: &[ExprId],
    value: &Value,
    expr: Option<&Expr>,
    what: &str,
) -> bool {
    match expr {
        Some(expr) => check_configuration_only(cx, values, expr, what),
        None => value.as_list().is_some_and(|list| {
            (list.items.iter().zip(values)).all(|(entry, &id)| match entry.value().as_expr() {
                Some(expr) => check_configuration_only(cx, &[id], expr, what),
                None => true,
            })
        }),
    }
}

/// `[a, b, c]`: three scalar expressions.
fn triple(cx: &mut Context, value: &Value, place: &Place, what: &str) -> Option<[ExprId; 3]> {
    let list = value.as_list()?;
    if list.items.len() != 3 {
        let message = format!(
            "{what} is a list of 3 entries `[x, y, z]` in ground axes, found {}",
            list.items.len()
        );
        cx.diagnostics.error(list.span, message);
        return None;
    }
    let entries: Vec<Option<ExprId>> = (list.items.iter())
        .map(|entry| scalar_entry(cx, entry, place))
        .collect();
    let entries: Vec<ExprId> = entries.into_iter().collect::<Option<_>>()?;
    entries.try_into().ok()
}

/// An entry of a list: a scalar expression.
fn scalar_entry(cx: &mut Context, entry: &Item, place: &Place) -> Option<ExprId> {
    let expr = match entry {
        Item::Plain(value) => item_expression(cx, value)?,
        Item::Named { name, .. } => {
            let message = "an entry of a position or direction is an expression, not `name = ...`";
            cx.diagnostics.error(name.span(), message);
            return None;
        }
    };
    evaluator(cx, place.space, place.reference).scalar(expr)
}

/// A box's `size = [a, b, c]`.
fn box_size(cx: &mut Context, value: &Value, place: &Place) -> Option<[ExprId; 3]> {
    let Some(list) = value.as_list().filter(|list| list.items.len() == 3) else {
        let message = "a box's size is a list of 3 edge lengths `[a, b, c]` along its local \
                       x, y and z axes";
        let found = value.as_list().map(|list| list.items.len());
        let message = match found {
            Some(found) => format!("{message}, found {found}"),
            None => message.to_string(),
        };
        cx.diagnostics.error(value.span(), message);
        return None;
    };
    let sizes: Vec<Option<ExprId>> = (list.items.iter())
        .map(|entry| match entry {
            Item::Plain(value) => size(cx, value, place),
            Item::Named { name, .. } => {
                let message = "an edge length is an expression, not `name = ...`";
                cx.diagnostics.error(name.span(), message);
                None
            }
        })
        .collect();
    let sizes: Vec<ExprId> = sizes.into_iter().collect::<Option<_>>()?;
    sizes.try_into().ok()
}

/// A size: a scalar of the parameters, positive at their defaults.
fn size(cx: &mut Context, value: &Value, place: &Place) -> Option<ExprId> {
    let expr = item_expression(cx, value)?;
    let id = evaluator(cx, place.space, place.reference).scalar(expr)?;
    let varies = (cx.sym.free_symbols(id).iter())
        .any(|&s| !matches!(cx.sym.symbol_info(s).kind, SymbolKind::Parameter));
    let span: Span = expr.first_span();
    if varies {
        let message = "a size depends on the parameters only: the page draws rigid shapes \
                       (no coordinates, no velocities)";
        cx.diagnostics.error(span, message);
        return None;
    }
    let at_defaults = cx.sym.evaluate(id, &|symbol| place.reference.value(symbol));
    if !(at_defaults > 0.0 && at_defaults.is_finite()) {
        let at = match cx.sym.free_symbols(id).is_empty() {
            true => "",
            false => " at the default parameters",
        };
        let message = format!("a size is positive: this one is {at_defaults}{at}");
        cx.diagnostics.error(span, message);
        return None;
    }
    Some(id)
}

#[cfg(test)]
mod tests;
