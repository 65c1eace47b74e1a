//! Spanned error messages shared by every stage of the compiler.
//!
//! A [`Diagnostic`] is one rejected piece of input: a span on the offending
//! token and a message that states the rule and what was found. Stages collect
//! them into [`Diagnostics`] so that all errors of one model are reported at
//! once, then hand them to one of the two doors:
//!
//! - the `model!` macro turns them into `compile_error!` invocations spanned
//!   on the offending tokens ([`Diagnostics::to_compile_errors`]);
//! - the build-script door prints `file:line:column: error: message` lines
//!   ([`Diagnostics::render`]).

use std::fmt;

use proc_macro2::{Span, TokenStream};
use quote::quote_spanned;

/// One error: where it is and what is wrong.
#[derive(Debug, Clone)]
pub struct Diagnostic {
    /// The offending token (or the closest token to a missing one).
    pub span: Span,
    /// States the rule that was broken and, where useful, what was found.
    pub message: String,
}

impl Diagnostic {
    /// An error at `span` with the given message.
    pub fn new(span: Span, message: impl Into<String>) -> Self {
        Diagnostic {
            span,
            message: message.into(),
        }
    }

    /// `file:LINE:COLUMN: error: message`, with a 1-based column.
    ///
    /// A span without a location (such as `Span::call_site()` outside a
    /// procedural macro) is reported at line 1, column 1.
    fn render_line(&self, file: &str) -> String {
        let start = self.span.start();
        let line = start.line.max(1);
        let column = start.column + 1;
        format!("{file}:{line}:{column}: error: {}", self.message)
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        formatter.write_str(&self.message)
    }
}

/// All errors found in one model, in the order they were found.
#[derive(Debug, Clone, Default)]
pub struct Diagnostics(Vec<Diagnostic>);

impl Diagnostics {
    /// An error of the generator itself, reported at `span` (the model's name).
    pub(crate) fn internal(span: Span, error: impl fmt::Display) -> Diagnostics {
        Diagnostic::new(
            span,
            format!("internal error while generating code for this model: {error}"),
        )
        .into()
    }

    /// No errors yet.
    pub fn new() -> Self {
        Diagnostics(Vec::new())
    }

    /// Records one more error.
    pub fn push(&mut self, diagnostic: Diagnostic) {
        self.0.push(diagnostic);
    }

    /// Records an error at `span` with the given message.
    pub fn error(&mut self, span: Span, message: impl Into<String>) {
        self.push(Diagnostic::new(span, message));
    }

    /// Whether no error has been recorded.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// How many errors have been recorded.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// The recorded errors, in order.
    pub fn iter(&self) -> std::slice::Iter<'_, Diagnostic> {
        self.0.iter()
    }

    /// `Ok(value)` when no error was recorded, otherwise `Err(self)`.
    pub fn into_result<T>(self, value: T) -> Result<T, Diagnostics> {
        if self.is_empty() {
            Ok(value)
        } else {
            Err(self)
        }
    }

    /// One `::core::compile_error!{ "message" }` per error, spanned on the
    /// offending token so that rustc points at it.
    pub fn to_compile_errors(&self) -> TokenStream {
        self.iter()
            .map(|diagnostic| {
                let message = &diagnostic.message;
                quote_spanned! {diagnostic.span=> ::core::compile_error!{ #message } }
            })
            .collect()
    }

    /// One `file:LINE:COLUMN: error: message` line per error (1-based line
    /// and column, each line ending with `\n`), for errors in a model file.
    pub fn render(&self, file: &str) -> String {
        self.iter()
            .map(|diagnostic| diagnostic.render_line(file) + "\n")
            .collect()
    }
}

impl From<Diagnostic> for Diagnostics {
    fn from(diagnostic: Diagnostic) -> Self {
        Diagnostics(vec![diagnostic])
    }
}

impl Extend<Diagnostic> for Diagnostics {
    fn extend<I: IntoIterator<Item = Diagnostic>>(&mut self, diagnostics: I) {
        self.0.extend(diagnostics);
    }
}

impl FromIterator<Diagnostic> for Diagnostics {
    fn from_iter<I: IntoIterator<Item = Diagnostic>>(diagnostics: I) -> Self {
        Diagnostics(diagnostics.into_iter().collect())
    }
}

impl IntoIterator for Diagnostics {
    type Item = Diagnostic;
    type IntoIter = std::vec::IntoIter<Diagnostic>;

    fn into_iter(self) -> Self::IntoIter {
        self.0.into_iter()
    }
}

impl<'a> IntoIterator for &'a Diagnostics {
    type Item = &'a Diagnostic;
    type IntoIter = std::slice::Iter<'a, Diagnostic>;

    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

/// The messages, one per line.
impl fmt::Display for Diagnostics {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (index, diagnostic) in self.iter().enumerate() {
            if index > 0 {
                formatter.write_str("\n")?;
            }
            write!(formatter, "{diagnostic}")?;
        }
        Ok(())
    }
}

impl std::error::Error for Diagnostics {}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_errors() -> Diagnostics {
        let mut diagnostics = Diagnostics::new();
        diagnostics.error(Span::call_site(), "first rule broken");
        diagnostics.push(Diagnostic::new(Span::call_site(), "second rule broken"));
        diagnostics
    }

    #[test]
    fn into_result_is_ok_only_without_errors() {
        assert_eq!(Diagnostics::new().into_result(7).ok(), Some(7));
        let error = two_errors().into_result(7).err();
        assert_eq!(error.map(|diagnostics| diagnostics.len()), Some(2));
    }

    #[test]
    fn display_lists_messages_one_per_line() {
        assert_eq!(
            two_errors().to_string(),
            "first rule broken\nsecond rule broken"
        );
    }

    #[test]
    fn compile_errors_hold_one_invocation_per_diagnostic() {
        let text = two_errors().to_compile_errors().to_string();
        assert_eq!(text.matches("compile_error").count(), 2);
        assert!(text.contains(":: core :: compile_error ! { \"first rule broken\" }"));
    }

    #[test]
    fn render_without_location_uses_line_one_column_one() {
        assert_eq!(
            Diagnostics::from(Diagnostic::new(Span::call_site(), "oops")).render("m.model"),
            "m.model:1:1: error: oops\n"
        );
    }

    #[test]
    fn iteration_and_collection_round_trip() {
        let collected: Diagnostics = two_errors().into_iter().collect();
        let messages: Vec<&str> = collected.iter().map(|d| d.message.as_str()).collect();
        assert_eq!(messages, ["first rule broken", "second rule broken"]);
        assert!(!collected.is_empty());
        assert_eq!((&collected).into_iter().count(), 2);
    }
}
