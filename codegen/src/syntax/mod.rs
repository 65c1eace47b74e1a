//! The model language's grammar: tokens in, a spanned syntax tree out.
//!
//! This stage is a pure grammar. It does not know which sections exist or
//! what shape each must have; the check stage decides that (and reports
//! unknown or missing sections). The same grammar serves both doors: the
//! tokens of a `chaplygin::model! { ... }` invocation ([`parse`]) and the
//! text of a `.model` file ([`parse_str`]).
//!
//! ```text
//! model      = attribute* visibility? "struct" IDENT "{" sections "}" ;
//! attribute  = "#" "[" ... "]" ;           (* `///` doc comments included *)
//! visibility = "pub" ( "(" ... ")" )? ;
//! sections   = ( section ( "," section )* ","? )? ;
//! section    = IDENT ":" value ;
//! value      = list | expr ;
//! list       = "[" ( item ( "," item )* ","? )? "]" ;
//! item       = IDENT "=" value | value ;
//! expr       = term ( ( "+" | "-" ) term )* ;         (* left-assoc *)
//! term       = unary ( ( "*" | "/" ) unary )* ;       (* left-assoc *)
//! unary      = "-" unary | power ;
//! power      = field ( "^" unary )? ;                 (* right-assoc *)
//! field      = operand ( "." IDENT )* ;               (* `ground.x` *)
//! operand    = NUMBER | IDENT | IDENT "(" arguments ")" | "(" expr ")" ;
//! arguments  = ( argument ( "," argument )* ","? )? ;
//! argument   = IDENT "=" value | value ;         (* keyword or positional *)
//! NUMBER     = untyped decimal literal: 2, 0.5, 1e-3, 1.5E2 ;
//! ```
//!
//! So `-x^2` is `-(x^2)`, `x^-1` is `x^(-1)`, `2^-3^2` is `2^(-(3^2))`,
//! `a*b^c^d` is `a*(b^(c^d))`, `a-b-c` is `(a-b)-c`, `2*-x` is `2*(-x)`,
//! `-r*lean.z^2` is `(-r)*((lean.z)^2)`.
//!
//! The grammar is written on syn: every syntax tree type implements
//! [`syn::parse::Parse`], comma-separated runs are [`syn::punctuated`]
//! lists, and what may follow an operand is named by a
//! [`syn::parse::Lookahead1`] ("expected one of: `+`, ..."). Sections, list
//! items and call arguments are parsed independently and their
//! [`syn::Error`]s combined, so all of their errors are reported together;
//! each becomes a [`Diagnostic`] spanned on the offending token.

mod ast;
mod expr;
mod literal;
mod model;
mod scope;
mod separated;

#[cfg(test)]
mod tests;

use proc_macro2::{LexError, TokenStream};

pub use ast::{Attribute, BinaryOperator, Expr, Item, Keyword, List, ModelSyntax, Section, Value};
pub use expr::MAX_EXPRESSION_DEPTH;

use crate::diagnostic::{Diagnostic, Diagnostics};

/// Parses the tokens of a `chaplygin::model! { ... }` invocation.
///
/// Groups nested too deeply are rejected before syn buffers the tokens
/// (which recurses into groups); then the tokens are parsed as a
/// [`ModelSyntax`] and every error becomes a [`Diagnostic`] at its span.
pub fn parse(tokens: TokenStream) -> Result<ModelSyntax, Diagnostics> {
    scope::check_group_depth(&tokens)
        .and_then(|()| syn::parse2(tokens))
        .map_err(diagnostics)
}

/// Parses the text of a `.model` file. Spans carry the file's lines and
/// columns, so [`Diagnostics::render`] can report them.
pub fn parse_str(source: &str) -> Result<ModelSyntax, Diagnostics> {
    match source.parse::<TokenStream>() {
        Ok(tokens) => parse(tokens),
        Err(error) => Err(lex_error(source, &error).into()),
    }
}

/// One diagnostic per message of a (combined) syn error, at its span.
fn diagnostics(error: syn::Error) -> Diagnostics {
    error
        .into_iter()
        .map(|error| Diagnostic::new(error.span(), error.to_string()))
        .collect()
}

/// Explains a lexing failure, judging by the character it stopped at.
fn lex_error(source: &str, error: &LexError) -> Diagnostic {
    let start = error.span().start();
    let character = start
        .line
        .checked_sub(1)
        .and_then(|line| source.lines().nth(line))
        .and_then(|line| line.chars().nth(start.column));
    let message = match character {
        Some(open @ ('(' | '[' | '{')) => {
            format!("unclosed delimiter `{open}`: it has no matching closing delimiter")
        }
        Some(close @ (')' | ']' | '}')) => format!(
            "unmatched closing delimiter `{close}`: it does not close the innermost open delimiter"
        ),
        Some(other) => format!(
            "cannot read the model text at `{other}`: expected Rust tokens \
             (an unterminated string or comment, or a character Rust does not allow)"
        ),
        None => "cannot read the model text: expected Rust tokens".to_owned(),
    };
    Diagnostic::new(error.span(), message)
}
