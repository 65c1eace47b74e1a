//! Names: coordinates, parameters and definitions, each declared once and
//! bound for the expressions of later sections.

use super::context::Context;
use super::items::{item_expression, named_item};
use crate::model::lower::Binding;
use crate::model::{Declared, Parameter, Variable};
use crate::sym::expr::arity;
use crate::sym::{Rational, SymbolKind};
use crate::syntax::{self, Expr, Item, Value};
use proc_macro2::Span;

/// Keywords that cannot name a parameter (parameters become struct fields).
const KEYWORDS: [&str; 51] = [
    "as", "async", "await", "break", "const", "continue", "crate", "dyn", "else", "enum", "extern",
    "false", "fn", "for", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub",
    "ref", "return", "self", "Self", "static", "struct", "super", "trait", "true", "type",
    "unsafe", "use", "where", "while", "abstract", "become", "box", "do", "final", "gen", "macro",
    "override", "priv", "typeof", "unsized", "virtual", "yield",
];

/// A name is declared once, among coordinates, parameters, definitions,
/// frames and points, and is not a function name.
pub(super) fn check_fresh_name(
    cx: &mut Context,
    name: &str,
    span: Span,
    kind: &'static str,
) -> bool {
    if arity(name).is_some() || name == "dot" {
        cx.diagnostics.error(
            span,
            format!("`{name}` is a function of the model language and cannot name a {kind}"),
        );
        return false;
    }
    if let Some(&(first, _)) = cx.declared.get(name) {
        let message = if kind == "parameter" && first == "coordinate" {
            format!("`{name}` is a coordinate and cannot also be used as a parameter")
        } else if first == kind {
            format!("`{name}` is declared twice as a {kind}")
        } else {
            format!("`{name}` is declared twice: first as a {first}, again as a {kind}")
        };
        cx.diagnostics.error(span, message);
        return false;
    }
    cx.declared.insert(name.to_string(), (kind, span));
    true
}

/// The coordinates, at least one, each a bare name.
pub(super) fn coordinates(cx: &mut Context, section: Option<&syntax::Section>) -> Vec<Variable> {
    let Some(list) = section.and_then(|s| cx.list(s)) else {
        return Vec::new();
    };
    if list.items.is_empty() {
        cx.diagnostics
            .error(list.span, "a model needs at least one coordinate");
    }
    let mut coordinates = Vec::new();
    for item in &list.items {
        let Item::Plain(Value::Expr(Expr::Name(ident))) = item else {
            cx.diagnostics.error(
                item.span(),
                "a coordinate is declared by its name alone, e.g. `theta`",
            );
            continue;
        };
        let name = ident.to_string();
        if !check_fresh_name(cx, &name, ident.span(), "coordinate") {
            continue;
        }
        // The nodes of the symbols are made in declaration order, so that
        // printed products list their factors in that order however the
        // derivations proceed.
        let symbol = cx.sym.declare(&name, SymbolKind::Coordinate);
        let velocity = cx.sym.velocity_of(symbol);
        cx.sym.symbol(symbol);
        cx.sym.symbol(velocity);
        cx.scope.bind(&name, Binding::Coordinate(symbol));
        coordinates.push(Variable {
            declared: Declared {
                name,
                span: ident.span(),
            },
            symbol,
        });
    }
    coordinates
}

/// The parameters, each `name = default` with a fresh name that can be a
/// struct field.
pub(super) fn parameters(cx: &mut Context, section: Option<&syntax::Section>) -> Vec<Parameter> {
    let Some(list) = section.and_then(|s| cx.list(s)) else {
        return Vec::new();
    };
    let mut parameters = Vec::new();
    for item in &list.items {
        let Some((declared, value)) = named_item(cx, item, "a parameter and its default") else {
            continue;
        };
        let default = check_numeric_default(cx, value);
        let field_ok = check_field_name(cx, &declared);
        if !check_fresh_name(cx, &declared.name, declared.span, "parameter") || !field_ok {
            continue;
        }
        // Declared even when its default is wrong, so its uses are not reported too.
        let symbol = cx.sym.declare(&declared.name, SymbolKind::Parameter);
        cx.sym.symbol(symbol);
        cx.scope.bind(&declared.name, Binding::Parameter(symbol));
        let Some(default) = default else { continue };
        parameters.push(Parameter {
            variable: Variable { declared, symbol },
            default,
        });
    }
    parameters
}

/// A parameter's default is a number literal, possibly negated.
fn check_numeric_default(cx: &mut Context, value: &Value) -> Option<Rational> {
    let parsed = match value {
        Value::Expr(Expr::Number { literal, .. }) => Rational::from_decimal(literal),
        Value::Expr(Expr::Negate { operand, .. }) => match operand.as_ref() {
            Expr::Number { literal, .. } => Rational::from_decimal(literal).map(|r| r.neg()),
            _ => None,
        },
        _ => None,
    };
    if parsed.is_none() {
        let coordinate = match value {
            Value::Expr(Expr::Name(name)) => cx
                .declared
                .get(&name.to_string())
                .is_some_and(|(kind, _)| *kind == "coordinate"),
            _ => false,
        };
        let message = if coordinate {
            "a parameter's default must be a number, and this is a coordinate (parameters are \
             constants), e.g. `m = 1.0` or `g = -9.81`"
        } else {
            "a parameter's default must be a number, e.g. `m = 1.0` or `g = -9.81`"
        };
        cx.diagnostics.error(value.span(), message);
    }
    parsed
}

/// A parameter name can be a struct field (not a Rust keyword).
fn check_field_name(cx: &mut Context, declared: &Declared) -> bool {
    let ok = !KEYWORDS.contains(&declared.name.as_str());
    if !ok {
        cx.diagnostics.error(
            declared.span,
            format!(
                "`{}` is a Rust keyword and cannot name a parameter (parameters become \
                 struct fields)",
                declared.name
            ),
        );
    }
    ok
}

/// The definitions, each `name = expression` over the names before it.
pub(super) fn definitions(cx: &mut Context, section: Option<&syntax::Section>) {
    let Some(list) = section.and_then(|s| cx.list(s)) else {
        return;
    };
    for item in &list.items {
        let Some((declared, value)) = named_item(cx, item, "a definition") else {
            continue;
        };
        let Some(expr) = item_expression(cx, value) else {
            continue;
        };
        let lowered = cx.lower(expr);
        if !check_fresh_name(cx, &declared.name, declared.span, "definition") {
            continue;
        }
        // A definition that failed is still declared, so its uses are not reported too.
        let id = lowered.unwrap_or_else(|| {
            let placeholder = cx.sym.declare(&declared.name, SymbolKind::Auxiliary);
            cx.sym.symbol(placeholder)
        });
        cx.scope.bind(&declared.name, Binding::Definition(id));
    }
}
