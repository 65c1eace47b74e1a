//! Mechanism expressions evaluated into scalars, vectors and points.
//!
//! The types follow the affine space: a point plus or minus a vector is a
//! point, a point minus a point is a vector, sums of vectors and scalar
//! multiples are vectors; `F.x` is a unit vector of frame `F`; `cross` and
//! `unit` make vectors, `inner` and `norm` scalars. Expressions free of all
//! of these are lowered as scalars by [`crate::model::lower`]. A value of
//! the wrong type is reported on its first token; a constant that an
//! operator or a vector function folds past the store's limit
//! ([`crate::sym::Store::within_constant_limit`]), on the operator or the
//! function, as in scalars.

use super::space::Space;
use super::vector::{self, Vector};
use crate::model::Parameter;
use crate::model::lower::Lowerer;
use crate::sym::expr::arity;
use crate::sym::{ExprId, Node, SymError, SymbolId};
use crate::syntax::{BinaryOperator, Expr, Value};
use proc_macro2::{Ident, Span};
use std::collections::HashMap;

/// The functions on vectors.
const VECTOR_FUNCTIONS: [&str; 4] = ["cross", "unit", "inner", "norm"];

/// A value of a mechanism expression.
#[derive(Clone, Copy, Debug)]
pub(in crate::model) enum Quantity {
    Scalar(ExprId),
    Vector(Vector),
    Point(Vector),
}

impl Quantity {
    fn kind(&self) -> &'static str {
        match self {
            Quantity::Scalar(_) => "a scalar",
            Quantity::Vector(_) => "a vector",
            Quantity::Point(_) => "a point",
        }
    }
}

/// Evaluates expressions against the frames and points declared so far.
pub(in crate::model) struct Evaluator<'a> {
    pub(in crate::model) lowerer: Lowerer<'a>,
    pub(in crate::model) space: &'a Space,
    /// The reference configuration, which fixes the sign of exact norms.
    pub(in crate::model) reference: &'a Reference,
}

/// The reference configuration: coordinates 0, parameters at their defaults.
pub(in crate::model) struct Reference(pub(in crate::model) HashMap<SymbolId, f64>);

impl Reference {
    /// The reference of a model whose parameters are `parameters`.
    pub(in crate::model) fn at_defaults(parameters: &[Parameter]) -> Reference {
        Reference(
            parameters
                .iter()
                .map(|p| (p.variable.symbol, p.default.to_f64()))
                .collect(),
        )
    }

    /// A symbol's value (0 for a coordinate).
    pub(in crate::model) fn value(&self, symbol: SymbolId) -> f64 {
        self.0.get(&symbol).copied().unwrap_or(0.0)
    }
}

