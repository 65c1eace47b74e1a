//! The derivation document of a model: what the compiler derived, as text,
//! LaTeX or JSON.
//!
//! [`derive_document`] runs the stages [`crate::generate`] runs (parse,
//! check, constraint analysis, emission) and the derivations emission is
//! built on, and lays out their results in sections:
//!
//! - names and sizes: coordinates, parameters (with defaults), inputs,
//!   constraints, momenta; n, c, k, p, s;
//! - the constraint analysis ([`crate::derive::constraints`], Moore): the
//!   basis of D, integrability, the growth vector, the classification, the
//!   degrees of freedom;
//! - the Lagrange-d'Alembert equations ([`crate::derive::lagrange_dalembert`],
//!   MATH.md section 2): `g`, `V`, `A`, `B`, the force `B u - C - dV/dq` and
//!   the drift `-Adot qdot` of
//!   `g qddot + C + dV/dq = A^T lambda + B u`, `A qddot + Adot qdot = 0`;
//! - the reduced port-Hamiltonian form ([`crate::derive::port_hamiltonian`],
//!   Duindam & Stramigioli, Theorem 1): `h`, `gbar`, `Gamma`, `Jbar`,
//!   `Hbar`, `Bbar`, and `xdot = Jbar dHbar/dx + Bbar u` one line per state,
//!   the expressions the generated `reduced_rhs` computes;
//! - with a symmetry, the momentum equation ([`crate::derive::momentum`],
//!   Koon & Marsden (1.1)-(1.3)): `e`, `A_nh`, `I`, `H`, `K`, `D` per
//!   momentum, `h B`, and `pdot = rdot^T H rdot + rdot^T K p + p^T D p + h B u`
//!   one line per momentum;
//! - the report, the generated `REPORT` text.
//!
//! Expressions are printed in the model language's syntax
//! ([`crate::sym::Store::display`]) and in LaTeX
//! ([`crate::sym::Store::latex`]). The JSON object has one member per
//! section (`names`, `sizes`, `constraints`, `lagrange_dalembert`,
//! `port_hamiltonian`, `momentum` (null without a symmetry), `report`),
//! each an object of its items by key:
//!
//! ```text
//! fact        the value: a string, number, boolean, or array
//! expression  {"symbol": "V", "text": "...", "latex": "..."}
//! matrix      {"symbol": "g", "rows": r, "columns": c, "text": [[...], ...],
//!              "latex": [[...], ...], "bmatrix": "\begin{bmatrix}...\end{bmatrix}"}
//! equations   [{"lhs": {"text", "latex"}, "rhs": {"text", "latex"}}, ...]
//! verbatim    the text (the report: `"report": {"text": "..."}`)
//! ```

mod render;
mod sections;

use crate::sym::Context;
use sections::{
    constraints_section, dalembert_section, momentum_section, names_section, reduced_section,
    sizes_section,
};

use crate::derive::constraints::ConstraintAnalysis;
use crate::derive::port_hamiltonian::items;
use crate::diagnostic::Diagnostics;
use crate::emit;
use crate::ir::Backend;
use crate::model::Model;
use crate::sym::latex::latex_rate;
use crate::sym::{ExprId, Matrix, SymbolId};
use crate::{Analysed, analysed_model, over_budget};
use serde_json::{Value, json};

/// The output format of [`derive_document`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Plain text for reading.
    Text,
    /// A standalone LaTeX document (`article`, `amsmath`).
    Latex,
    /// A JSON object (see the module documentation).
    Json,
}

/// A format name that is not `text`, `latex` or `json`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown document format `{0}`: expected `text`, `latex` or `json`")]
pub struct UnknownFormat(pub String);

impl std::str::FromStr for Format {
    type Err = UnknownFormat;

    fn from_str(name: &str) -> Result<Format, UnknownFormat> {
        match name {
            "text" => Ok(Format::Text),
            "latex" => Ok(Format::Latex),
            "json" => Ok(Format::Json),
            _ => Err(UnknownFormat(name.to_string())),
        }
    }
}

/// The derivation document of the model text (the text
/// [`crate::generate`] takes), in `format`, the derivation's numeric
/// searches running on the engines `backend` makes; the model's
/// diagnostics when it does not compile.
pub fn derive_document(
    source: &str,
    format: Format,
    backend: &dyn Backend,
) -> Result<String, Diagnostics> {
    let document = Document::derive(source, backend)?;
    Ok(match format {
        Format::Text => render::text(&document),
        Format::Latex => render::latex(&document),
        Format::Json => render::json(&document),
    })
}

/// The model's name and its sections, in order.
struct Document {
    title: String,
    sections: Vec<Section>,
}

/// A titled list of items; `key` names it in JSON.
struct Section {
    key: &'static str,
    title: &'static str,
    items: Vec<Item>,
}

/// An expression in both notations.
struct Printed {
    text: String,
    latex: String,
}

/// One line `lhs = rhs`.
struct Equation {
    lhs: Printed,
    rhs: Printed,
}

