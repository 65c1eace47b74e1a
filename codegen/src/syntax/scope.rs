//! Where a parser stands: the group it is inside, how deeply it is nested,
//! and how errors there name the token they stop at.
//!
//! The nesting of groups, calls, unary minus and operator operands is
//! bounded by [`MAX_NESTING`], so hostile input cannot overflow the stack.
//! syn builds its token buffer by recursing into groups, so the depth of the
//! groups is checked on the raw tokens ([`check_group_depth`]) before syn
//! sees them.

use proc_macro2::{Delimiter, Span, TokenStream, TokenTree};
use syn::parse::{Lookahead1, ParseStream};
use syn::{Error, Result};

/// How deeply parentheses, calls, lists, unary minus and operator operands
/// may nest while parsing; keeps the parser's recursion bounded.
pub(super) const MAX_NESTING: usize = 200;

/// The error for nesting past [`MAX_NESTING`], at `span`.
fn too_deep(span: Span) -> Error {
    let message = format!(
        "nested too deeply (more than {MAX_NESTING} levels of parentheses, lists, \
         calls or operators); split the expression with `define`"
    );
    Error::new(span, message)
}

/// Rejects groups nested more than [`MAX_NESTING`] deep, at the first group
/// past the limit, walking the tokens without recursion.
pub(super) fn check_group_depth(tokens: &TokenStream) -> Result<()> {
    let mut open = vec![tokens.clone().into_iter()];
    while let Some(level) = open.last_mut() {
        match level.next() {
            Some(TokenTree::Group(group)) => {
                if open.len() > MAX_NESTING {
                    return Err(too_deep(group.span()));
                }
                open.push(group.stream().into_iter());
            }
            Some(_) => {}
            None => {
                open.pop();
            }
        }
    }
    Ok(())
}

/// The parsing context threaded through the recursive parsers.
#[derive(Debug, Clone, Copy)]
pub(super) struct Scope {
    /// How many nested levels enclose the current position.
    nesting: usize,
    /// What ends the current group, as "found ..." names it: "`]`", or "the
    /// end of the input".
    closing: &'static str,
    /// Whether `,` separates the things parsed in this group (sections, list
    /// items, call arguments) rather than ending the group early.
    commas: bool,
    /// The span to blame at the end of the outermost input, where syn's own
    /// is the call site; inside a group syn gives the closing delimiter.
    input_end: Option<Span>,
}

impl Scope {
    /// The whole input, whose last token is at `last_token` (if known).
    pub(super) fn outermost(last_token: Option<Span>) -> Self {
        Scope {
            nesting: 0,
            closing: "the end of the input",
            commas: false,
            input_end: last_token,
        }
    }

    /// Inside a group with `delimiter`; `commas` says whether `,` separates
    /// its contents.
    pub(super) fn inside(self, delimiter: Delimiter, commas: bool) -> Self {
        let closing = match delimiter {
            Delimiter::Parenthesis => "`)`",
            Delimiter::Bracket => "`]`",
            Delimiter::Brace => "`}`",
            Delimiter::None => "the end of the interpolated expression",
        };
        Scope {
            closing,
            commas,
            input_end: None,
            ..self
        }
    }

    /// One level deeper, or an error at the next token past [`MAX_NESTING`].
    pub(super) fn deeper(self, input: ParseStream) -> Result<Self> {
        if self.nesting >= MAX_NESTING {
            return Err(too_deep(self.next_span(input)));
        }
        Ok(Scope {
            nesting: self.nesting + 1,
            ..self
        })
    }

    /// Whether `,` separates what is parsed here.
    pub(super) fn commas(self) -> bool {
        self.commas
    }

    /// The next token's span, or the end of the group.
    pub(super) fn next_span(self, input: ParseStream) -> Span {
        match input.cursor().token_tree() {
            Some((token, _)) => token.span(),
            None => self.input_end.unwrap_or_else(|| input.span()),
        }
    }

    /// The next token as "found ..." names it: "`name`", "`(`", "`]`".
    pub(super) fn found(self, input: ParseStream) -> String {
        match input.cursor().token_tree() {
            Some((token, _)) => describe(&token),
            None => self.closing.to_owned(),
        }
    }

    /// "expected {what}, found {the next token}", at the next token.
    pub(super) fn expected(self, input: ParseStream, what: &str) -> Error {
        let message = format!("expected {what}, found {}", self.found(input));
        Error::new(self.next_span(input), message)
    }

    /// The lookahead's "expected one of ..." at the next token, with what
    /// was found there.
    pub(super) fn unexpected(self, input: ParseStream, lookahead: Lookahead1) -> Error {
        let message = format!("{}, found {}", lookahead.error(), self.found(input));
        Error::new(self.next_span(input), message)
    }
}

/// A token as error messages name it: "`name`", "`;`", "`1.0f64`", "`(`".
fn describe(token: &TokenTree) -> String {
    match token {
        TokenTree::Group(group) => match group.delimiter() {
            Delimiter::Parenthesis => "`(`".to_owned(),
            Delimiter::Bracket => "`[`".to_owned(),
            Delimiter::Brace => "`{`".to_owned(),
            Delimiter::None => format!("`{}`", group.stream()),
        },
        other => format!("`{other}`"),
    }
}

/// Errors collected while parsing goes on past them, combined into one
/// [`syn::Error`] so that all are reported at once.
#[derive(Default)]
pub(super) struct Errors(Option<Error>);

impl Errors {
    /// Records one more error.
    pub(super) fn push(&mut self, error: Error) {
        match &mut self.0 {
            Some(errors) => errors.combine(error),
            None => self.0 = Some(error),
        }
    }

    /// The value of `result`, or `None` after recording its error.
    pub(super) fn keep<T>(&mut self, result: Result<T>) -> Option<T> {
        result.map_err(|error| self.push(error)).ok()
    }

    /// `Ok(value)` when nothing was recorded, otherwise every error.
    pub(super) fn finish<T>(self, value: T) -> Result<T> {
        match self.0 {
            Some(errors) => Err(errors),
            None => Ok(value),
        }
    }

    /// Every recorded error followed by `last`.
    pub(super) fn fail<T>(self, last: Error) -> Result<T> {
        Err(match self.0 {
            Some(mut errors) => {
                errors.combine(last);
                errors
            }
            None => last,
        })
    }
}
