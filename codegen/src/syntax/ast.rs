//! The syntax tree of one model, with a span on every node.
//!
//! The tree records what was written, not what it means: which sections
//! exist, and what shape each must have, is decided by the check stage.

use std::fmt;

use proc_macro2::{Ident, Span, TokenStream};

/// A whole model: `#[attributes] visibility struct Name { sections }`.
#[derive(Debug, Clone)]
pub struct ModelSyntax {
    /// Doc comment lines in order, as the tokens give them: `/// text`
    /// yields `" text"` (the leading space is kept).
    pub docs: Vec<String>,
    /// Outer attributes other than docs, such as `#[deny_holonomic]`.
    pub attributes: Vec<Attribute>,
    /// The visibility as written: empty, `pub`, `pub(crate)`, `pub(in path)`...
    pub visibility: TokenStream,
    /// The struct's name.
    pub name: Ident,
    /// The sections in the order written.
    pub sections: Vec<Section>,
}

/// An outer attribute `#[name rest]`, for example `#[deny_holonomic]`.
#[derive(Debug, Clone)]
pub struct Attribute {
    /// The first identifier inside the brackets.
    pub name: Ident,
    /// The tokens after the name (empty for `#[deny_holonomic]`).
    pub tokens: TokenStream,
}

/// One `key: value` entry of the struct body.
#[derive(Debug, Clone)]
pub struct Section {
    /// The section name, such as `coordinates`.
    pub key: Ident,
    /// What follows the `:`.
    pub value: Value,
}

/// A section value or list item: an expression or a bracketed list.
#[derive(Debug, Clone)]
pub enum Value {
    /// A single expression, such as `m/2*dot(x)^2` or `se2(x, y, theta)`.
    Expr(Expr),
    /// A bracketed list, such as `[x, y]` or `[[1, 0], [0, 1]]`.
    List(List),
}

impl Value {
    /// The list's bracket span, or the start of the expression.
    pub fn span(&self) -> Span {
        match self {
            Value::Expr(expr) => expr.first_span(),
            Value::List(list) => list.span,
        }
    }

    /// The expression, if this value is one.
    pub fn as_expr(&self) -> Option<&Expr> {
        match self {
            Value::Expr(expr) => Some(expr),
            Value::List(_) => None,
        }
    }

    /// The list, if this value is one.
    pub fn as_list(&self) -> Option<&List> {
        match self {
            Value::List(list) => Some(list),
            Value::Expr(_) => None,
        }
    }
}

/// `[item, item, ...]`; may be empty and may end with a comma.
#[derive(Debug, Clone)]
pub struct List {
    /// The items in the order written.
    pub items: Vec<Item>,
    /// The span of the whole bracket group.
    pub span: Span,
}

/// One list item: `name = value` or just `value`.
#[derive(Debug, Clone)]
pub enum Item {
    /// `name = value`, such as `m = 1.0` or `torso = [0, 0, 1, 1, 0]`.
    Named {
        /// The identifier before `=`.
        name: Ident,
        /// What follows the `=`.
        value: Value,
    },
    /// Anything that is not `identifier = value`, such as `x` or `[1, 0]`.
    Plain(Value),
}

impl Item {
    /// The name of a `name = value` item.
    pub fn name(&self) -> Option<&Ident> {
        match self {
            Item::Named { name, .. } => Some(name),
            Item::Plain(_) => None,
        }
    }

    /// The value, named or not.
    pub fn value(&self) -> &Value {
        match self {
            Item::Named { value, .. } | Item::Plain(value) => value,
        }
    }

    /// The name's span for a named item, otherwise the value's span.
    pub fn span(&self) -> Span {
        match self {
            Item::Named { name, .. } => name.span(),
            Item::Plain(value) => value.span(),
        }
    }
}

/// A keyword argument `name = value` of a call, such as `radius = r`.
#[derive(Debug, Clone)]
pub struct Keyword {
    /// The identifier before `=`.
    pub name: Ident,
    /// What follows the `=`.
    pub value: Value,
}

/// An expression. Parentheses only group and leave no node behind.
#[derive(Debug, Clone)]
pub enum Expr {
    /// An untyped decimal literal. `literal` is the token text with any `_`
    /// separators removed, so it always parses as `f64` and has the form
    /// `digits [. digits] [(e|E) [+|-] digits]`: `"2"`, `"0.05"`, `"1e-3"`.
    Number {
        /// The literal's text, for example `"1.5E2"`.
        literal: String,
        /// The literal token.
        span: Span,
    },
    /// A name: a coordinate, parameter, defined name, ... (resolved later).
    Name(Ident),
    /// `function(arguments)`: any identifier directly followed by `( ... )`,
    /// such as `sin(x)`, `dot(q)`, `se2(x, y, theta)`,
    /// `no_slip(wheel, contact, [ground.x, ground.y])` or
    /// `sphere(center = [x, y, r], radius = r)`.
    Call {
        /// The identifier before the parentheses.
        function: Ident,
        /// The comma-separated positional arguments (possibly none):
        /// expressions, or bracketed lists such as a list of directions or
        /// a 3 x 3 matrix.
        arguments: Vec<Value>,
        /// The keyword arguments `name = value`, in the order written
        /// (only a drawing's shapes take them; the check stage says so
        /// elsewhere).
        keywords: Vec<Keyword>,
        /// The span of the parenthesized group.
        span: Span,
    },
    /// `base.field`, such as the unit vector `ground.x` of a frame.
    Field {
        /// What the field is taken of.
        base: Box<Expr>,
        /// The identifier after the `.`.
        field: Ident,
    },
    /// `-operand`.
    Negate {
        /// What is negated.
        operand: Box<Expr>,
        /// The `-` token.
        span: Span,
    },
    /// `left operator right`.
    Binary {
        /// Which operation.
        operator: BinaryOperator,
        /// The left operand.
        left: Box<Expr>,
        /// The right operand.
        right: Box<Expr>,
        /// The operator token.
        span: Span,
    },
}

impl Expr {
    /// The node's own token: the literal, the name, the called function's
    /// name, the field's name, the `-` of a negation, or a binary operator.
    pub fn span(&self) -> Span {
        match self {
            Expr::Number { span, .. } | Expr::Negate { span, .. } | Expr::Binary { span, .. } => {
                *span
            }
            Expr::Name(name) => name.span(),
            Expr::Call { function, .. } => function.span(),
            Expr::Field { field, .. } => field.span(),
        }
    }

    /// The first token of the expression, for errors about the expression as
    /// a whole. A parenthesized expression starts inside its `(`.
    pub fn first_span(&self) -> Span {
        match self {
            Expr::Binary { left, .. } | Expr::Field { base: left, .. } => left.first_span(),
            other => other.span(),
        }
    }
}

/// The binary operators, from lowest to highest precedence:
/// `+ -`, then `* /` (all left-associative), then `^` (right-associative).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BinaryOperator {
    /// `+`
    Add,
    /// `-`
    Subtract,
    /// `*`
    Multiply,
    /// `/`
    Divide,
    /// `^`
    Power,
}

impl BinaryOperator {
    /// The operator's character as written.
    pub fn symbol(self) -> char {
        match self {
            BinaryOperator::Add => '+',
            BinaryOperator::Subtract => '-',
            BinaryOperator::Multiply => '*',
            BinaryOperator::Divide => '/',
            BinaryOperator::Power => '^',
        }
    }
}

impl fmt::Display for BinaryOperator {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(formatter, "{}", self.symbol())
    }
}
