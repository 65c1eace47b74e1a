//! The recursive-descent parser behind [`super::parse`].
//!
//! Each parsing method returns `None` after recording why in the parser's
//! diagnostics. Sections, list items and call arguments are parsed
//! independently of their neighbours, so one mistake does not hide others.

use proc_macro2::{Delimiter, Group, Ident, Literal, Span, TokenStream, TokenTree};

use super::ast::{Attribute, BinaryOperator, Expr, Item, List, ModelSyntax, Section, Value};
use super::literal::{decimal_number, string_value};
use super::tokens::{Boundary, Chunk, Cursor, describe, is_punct, split_at_commas};
use crate::diagnostic::Diagnostics;

/// How deeply parentheses, calls, lists, unary minus and operator operands
/// may nest while parsing; keeps the parser's recursion bounded.
const MAX_NESTING: usize = 200;

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
struct Parsed {
    expr: Expr,
    depth: usize,
}

impl Parsed {
    fn leaf(expr: Expr) -> Self {
        Parsed { expr, depth: 1 }
    }
}

/// The header of a model: everything but the body's sections.
struct Header<'a> {
    docs: Vec<String>,
    attributes: Vec<Attribute>,
    visibility: TokenStream,
    name: Ident,
    body: &'a Group,
}

/// Parses model tokens, collecting every error it can find.
#[derive(Default)]
pub(super) struct Parser {
    diagnostics: Diagnostics,
    nesting: usize,
}

impl Parser {
    /// Parses a whole model: attributes, visibility, `struct Name { ... }`.
    pub(super) fn parse_model(mut self, tokens: TokenStream) -> Result<ModelSyntax, Diagnostics> {
        let tokens: Vec<TokenTree> = tokens.into_iter().collect();
        let last_span = tokens.last().map_or_else(Span::call_site, TokenTree::span);
        let mut cursor = Cursor::new(&tokens, Boundary::end_of_input(last_span));
        let Some(header) = self.parse_header(&mut cursor) else {
            return Err(self.diagnostics);
        };
        let sections = self.parse_sections(header.body);
        if !cursor.is_at_end() {
            let message = format!(
                "unexpected tokens after the model's closing brace: found {}",
                cursor.found()
            );
            self.diagnostics.error(cursor.span(), message);
        }
        let model = ModelSyntax {
            docs: header.docs,
            attributes: header.attributes,
            visibility: header.visibility,
            name: header.name,
            sections,
        };
        self.diagnostics.into_result(model)
    }

    /// Records "expected {what}, found {the next token}" at the next token.
    fn expected<T>(&mut self, cursor: &Cursor, what: &str) -> Option<T> {
        let message = format!("expected {what}, found {}", cursor.found());
        self.diagnostics.error(cursor.span(), message);
        None
    }

