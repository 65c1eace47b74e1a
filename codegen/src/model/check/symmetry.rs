//! The symmetry group: its factors, and the invariance of the Lagrangian and
//! the constraints.

use super::context::Context;
use crate::model::invariance::{Invariants, first_broken};
use crate::model::{GroupFactor, Symmetry, Variable};
use crate::syntax::{self, BinaryOperator, Expr, Value};
use proc_macro2::Ident;

/// The Lagrangian and the constraints are invariant under the declared
/// group. Where they are not, but are under an `se2` factor with its
/// coordinates in another order, the error names that order.
pub(super) fn check_invariant(cx: &mut Context, symmetry: &Symmetry, model: &Invariants) {
    match first_broken(&mut cx.sym, symmetry, model) {
        Ok(None) => {}
        Ok(Some(broken)) => {
            let reordered = reordered_se2(cx, symmetry, model).map_or_else(String::new, |se2| {
                format!("; it is invariant under {se2}: se2 takes the position, then the heading")
            });
            cx.diagnostics.error(
                symmetry.span,
                format!(
                    "{} not invariant under the declared symmetry group: the momentum \
                     equation needs the Lagrangian and the constraints to be invariant{reordered}",
                    broken.describe()
                ),
            );
        }
        Err(error) => cx.diagnostics.error(symmetry.span, error.to_string()),
    }
}

/// The first `se2(a, b, c)` of an `se2` factor's coordinates in another
/// order under which, the other factors as declared, the model is
/// invariant: the heading written first, say.
fn reordered_se2(cx: &mut Context, symmetry: &Symmetry, model: &Invariants) -> Option<String> {
    for (k, factor) in symmetry.factors.iter().enumerate() {
        let GroupFactor::Se2 { x, y, theta } = *factor else {
            continue;
        };
        let orders = [
            [x, theta, y],
            [y, x, theta],
            [y, theta, x],
            [theta, x, y],
            [theta, y, x],
        ];
        for [a, b, c] in orders {
            let mut reordered = symmetry.clone();
            reordered.factors[k] = GroupFactor::Se2 {
                x: a,
                y: b,
                theta: c,
            };
            if let Ok(None) = first_broken(&mut cx.sym, &reordered, model) {
                let name = |i: usize| model.coordinates[i].declared.name.to_string();
                return Some(format!("se2({}, {}, {})", name(a), name(b), name(c)));
            }
        }
    }
    None
}

/// A symmetry is a product of `se2(x, y, theta)`, `translation(q)` and
/// `rotation(q)` of distinct coordinates.
pub(super) fn symmetry(
    cx: &mut Context,
    section: Option<&syntax::Section>,
    coordinates: &[Variable],
) -> Option<Symmetry> {
    let section = section?;
    let expr = cx.expression(section)?;
    let mut calls = Vec::new();
    product_factors(expr, &mut calls);
    let mut factors = Vec::new();
    let mut used: Vec<usize> = Vec::new();
    for factor in calls {
        let Expr::Call {
            function,
            arguments,
            ..
        } = factor
        else {
            cx.diagnostics.error(
                factor.first_span(),
                "a symmetry is a product of se2(x, y, theta), translation(q) and rotation(q)",
            );
            return None;
        };
        let indices = group_coordinates(cx, function, arguments, coordinates, &mut used)?;
        factors.push(match (function.to_string().as_str(), indices.as_slice()) {
            ("se2", &[x, y, theta]) => GroupFactor::Se2 { x, y, theta },
            ("translation", &[q]) => GroupFactor::Translation(q),
            ("rotation", &[q]) => GroupFactor::Rotation(q),
            _ => return None,
        });
    }
    Some(Symmetry {
        factors,
        span: expr.first_span(),
    })
}

/// The coordinates a group factor acts on: known group, right arity,
/// declared and not used by another factor.
fn group_coordinates(
    cx: &mut Context,
    function: &Ident,
    arguments: &[Value],
    coordinates: &[Variable],
    used: &mut Vec<usize>,
) -> Option<Vec<usize>> {
    let arity = match function.to_string().as_str() {
        "se2" => 3,
        "translation" | "rotation" => 1,
        other => {
            cx.diagnostics.error(
                function.span(),
                format!(
                    "unknown symmetry group `{other}`: the groups are se2(x, y, theta), \
                     translation(q) and rotation(q)"
                ),
            );
            return None;
        }
    };
    if arguments.len() != arity {
        cx.diagnostics.error(
            function.span(),
            format!(
                "`{function}` acts on {arity} coordinate(s), found {}",
                arguments.len()
            ),
        );
        return None;
    }
    let mut indices = Vec::with_capacity(arity);
    for argument in arguments {
        let found = match argument {
            Value::Expr(Expr::Name(ident)) => {
                coordinates.iter().position(|c| *ident == c.declared.name)
            }
            _ => None,
        };
        match found {
            Some(index) if !used.contains(&index) => {
                used.push(index);
                indices.push(index);
            }
            Some(_) => {
                cx.diagnostics.error(
                    argument.span(),
                    "a coordinate appears twice in the symmetry group",
                );
                return None;
            }
            None => {
                cx.diagnostics.error(
                    argument.span(),
                    "a symmetry acts on coordinates: this is not one of the model's coordinates",
                );
                return None;
            }
        }
    }
    Some(indices)
}

/// The factors of a product.
fn product_factors<'a>(expr: &'a Expr, factors: &mut Vec<&'a Expr>) {
    match expr {
        Expr::Binary {
            operator: BinaryOperator::Multiply,
            left,
            right,
            ..
        } => {
            product_factors(left, factors);
            product_factors(right, factors);
        }
        _ => factors.push(expr),
    }
}
