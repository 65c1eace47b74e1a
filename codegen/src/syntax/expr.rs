//! Values and expressions: a value is a bracketed list of items or an
//! expression, and a call's arguments are values, so the two are one
//! recursive grammar.
//!
//! Expressions are parsed by precedence climbing on a syn parse stream.
//! From loosest to tightest: `+ -` and `* /` (left-associative), unary `-`,
//! `^` (right-associative, its right operand may start with `-`), then field
//! selection `base.field`. So `-x^2` is `-(x^2)`, `2^-3^2` is `2^(-(3^2))`
//! and `-r*lean.z^2` is `(-r)*((lean.z)^2)`.
//!
//! Every node's depth is tracked so that expressions deeper than
//! [`MAX_EXPRESSION_DEPTH`] are rejected here, before later stages walk them
//! recursively. The items of a list and the arguments of a call are parsed
//! each on its own ([`parse_comma_separated`]), so one mistake does not
//! hide the others.

use proc_macro2::{Delimiter, Ident, Literal, Punct, Span, TokenTree};
use syn::ext::IdentExt;
use syn::parse::{End, Lookahead1, Parse, ParseStream, Parser};
use syn::{Error, Result, Token, bracketed, parenthesized, token};

use super::ast::{BinaryOperator, Expr, Item, Keyword, List, Value};
use super::literal::decimal_number;
use super::scope::Scope;
use super::separated::parse_comma_separated;

/// The largest depth (longest root-to-leaf path) of a parsed expression, so
/// that later stages can walk expressions recursively without overflowing
/// the stack.
pub const MAX_EXPRESSION_DEPTH: usize = 1000;

/// The precedence of `+` and `-`; `*` and `/` bind tighter, `^` tightest.
const ADDITIVE_PRECEDENCE: u8 = 1;
const MULTIPLICATIVE_PRECEDENCE: u8 = 2;
/// A unary minus applies to an operand together with any `^` after it:
/// `-x^2` is `-(x^2)`.
const POWER_PRECEDENCE: u8 = 3;

impl BinaryOperator {
    fn precedence(self) -> u8 {
        match self {
            BinaryOperator::Add | BinaryOperator::Subtract => ADDITIVE_PRECEDENCE,
            BinaryOperator::Multiply | BinaryOperator::Divide => MULTIPLICATIVE_PRECEDENCE,
            BinaryOperator::Power => POWER_PRECEDENCE,
        }
    }

    /// The least precedence an operator inside the right operand must have:
    /// left-associative operators stop at their own level, `^` does not.
    fn right_operand_precedence(self) -> u8 {
        match self {
            BinaryOperator::Power => POWER_PRECEDENCE,
            other => other.precedence() + 1,
        }
    }
}

/// An expression together with its depth.
pub(super) struct Parsed {
    pub(super) expr: Expr,
    pub(super) depth: usize,
}

impl Parsed {
    fn leaf(expr: Expr) -> Self {
        Parsed { expr, depth: 1 }
    }

    /// A node whose deepest child has `child_depth`, rejecting expressions
    /// deeper than [`MAX_EXPRESSION_DEPTH`].
    fn node(expr: Expr, child_depth: usize) -> Result<Self> {
        let depth = child_depth + 1;
        if depth > MAX_EXPRESSION_DEPTH {
            let message = format!(
                "expression too deep (more than {MAX_EXPRESSION_DEPTH} nested operations); \
                 split it into named parts with `define`"
            );
            return Err(Error::new(expr.span(), message));
        }
        Ok(Parsed { expr, depth })
    }
}

/// An expression filling the whole input.
impl Parse for Expr {
    fn parse(input: ParseStream) -> Result<Self> {
        parse_expression(input, Scope::outermost(None)).map(|parsed| parsed.expr)
    }
}

/// An expression up to the end of the group, or up to a `,` where commas
/// separate the group's contents.
pub(super) fn parse_expression(input: ParseStream, scope: Scope) -> Result<Parsed> {
    parse_operations(input, scope, 0)
}

/// Precedence climbing: an operand, then every binary operator binding at
/// least as tightly as `min_precedence`, with its right operand.
fn parse_operations(input: ParseStream, scope: Scope, min_precedence: u8) -> Result<Parsed> {
    let scope = scope.deeper(input)?;
    let mut left = parse_operand(input, scope)?;
    while let Some(operator) = next_operator(input, scope)?
        && operator.precedence() >= min_precedence
    {
        let span = input.parse::<Punct>()?.span();
        let right = parse_operations(input, scope, operator.right_operand_precedence())?;
        let depth = left.depth.max(right.depth);
        let expr = Expr::Binary {
            operator,
            left: Box::new(left.expr),
            right: Box::new(right.expr),
            span,
        };
        left = Parsed::node(expr, depth)?;
    }
    Ok(left)
}

