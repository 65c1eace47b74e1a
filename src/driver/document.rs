//! The derivation document of a model (the
//! constraint analysis, the Lagrange-d'Alembert equations, the reduced
//! port-Hamiltonian form, the momentum equation with a symmetry, the
//! report) as text, LaTeX or JSON, from `chaplygin_codegen::document`; or
//! the Rust the model compiles to.
//! For a model declared as a mechanism, each format also shows what the
//! mechanism sections derived (docs/INTERFACE.md section 4): the frames and
//! points, the bodies' `T` and `V`, the rolling-contact rows of `A(q)` and
//! the holonomic constraints `f(q)`; as a section before the constraint
//! analysis in text and LaTeX, as the `mechanism` object in JSON:
//!
//! ```text
//! "mechanism": {"frames": [..], "points": [..],
//!               "kinetic_energy": {"text", "latex"}, "potential_energy": {..},
//!               "contacts": {NAME: {"text": [..], "latex": [..]}, ..},
//!               "holonomic": {NAME: {"text", "latex"}, ..}}
//! ```

use super::catalog::Source;
use crate::driver::Failure;
use crate::jit::Native;
use chaplygin_codegen::diagnostic::Diagnostics;
use chaplygin_codegen::document::{self, derive_document};
use chaplygin_codegen::interpret::{Backend, Interpreter};
use chaplygin_codegen::model::{Declared, Model, check};
use chaplygin_codegen::sym::{Context, RationalFunction};
use chaplygin_codegen::syntax::parse_str;
use serde_json::{Map, Value, json};

/// The document's format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Format {
    /// Plain text.
    Text,
    /// LaTeX.
    Latex,
    /// JSON.
    Json,
    /// The Rust that `chaplygin::model!` and the build script compile for
    /// the model, formatted.
    Rust,
}

/// A model rejected by the compiler: its diagnostics rendered
/// (`file:line:col: error: ...`), and the first one's place and message.
#[derive(Debug, thiserror::Error)]
#[error("{rendered}")]
pub struct Rejected {
    /// Every diagnostic, one `file:line:col: error: message` each with its
    /// source line.
    pub rendered: String,
    /// The first diagnostic's line, from 1.
    pub line: usize,
    /// The first diagnostic's column, from 1.
    pub column: usize,
    /// The first diagnostic's message.
    pub message: String,
}

impl Rejected {
    /// The `diagnostics` of the model text called `file`.
    pub fn new(file: &str, diagnostics: &Diagnostics) -> Self {
        let first = diagnostics.iter().next();
        let start = first.map(|diagnostic| diagnostic.span.start());
        Self {
            rendered: diagnostics.render(file).trim_end().to_string(),
            line: start.map_or(0, |start| start.line.max(1)),
            column: start.map_or(0, |start| start.column + 1),
            message: first.map_or_else(String::new, |diagnostic| diagnostic.message.clone()),
        }
    }
}

/// The derivation document of the model in `source`, its numeric searches
/// run as native code where Cranelift supports the host (the same numbers
/// as the interpreter's).
///
/// # Errors
/// The model's diagnostics ([`Rejected`]).
pub fn document(source: &Source, format: Format) -> Result<String, Failure> {
    let rejected = |diagnostics: Diagnostics| -> Failure {
        Rejected::new(&source.file_name(), &diagnostics).into()
    };
    let document_format = match format {
        Format::Text => document::Format::Text,
        Format::Latex => document::Format::Latex,
        Format::Json => document::Format::Json,
        Format::Rust => return chaplygin_codegen::generate(source.text()).map_err(rejected),
    };
    let native = Native::for_host().ok();
    let backend: &dyn Backend = match &native {
        Some(native) => native,
        None => &Interpreter,
    };
    let text = derive_document(source.text(), document_format, backend).map_err(rejected)?;
    let syntax = parse_str(source.text()).map_err(rejected)?;
    let (model, mut cx) = check(&syntax).map_err(rejected)?;
    if !model.mechanism.is_declared() {
        return Ok(text);
    }
    let mechanism = MechanismSection::of(&model, &mut cx);
    Ok(match format {
        Format::Text => before(&text, "\n\nConstraint analysis", &mechanism.text(), "\n\n"),
        Format::Latex => before(
            &text,
            "\n\\section*{Constraint analysis",
            &mechanism.latex(),
            "\n",
        ),
        Format::Json => mechanism.json(&text)?,
        Format::Rust => text,
    })
}

/// `text` with `section` inserted before `heading` (at the end without
/// it), `separator` in front.
fn before(text: &str, heading: &str, section: &str, separator: &str) -> String {
    match text.find(heading) {
        Some(at) => format!("{}{separator}{section}{}", &text[..at], &text[at..]),
        None => format!("{text}{separator}{section}\n"),
    }
}

/// An expression printed as text and as LaTeX.
struct Printed {
    text: String,
    latex: String,
}

impl Printed {
    fn json(&self) -> Value {
        json!({"text": self.text, "latex": self.latex})
    }
}

/// What the mechanism sections derived, printed.
struct MechanismSection {
    frames: Vec<String>,
    points: Vec<String>,
    kinetic_energy: Printed,
    potential_energy: Printed,
    /// Each rolling-contact row of `A(q)`, by name.
    contacts: Vec<(String, Vec<Printed>)>,
    /// Each holonomic constraint's `f(q)`, by name.
    holonomic: Vec<(String, Printed)>,
}

