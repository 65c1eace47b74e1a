//! The derivation report emitted as `REPORT: &str` (docs/INTERFACE.md section 2).
//!
//! A [`Report`] is a list of sections, each a title and plain lines, rendered
//! as text:
//!
//! ```text
//! Snakeboard
//!
//! Constraints
//!   sizes: n = 5, c = 2, k = 3, p = 2
//!   ...
//! ```
//!
//! Each derivation contributes its own section; the wording of a line is
//! part of the contract users and tests read (`growth vector (3, 4, 5)`).

use super::Function;
use super::shared::SharedItem;
use crate::derive::constraints::{ConstraintAnalysis, Method, charts};
use crate::model::Model;
use crate::sym::Context;
use crate::sym::RationalFunction;

/// A plain-text report: a title, then titled sections of lines.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Report {
    title: String,
    sections: Vec<Section>,
}

/// One titled section of a [`Report`].
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Section {
    title: String,
    lines: Vec<String>,
}

impl Report {
    /// An empty report with a title.
    pub fn new(title: impl Into<String>) -> Report {
        Report {
            title: title.into(),
            sections: Vec::new(),
        }
    }

    /// Appends a section.
    pub fn push(&mut self, section: Section) {
        self.sections.push(section);
    }

    /// The title, then each section after a blank line, its lines indented.
    pub fn render(&self) -> String {
        let mut text = self.title.clone();
        text.push('\n');
        for section in &self.sections {
            text.push('\n');
            text.push_str(&section.title);
            text.push('\n');
            for line in &section.lines {
                text.push_str("  ");
                text.push_str(line);
                text.push('\n');
            }
        }
        text
    }
}

impl Section {
    /// An empty section with a title.
    pub fn new(title: impl Into<String>) -> Section {
        Section {
            title: title.into(),
            lines: Vec::new(),
        }
    }

    /// Appends a line.
    pub fn line(&mut self, line: impl Into<String>) -> &mut Section {
        self.lines.push(line.into());
        self
    }
}

/// Sizes, speeds, the basis of D, integrability, growth and Moore's test.
pub(super) fn constraints(
    model: &Model,
    cx: &mut Context,
    analysis: &ConstraintAnalysis,
) -> Section {
    let mut section = Section::new("Constraints (Frobenius, Chow, Moore)");
    let (n, c, k, p) = (model.n(), model.c(), model.k(), model.p());
    section.line(format!("sizes: n = {n}, c = {c}, k = {k}, p = {p}"));
    for row in &model.redundant_rows {
        section.line(format!("redundant contact row dropped: {}", row.describe()));
    }
    if let Some(locked) = analysis.locked.describe(model) {
        section.line(format!("bodies unable to move: {locked}"));
    }
    for set in &analysis.coordinate_sets {
        section.line(set.warning(model, cx));
    }
    let basis = &analysis.basis;
    section.line(format!(
        "dependent speeds: {}",
        speeds(basis.speed_names(model, &basis.dependent))
    ));
    section.line(format!(
        "independent speeds: {}",
        speeds(basis.speed_names(model, &basis.independent))
    ));
    match &analysis.basis.fields {
        Some(fields) => {
            section.line("basis of D:");
            for j in 0..fields.columns() {
                let entries: Vec<RationalFunction> =
                    (0..n).map(|i| fields.get(i, j).clone()).collect();
                section.line(format!("  X{} = [{}]", j + 1, displayed(cx, &entries)));
            }
        }
        None => {
            section.line(
                "basis of D: structured, the dependent speeds by elimination of A \
                 (the exact form is too large to derive)",
            );
        }
    }
    for line in charts::report_lines(model, &analysis.basis, &analysis.charts) {
        section.line(line);
    }
    section.line(format!(
        "integrable (A [X_i, X_j] = 0 for all i, j): {}",
        yes_no(analysis.integrable)
    ));
    if analysis.integrability_method == Method::Modular {
        section.line(format!(
            "  decided {}",
            analysis.integrability_method.describe()
        ));
    }
    section.line(format!("growth vector {}", tuple(&analysis.growth)));
    if !analysis.growth_complete {
        section.line("  cut short: its next level exceeds the derivation budget");
    }
    if analysis.growth_method == Method::Modular {
        section.line(format!("  decided {}", analysis.growth_method.describe()));
    }
    section.line(format!(
        "classification: {}",
        analysis.classification.describe()
    ));
    if let Some(reachable) = analysis.growth.last() {
        let bound = if analysis.growth_complete {
            ""
        } else {
            "at least "
        };
        section.line(format!(
            "reachable dimension (last rank of the growth): {bound}{reachable} of n = {n}"
        ));
    }
    section.line(format!(
        "Moore's mixed-partials test (is each row exact? misses integrating factors): {}",
        moore(model, analysis)
    ));
    for integral in &analysis.integrals {
        section.line(format!(
            "integral of the constraints: {}",
            integral.describe(model, cx)
        ));
    }
    section
}