/// The binary operator after an operand, or `None` where the expression
/// ends: at the end of the group, or at a `,` where commas separate. Any
/// other token is an error naming everything that may follow an operand.
/// The tokens are peeked directly; only the error path builds a
/// [`syn::parse::Lookahead1`] (which records every token it is asked about).
fn next_operator(input: ParseStream, scope: Scope) -> Result<Option<BinaryOperator>> {
    let operator = if input.peek(Token![+]) {
        BinaryOperator::Add
    } else if input.peek(Token![-]) {
        BinaryOperator::Subtract
    } else if input.peek(Token![*]) {
        BinaryOperator::Multiply
    } else if input.peek(Token![/]) {
        BinaryOperator::Divide
    } else if input.peek(Token![^]) {
        BinaryOperator::Power
    } else if (scope.commas() && input.peek(Token![,])) || input.is_empty() {
        return Ok(None);
    } else {
        return Err(scope.unexpected(input, operand_followers(input, scope)));
    };
    Ok(Some(operator))
}

/// What may follow an operand, as a lookahead that names each of them.
fn operand_followers(input: ParseStream, scope: Scope) -> Lookahead1 {
    let lookahead = input.lookahead1();
    let follows = lookahead.peek(Token![+])
        || lookahead.peek(Token![-])
        || lookahead.peek(Token![*])
        || lookahead.peek(Token![/])
        || lookahead.peek(Token![^])
        || (scope.commas() && lookahead.peek(Token![,]))
        || lookahead.peek(End);
    debug_assert!(!follows, "asked only where no operator and no end follows");
    lookahead
}

/// A primary operand followed by any number of `.field` selections.
fn parse_operand(input: ParseStream, scope: Scope) -> Result<Parsed> {
    let mut operand = parse_primary(input, scope)?;
    while input.peek(Token![.]) {
        input.parse::<Token![.]>()?;
        if !input.peek(Ident::peek_any) {
            let what = "a field name after `.`, such as `x` in `ground.x`";
            return Err(scope.expected(input, what));
        }
        let expr = Expr::Field {
            base: Box::new(operand.expr),
            field: input.call(Ident::parse_any)?,
        };
        operand = Parsed::node(expr, operand.depth)?;
    }
    Ok(operand)
}

/// A number, a name, a call, `-operand` or `( expression )`.
fn parse_primary(input: ParseStream, scope: Scope) -> Result<Parsed> {
    let expected = "an operand (a number, a name, a call like `sin(x)`, or `( ... )`)";
    if input.cursor().group(Delimiter::None).is_some() {
        parse_interpolated(input, scope)
    } else if input.peek(Token![-]) {
        let minus = input.parse::<Token![-]>()?;
        let operand = parse_operations(input, scope, POWER_PRECEDENCE)?;
        let expr = Expr::Negate {
            operand: Box::new(operand.expr),
            span: minus.span,
        };
        Parsed::node(expr, operand.depth)
    } else if input.cursor().literal().is_some() {
        parse_number(&input.parse()?)
    } else if input.peek(Ident::peek_any) {
        let name = input.call(Ident::parse_any)?;
        if input.peek(token::Paren) {
            parse_call(input, scope, name)
        } else {
            Ok(Parsed::leaf(Expr::Name(name)))
        }
    } else if input.peek(token::Paren) {
        let content;
        let parentheses = parenthesized!(content in input);
        let scope = scope.inside(Delimiter::Parenthesis, false);
        parse_grouped(&content, scope, parentheses.span.join())
    } else if input.peek(token::Bracket) {
        let message = "a list `[...]` cannot be part of an expression; \
                       lists are whole values such as `[a, b]`, or call arguments";
        Err(Error::new(scope.next_span(input), message))
    } else if input.peek(Token![*]) {
        let message =
            format!("expected {expected}, found `*` (powers are written `x^2`, not `x**2`)");
        Err(Error::new(scope.next_span(input), message))
    } else {
        Err(scope.expected(input, expected))
    }
}

/// The expression inside `( )` or an invisible group, which spans `span`.
fn parse_grouped(content: ParseStream, scope: Scope, span: Span) -> Result<Parsed> {
    if content.is_empty() {
        let message = "empty parentheses: expected an expression inside `( )`";
        return Err(Error::new(span, message));
    }
    parse_expression(content, scope)
}

/// An invisible group, as a `macro_rules!` fragment such as `$e:expr`
/// arrives: one operand, as if parenthesized.
fn parse_interpolated(input: ParseStream, scope: Scope) -> Result<Parsed> {
    let TokenTree::Group(group) = input.parse::<TokenTree>()? else {
        return Err(scope.expected(input, "an interpolated expression"));
    };
    let scope = scope.inside(Delimiter::None, false);
    let parse = |content: ParseStream| parse_grouped(content, scope, group.span());
    parse.parse2(group.stream())
}

