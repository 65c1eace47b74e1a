//! The frame of a model: doc comments and attributes, the visibility,
//! `struct Name`, and the braced body of `key: value` sections.

use proc_macro2::{Delimiter, Group, Ident, Span, TokenStream};
use quote::ToTokens;
use syn::ext::IdentExt;
use syn::parse::{Parse, ParseStream};
use syn::{Error, LitStr, Result, Token, Visibility, braced, bracketed, token};

use super::ast::{Attribute, ModelSyntax, Section};
use super::expr::parse_value;
use super::scope::{Errors, Scope};
use super::separated::parse_comma_separated;

mod keyword {
    syn::custom_keyword!(doc);
}

/// Everything before the body.
struct Header {
    docs: Vec<String>,
    attributes: Vec<Attribute>,
    visibility: TokenStream,
    name: Ident,
}

/// `#[attributes] visibility struct Name { sections }`, with every error in
/// the attributes and the sections reported together.
impl Parse for ModelSyntax {
    fn parse(input: ParseStream) -> Result<Self> {
        let scope = Scope::outermost(last_token_span(input));
        let mut errors = Errors::default();
        let header = match parse_header(input, scope, &mut errors) {
            Ok(header) => header,
            Err(error) => return errors.fail(error),
        };
        if !input.peek(token::Brace) {
            let what = format!(
                "`{{` and the model's sections after `struct {}`",
                header.name
            );
            return errors.fail(scope.expected(input, &what));
        }
        let body;
        braced!(body in input);
        let sections = errors.keep(parse_sections(&body, scope));
        if !input.is_empty() {
            let message = format!(
                "unexpected tokens after the model's closing brace: found {}",
                scope.found(input)
            );
            errors.push(Error::new(scope.next_span(input), message));
            input.parse::<TokenStream>()?;
        }
        errors.finish(ModelSyntax {
            docs: header.docs,
            attributes: header.attributes,
            visibility: header.visibility,
            name: header.name,
            sections: sections.unwrap_or_default(),
        })
    }
}

/// The span of the input's last token, if any.
fn last_token_span(input: ParseStream) -> Option<Span> {
    let mut cursor = input.cursor();
    let mut last = None;
    while let Some((token, rest)) = cursor.token_tree() {
        last = Some(token.span());
        cursor = rest;
    }
    last
}

