//! Walking a flat run of token trees: a cursor, comma splitting, and the
//! wording of "found ..." in error messages.

use proc_macro2::{Delimiter, Span, TokenTree};

/// What comes right after a run of tokens: a separating `,`, a closing
/// delimiter, or the end of the input. Errors about a missing token point
/// at it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Boundary {
    /// The span to blame when the run ends too early.
    pub(super) span: Span,
    /// How to name it in "found ..." (for example "`,`").
    pub(super) description: &'static str,
}

impl Boundary {
    /// A separating comma.
    pub(super) fn comma(span: Span) -> Self {
        Boundary {
            span,
            description: "`,`",
        }
    }

    /// The closing delimiter of a group with the given delimiter.
    pub(super) fn closing(delimiter: Delimiter, span: Span) -> Self {
        let description = match delimiter {
            Delimiter::Parenthesis => "`)`",
            Delimiter::Bracket => "`]`",
            Delimiter::Brace => "`}`",
            Delimiter::None => "the end of the interpolated expression",
        };
        Boundary { span, description }
    }

    /// The end of the whole input; `span` is its last token, if any.
    pub(super) fn end_of_input(span: Span) -> Self {
        Boundary {
            span,
            description: "the end of the input",
        }
    }
}

/// A position in a run of token trees that ends at a [`Boundary`].
pub(super) struct Cursor<'a> {
    tokens: &'a [TokenTree],
    position: usize,
    end: Boundary,
}

impl<'a> Cursor<'a> {
    pub(super) fn new(tokens: &'a [TokenTree], end: Boundary) -> Self {
        Cursor {
            tokens,
            position: 0,
            end,
        }
    }

    /// The tokens not consumed yet.
    pub(super) fn rest(&self) -> &'a [TokenTree] {
        &self.tokens[self.position..]
    }

    pub(super) fn peek(&self) -> Option<&'a TokenTree> {
        self.rest().first()
    }

    /// Consumes and returns the next token.
    pub(super) fn next_token(&mut self) -> Option<&'a TokenTree> {
        let token = self.peek()?;
        self.position += 1;
        Some(token)
    }

    pub(super) fn is_at_end(&self) -> bool {
        self.rest().is_empty()
    }

    /// Whether the next token is the punctuation `character`.
    pub(super) fn peek_punct(&self, character: char) -> bool {
        self.peek().is_some_and(|token| is_punct(token, character))
    }

    /// Whether the next token is the identifier `word`.
    pub(super) fn peek_ident(&self, word: &str) -> bool {
        matches!(self.peek(), Some(TokenTree::Ident(ident)) if ident == word)
    }

    /// The next token's span, or the boundary's when nothing is left.
    pub(super) fn span(&self) -> Span {
        self.peek().map_or(self.end.span, TokenTree::span)
    }

    /// The next token as "found ..." should name it.
    pub(super) fn found(&self) -> String {
        self.peek()
            .map_or_else(|| self.end.description.to_owned(), describe)
    }
}

/// Whether `token` is the punctuation `character`.
pub(super) fn is_punct(token: &TokenTree, character: char) -> bool {
    matches!(token, TokenTree::Punct(punct) if punct.as_char() == character)
}

/// A token as error messages name it: "`name`", "`;`", "`1.0f64`", "`(`".
pub(super) fn describe(token: &TokenTree) -> String {
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

/// A comma-free run of tokens and what ends it.
pub(super) struct Chunk<'a> {
    pub(super) tokens: &'a [TokenTree],
    pub(super) end: Boundary,
}

impl Chunk<'_> {
    pub(super) fn cursor(&self) -> Cursor<'_> {
        Cursor::new(self.tokens, self.end)
    }
}

/// Splits a group's tokens at its top-level commas. Every chunk but the last
/// ends at a comma; the last ends at `close` and is empty after a trailing
/// comma or in an empty group.
pub(super) fn split_at_commas(tokens: &[TokenTree], close: Boundary) -> Vec<Chunk<'_>> {
    let mut chunks = Vec::new();
    let mut start = 0;
    for (index, token) in tokens.iter().enumerate() {
        if is_punct(token, ',') {
            chunks.push(Chunk {
                tokens: &tokens[start..index],
                end: Boundary::comma(token.span()),
            });
            start = index + 1;
        }
    }
    chunks.push(Chunk {
        tokens: &tokens[start..],
        end: close,
    });
    chunks
}