/// A numeric literal; a negative literal (from interpolated tokens) is a
/// negation of its magnitude.
fn parse_number(literal: &Literal) -> Result<Parsed> {
    let text = literal.to_string();
    let span = literal.span();
    let (negative, magnitude) = match text.strip_prefix('-') {
        Some(magnitude) => (true, magnitude),
        None => (false, text.as_str()),
    };
    let number = Expr::Number {
        literal: decimal_number(magnitude).map_err(|message| Error::new(span, message))?,
        span,
    };
    if negative {
        let expr = Expr::Negate {
            operand: Box::new(number),
            span,
        };
        return Parsed::node(expr, 1);
    }
    Ok(Parsed::leaf(number))
}

/// One argument of a call: positional, or `name = value`.
enum Argument {
    Positional(Value),
    Keyword(Keyword),
}

/// `function(argument, ...)`, each argument parsed independently: an
/// expression or a bracketed list (one level deep; its own nesting is
/// bounded by the scope), after `name =` for a keyword argument.
fn parse_call(input: ParseStream, scope: Scope, function: Ident) -> Result<Parsed> {
    let scope = scope.deeper(input)?;
    let content;
    let parentheses = parenthesized!(content in input);
    let scope = scope.inside(Delimiter::Parenthesis, true);
    let empty = "empty argument: expected an expression before this `,`";
    let parsed =
        parse_comma_separated(&content, empty, |argument| parse_argument(argument, scope))?;
    let depth = parsed.iter().map(|(_, depth)| *depth).max();
    let (mut arguments, mut keywords) = (Vec::new(), Vec::new());
    for (argument, _) in parsed {
        match argument {
            Argument::Positional(value) => arguments.push(value),
            Argument::Keyword(keyword) => keywords.push(keyword),
        }
    }
    let expr = Expr::Call {
        function,
        arguments,
        keywords,
        span: parentheses.span.join(),
    };
    Parsed::node(expr, depth.unwrap_or(0))
}

/// `name = value` (when an identifier is followed by `=`) or `value`, with
/// the depth it adds to its call.
fn parse_argument(input: ParseStream, scope: Scope) -> Result<(Argument, usize)> {
    if input.peek(Ident::peek_any) && input.peek2(Token![=]) {
        let name = input.call(Ident::parse_any)?;
        input.parse::<Token![=]>()?;
        let expected = format!("a value after `{name} =`");
        let (value, depth) = parse_value(input, scope, &expected)?;
        return Ok((Argument::Keyword(Keyword { name, value }), depth));
    }
    let (value, depth) = parse_value(input, scope, "`(`")?;
    Ok((Argument::Positional(value), depth))
}

/// A list or an expression filling the whole input.
impl Parse for Value {
    fn parse(input: ParseStream) -> Result<Self> {
        parse_value(input, Scope::outermost(None), "a value").map(|(value, _)| value)
    }
}

/// `[item, ...]` filling the whole input.
impl Parse for List {
    fn parse(input: ParseStream) -> Result<Self> {
        parse_list(input, Scope::outermost(None))
    }
}

/// `name = value` or `value`, filling the whole input.
impl Parse for Item {
    fn parse(input: ParseStream) -> Result<Self> {
        parse_item(input, Scope::outermost(None))
    }
}

/// A list or an expression, with the depth it adds to a call it is an
/// argument of (a list counts as one level). `expected` says what is
/// missing when there is nothing, such as "a value after `m =`".
pub(super) fn parse_value(
    input: ParseStream,
    scope: Scope,
    expected: &str,
) -> Result<(Value, usize)> {
    if input.is_empty() || input.peek(Token![,]) {
        return Err(scope.expected(input, expected));
    }
    if !input.peek(token::Bracket) {
        let parsed = parse_expression(input, scope)?;
        return Ok((Value::Expr(parsed.expr), parsed.depth));
    }
    let list = parse_list(input, scope)?;
    if !(input.is_empty() || input.peek(Token![,])) {
        let what = "`,` after the list (a list `[...]` is a whole value)";
        return Err(scope.expected(input, what));
    }
    Ok((Value::List(list), 1))
}

/// `[item, ...]`, each item parsed on its own.
fn parse_list(input: ParseStream, scope: Scope) -> Result<List> {
    let scope = scope.deeper(input)?;
    let content;
    let brackets = bracketed!(content in input);
    let scope = scope.inside(Delimiter::Bracket, true);
    let empty = "empty list item: expected a value before this `,`";
    let items = parse_comma_separated(&content, empty, |item| parse_item(item, scope))?;
    Ok(List {
        items: items.into_iter().collect(),
        span: brackets.span.join(),
    })
}

/// `name = value` (when an identifier is followed by `=`) or `value`.
fn parse_item(input: ParseStream, scope: Scope) -> Result<Item> {
    if input.peek(Ident::peek_any) && input.peek2(Token![=]) {
        let name = input.call(Ident::parse_any)?;
        input.parse::<Token![=]>()?;
        let expected = format!("a value after `{name} =`");
        let (value, _) = parse_value(input, scope, &expected)?;
        return Ok(Item::Named { name, value });
    }
    let (value, _) = parse_value(input, scope, "a value")?;
    Ok(Item::Plain(value))
}