/// Operation counts of each emitted function, before and after CSE. Before
/// CSE every shared node counts each time it is used (what expanding the
/// expression would cost); counts from a billion on are written in
/// scientific notation, and the count saturates at `u64::MAX` (1.84e19).
pub(super) fn operations(functions: &[Function], shared: &[SharedItem]) -> Section {
    let mut section = Section::new("Operation counts (before CSE -> after CSE)");
    let named = functions
        .iter()
        .map(|function| (function.name.to_string(), function.operations))
        .chain(
            shared
                .iter()
                .map(|body| (format!("{} (shared body)", body.name), body.operations)),
        );
    for (name, operations) in named {
        section.line(format!(
            "{name}: {} -> {}",
            count(operations.before_cse),
            count(operations.after_cse)
        ));
    }
    section
}

/// `n` in full below a billion, else as `1.23e12`.
fn count(n: u64) -> String {
    if n < 1_000_000_000 {
        n.to_string()
    } else {
        format!("{:.2e}", n as f64)
    }
}

/// The speeds' names, or `none`.
fn speeds(names: Vec<String>) -> String {
    if names.is_empty() {
        "none".to_string()
    } else {
        names.join(", ")
    }
}

fn displayed(cx: &mut Context, entries: &[RationalFunction]) -> String {
    let texts: Vec<String> = entries
        .iter()
        .map(|entry| {
            let id = cx.expression_of(entry);
            cx.display(id).to_string()
        })
        .collect();
    texts.join(", ")
}

fn tuple(values: &[usize]) -> String {
    let texts: Vec<String> = values.iter().map(usize::to_string).collect();
    format!("({})", texts.join(", "))
}

fn yes_no(value: bool) -> &'static str {
    if value { "yes" } else { "no" }
}

/// Each row's verdict: `name exact` or `name not exact`.
fn moore(model: &Model, analysis: &ConstraintAnalysis) -> String {
    let verdicts: Vec<String> = model
        .constraints
        .iter()
        .zip(&analysis.exact_rows)
        .map(|(row, &exact)| {
            let verdict = if exact { "exact" } else { "not exact" };
            format!("{} {verdict}", row.name)
        })
        .collect();
    if verdicts.is_empty() {
        "no rows".to_string()
    } else {
        verdicts.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::{Report, Section, constraints, count};

    #[test]
    fn large_counts_are_written_in_scientific_notation() {
        assert_eq!(count(999_999_999), "999999999");
        assert_eq!(count(2_954_864_102_913_747_000), "2.95e18");
        assert_eq!(count(u64::MAX), "1.84e19");
        assert_eq!(count(7_000_000_000).parse::<f64>(), Ok(7e9));
    }

    use crate::derive::constraints::analyse;
    use crate::model::check;
    use crate::syntax::parse_str;

    /// `(1 + x^2) d(x y + z)`: holonomic by Frobenius, not exact for Moore.
    #[test]
    fn an_integrating_factor_is_reported_holonomic_and_not_exact() {
        let source = "pub struct M {
            coordinates: [x, y, z],
            kinetic_energy: dot(x)^2/2 + dot(y)^2/2 + dot(z)^2/2,
            constraints: [level = (1 + x^2)*(y*dot(x) + x*dot(y) + dot(z))],
        }";
        let (model, mut cx) = check(&parse_str(source).expect("parses")).expect("checks");
        let analysis = analyse(&model, &mut cx).expect("analyses");
        let mut report = Report::new("M");
        report.push(constraints(&model, &mut cx, &analysis));
        let text = report.render();
        for line in [
            "  sizes: n = 3, c = 1, k = 2, p = 0\n",
            "  dependent speeds: dot(z)\n",
            "  independent speeds: dot(x), dot(y)\n",
            "    X1 = [1, 0, -y]\n",
            "    X2 = [0, 1, -x]\n",
            "  integrable (A [X_i, X_j] = 0 for all i, j): yes\n",
            "  growth vector (2)\n",
            "  classification: holonomic\n",
            "  reachable dimension (last rank of the growth): 2 of n = 3\n",
            "misses integrating factors): level not exact\n",
        ] {
            assert!(text.contains(line), "{line:?} not in\n{text}");
        }
    }

    #[test]
    fn sections_render_under_their_titles_with_indented_lines() {
        let mut report = Report::new("Model");
        let mut first = Section::new("One");
        first.line("a").line("b");
        report.push(first);
        report.push(Section::new("Two"));
        assert_eq!(report.render(), "Model\n\nOne\n  a\n  b\n\nTwo\n");
    }
}
