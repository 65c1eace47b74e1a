//! Where the model's own expressions are defined: the guards of its square
//! roots, logarithms, divisions, tangents and inverse functions.
//!
//! A model written by its energy or declared as a mechanism can leave its
//! domain: the benchmark bicycle's front contact,
//! `front_hub - rF unit(cross(fork.y, cross(fork.y, ground.z)))`, divides
//! by the square root of `|fork.y x (fork.y x z)|^2`, which vanishes where
//! the front wheel's plane lies flat. Each such operation of the
//! expressions the emitted code computes (the points, the holonomic
//! constraints, the constraint rows, the frames, the energies and the mass
//! matrix, in that order) gives one guard, named after the first of them
//! it appears in:
//!
//! | operation | guard | holds where |
//! |---|---|---|
//! | `b^(1/2)`, `b^(-1/2)`, another fractional power, `ln(b)` | `b` | `b > 0` |
//! | `b^(-k)` | `b` | `b != 0` (its sign kept) |
//! | `tan(a)` | `cos(a)` | `cos(a) != 0` (its sign kept) |
//! | `asin(u)`, `acos(u)` | `1 - u^2` | `1 - u^2 > 0`, where the slope is finite |
//! | `atan2(y, x)` | `x^2 + y^2` | `x^2 + y^2 != 0` |
//!
//! A run evaluates them where a step fails and names the one the step
//! crossed (`chaplygin_runtime::system::Domain`). The emitted domain adds,
//! after them, the factors of the sets where the coordinates are singular
//! ([`super::coordinate_sets`]).

use super::Model;
use crate::sym::Context;
use crate::sym::{ExprId, Function, Node, Rational, SymError};
use chaplygin_runtime::system::Guard;

/// One guarded expression.
#[derive(Clone, Debug, PartialEq)]
pub struct Guarded {
    /// What it guards, where, and what must hold.
    pub description: String,
    /// The expression whose value is checked.
    pub expression: ExprId,
    /// What must hold.
    pub guard: Guard,
}

/// The longest expression text a description prints.
const SHORT: usize = 72;

/// The guards of `model`'s expressions, in the order of the module
/// documentation, each once.
pub fn guards(model: &Model, cx: &mut Context) -> Result<Vec<Guarded>, SymError> {
    let mut guards: Vec<Guarded> = Vec::new();
    for (source, roots) in sources(model) {
        for id in cx.reachable(&roots) {
            let Some((operation, base, guard)) = guarded(cx, id)? else {
                continue;
            };
            if guards.iter().any(|g| g.expression == base) {
                continue;
            }
            let description = describe(cx, operation, &source, base, guard);
            guards.push(Guarded {
                description,
                expression: base,
                guard,
            });
        }
    }
    Ok(guards)
}

/// The operation at `id`, if it has a guard: its name, the guarded
/// expression and what must hold.
fn guarded(
    cx: &mut Context,
    id: ExprId,
) -> Result<Option<(&'static str, ExprId, Guard)>, SymError> {
    Ok(match cx.node(id).clone() {
        Node::Pow(base, exponent) if cx.as_number(base).is_none() => match exponent.to_small() {
            Some((n, 1)) if n < 0 => Some(("a division", base, Guard::NonZero)),
            Some((_, 1)) => None,
            Some((1, 2)) | Some((-1, 2)) => Some(("a square root", base, Guard::Positive)),
            _ => Some(("a fractional power", base, Guard::Positive)),
        },
        Node::Call(Function::Ln, argument) => Some(("a logarithm", argument, Guard::Positive)),
        Node::Call(Function::Tan, argument) => {
            let cosine = cx.apply(Function::Cos, argument)?;
            Some(("a tangent", cosine, Guard::NonZero))
        }
        Node::Call(Function::Asin | Function::Acos, argument) => {
            let one = cx.integer(1);
            let square = cx.pow_of_expression(argument, Rational::integer(2));
            let room = cx.sub(one, square);
            Some(("an inverse sine or cosine", room, Guard::Positive))
        }
        Node::Atan2(y, x) => {
            let x_square = cx.pow_of_expression(x, Rational::integer(2));
            let y_square = cx.pow_of_expression(y, Rational::integer(2));
            let radius_square = cx.add2(x_square, y_square);
            Some(("an atan2", radius_square, Guard::NonZero))
        }
        _ => None,
    })
}

