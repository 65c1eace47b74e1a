//! `chaplygin derive`: the derivation document of a model (the
//! constraint analysis, the Lagrange-d'Alembert equations, the reduced
//! port-Hamiltonian form, the momentum equation with a symmetry, the
//! report) as text, LaTeX or JSON, from `chaplygin_codegen::document`.

use crate::catalog;
use chaplygin_codegen::document::{self, derive_document};
use std::error::Error;

/// The document's format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// Plain text.
    Text,
    /// LaTeX.
    Latex,
    /// JSON.
    Json,
}

impl From<Format> for document::Format {
    fn from(format: Format) -> Self {
        match format {
            Format::Text => document::Format::Text,
            Format::Latex => document::Format::Latex,
            Format::Json => document::Format::Json,
        }
    }
}

/// A model rejected by the compiler: its diagnostics, `file:line:col: error: ...`.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct Rejected(pub String);

/// The document of `model` (a built-in name or a `.model` path).
///
/// # Errors
/// An unknown model, or the model's diagnostics.
pub fn document(model: &str, format: Format) -> Result<String, Box<dyn Error>> {
    let source = catalog::lookup(model)?;
    derive_document(source.text(), format.into()).map_err(|diagnostics| {
        Rejected(
            diagnostics
                .render(&source.file_name())
                .trim_end()
                .to_string(),
        )
        .into()
    })
}