/// Attributes, visibility and `struct Name`. Errors in single attributes
/// are recorded in `errors` and parsing goes on.
fn parse_header(input: ParseStream, scope: Scope, errors: &mut Errors) -> Result<Header> {
    let mut docs = Vec::new();
    let mut attributes = Vec::new();
    while input.peek(Token![#]) {
        match errors.keep(parse_outer_attribute(input, scope)) {
            Some(OuterAttribute::Doc(text)) => docs.push(text),
            Some(OuterAttribute::Other(attribute)) => attributes.push(attribute),
            None => {}
        }
    }
    let visibility = input.parse::<Visibility>()?.into_token_stream();
    if !input.peek(Token![struct]) {
        return Err(scope.expected(input, "`struct Name { ... }`"));
    }
    input.parse::<Token![struct]>()?;
    if !input.peek(Ident::peek_any) {
        return Err(scope.expected(input, "the model's name after `struct`"));
    }
    Ok(Header {
        docs,
        attributes,
        visibility,
        name: input.call(Ident::parse_any)?,
    })
}

/// An attribute before `struct`.
enum OuterAttribute {
    /// A doc comment (`/// text`) or `#[doc = "text"]`: its text.
    Doc(String),
    /// Any other attribute.
    Other(Attribute),
}

/// `#[doc = "text"]` or `#[name tokens...]`. Inner attributes (`#![...]`,
/// `//!`) are errors, consumed whole so that parsing can go on.
fn parse_outer_attribute(input: ParseStream, scope: Scope) -> Result<OuterAttribute> {
    input.parse::<Token![#]>()?;
    if input.peek(Token![!]) {
        let message = "inner attributes and `//!` comments are not allowed in the model; \
                       document the model with `///` before `struct`";
        let error = Error::new(scope.next_span(input), message);
        input.parse::<Token![!]>()?;
        if input.peek(token::Bracket) {
            input.parse::<Group>()?;
        }
        return Err(error);
    }
    if !input.peek(token::Bracket) {
        return Err(scope.expected(input, "`[` after `#` to start an attribute"));
    }
    let content;
    let brackets = bracketed!(content in input);
    if content.peek(keyword::doc) && content.peek2(Token![=]) {
        return parse_doc(&content, brackets.span.join()).map(OuterAttribute::Doc);
    }
    content.parse().map(OuterAttribute::Other)
}

/// The text of `doc = "text"` inside `#[...]` (which spans `span`).
fn parse_doc(content: ParseStream, span: Span) -> Result<String> {
    content.parse::<keyword::doc>()?;
    content.parse::<Token![=]>()?;
    match content.parse::<LitStr>() {
        Ok(text) if content.is_empty() => Ok(text.value()),
        _ => {
            content.parse::<TokenStream>()?;
            let message = "expected a string literal in `#[doc = \"...\"]`";
            Err(Error::new(span, message))
        }
    }
}

/// The inside of `#[...]`: a name and any tokens after it.
impl Parse for Attribute {
    fn parse(input: ParseStream) -> Result<Self> {
        if !input.peek(Ident::peek_any) {
            let scope = Scope::outermost(None).inside(Delimiter::Bracket, false);
            return Err(scope.expected(input, "an attribute name inside `#[...]`"));
        }
        Ok(Attribute {
            name: input.call(Ident::parse_any)?,
            tokens: input.parse()?,
        })
    }
}

/// The comma-separated sections of the body, each parsed on its own.
fn parse_sections(body: ParseStream, scope: Scope) -> Result<Vec<Section>> {
    let scope = scope.inside(Delimiter::Brace, true);
    let empty = "empty section: expected `name: value` before this `,`";
    let sections = parse_comma_separated(body, empty, |section| parse_section(section, scope))?;
    Ok(sections.into_iter().collect())
}

/// `key: value` filling the whole input.
impl Parse for Section {
    fn parse(input: ParseStream) -> Result<Self> {
        parse_section(input, Scope::outermost(None))
    }
}

/// `key: value`; doc comments or attributes before it are reported, and
/// the section is still parsed.
fn parse_section(input: ParseStream, scope: Scope) -> Result<Section> {
    let mut errors = Errors::default();
    if input.peek(Token![#]) {
        let message = "doc comments and attributes are only allowed before `struct`; \
                       use `//` comments inside the model";
        errors.push(Error::new(scope.next_span(input), message));
        skip_attributes(input)?;
    }
    match parse_key_and_value(input, scope) {
        Ok(section) => errors.finish(section),
        Err(error) => errors.fail(error),
    }
}

/// Skips `#[...]`, `#![...]` and stray `#`s.
fn skip_attributes(input: ParseStream) -> Result<()> {
    while input.peek(Token![#]) {
        input.parse::<Token![#]>()?;
        input.parse::<Option<Token![!]>>()?;
        if input.peek(token::Bracket) {
            input.parse::<Group>()?;
        }
    }
    Ok(())
}

fn parse_key_and_value(input: ParseStream, scope: Scope) -> Result<Section> {
    if !input.peek(Ident::peek_any) {
        return Err(scope.expected(input, "a section name such as `coordinates`"));
    }
    let key = input.call(Ident::parse_any)?;
    if !input.peek(Token![:]) {
        return Err(scope.expected(input, &format!("`:` after the section name `{key}`")));
    }
    input.parse::<Token![:]>()?;
    let (value, _) = parse_value(input, scope, &format!("a value after `{key}:`"))?;
    Ok(Section { key, value })
}