    fn parse_header<'a>(&mut self, cursor: &mut Cursor<'a>) -> Option<Header<'a>> {
        let (docs, attributes) = self.parse_outer_attributes(cursor)?;
        let visibility = parse_visibility(cursor);
        if !cursor.peek_ident("struct") {
            return self.expected(cursor, "`struct Name { ... }`");
        }
        cursor.next_token();
        let Some(TokenTree::Ident(name)) = cursor.peek() else {
            return self.expected(cursor, "the model's name after `struct`");
        };
        cursor.next_token();
        let Some(TokenTree::Group(body)) = cursor
            .peek()
            .filter(|token| is_group(token, Delimiter::Brace))
        else {
            let what = format!("`{{` and the model's sections after `struct {name}`");
            return self.expected(cursor, &what);
        };
        cursor.next_token();
        Some(Header {
            docs,
            attributes,
            visibility,
            name: name.clone(),
            body,
        })
    }

    /// Reads `#[...]` attributes, separating doc comments from the others.
    fn parse_outer_attributes(
        &mut self,
        cursor: &mut Cursor,
    ) -> Option<(Vec<String>, Vec<Attribute>)> {
        let mut docs = Vec::new();
        let mut attributes = Vec::new();
        while let Some(group) = self.next_attribute(cursor, "the model")? {
            let contents: Vec<TokenTree> = group.stream().into_iter().collect();
            if let Some(doc) = self.doc_attribute(&contents, group.span()) {
                docs.extend(doc);
            } else if let Some(attribute) = self.attribute(&contents, group.span()) {
                attributes.push(attribute);
            }
        }
        Some((docs, attributes))
    }

    /// Consumes `#[...]` and returns its bracket group; `Some(None)` when the
    /// next token is not `#`. Inner attributes (`#![...]`, `//!`) are errors
    /// that are reported and skipped; `place` names where they appeared.
    fn next_attribute<'a>(
        &mut self,
        cursor: &mut Cursor<'a>,
        place: &str,
    ) -> Option<Option<&'a Group>> {
        while cursor.peek_punct('#') {
            cursor.next_token();
            if cursor.peek_punct('!') {
                let message = format!(
                    "inner attributes and `//!` comments are not allowed in {place}; \
                     document the model with `///` before `struct`"
                );
                self.diagnostics.error(cursor.span(), message);
                cursor.next_token();
                cursor.next_token();
                continue;
            }
            return match cursor.peek() {
                Some(TokenTree::Group(group)) if group.delimiter() == Delimiter::Bracket => {
                    cursor.next_token();
                    Some(Some(group))
                }
                _ => self.expected(cursor, "`[` after `#` to start an attribute"),
            };
        }
        Some(None)
    }

    /// For `#[doc = "text"]`: `Some(Some(text))`, or `Some(None)` after
    /// reporting a malformed doc attribute. `None` for other attributes.
    fn doc_attribute(&mut self, contents: &[TokenTree], span: Span) -> Option<Option<String>> {
        let [TokenTree::Ident(name), TokenTree::Punct(equals), rest @ ..] = contents else {
            return None;
        };
        if name != "doc" || equals.as_char() != '=' {
            return None;
        }
        let text = match rest {
            [TokenTree::Literal(literal)] => string_value(&literal.to_string()),
            _ => None,
        };
        if text.is_none() {
            let message = "expected a string literal in `#[doc = \"...\"]`";
            self.diagnostics.error(span, message);
        }
        Some(text)
    }

    /// Any other attribute: `#[name tokens...]`.
    fn attribute(&mut self, contents: &[TokenTree], span: Span) -> Option<Attribute> {
        let Some((TokenTree::Ident(name), rest)) = contents.split_first() else {
            let found = contents.first().map_or_else(|| "`]`".to_owned(), describe);
            let message = format!("expected an attribute name inside `#[...]`, found {found}");
            self.diagnostics.error(span, message);
            return None;
        };
        Some(Attribute {
            name: name.clone(),
            tokens: rest.iter().cloned().collect(),
        })
    }

    /// Parses the comma-separated `key: value` sections of the struct body.
    fn parse_sections(&mut self, body: &Group) -> Vec<Section> {
        let tokens: Vec<TokenTree> = body.stream().into_iter().collect();
        let close = Boundary::closing(Delimiter::Brace, body.span_close());
        let message = "empty section: expected `name: value` before this `,`";
        self.non_empty_chunks(split_at_commas(&tokens, close), message)
            .iter()
            .filter_map(|chunk| self.parse_section(&mut chunk.cursor()))
            .collect()
    }

    /// Drops the final empty chunk (after a trailing comma, or of an empty
    /// group) and reports any other empty chunk at its comma with `message`.
    fn non_empty_chunks<'a>(&mut self, chunks: Vec<Chunk<'a>>, message: &str) -> Vec<Chunk<'a>> {
        let last = chunks.len().saturating_sub(1);
        let mut non_empty = Vec::with_capacity(chunks.len());
        for (index, chunk) in chunks.into_iter().enumerate() {
            if !chunk.tokens.is_empty() {
                non_empty.push(chunk);
            } else if index != last {
                self.diagnostics.error(chunk.end.span, message);
            }
        }
        non_empty
    }

    fn parse_section(&mut self, cursor: &mut Cursor) -> Option<Section> {
        self.skip_section_attributes(cursor);
        let Some(TokenTree::Ident(key)) = cursor.peek() else {
            return self.expected(cursor, "a section name such as `coordinates`");
        };
        cursor.next_token();
        if !cursor.peek_punct(':') {
            return self.expected(cursor, &format!("`:` after the section name `{key}`"));
        }
        cursor.next_token();
        let value = self.parse_value(cursor, &format!("`{key}:`"))?;
        Some(Section {
            key: key.clone(),
            value,
        })
    }

    /// Reports and skips doc comments or attributes placed on a section.
    fn skip_section_attributes(&mut self, cursor: &mut Cursor) {
        let span = cursor.span();
        let mut found_any = false;
        while let Some(Some(_)) = self.next_attribute(cursor, "the model's body") {
            found_any = true;
        }
        if found_any {
            let message = "doc comments and attributes are only allowed before `struct`; \
                           use `//` comments inside the model";
            self.diagnostics.error(span, message);
        }
    }

    /// Parses a list or an expression filling the rest of the cursor;
    /// `after` names what precedes it, for the error if nothing does.
    fn parse_value(&mut self, cursor: &mut Cursor, after: &str) -> Option<Value> {
        match cursor.peek() {
            None => self.expected(cursor, &format!("a value after {after}")),
            Some(TokenTree::Group(group)) if group.delimiter() == Delimiter::Bracket => {
                cursor.next_token();
                let list = self.parse_list(group)?;
                if !cursor.is_at_end() {
                    let what = "`,` after the list (a list `[...]` is a whole value)";
                    return self.expected(cursor, what);
                }
                Some(Value::List(list))
            }
            Some(_) => self.parse_whole_expression(cursor).map(Value::Expr),
        }
    }

    /// Parses `[item, ...]`, each item independently.
    fn parse_list(&mut self, group: &Group) -> Option<List> {
        self.nested(group.span(), |parser| {
            let tokens: Vec<TokenTree> = group.stream().into_iter().collect();
            let close = Boundary::closing(Delimiter::Bracket, group.span_close());
            let message = "empty list item: expected a value before this `,`";
            let items = parser
                .non_empty_chunks(split_at_commas(&tokens, close), message)
                .iter()
                .filter_map(|chunk| parser.parse_item(&mut chunk.cursor()))
                .collect();
            Some(List {
                items,
                span: group.span(),
            })
        })
    }

    /// `name = value` (when an identifier is followed by `=`) or `value`.
    fn parse_item(&mut self, cursor: &mut Cursor) -> Option<Item> {
        if let [TokenTree::Ident(name), equals, ..] = cursor.rest()
            && is_punct(equals, '=')
        {
            cursor.next_token();
            cursor.next_token();
            let value = self.parse_value(cursor, &format!("`{name} =`"))?;
            return Some(Item::Named {
                name: name.clone(),
                value,
            });
        }
        self.parse_value(cursor, "the list item").map(Item::Plain)
    }

    /// Parses an expression that must use up the whole cursor.
    fn parse_whole_expression(&mut self, cursor: &mut Cursor) -> Option<Expr> {
        let parsed = self.parse_expression(cursor, 0)?;
        if !cursor.is_at_end() {
            let what = "an operator (`+`, `-`, `*`, `/` or `^`) or the end of the expression";
            return self.expected(cursor, what);
        }
        Some(parsed.expr)
    }

    /// Precedence climbing: an operand, then every binary operator binding
    /// at least as tightly as `min_precedence`, with its right operand.
    fn parse_expression(&mut self, cursor: &mut Cursor, min_precedence: u8) -> Option<Parsed> {
        self.nested(cursor.span(), |parser| {
            let mut left = parser.parse_operand(cursor)?;
            while let Some((operator, span)) = peek_binary_operator(cursor)
                && operator.precedence() >= min_precedence
            {
                cursor.next_token();
                let right = parser.parse_expression(cursor, operator.right_operand_precedence())?;
                let depth = left.depth.max(right.depth);
                let expr = Expr::Binary {
                    operator,
                    left: Box::new(left.expr),
                    right: Box::new(right.expr),
                    span,
                };
                left = parser.node(expr, depth)?;
            }
            Some(left)
        })
    }

    /// A primary operand followed by any number of `.field` selections.
    fn parse_operand(&mut self, cursor: &mut Cursor) -> Option<Parsed> {
        let mut operand = self.parse_primary(cursor)?;
        while cursor.peek_punct('.') {
            cursor.next_token();
            let Some(TokenTree::Ident(field)) = cursor.peek() else {
                return self.expected(cursor, "a field name after `.`, such as `x` in `ground.x`");
            };
            cursor.next_token();
            let expr = Expr::Field {
                base: Box::new(operand.expr),
                field: field.clone(),
            };
            operand = self.node(expr, operand.depth)?;
        }
        Some(operand)
    }

    /// A number, a name, a call, `-operand` or `( expression )`.
    fn parse_primary(&mut self, cursor: &mut Cursor) -> Option<Parsed> {
        let expected = "an operand (a number, a name, a call like `sin(x)`, or `( ... )`)";
        let Some(token) = cursor.peek() else {
            return self.expected(cursor, expected);
        };
        match token {
            TokenTree::Punct(minus) if minus.as_char() == '-' => {
                cursor.next_token();
                let operand = self.parse_expression(cursor, POWER_PRECEDENCE)?;
                let expr = Expr::Negate {
                    operand: Box::new(operand.expr),
                    span: minus.span(),
                };
                self.node(expr, operand.depth)
            }
            TokenTree::Literal(literal) => {
                cursor.next_token();
                self.number(literal)
            }
            TokenTree::Ident(name) => {
                cursor.next_token();
                match cursor.peek() {
                    Some(TokenTree::Group(group))
                        if group.delimiter() == Delimiter::Parenthesis =>
                    {
                        cursor.next_token();
                        self.parse_call(name, group)
                    }
                    _ => Some(Parsed::leaf(Expr::Name(name.clone()))),
                }
            }
            TokenTree::Group(group)
                if matches!(group.delimiter(), Delimiter::Parenthesis | Delimiter::None) =>
            {
                cursor.next_token();
                self.parse_parenthesized(group)
            }
            TokenTree::Group(group) if group.delimiter() == Delimiter::Bracket => {
                let message = "a list `[...]` cannot be part of an expression; \
                               lists are whole values such as `[a, b]`, or call arguments";
                self.diagnostics.error(group.span(), message);
                None
            }
            TokenTree::Punct(star) if star.as_char() == '*' => {
                let message = format!(
                    "expected {expected}, found `*` (powers are written `x^2`, not `x**2`)"
                );
                self.diagnostics.error(star.span(), message);
                None
            }
            _ => self.expected(cursor, expected),
        }
    }

    /// A numeric literal; a negative literal (from interpolated tokens) is
    /// a negation of its magnitude.
    fn number(&mut self, literal: &Literal) -> Option<Parsed> {
        let text = literal.to_string();
        let span = literal.span();
        let (negative, magnitude) = match text.strip_prefix('-') {
            Some(magnitude) => (true, magnitude),
            None => (false, text.as_str()),
        };
        let number = match decimal_number(magnitude) {
            Ok(literal) => Expr::Number { literal, span },
            Err(message) => {
                self.diagnostics.error(span, message);
                return None;
            }
        };
        if negative {
            let expr = Expr::Negate {
                operand: Box::new(number),
                span,
            };
            return self.node(expr, 1);
        }
        Some(Parsed::leaf(number))
    }

    /// `function(argument, ...)`, each argument parsed independently.
    fn parse_call(&mut self, function: &Ident, group: &Group) -> Option<Parsed> {
        self.nested(group.span(), |parser| {
            let tokens: Vec<TokenTree> = group.stream().into_iter().collect();
            let close = Boundary::closing(Delimiter::Parenthesis, group.span_close());
            let message = "empty argument: expected an expression before this `,`";
            let chunks = parser.non_empty_chunks(split_at_commas(&tokens, close), message);
            let arguments: Vec<(Value, usize)> = chunks
                .iter()
                .filter_map(|chunk| parser.parse_argument(&mut chunk.cursor()))
                .collect();
            if arguments.len() != chunks.len() {
                return None;
            }
            let depth = arguments.iter().map(|(_, depth)| *depth).max();
            let expr = Expr::Call {
                function: function.clone(),
                arguments: arguments.into_iter().map(|(value, _)| value).collect(),
                span: group.span(),
            };
            parser.node(expr, depth.unwrap_or(0))
        })
    }

    /// One call argument with its depth: a bracketed list (counted as one
    /// level; its nesting is bounded by [`MAX_NESTING`]) or an expression.
    fn parse_argument(&mut self, cursor: &mut Cursor) -> Option<(Value, usize)> {
        if let Some(TokenTree::Group(group)) = cursor.peek()
            && group.delimiter() == Delimiter::Bracket
        {
            cursor.next_token();
            let list = self.parse_list(group)?;
            self.require_end_of_argument(cursor)?;
            return Some((Value::List(list), 1));
        }
        let parsed = self.parse_expression(cursor, 0)?;
        self.require_end_of_argument(cursor)?;
        Some((Value::Expr(parsed.expr), parsed.depth))
    }

    fn require_end_of_argument(&mut self, cursor: &Cursor) -> Option<()> {
        if cursor.is_at_end() {
            return Some(());
        }
        self.expected(cursor, "an operator or the end of the argument")
    }

    /// `( expression )`, or an invisible group from a `macro_rules!` fragment.
    fn parse_parenthesized(&mut self, group: &Group) -> Option<Parsed> {
        let tokens: Vec<TokenTree> = group.stream().into_iter().collect();
        let close = Boundary::closing(group.delimiter(), group.span_close());
        let mut cursor = Cursor::new(&tokens, close);
        if cursor.is_at_end() {
            let message = "empty parentheses: expected an expression inside `( )`";
            self.diagnostics.error(group.span(), message);
            return None;
        }
        let parsed = self.parse_expression(&mut cursor, 0)?;
        if !cursor.is_at_end() {
            return self.expected(&cursor, "an operator or `)` closing the parentheses");
        }
        Some(parsed)
    }

    /// Wraps a node whose deepest child has `child_depth`, rejecting
    /// expressions deeper than [`MAX_EXPRESSION_DEPTH`].
    fn node(&mut self, expr: Expr, child_depth: usize) -> Option<Parsed> {
        let depth = child_depth + 1;
        if depth > MAX_EXPRESSION_DEPTH {
            let message = format!(
                "expression too deep (more than {MAX_EXPRESSION_DEPTH} nested operations); \
                 split it into named parts with `define`"
            );
            self.diagnostics.error(expr.span(), message);
            return None;
        }
        Some(Parsed { expr, depth })
    }

    /// Runs `parse` one nesting level deeper, refusing to go past
    /// [`MAX_NESTING`] so that hostile input cannot overflow the stack.
    fn nested<T>(&mut self, span: Span, parse: impl FnOnce(&mut Self) -> Option<T>) -> Option<T> {
        if self.nesting >= MAX_NESTING {
            let message = format!(
                "nested too deeply (more than {MAX_NESTING} levels of parentheses, lists, \
                 calls or operators); split the expression with `define`"
            );
            self.diagnostics.error(span, message);
            return None;
        }
        self.nesting += 1;
        let parsed = parse(self);
        self.nesting -= 1;
        parsed
    }
}

/// `pub`, `pub(crate)`, `pub(super)`, `pub(in path)`, or nothing.
fn parse_visibility(cursor: &mut Cursor) -> TokenStream {
    let mut visibility = TokenStream::new();
    if !cursor.peek_ident("pub") {
        return visibility;
    }
    visibility.extend(cursor.next_token().cloned());
    if let Some(group) = cursor
        .peek()
        .filter(|token| is_group(token, Delimiter::Parenthesis))
    {
        visibility.extend([group.clone()]);
        cursor.next_token();
    }
    visibility
}

fn is_group(token: &TokenTree, delimiter: Delimiter) -> bool {
    matches!(token, TokenTree::Group(group) if group.delimiter() == delimiter)
}

/// The binary operator at the cursor, with its span, without consuming it.
fn peek_binary_operator(cursor: &Cursor) -> Option<(BinaryOperator, Span)> {
    match cursor.peek()? {
        TokenTree::Punct(punct) => {
            BinaryOperator::from_symbol(punct.as_char()).map(|operator| (operator, punct.span()))
        }
        _ => None,
    }
}
