//! The comma-separated runs that sections, list items and call arguments
//! come in.
//!
//! Each entry of a run is parsed on its own: one that fails is skipped up
//! to the next comma, and the errors of all entries are combined, so one
//! mistake does not hide the others.

use proc_macro2::TokenTree;
use syn::parse::ParseStream;
use syn::punctuated::Punctuated;
use syn::{Error, Result, Token};

use super::scope::Errors;

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