impl MechanismSection {
    /// The section of a checked model declared as a mechanism, its
    /// expressions in `cx`.
    fn of(model: &Model, cx: &mut Context) -> Self {
        let mechanism = &model.mechanism;
        let (n, rows) = (model.n(), &model.constraint_matrix);
        let first_contact = model.c() - mechanism.contacts.len() - mechanism.holonomic.len();
        let names = |declared: &[Declared]| declared.iter().map(|d| d.name.clone()).collect();
        let mut printed = |form: &RationalFunction| {
            let expression = cx.expression_of(form);
            Printed {
                text: cx.display(expression).to_string(),
                latex: cx.latex(expression),
            }
        };
        let contacts = (mechanism.contacts.iter().enumerate())
            .map(|(offset, contact)| {
                let row = first_contact + offset;
                let entries = (0..n).map(|j| printed(rows.get(row, j))).collect();
                (contact.name.clone(), entries)
            })
            .collect();
        let holonomic = (mechanism.holonomic.iter().enumerate())
            .map(|(i, h)| {
                (
                    h.name.clone(),
                    printed(mechanism.holonomic_residual.get(i, 0)),
                )
            })
            .collect();
        MechanismSection {
            frames: names(&mechanism.frames),
            points: names(&mechanism.points),
            kinetic_energy: printed(&mechanism.kinetic_energy),
            potential_energy: printed(&mechanism.potential_energy),
            contacts,
            holonomic,
        }
    }

    /// The section as text.
    fn text(&self) -> String {
        let listed = |names: &[String]| match names.is_empty() {
            true => "none".to_string(),
            false => names.join(", "),
        };
        let mut lines = vec![
            "Mechanism (frames, bodies, contacts)".to_string(),
            format!("  frames: {}", listed(&self.frames)),
            format!("  points: {}", listed(&self.points)),
            format!("  T of the bodies = {}", self.kinetic_energy.text),
            format!("  V of the bodies = {}", self.potential_energy.text),
            "  rolling contacts (A_i qdot = 0, rows of A):".to_string(),
        ];
        if self.contacts.is_empty() {
            lines.push("    none".to_string());
        }
        for (name, row) in &self.contacts {
            let entries: Vec<&str> = row.iter().map(|e| e.text.as_str()).collect();
            lines.push(format!("    {name}: [{}]", entries.join(", ")));
        }
        lines.push("  holonomic constraints f(q) = 0:".to_string());
        if self.holonomic.is_empty() {
            lines.push("    none".to_string());
        }
        for (name, residual) in &self.holonomic {
            lines.push(format!("    {name}: {}", residual.text));
        }
        lines.join("\n")
    }

    /// The section as LaTeX, a `\section*` of the derivation document.
    fn latex(&self) -> String {
        let listed = |names: &[String]| match names.is_empty() {
            true => "none".to_string(),
            false => escaped(&names.join(", ")),
        };
        let mut out = vec![
            "\\section*{Mechanism (frames, bodies, contacts)}".to_string(),
            "\\begin{description}".to_string(),
            format!("\\item[frames] {}", listed(&self.frames)),
            format!("\\item[points] {}", listed(&self.points)),
            "\\end{description}".to_string(),
            format!(
                "\\[ T_{{\\text{{bodies}}}} = {} \\]",
                self.kinetic_energy.latex
            ),
            format!(
                "\\[ V_{{\\text{{bodies}}}} = {} \\]",
                self.potential_energy.latex
            ),
        ];
        for (name, row) in &self.contacts {
            let entries: Vec<&str> = row.iter().map(|e| e.latex.as_str()).collect();
            out.push(format!(
                "\\[ A_{{\\text{{{}}}}} = \\begin{{bmatrix}} {} \\end{{bmatrix}} \\]",
                escaped(name),
                entries.join(" & ")
            ));
        }
        for (name, residual) in &self.holonomic {
            out.push(format!(
                "\\[ f_{{\\text{{{}}}}}(q) = {} = 0 \\]",
                escaped(name),
                residual.latex
            ));
        }
        out.join("\n") + "\n"
    }

    /// The JSON document `document` with the section as its `mechanism` object.
    fn json(&self, document: &str) -> Result<String, serde_json::Error> {
        let mut root: Map<String, Value> = serde_json::from_str(document)?;
        let contacts: Map<String, Value> = (self.contacts.iter())
            .map(|(name, row)| {
                let text: Vec<&str> = row.iter().map(|e| e.text.as_str()).collect();
                let latex: Vec<&str> = row.iter().map(|e| e.latex.as_str()).collect();
                (name.clone(), json!({"text": text, "latex": latex}))
            })
            .collect();
        let holonomic: Map<String, Value> = (self.holonomic.iter())
            .map(|(name, residual)| (name.clone(), residual.json()))
            .collect();
        let section = json!({
            "frames": self.frames,
            "points": self.points,
            "kinetic_energy": self.kinetic_energy.json(),
            "potential_energy": self.potential_energy.json(),
            "contacts": contacts,
            "holonomic": holonomic,
        });
        root.insert("mechanism".into(), section);
        let mut text = serde_json::to_string_pretty(&Value::Object(root))?;
        text.push('\n');
        Ok(text)
    }
}

/// A name in LaTeX text: underscores escaped.
fn escaped(name: &str) -> String {
    name.replace('_', "\\_")
}
