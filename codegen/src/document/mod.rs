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

use crate::derive::constraints::ConstraintAnalysis;
use crate::derive::lagrange_dalembert::{self, LagrangeDalembert};
use crate::derive::momentum::Momentum;
use crate::derive::port_hamiltonian::{Exact, PortHamiltonian, items};
use crate::diagnostic::Diagnostics;
use crate::emit;
use crate::model::Model;
use crate::sym::latex::latex_rate;
use crate::sym::{ExprId, Matrix, SymbolId};
use crate::{analysed_model, over_budget};
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
/// [`crate::generate`] takes), in `format`; the model's diagnostics when it
/// does not compile.
pub fn derive_document(source: &str, format: Format) -> Result<String, Diagnostics> {
    let document = Document::derive(source)?;
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
    fn derive(source: &str) -> Result<Document, Diagnostics> {
        let (mut model, constraints) = analysed_model(source)?;
        let document = Self::derive_analysed(&mut model, &constraints);
        over_budget(&model)?;
        document
    }

    fn derive_analysed(
        model: &mut Model,
        constraints: &ConstraintAnalysis,
    ) -> Result<Document, Diagnostics> {
        let derivation = crate::derive::derivation(model, constraints)?;
        let emitted = emit::emit(model, constraints, &derivation)?;
        let rhs = derivation.reduced_items.outputs(items::Item::ReducedRhs);
        let (dalembert, reduced) = (&derivation.lagrange_dalembert, &derivation.reduced);
        let momentum = &derivation.momentum;
        let mut sections = vec![
            names_section(model, reduced),
            sizes_section(model),
            constraints_section(model, constraints),
            dalembert_section(model, dalembert),
            reduced_section(model, reduced, rhs),
        ];
        if let Some(momentum) = momentum {
            sections.push(momentum_section(model, momentum, &dalembert.inputs));
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

fn printed(model: &Model, id: ExprId) -> Printed {
    Printed {
        text: model.store.display(id).to_string(),
        latex: model.store.latex(id),
    }
}

/// A symbol's name in both notations (`dot(x)`, `\dot{x}`; `alpha1`, `\alpha_{1}`).
fn symbol_name(model: &mut Model, symbol: SymbolId) -> Printed {
    let id = model.store.symbol(symbol);
    printed(model, id)
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
    let text = if names.is_empty() {
        "none".to_string()
    } else {
        names.join(", ")
    };
    fact(key, label, json!(names), text)
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

fn matrix_item(model: &mut Model, key: &str, symbol: Printed, matrix: &Matrix) -> Item {
    let entries = matrix.to_expressions(&mut model.store);
    Item::Matrix {
        key: key.to_string(),
        matrix: Table {
            symbol,
            rows: matrix.rows(),
            columns: matrix.columns(),
            entries: entries.iter().map(|&e| printed(model, e)).collect(),
        },
    }
}

fn expression_item(model: &mut Model, key: &str, symbol: Printed, id: ExprId) -> Item {
    Item::Expression {
        key: key.to_string(),
        symbol,
        value: printed(model, id),
    }
}

/// `dot(symbol) = value` for each pair.
fn rates(model: &Model, symbols: &[SymbolId], values: &[ExprId]) -> Vec<Equation> {
    symbols
        .iter()
        .zip(values)
        .map(|(&symbol, &value)| {
            let name = &model.store.symbol_info(symbol).name;
            Equation {
                lhs: label(&format!("dot({name})"), &latex_rate(name)),
                rhs: printed(model, value),
            }
        })
        .collect()
}

// ----- sections -------------------------------------------------------------------

fn names_section(model: &Model, reduced: &PortHamiltonian) -> Section {
    let declared = |list: &[crate::model::Declared]| list.iter().map(|d| d.name.clone()).collect();
    let parameters: Vec<Value> = model
        .parameters
        .iter()
        .map(|p| json!({"name": p.variable.declared.name, "default": p.default.to_f64()}))
        .collect();
    let parameter_text: Vec<String> = model
        .parameters
        .iter()
        .map(|p| format!("{} = {}", p.variable.declared.name, p.default.to_f64()))
        .collect();
    Section {
        key: "names",
        title: "Names",
        items: vec![
            word_fact("model", "model", &model.name.to_string()),
            names_fact(
                "coordinates",
                "coordinates q",
                model
                    .coordinates
                    .iter()
                    .map(|c| c.declared.name.clone())
                    .collect(),
            ),
            fact(
                "parameters",
                "parameters (defaults)",
                Value::Array(parameters),
                parameter_text.join(", "),
            ),
            names_fact("inputs", "inputs u", declared(&model.inputs)),
            names_fact("constraints", "constraints", declared(&model.constraints)),
            names_fact(
                "momenta",
                "reduced momenta alpha",
                reduced.momentum_names.clone(),
            ),
        ],
    }
}

fn sizes_section(model: &Model) -> Section {
    let (n, c, k, p) = (model.n(), model.c(), model.k(), model.p());
    Section {
        key: "sizes",
        title: "Sizes",
        items: vec![
            count_fact("n", "coordinates n", n),
            count_fact("c", "constraints c", c),
            count_fact("k", "degrees of freedom in velocity k = n - c", k),
            count_fact("p", "inputs p", p),
            count_fact("s", "reduced state s = n + k", n + k),
        ],
    }
}

fn constraints_section(model: &mut Model, analysis: &ConstraintAnalysis) -> Section {
    let speeds = |indices: &[usize]| -> Vec<String> {
        indices
            .iter()
            .map(|&i| format!("dot({})", model.coordinates[i].declared.name))
            .collect()
    };
    let (dependent, independent) = (
        speeds(&analysis.basis.dependent),
        speeds(&analysis.basis.independent),
    );
    let (exact_rows, exact_text): (Vec<Value>, Vec<String>) = model
        .constraints
        .iter()
        .zip(&analysis.exact_rows)
        .map(|(row, &exact)| {
            let verdict = if exact { "exact" } else { "not exact" };
            (
                json!({"constraint": row.name, "exact": exact}),
                format!("{} {verdict}", row.name),
            )
        })
        .unzip();
    let growth: Vec<String> = analysis.growth.iter().map(usize::to_string).collect();
    let reachable = analysis.growth.last().copied().unwrap_or(model.n());
    Section {
        key: "constraints",
        title: "Constraint analysis (Frobenius, Chow, Moore)",
        items: vec![
            names_fact("dependent_speeds", "dependent speeds", dependent),
            names_fact("independent_speeds", "independent speeds", independent),
            basis_item(model, analysis),
            flag_fact(
                "integrable",
                "integrable (A [X_i, X_j] = 0 for all i, j)",
                analysis.integrable,
            ),
            word_fact(
                "integrability_decided",
                "integrability decided",
                analysis.integrability_method.describe(),
            ),
            fact(
                "growth_vector",
                "growth vector",
                json!(analysis.growth),
                format!("({})", growth.join(", ")),
            ),
            flag_fact(
                "growth_complete",
                "growth vector complete",
                analysis.growth_complete,
            ),
            word_fact(
                "growth_decided",
                "growth vector decided",
                analysis.growth_method.describe(),
            ),
            word_fact(
                "classification",
                "classification",
                analysis.classification.describe(),
            ),
            count_fact(
                "degrees_of_freedom",
                "degrees of freedom in velocity",
                model.k(),
            ),
            count_fact(
                "reachable_dimension",
                "reachable dimension (last rank of the growth)",
                reachable,
            ),
            fact(
                "exact_rows",
                "Moore's test (is each row exact?)",
                Value::Array(exact_rows),
                if exact_text.is_empty() {
                    "no constraints".to_string()
                } else {
                    exact_text.join(", ")
                },
            ),
        ],
    }
}

fn dalembert_section(model: &mut Model, derivation: &LagrangeDalembert) -> Section {
    let potential = model.store.expression_of(&model.potential_energy.clone());
    let system = &derivation.saddle_point;
    let equations = vec![
        Equation {
            lhs: label(
                "g qddot + C + dV/dq",
                "g \\ddot{q} + C + \\frac{\\partial V}{\\partial q}",
            ),
            rhs: label("A^T lambda + B u", "A^{T} \\lambda + B u"),
        },
        Equation {
            lhs: label("A qddot + Adot qdot", "A \\ddot{q} + \\dot{A} \\dot{q}"),
            rhs: label("0", "0"),
        },
    ];
    let solve = match derivation.strategy {
        lagrange_dalembert::Strategy::Symbolic => "closed form",
        lagrange_dalembert::Strategy::Numeric => "numeric solve of the saddle-point system",
    };
    Section {
        key: "lagrange_dalembert",
        title: "Lagrange-d'Alembert equations",
        items: vec![
            Item::Equations {
                key: "equations".into(),
                lines: equations,
            },
            matrix_item(
                model,
                "mass_matrix",
                label("g", "g"),
                &model.mass_matrix.clone(),
            ),
            expression_item(model, "potential", label("V", "V"), potential),
            matrix_item(
                model,
                "constraint_matrix",
                label("A", "A"),
                &model.constraint_matrix.clone(),
            ),
            matrix_item(
                model,
                "input_matrix",
                label("B", "B"),
                &model.input_matrix.clone(),
            ),
            matrix_item(
                model,
                "force",
                label(
                    "B u - C - dV/dq",
                    "B u - C - \\frac{\\partial V}{\\partial q}",
                ),
                &system.force,
            ),
            matrix_item(
                model,
                "drift",
                label("-Adot qdot", "-\\dot{A} \\dot{q}"),
                &system.drift,
            ),
            word_fact("solve", "acceleration computed by", solve),
        ],
    }
}

/// X as a matrix when exact; a statement of how it is computed when not.
fn basis_item(model: &mut Model, analysis: &ConstraintAnalysis) -> Item {
    match &analysis.basis.fields {
        Some(fields) => matrix_item(
            model,
            "basis",
            label("X = [X1 ... Xk], a basis of D", "X"),
            fields,
        ),
        None => word_fact(
            "basis",
            "X = [X1 ... Xk], a basis of D",
            "structured: the dependent speeds by elimination of A, not expanded \
             (the exact form exceeds its derivation budget)",
        ),
    }
}

fn reduced_section(model: &mut Model, reduced: &PortHamiltonian, rhs: &[ExprId]) -> Section {
    let mut items = vec![
        flag_fact(
            "declared_basis",
            "momentum basis declared",
            reduced.declared_basis,
        ),
        names_fact("momenta", "momenta", reduced.momentum_names.clone()),
    ];
    match reduced.exact() {
        Some(exact) => items.extend(exact_items(model, reduced, exact, rhs)),
        None => items.extend(structured_items(reduced)),
    }
    Section {
        key: "port_hamiltonian",
        title: "Reduced port-Hamiltonian form (Duindam & Stramigioli)",
        items,
    }
}

/// The exact matrices, the energy and the reduced equations.
fn exact_items(
    model: &mut Model,
    reduced: &PortHamiltonian,
    exact: &Exact,
    rhs: &[ExprId],
) -> Vec<Item> {
    let hamiltonian = model.store.expression_of(&exact.hamiltonian);
    let equations = rates(model, &reduced.state(model), rhs);
    let matrices = [
        ("momentum_basis", label("h", "h"), &exact.basis),
        ("metric", label("gbar", "\\bar{g}"), &exact.metric),
        ("gyroscopic", label("Gamma", "\\Gamma"), &exact.gyroscopic),
        (
            "structure_matrix",
            label("Jbar", "\\bar{J}"),
            &exact.structure,
        ),
        (
            "input_matrix",
            label("Bbar", "\\bar{B}"),
            &exact.input_matrix,
        ),
    ];
    let mut items: Vec<Item> = matrices
        .into_iter()
        .map(|(key, symbol, matrix)| matrix_item(model, key, symbol, matrix))
        .collect();
    items.extend([
        flag_fact("metric_constant", "gbar constant", reduced.metric_constant),
        flag_fact("metric_diagonal", "gbar diagonal", reduced.metric_diagonal),
        expression_item(model, "hamiltonian", label("Hbar", "\\bar{H}"), hamiltonian),
        Item::Equations {
            key: "equations".into(),
            lines: equations,
        },
    ]);
    items
}

/// How the structured form computes what the exact one would print.
fn structured_items(reduced: &PortHamiltonian) -> Vec<Item> {
    vec![
        word_fact(
            "derivation",
            "reduced form derived",
            "structured (the exact form exceeds its derivation budget): h = X^T g, \
             gbar_inv = X^T g X, gbar by elimination, Gamma = gbar S gbar with \
             S_ab = alpha_c dh^c(X_a, X_b); qdot = X alpha, \
             alphadot = gbar (-X^T dHbar/dq + S alpha + X^T B u); Jbar skew by construction",
        ),
        flag_fact("metric_constant", "gbar constant", reduced.metric_constant),
        flag_fact("metric_diagonal", "gbar diagonal", reduced.metric_diagonal),
        word_fact(
            "metric_facts_decided",
            "gbar facts decided",
            reduced.facts_method.describe(),
        ),
    ]
}

fn momentum_section(model: &mut Model, momentum: &Momentum, inputs: &[SymbolId]) -> Section {
    let shape: Vec<String> = momentum
        .shape
        .iter()
        .map(|&i| model.coordinates[i].declared.name.clone())
        .collect();
    let names: Vec<Printed> = momentum
        .momenta
        .iter()
        .map(|&p| symbol_name(model, p))
        .collect();
    let momenta: Vec<String> = names.iter().map(|name| name.text.clone()).collect();
    let mut items = vec![
        names_fact("shape", "shape coordinates r", shape),
        names_fact("momenta", "momenta p", momenta),
        matrix_item(model, "basis", label("e", "e"), &momentum.basis),
        matrix_item(
            model,
            "connection",
            label("A_nh", "A_{\\mathrm{nh}}"),
            &momentum.connection,
        ),
        matrix_item(
            model,
            "locked_inertia",
            label("I", "I"),
            &momentum.locked_inertia,
        ),
    ];
    for (name, coefficients) in names.iter().zip(&momentum.coefficients) {
        for (tensor, matrix) in [
            ("H", &coefficients.shape),
            ("K", &coefficients.mixed),
            ("D", &coefficients.momentum),
        ] {
            let symbol = label(
                &format!("{tensor} ({})", name.text),
                &format!("{tensor}^{{{}}}", name.latex),
            );
            items.push(matrix_item(
                model,
                &format!("{tensor}_{}", name.text),
                symbol,
                matrix,
            ));
        }
    }
    items.push(matrix_item(
        model,
        "input_coupling",
        label("h B", "h B"),
        &momentum.input_coupling,
    ));
    let forced = forced_momentum_rhs(model, momentum, inputs);
    items.push(Item::Equations {
        key: "equations".into(),
        lines: rates(model, &momentum.momenta, &forced),
    });
    Section {
        key: "momentum",
        title: "Momentum equation (Bloch-Krishnaprasad-Marsden-Murray; Koon & Marsden)",
        items,
    }
}

/// `pdot_i = rhs_i + sum_j (h B)_ij u_j`.
fn forced_momentum_rhs(model: &mut Model, momentum: &Momentum, inputs: &[SymbolId]) -> Vec<ExprId> {
    let coupling = &momentum.input_coupling;
    (0..momentum.rhs.len())
        .map(|i| {
            let mut terms = vec![model.store.expression_of(&momentum.rhs[i])];
            for (j, &input) in inputs.iter().enumerate() {
                let entry = model.store.expression_of(coupling.get(i, j));
                let u = model.store.symbol(input);
                terms.push(model.store.mul2(entry, u));
            }
            model.store.add(&terms)
        })
        .collect()
}

#[cfg(test)]
mod tests;
