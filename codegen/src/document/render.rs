//! The three renderings of a [`Document`].
//!
//! Text: the title, then each section's title and its items indented, a
//! matrix one row per line, an equation `lhs = rhs` per line.
//!
//! LaTeX: a standalone `article` using `amsmath`; a section per section,
//! facts in a `description` list, expressions and matrices (`bmatrix`) in
//! display math, equations in `align*`, the report `verbatim`.
//!
//! JSON: `{"model": name, <section key>: {<item key>: item, ...}, ...}` with
//! `"momentum": null` when the model has no symmetry, the items as the
//! documentation of [`super`] lays them out.

use super::{Document, Equation, Item, Printed, Table};
use crate::sym::latex::bmatrix;
use serde_json::{Map, Value, json};
use std::fmt::Write;

/// LaTeX's default column limit of `bmatrix`.
const DEFAULT_MATRIX_COLUMNS: usize = 10;

pub(super) fn text(document: &Document) -> String {
    let mut out = format!("{}\n", document.title);
    for section in &document.sections {
        let _ = write!(out, "\n{}\n", section.title);
        for item in &section.items {
            text_item(&mut out, item);
        }
    }
    out
}

fn text_item(out: &mut String, item: &Item) {
    match item {
        Item::Fact { label, text, .. } => {
            let _ = writeln!(out, "  {label}: {text}");
        }
        Item::Expression { symbol, value, .. } => {
            let _ = writeln!(out, "  {} = {}", symbol.text, value.text);
        }
        Item::Matrix {
            matrix:
                Table {
                    symbol,
                    rows,
                    columns,
                    entries,
                },
            ..
        } => {
            if entries.is_empty() {
                let _ = writeln!(out, "  {} = (empty, {rows} x {columns})", symbol.text);
                return;
            }
            let _ = writeln!(out, "  {} =", symbol.text);
            for row in entries.chunks((*columns).max(1)) {
                let cells: Vec<&str> = row.iter().map(|e| e.text.as_str()).collect();
                let _ = writeln!(out, "    [{}]", cells.join(", "));
            }
        }
        Item::Equations { lines, .. } => {
            for Equation { lhs, rhs } in lines {
                let _ = writeln!(out, "  {} = {}", lhs.text, rhs.text);
            }
        }
        Item::Verbatim { text, .. } => {
            for line in text.lines() {
                if line.is_empty() {
                    out.push('\n');
                } else {
                    let _ = writeln!(out, "  {line}");
                }
            }
        }
    }
}

pub(super) fn latex(document: &Document) -> String {
    let widest = document
        .sections
        .iter()
        .flat_map(|s| &s.items)
        .filter_map(|item| match item {
            Item::Matrix { matrix, .. } => Some(matrix.columns),
            _ => None,
        })
        .fold(DEFAULT_MATRIX_COLUMNS, usize::max);
    let mut out = String::from("\\documentclass{article}\n\\usepackage{amsmath}\n");
    let _ = writeln!(out, "\\setcounter{{MaxMatrixCols}}{{{widest}}}");
    let _ = writeln!(out, "\\title{{{}}}", escape(&document.title));
    out.push_str("\\date{}\n\\begin{document}\n\\maketitle\n");
    for section in &document.sections {
        let _ = writeln!(out, "\n\\section*{{{}}}", escape(section.title));
        let mut facts = String::new();
        for item in &section.items {
            if let Item::Fact { label, text, .. } = item {
                let _ = writeln!(facts, "\\item[{}] {}", escape(label), escape(text));
                continue;
            }
            flush_facts(&mut out, &mut facts);
            latex_item(&mut out, item);
        }
        flush_facts(&mut out, &mut facts);
    }
    out.push_str("\\end{document}\n");
    out
}

fn flush_facts(out: &mut String, facts: &mut String) {
    if !facts.is_empty() {
        let _ = write!(out, "\\begin{{description}}\n{facts}\\end{{description}}\n");
        facts.clear();
    }
}

fn latex_item(out: &mut String, item: &Item) {
    match item {
        Item::Fact { .. } => {}
        Item::Expression { symbol, value, .. } => {
            let _ = writeln!(out, "\\[ {} = {} \\]", symbol.latex, value.latex);
        }
        Item::Matrix { matrix, .. } => {
            let _ = writeln!(
                out,
                "\\[ {} = {} \\]",
                matrix.symbol.latex,
                matrix.bmatrix()
            );
        }
        Item::Equations { lines, .. } => {
            let rows: Vec<String> = lines
                .iter()
                .map(|Equation { lhs, rhs }| format!("{} &= {}", lhs.latex, rhs.latex))
                .collect();
            let _ = writeln!(
                out,
                "\\begin{{align*}}\n{}\n\\end{{align*}}",
                rows.join(" \\\\\n")
            );
        }
        Item::Verbatim { text, .. } => {
            let _ = writeln!(out, "\\begin{{verbatim}}\n{text}\\end{{verbatim}}");
        }
    }
}

impl Table {
    fn bmatrix(&self) -> String {
        let cells: Vec<String> = self.entries.iter().map(|e| e.latex.clone()).collect();
        bmatrix(&cells, self.columns)
    }
}

/// Text for LaTeX's text mode: its special characters escaped.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for character in text.chars() {
        match character {
            '\\' => out.push_str("\\textbackslash{}"),
            '^' => out.push_str("\\textasciicircum{}"),
            '~' => out.push_str("\\textasciitilde{}"),
            '&' | '%' | '$' | '#' | '_' | '{' | '}' => {
                out.push('\\');
                out.push(character);
            }
            _ => out.push(character),
        }
    }
    out
}

pub(super) fn json(document: &Document) -> String {
    let mut root = Map::new();
    root.insert("model".into(), json!(document.title));
    root.insert("momentum".into(), Value::Null);
    for section in &document.sections {
        let items: Map<String, Value> = section
            .items
            .iter()
            .map(|item| (key(item).to_string(), json_item(item)))
            .collect();
        root.insert(section.key.into(), Value::Object(items));
    }
    let mut text = serde_json::to_string_pretty(&Value::Object(root)).unwrap_or_default();
    text.push('\n');
    text
}

fn key(item: &Item) -> &str {
    match item {
        Item::Fact { key, .. }
        | Item::Expression { key, .. }
        | Item::Matrix { key, .. }
        | Item::Equations { key, .. }
        | Item::Verbatim { key, .. } => key,
    }
}

fn json_item(item: &Item) -> Value {
    match item {
        Item::Fact { value, .. } => value.clone(),
        Item::Expression { symbol, value, .. } => {
            json!({"symbol": symbol.text, "text": value.text, "latex": value.latex})
        }
        Item::Matrix { matrix, .. } => {
            let table = |pick: fn(&Printed) -> &String| -> Value {
                matrix
                    .entries
                    .chunks(matrix.columns.max(1))
                    .map(|row| row.iter().map(|e| json!(pick(e))).collect::<Value>())
                    .collect()
            };
            json!({
                "symbol": matrix.symbol.text,
                "rows": matrix.rows,
                "columns": matrix.columns,
                "text": table(|e| &e.text),
                "latex": table(|e| &e.latex),
                "bmatrix": matrix.bmatrix(),
            })
        }
        Item::Equations { lines, .. } => lines
            .iter()
            .map(|Equation { lhs, rhs }| {
                json!({
                    "lhs": {"text": lhs.text, "latex": lhs.latex},
                    "rhs": {"text": rhs.text, "latex": rhs.latex},
                })
            })
            .collect(),
        Item::Verbatim { text, .. } => json!(text),
    }
}