impl Evaluator<'_> {
    /// A scalar, or `None` after reporting.
    pub(in crate::model) fn scalar(&mut self, expr: &Expr) -> Option<ExprId> {
        match self.evaluate(expr)? {
            Quantity::Scalar(value) => Some(value),
            other => self.mismatch(expr, other, "a scalar"),
        }
    }

    /// A vector, or `None` after reporting.
    pub(in crate::model) fn vector(&mut self, expr: &Expr) -> Option<Vector> {
        match self.evaluate(expr)? {
            Quantity::Vector(value) => Some(value),
            other => self.mismatch(expr, other, "a vector"),
        }
    }

    /// A point, or `None` after reporting.
    pub(in crate::model) fn point(&mut self, expr: &Expr) -> Option<Vector> {
        match self.evaluate(expr)? {
            Quantity::Point(value) => Some(value),
            other => self.mismatch(expr, other, "a point"),
        }
    }

    fn mismatch<T>(&mut self, expr: &Expr, found: Quantity, expected: &str) -> Option<T> {
        let message = format!("{} where {expected} belongs", found.kind());
        self.error(expr.first_span(), message)
    }

    fn error<T>(&mut self, span: Span, message: impl Into<String>) -> Option<T> {
        self.lowerer.diagnostics.error(span, message);
        None
    }

    /// `value`, or `None` after reporting at `span` a constant of it (of a
    /// scalar, or of a component of a vector or point) past the store's
    /// limit.
    fn within_constant_limit(&mut self, value: Quantity, span: Span) -> Option<Quantity> {
        let components = match &value {
            Quantity::Scalar(scalar) => std::slice::from_ref(scalar),
            Quantity::Vector(components) | Quantity::Point(components) => &components[..],
        };
        let cx = &*self.lowerer.cx;
        match (components.iter()).try_for_each(|&c| cx.within_constant_limit(c).map(drop)) {
            Ok(()) => Some(value),
            Err(error) => self.error(span, error.to_string()),
        }
    }

    /// The value of any mechanism expression.
    pub(in crate::model) fn evaluate(&mut self, expr: &Expr) -> Option<Quantity> {
        if let Some(unknown) = self.unknown_name(expr) {
            let message = format!(
                "unknown name `{unknown}`: expressions here may use the coordinates, the \
                 parameters, the definitions, `dot(q)`, the points declared before this one \
                 and the unit vectors `F.x`, `F.y`, `F.z` of the frames"
            );
            return self.error(unknown.span(), message);
        }
        if self.is_plain(expr) {
            return self.lowerer.lower(expr).map(Quantity::Scalar);
        }
        match expr {
            Expr::Name(ident) => self.name(ident),
            Expr::Field { base, field } => self.unit_vector(base, field).map(Quantity::Vector),
            // Keyword arguments are reported where the section is read.
            Expr::Call { keywords, .. } if !keywords.is_empty() => None,
            Expr::Call {
                function,
                arguments,
                ..
            } => self.call(function, arguments),
            Expr::Negate { operand, span } => self.negate(operand, *span),
            Expr::Binary {
                operator,
                left,
                right,
                span,
            } => self.binary(*operator, left, right, *span),
            Expr::Number { .. } => self.lowerer.lower(expr).map(Quantity::Scalar),
        }
    }

    /// True when no frame, point or vector function occurs: a scalar expression.
    fn is_plain(&self, expr: &Expr) -> bool {
        match expr {
            Expr::Number { .. } => true,
            Expr::Name(ident) => {
                let name = ident.to_string();
                self.space.point(&name).is_none()
                    && self.space.frame(&name).is_none()
                    && !self.space.is_broken(&name)
            }
            Expr::Field { .. } => false,
            Expr::Call {
                function,
                arguments,
                ..
            } => {
                !VECTOR_FUNCTIONS.contains(&function.to_string().as_str())
                    && arguments.iter().all(|argument| match argument {
                        Value::Expr(expr) => self.is_plain(expr),
                        Value::List(_) => true,
                    })
            }
            Expr::Negate { operand, .. } => self.is_plain(operand),
            Expr::Binary { left, right, .. } => self.is_plain(left) && self.is_plain(right),
        }
    }

    /// The first name that is neither a scalar's, a point's nor a frame's
    /// (called functions and the fields after `.` are not names).
    fn unknown_name<'e>(&self, expr: &'e Expr) -> Option<&'e Ident> {
        match expr {
            Expr::Number { .. } => None,
            Expr::Name(ident) => {
                let name = ident.to_string();
                let known = self.lowerer.scope.get(&name).is_some()
                    || self.space.is_broken(&name)
                    || self.space.point(&name).is_some()
                    || self.space.frame(&name).is_some();
                (!known).then_some(ident)
            }
            Expr::Field { .. } => None,
            Expr::Call {
                function,
                arguments,
                ..
            } if function != "dot" => arguments
                .iter()
                .filter_map(Value::as_expr)
                .find_map(|a| self.unknown_name(a)),
            Expr::Call { .. } => None,
            Expr::Negate { operand, .. } => self.unknown_name(operand),
            Expr::Binary { left, right, .. } => {
                self.unknown_name(left).or_else(|| self.unknown_name(right))
            }
        }
    }

    fn name(&mut self, ident: &Ident) -> Option<Quantity> {
        let name = ident.to_string();
        if let Some(position) = self.space.point(&name) {
            return Some(Quantity::Point(*position));
        }
        if self.space.is_broken(&name) {
            return None;
        }
        self.error(
            ident.span(),
            format!(
                "`{name}` is a frame, not a value: its unit vectors are `{name}.x`, `{name}.y` \
                 and `{name}.z`"
            ),
        )
    }

    /// `F.x`, `F.y`, `F.z`.
    fn unit_vector(&mut self, base: &Expr, field: &Ident) -> Option<Vector> {
        let frame = match base {
            Expr::Name(ident) if self.space.is_broken(&ident.to_string()) => return None,
            Expr::Name(ident) => self.space.frame(&ident.to_string()),
            _ => None,
        };
        let Some(frame) = frame else {
            return self.error(
                base.first_span(),
                "unknown frame: `.x`, `.y`, `.z` select the unit vectors of a frame declared in \
                 `frames` (or `ground`)",
            );
        };
        match axis_index(field) {
            Some(axis) => Some(frame.axis(axis)),
            None => self.error(
                field.span(),
                format!("a frame's unit vectors are `.x`, `.y` and `.z`, found `.{field}`"),
            ),
        }
    }

    fn call(&mut self, function: &Ident, arguments: &[Value]) -> Option<Quantity> {
        let name = function.to_string();
        let expressions: Vec<&Expr> = arguments.iter().filter_map(Value::as_expr).collect();
        if expressions.len() != arguments.len() {
            let list = arguments.iter().find(|a| a.as_list().is_some())?;
            return self.error(list.span(), "a list `[...]` where an expression belongs");
        }
        let expected = match name.as_str() {
            "cross" | "inner" => 2,
            _ => arity(&name).unwrap_or(1),
        };
        if expressions.len() != expected {
            let error = SymError::ArgumentCount {
                name,
                expected,
                found: expressions.len(),
            };
            return self.error(function.span(), error.to_string());
        }
        let value = match name.as_str() {
            "cross" | "inner" => {
                let a = self.vector(expressions[0]);
                let b = self.vector(expressions[1]);
                let (a, b) = (a?, b?);
                let cx = &mut *self.lowerer.cx;
                Some(if name == "cross" {
                    Quantity::Vector(vector::cross(cx, &a, &b))
                } else {
                    Quantity::Scalar(vector::inner(cx, &a, &b))
                })
            }
            "unit" | "norm" => {
                let a = self.vector(expressions[0])?;
                let cx = &mut *self.lowerer.cx;
                let reference = self.reference;
                let value_at = |symbol| reference.value(symbol);
                let value = if name == "unit" {
                    vector::unit(cx, &a, &value_at).map(Quantity::Vector)
                } else {
                    vector::norm(cx, &a, &value_at).map(Quantity::Scalar)
                };
                value
                    .map_err(|error| {
                        self.lowerer
                            .diagnostics
                            .error(function.span(), error.to_string())
                    })
                    .ok()
            }
            _ => {
                let arguments: Vec<Option<ExprId>> =
                    expressions.iter().map(|&e| self.scalar(e)).collect();
                let arguments: Vec<ExprId> = arguments.into_iter().collect::<Option<_>>()?;
                let applied = self.lowerer.cx.apply_named(&name, &arguments);
                applied
                    .map(Quantity::Scalar)
                    .map_err(|error| {
                        self.lowerer
                            .diagnostics
                            .error(function.span(), error.to_string())
                    })
                    .ok()
            }
        };
        self.within_constant_limit(value?, function.span())
    }

    fn negate(&mut self, operand: &Expr, span: Span) -> Option<Quantity> {
        match self.evaluate(operand)? {
            Quantity::Scalar(s) => Some(Quantity::Scalar(self.lowerer.cx.neg(s))),
            Quantity::Vector(v) => Some(Quantity::Vector(vector::neg(self.lowerer.cx, &v))),
            Quantity::Point(_) => self.error(
                span,
                "a point cannot be negated: `P - Q` of two points is a vector",
            ),
        }
    }

    fn binary(
        &mut self,
        operator: BinaryOperator,
        left: &Expr,
        right: &Expr,
        span: Span,
    ) -> Option<Quantity> {
        let left_value = self.evaluate(left);
        let right_value = self.evaluate(right);
        let (a, b) = (left_value?, right_value?);
        let cx = &mut *self.lowerer.cx;
        use BinaryOperator::{Add, Divide, Multiply, Power, Subtract};
        use Quantity::{Point, Scalar, Vector as Free};
        let value = match (operator, a, b) {
            (Add, Scalar(x), Scalar(y)) => Scalar(cx.add2(x, y)),
            (Subtract, Scalar(x), Scalar(y)) => Scalar(cx.sub(x, y)),
            (Multiply, Scalar(x), Scalar(y)) => Scalar(cx.mul2(x, y)),
            (Add, Free(u), Free(v)) => Free(vector::add(cx, &u, &v)),
            (Subtract, Free(u), Free(v)) => Free(vector::sub(cx, &u, &v)),
            (Add, Point(p), Free(v)) | (Add, Free(v), Point(p)) => Point(vector::add(cx, &p, &v)),
            (Subtract, Point(p), Free(v)) => Point(vector::sub(cx, &p, &v)),
            (Subtract, Point(p), Point(r)) => Free(vector::sub(cx, &p, &r)),
            (Multiply, Scalar(s), Free(v)) | (Multiply, Free(v), Scalar(s)) => {
                Free(vector::scale(cx, s, &v))
            }
            (Divide | Power, Scalar(x), Scalar(y)) => {
                return self.scalar_quotient_or_power(operator, x, y, right, span);
            }
            (Divide, Free(v), Scalar(s)) => {
                let reciprocal = cx.integer(1);
                match cx.div(reciprocal, s) {
                    Ok(r) => Free(vector::scale(cx, r, &v)),
                    Err(error) => return self.error(span, error.to_string()),
                }
            }
            (operator, a, b) => {
                return self.error(
                    span,
                    format!(
                        "`{operator}` is not defined between {} and {}: points and vectors add \
                         and subtract, scalars multiply vectors, `inner` and `cross` multiply \
                         two vectors",
                        a.kind(),
                        b.kind()
                    ),
                );
            }
        };
        self.within_constant_limit(value, span)
    }

    /// `a / b` and `a ^ n` of scalars that involve vectors (`norm(v)^2`).
    fn scalar_quotient_or_power(
        &mut self,
        operator: BinaryOperator,
        a: ExprId,
        b: ExprId,
        right: &Expr,
        span: Span,
    ) -> Option<Quantity> {
        let cx = &mut *self.lowerer.cx;
        let result = if operator == BinaryOperator::Divide {
            cx.div(a, b)
        } else {
            let Node::Number(exponent) = cx.node(b).clone() else {
                return self.error(
                    right.first_span(),
                    "an exponent must be a constant number (an integer or a fraction like 1/2)",
                );
            };
            cx.pow(a, exponent)
        };
        match result {
            Ok(value) => self.within_constant_limit(Quantity::Scalar(value), span),
            Err(error) => self.error(span, error.to_string()),
        }
    }
}

/// `x`, `y`, `z` as 0, 1, 2.
pub(in crate::model) fn axis_index(axis: &Ident) -> Option<usize> {
    ["x", "y", "z"].iter().position(|name| axis == name)
}
