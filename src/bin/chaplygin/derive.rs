//! `chaplygin derive`: the derivation document of a model (the
//! constraint analysis, the Lagrange-d'Alembert equations, the reduced
//! port-Hamiltonian form, the momentum equation with a symmetry, the
//! report) as text, LaTeX or JSON, from `chaplygin_codegen::document`.
//! For a model declared as a mechanism, the text also shows what the
//! mechanism sections derived: the bodies' `T` and `V`, the rolling-contact
//! rows and the holonomic constraints.

use crate::catalog;
use chaplygin_codegen::diagnostic::Diagnostics;
use chaplygin_codegen::document::{self, derive_document};
use chaplygin_codegen::model::{Model, check};
use chaplygin_codegen::sym::RationalFunction;
use chaplygin_codegen::syntax::parse_str;
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
    let rejected = |diagnostics: Diagnostics| -> Box<dyn Error> {
        Rejected(
            diagnostics
                .render(&source.file_name())
                .trim_end()
                .to_string(),
        )
        .into()
    };
    let text = derive_document(source.text(), format.into()).map_err(rejected)?;
    if format != Format::Text {
        return Ok(text);
    }
    let syntax = parse_str(source.text()).map_err(rejected)?;
    let mut checked = check(&syntax).map_err(rejected)?;
    if !checked.mechanism.is_declared() {
        return Ok(text);
    }
    let mechanism = mechanism_section(&mut checked);
    Ok(match text.find(BEFORE_MECHANISM) {
        Some(at) => format!("{}\n\n{mechanism}{}", &text[..at], &text[at..]),
        None => format!("{text}\n{mechanism}"),
    })
}

/// The heading the mechanism section is printed before.
const BEFORE_MECHANISM: &str = "\n\nConstraint analysis";

/// What the mechanism sections derived, as text.
fn mechanism_section(model: &mut Model) -> String {
    let mechanism = model.mechanism.clone();
    let (n, rows) = (model.n(), model.constraint_matrix.clone());
    let first_contact = model.c() - mechanism.contacts.len() - mechanism.holonomic.len();
    let names = |declared: &[chaplygin_codegen::model::Declared]| {
        let names: Vec<&str> = declared.iter().map(|d| d.name.as_str()).collect();
        if names.is_empty() {
            "none".to_string()
        } else {
            names.join(", ")
        }
    };
    let mut printed = |form: &RationalFunction| {
        let expression = model.store.expression_of(form);
        model.store.display(expression).to_string()
    };
    let mut lines = vec![
        "Mechanism (frames, bodies, contacts)".to_string(),
        format!("  frames: {}", names(&mechanism.frames)),
        format!("  points: {}", names(&mechanism.points)),
        format!("  T of the bodies = {}", printed(&mechanism.kinetic_energy)),
        format!(
            "  V of the bodies = {}",
            printed(&mechanism.potential_energy)
        ),
    ];
    lines.push("  rolling contacts (A_i qdot = 0, rows of A):".to_string());
    if mechanism.contacts.is_empty() {
        lines.push("    none".to_string());
    }
    for (offset, contact) in mechanism.contacts.iter().enumerate() {
        let row = first_contact + offset;
        let entries: Vec<String> = (0..n).map(|j| printed(rows.get(row, j))).collect();
        lines.push(format!("    {}: [{}]", contact.name, entries.join(", ")));
    }
    lines.push("  holonomic constraints f(q) = 0:".to_string());
    if mechanism.holonomic.is_empty() {
        lines.push("    none".to_string());
    }
    for (i, holonomic) in mechanism.holonomic.iter().enumerate() {
        let residual = printed(mechanism.holonomic_residual.get(i, 0));
        lines.push(format!("    {}: {residual}", holonomic.name));
    }
    lines.join("\n")
}