/// The named expressions searched, in order.
fn sources(model: &Model) -> Vec<(String, Vec<ExprId>)> {
    let mechanism = &model.mechanism;
    let mut sources = Vec::new();
    for (i, point) in mechanism.points.iter().enumerate() {
        let row = mechanism.expressions.positions.row_entries(i);
        sources.push((format!("point `{}`", point.name), row));
    }
    for (i, constraint) in mechanism.holonomic.iter().enumerate() {
        let residual = *mechanism.expressions.holonomic_residual.get(i, 0);
        sources.push((
            format!("holonomic constraint `{}`", constraint.name),
            vec![residual],
        ));
    }
    for (i, constraint) in model.constraints.iter().enumerate() {
        let row = model.constraint_expressions.row_entries(i);
        sources.push((format!("constraint `{}`", constraint.name), row));
    }
    for (i, frame) in mechanism.frames.iter().enumerate() {
        let rotation = mechanism.expressions.orientations.row_entries(i);
        sources.push((format!("frame `{}`", frame.name), rotation));
    }
    let energies = &model.energy_expressions;
    sources.push(("the kinetic energy".to_string(), vec![energies.kinetic]));
    sources.push(("the potential energy".to_string(), vec![energies.potential]));
    sources.push((
        "the mass matrix".to_string(),
        energies.mass_matrix.entries().to_vec(),
    ));
    sources
}

/// `a square root in point `front_contact`: sqrt(...) needs ... > 0`.
fn describe(cx: &Context, operation: &str, source: &str, base: ExprId, guard: Guard) -> String {
    let mut text = cx.display(base).to_string();
    if text.len() > SHORT {
        let cut = (0..=SHORT)
            .rev()
            .find(|&i| text.is_char_boundary(i))
            .unwrap_or(0);
        text.truncate(cut);
        text.push_str("...");
    }
    let holds = match guard {
        Guard::Positive => "must stay positive",
        Guard::NonZero => "must not vanish",
    };
    format!("{operation} in {source}: {text} {holds}")
}

#[cfg(test)]
mod tests {
    use super::guards;
    use crate::model::check;
    use crate::syntax::parse_str;
    use chaplygin_runtime::system::Guard;

    /// A bead on a wire `y = ln(x)`, pushed by a spring of rest length
    /// `sqrt(x)`, with a damper-free constraint dividing by `1 + x^2` and a
    /// heading through `tan(theta)`: one guard of each kind, named after the
    /// first expression each appears in.
    const GUARDED: &str = "
        pub struct Guarded {
            coordinates: [x, y, theta],
            parameters: [m = 1.0, k = 2.0],
            kinetic_energy: m/2*(dot(x)^2 + dot(y)^2 + dot(theta)^2),
            potential_energy: k/2*(y - sqrt(x))^2 + ln(x),
            constraints: [
                wire = dot(y) - dot(x)/(1 + x^2) - tan(theta)*dot(theta),
            ],
        }
    ";

    #[test]
    fn each_square_root_logarithm_division_and_tangent_is_guarded() {
        let (model, mut cx) = check(&parse_str(GUARDED).expect("parses")).expect("checks");
        let guards = guards(&model, &mut cx).expect("guards");
        let found = |needle: &str, guard: Guard| {
            guards
                .iter()
                .filter(|g| g.description.contains(needle) && g.guard == guard)
                .count()
        };
        let listed: Vec<&str> = guards.iter().map(|g| g.description.as_str()).collect();
        assert_eq!(
            found(
                "in constraint `wire`: 1 + x^2 must not vanish",
                Guard::NonZero
            ),
            1,
            "{listed:?}"
        );
        assert_eq!(
            found(
                "in constraint `wire`: cos(theta) must not vanish",
                Guard::NonZero
            ),
            1,
            "{listed:?}"
        );
        // sqrt(x) and ln(x) guard the same expression, once
        assert_eq!(
            found(": x must stay positive", Guard::Positive),
            1,
            "{listed:?}"
        );
        assert_eq!(guards.len(), 3, "{listed:?}");
    }

    /// `asin(u)` and `acos(u)` need `1 - u^2 > 0`, `atan2(y, x)` a point
    /// off the origin; `atan` is defined everywhere.
    #[test]
    fn inverse_functions_are_guarded() {
        let source = "
            pub struct Inverse {
                coordinates: [x, y],
                parameters: [m = 1.0],
                kinetic_energy: m/2*(dot(x)^2 + dot(y)^2),
                potential_energy: asin(x/2) + acos(y) + atan2(y, x) + atan(x*y),
            }
        ";
        let (model, mut cx) = check(&parse_str(source).expect("parses")).expect("checks");
        let guards = guards(&model, &mut cx).expect("guards");
        let listed: Vec<(&str, Guard)> = guards
            .iter()
            .map(|g| (g.description.as_str(), g.guard))
            .collect();
        let expected = [
            ("1 - 1/4*x^2 must stay positive", Guard::Positive),
            ("1 - y^2 must stay positive", Guard::Positive),
            ("x^2 + y^2 must not vanish", Guard::NonZero),
        ];
        for (text, guard) in expected {
            let found = listed
                .iter()
                .filter(|(description, kind)| description.ends_with(text) && *kind == guard)
                .count();
            assert_eq!(found, 1, "{text}: {listed:?}");
        }
        assert_eq!(guards.len(), 3, "{listed:?}");
    }
}
