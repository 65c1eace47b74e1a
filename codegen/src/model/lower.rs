//! Lowering of syntax expressions into the model's expression store.
//!
//! Names resolve to coordinates, parameters and earlier definitions;
//! `dot(q)` to the velocity of coordinate `q`; the functions are
//! `sin cos tan sqrt exp ln asin acos atan` of one argument and
//! `atan2(y, x)` of two ([`crate::sym::expr::FUNCTION_ARITIES`]). Exponents must be constant numbers, and the
//! constants an operator folds are held to the store's limit
//! ([`crate::sym::Store::within_constant_limit`]). Every failure becomes a
//! diagnostic on the offending token, and both operands of an operator are
//! lowered even when one fails, so all errors are reported.

use crate::diagnostic::Diagnostics;
use crate::sym::expr::{FUNCTION_LIST, arity};
use crate::sym::{Context, ExprId, Node, Rational, SymError, SymbolId};
use crate::syntax::{BinaryOperator, Expr, Value};
use proc_macro2::Span;
use std::collections::HashMap;

/// What a name in an expression stands for.
#[derive(Clone, Copy, Debug)]
pub(super) enum Binding {
    Coordinate(SymbolId),
    Parameter(SymbolId),
    Definition(ExprId),
}

/// The names visible to an expression.
#[derive(Default, Debug)]
pub(super) struct Scope {
    names: HashMap<String, Binding>,
}

impl Scope {
    pub(super) fn bind(&mut self, name: &str, binding: Binding) {
        self.names.insert(name.to_string(), binding);
    }

    pub(super) fn get(&self, name: &str) -> Option<Binding> {
        self.names.get(name).copied()
    }
}

/// Lowers expressions, collecting diagnostics.
pub(super) struct Lowerer<'a> {
    pub(super) cx: &'a mut Context,
    pub(super) scope: &'a Scope,
    pub(super) diagnostics: &'a mut Diagnostics,
}

impl Lowerer<'_> {
    /// The expression, or `None` after reporting why it cannot be built.
    pub(super) fn lower(&mut self, expr: &Expr) -> Option<ExprId> {
        match expr {
            Expr::Number { literal, span } => self.number(literal, *span),
            Expr::Name(ident) => self.name(&ident.to_string(), ident.span()),
            // Keyword arguments are reported where the section is read.
            Expr::Call { keywords, .. } if !keywords.is_empty() => None,
            Expr::Call {
                function,
                arguments,
                ..
            } => self.call(function, arguments),
            Expr::Field { base, field } => {
                let message = format!(
                    "`.{field}` selects a frame's unit vector, a vector, where a scalar belongs"
                );
                self.diagnostics.error(base.first_span(), message);
                None
            }
            Expr::Negate { operand, .. } => {
                let operand = self.lower(operand)?;
                Some(self.cx.neg(operand))
            }
            Expr::Binary {
                operator,
                left,
                right,
                span,
            } => self.binary(*operator, left, right, *span),
        }
    }

    fn number(&mut self, literal: &str, span: Span) -> Option<ExprId> {
        match Rational::from_decimal(literal) {
            Some(value) => Some(self.cx.number(value)),
            None => {
                self.diagnostics.error(
                    span,
                    format!("the number `{literal}` is out of range for an exact rational"),
                );
                None
            }
        }
    }

    fn name(&mut self, name: &str, span: Span) -> Option<ExprId> {
        match self.scope.get(name) {
            Some(Binding::Coordinate(symbol) | Binding::Parameter(symbol)) => {
                Some(self.cx.symbol(symbol))
            }
            Some(Binding::Definition(expression)) => Some(expression),
            None => {
                self.diagnostics.error(
                    span,
                    format!(
                        "unknown name `{name}`: expressions may use the coordinates, the \
                         parameters, the definitions made before this point, and `dot(q)`"
                    ),
                );
                None
            }
        }
    }

    fn call(&mut self, function: &proc_macro2::Ident, arguments: &[Value]) -> Option<ExprId> {
        let name = function.to_string();
        if name == "dot" {
            return self.velocity(function, arguments);
        }
        let Some(expected) = arity(&name) else {
            self.diagnostics.error(
                function.span(),
                format!(
                    "unknown function `{name}`: the functions are {FUNCTION_LIST}, and dot(q) \
                     for a velocity"
                ),
            );
            return None;
        };
        if arguments.len() != expected {
            let error = SymError::ArgumentCount {
                name,
                expected,
                found: arguments.len(),
            };
            self.diagnostics.error(function.span(), error.to_string());
            return None;
        }
        let lowered: Vec<Option<ExprId>> = arguments
            .iter()
            .map(|argument| self.scalar_argument(argument))
            .collect();
        let lowered: Vec<ExprId> = lowered.into_iter().collect::<Option<_>>()?;
        let applied = self.cx.apply_named(&name, &lowered);
        self.report(applied, function.span())
    }

    /// A function's argument, which must be a scalar expression.
    fn scalar_argument(&mut self, argument: &Value) -> Option<ExprId> {
        match argument {
            Value::Expr(expr) => self.lower(expr),
            Value::List(list) => {
                let message = "a list `[...]` where a scalar argument belongs";
                self.diagnostics.error(list.span, message);
                None
            }
        }
    }

    /// `dot(q)`: the velocity of a coordinate.
    fn velocity(&mut self, function: &proc_macro2::Ident, arguments: &[Value]) -> Option<ExprId> {
        let [Value::Expr(Expr::Name(argument))] = arguments else {
            // Point at the surplus argument, the one that is not a name, or `dot` itself.
            let span = match arguments {
                [] => function.span(),
                [only] => only.span(),
                [_, surplus, ..] => surplus.span(),
            };
            self.diagnostics.error(
                span,
                "`dot()` takes exactly one coordinate name, e.g. `dot(theta)`",
            );
            return None;
        };
        let name = argument.to_string();
        match self.scope.get(&name) {
            Some(Binding::Coordinate(coordinate)) => {
                let velocity = self.cx.velocity_of(coordinate);
                Some(self.cx.symbol(velocity))
            }
            Some(_) => {
                self.diagnostics.error(
                    argument.span(),
                    format!(
                        "`dot()` of `{name}`, which is not a coordinate: only coordinates have \
                         velocities"
                    ),
                );
                None
            }
            None => self.name(&name, argument.span()),
        }
    }

    fn binary(
        &mut self,
        operator: BinaryOperator,
        left: &Expr,
        right: &Expr,
        span: Span,
    ) -> Option<ExprId> {
        let left_value = self.lower(left);
        let right_value = self.lower(right);
        let (a, b) = (left_value?, right_value?);
        let value = match operator {
            BinaryOperator::Add => Ok(self.cx.add2(a, b)),
            BinaryOperator::Subtract => Ok(self.cx.sub(a, b)),
            BinaryOperator::Multiply => Ok(self.cx.mul2(a, b)),
            BinaryOperator::Divide => self.cx.div(a, b),
            BinaryOperator::Power => {
                let Node::Number(exponent) = self.cx.node(b).clone() else {
                    self.diagnostics.error(
                        right.first_span(),
                        "an exponent must be a constant number (an integer or a fraction like 1/2)",
                    );
                    return None;
                };
                self.cx.pow(a, exponent)
            }
        };
        let bounded = value.and_then(|value| self.cx.within_constant_limit(value));
        self.report(bounded, span)
    }

    fn report(&mut self, result: Result<ExprId, SymError>, span: Span) -> Option<ExprId> {
        result
            .map_err(|error| self.diagnostics.error(span, error.to_string()))
            .ok()
    }
}