/// A named `rows x columns` matrix, entries row-major.
struct Table {
    symbol: Printed,
    rows: usize,
    columns: usize,
    entries: Vec<Printed>,
}

/// What a section holds; `key` names the item in JSON.
enum Item {
    /// A plain value: a name list, a size, a flag, a classification;
    /// `text` is how it reads.
    Fact {
        key: String,
        label: &'static str,
        value: Value,
        text: String,
    },
    /// A named expression, `symbol = value`.
    Expression {
        key: String,
        symbol: Printed,
        value: Printed,
    },
    /// A named matrix.
    Matrix { key: String, matrix: Table },
    /// A system of equations.
    Equations { key: String, lines: Vec<Equation> },
    /// Preformatted text.
    Verbatim { key: String, text: String },
}

impl Document {
    fn derive(source: &str, backend: &dyn Backend) -> Result<Document, Diagnostics> {
        let Analysed {
            model,
            mut cx,
            constraints,
        } = analysed_model(source, backend)?;
        let document = Self::derive_analysed(&model, &mut cx, &constraints, backend);
        over_budget(&model, &cx)?;
        document
    }

    fn derive_analysed(
        model: &Model,
        cx: &mut Context,
        constraints: &ConstraintAnalysis,
        backend: &dyn Backend,
    ) -> Result<Document, Diagnostics> {
        let derivation = crate::derive::derivation(model, cx, constraints, backend)?;
        let emitted = emit::emit(model, cx, constraints, &derivation)?;
        let rhs = derivation.reduced_items.outputs(items::Item::ReducedRhs);
        let (dalembert, reduced) = (&derivation.lagrange_dalembert, &derivation.reduced);
        let momentum = &derivation.momentum;
        let mut sections = vec![
            names_section(model, reduced),
            sizes_section(model),
            constraints_section(model, cx, constraints),
            dalembert_section(model, cx, dalembert),
            reduced_section(model, cx, reduced, rhs),
        ];
        if let Some(momentum) = momentum {
            sections.push(momentum_section(model, cx, momentum, &dalembert.inputs));
        }
        sections.push(Section {
            key: "report",
            title: "Report",
            items: vec![Item::Verbatim {
                key: "text".into(),
                text: emitted.report,
            }],
        });
        Ok(Document {
            title: model.name.to_string(),
            sections,
        })
    }
}

// ----- items -------------------------------------------------------------------

fn printed(cx: &Context, id: ExprId) -> Printed {
    Printed {
        text: cx.display(id).to_string(),
        latex: cx.latex(id),
    }
}

/// A symbol's name in both notations (`dot(x)`, `\dot{x}`; `alpha1`, `\alpha_{1}`).
fn symbol_name(cx: &mut Context, symbol: SymbolId) -> Printed {
    let id = cx.symbol(symbol);
    printed(cx, id)
}

/// A label that is not an expression: `text` as is, `latex` in math mode.
fn label(text: &str, latex: &str) -> Printed {
    Printed {
        text: text.to_string(),
        latex: latex.to_string(),
    }
}

fn fact(key: &str, label: &'static str, value: Value, text: String) -> Item {
    Item::Fact {
        key: key.to_string(),
        label,
        value,
        text,
    }
}

/// A list of names, read as `a, b, c` (or `none`).
fn names_fact(key: &str, label: &'static str, names: Vec<String>) -> Item {
    let text = listed_or_none(&names);
    fact(key, label, json!(names), text)
}

/// The names joined by commas, or `none`.
fn listed_or_none(names: &[String]) -> String {
    match names.is_empty() {
        true => "none".to_string(),
        false => names.join(", "),
    }
}

fn count_fact(key: &str, label: &'static str, count: usize) -> Item {
    fact(key, label, json!(count), count.to_string())
}

fn flag_fact(key: &str, label: &'static str, flag: bool) -> Item {
    let text = if flag { "yes" } else { "no" };
    fact(key, label, json!(flag), text.to_string())
}

fn word_fact(key: &str, label: &'static str, word: &str) -> Item {
    fact(key, label, json!(word), word.to_string())
}

fn matrix_item(cx: &mut Context, key: &str, symbol: Printed, matrix: &Matrix) -> Item {
    let entries = matrix.to_expressions(cx);
    Item::Matrix {
        key: key.to_string(),
        matrix: Table {
            symbol,
            rows: matrix.rows(),
            columns: matrix.columns(),
            entries: entries.iter().map(|&e| printed(cx, e)).collect(),
        },
    }
}

fn expression_item(cx: &mut Context, key: &str, symbol: Printed, id: ExprId) -> Item {
    Item::Expression {
        key: key.to_string(),
        symbol,
        value: printed(cx, id),
    }
}

/// `dot(symbol) = value` for each pair.
fn rates(cx: &Context, symbols: &[SymbolId], values: &[ExprId]) -> Vec<Equation> {
    symbols
        .iter()
        .zip(values)
        .map(|(&symbol, &value)| {
            let name = &cx.symbol_info(symbol).name;
            Equation {
                lhs: label(&format!("dot({name})"), &latex_rate(name)),
                rhs: printed(cx, value),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests;
