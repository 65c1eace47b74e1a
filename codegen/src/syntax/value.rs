//! Values, bracketed lists and their items, and the comma-separated runs
//! that sections, list items and call arguments come in.
//!
//! Each entry of a comma-separated run is parsed on its own: one that fails
//! is skipped up to the next comma, and the errors of all entries are
//! combined, so one mistake does not hide the others.

use proc_macro2::{Delimiter, Ident, TokenTree};
use syn::ext::IdentExt;
use syn::parse::{Parse, ParseStream};
use syn::punctuated::Punctuated;
use syn::{Error, Result, Token, bracketed, token};

use super::ast::{Item, List, Value};
use super::expr::parse_expression;
use super::scope::{Errors, Scope};

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

/// `entry ( "," entry )* ","?` up to the end of `input`, each entry parsed
/// by `parse_entry` on its own; an empty entry (`a, , b`) is reported at its
/// comma with the message `empty`. All entries' errors come back together.
pub(super) fn parse_comma_separated<T>(
    input: ParseStream,
    empty: &str,
    mut parse_entry: impl FnMut(ParseStream) -> Result<T>,
) -> Result<Punctuated<T, Token![,]>> {
    let mut entries = Punctuated::new();
    let mut errors = Errors::default();
    while !input.is_empty() {
        if let Some(comma) = input.parse::<Option<Token![,]>>()? {
            errors.push(Error::new(comma.span, empty));
            continue;
        }
        let entry = parse_entry(input).and_then(|entry| Ok((entry, parse_separator(input)?)));
        match entry {
            Ok((entry, comma)) => {
                entries.push_value(entry);
                if let Some(comma) = comma {
                    entries.push_punct(comma);
                }
            }
            Err(error) => {
                errors.push(error);
                skip_past_comma(input)?;
            }
        }
    }
    errors.finish(entries)
}

/// The `,` after an entry, or `None` at the end of the group.
fn parse_separator(input: ParseStream) -> Result<Option<Token![,]>> {
    if input.is_empty() {
        return Ok(None);
    }
    input.parse().map(Some)
}

/// Skips the rest of a failed entry and the comma after it.
fn skip_past_comma(input: ParseStream) -> Result<()> {
    input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((token, next)) = rest.token_tree() {
            rest = next;
            if matches!(token, TokenTree::Punct(punct) if punct.as_char() == ',') {
                break;
            }
        }
        Ok(((), rest))
    })
}
