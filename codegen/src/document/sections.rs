//! The document's sections, one function each: names and sizes, the
//! constraint analysis, the Lagrange-d'Alembert equations, the reduced
//! port-Hamiltonian form, the momentum equation.

use super::{
    Equation, Item, Printed, Section, count_fact, expression_item, fact, flag_fact, label,
    listed_or_none, matrix_item, names_fact, rates, symbol_name, word_fact,
};
use crate::derive::constraints::ConstraintAnalysis;
use crate::derive::lagrange_dalembert::{self, LagrangeDalembert};
use crate::derive::momentum::Momentum;
use crate::derive::port_hamiltonian::{Exact, PortHamiltonian};
use crate::model::Model;
use crate::sym::Context;
use crate::sym::{ExprId, SymbolId};
use serde_json::{Value, json};

pub(super) fn names_section(model: &Model, reduced: &PortHamiltonian) -> Section {
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

pub(super) fn sizes_section(model: &Model) -> Section {
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

pub(super) fn constraints_section(
    model: &Model,
    cx: &mut Context,
    analysis: &ConstraintAnalysis,
) -> Section {
    let basis = &analysis.basis;
    let (dependent, independent) = (
        basis.speed_names(model, &basis.dependent),
        basis.speed_names(model, &basis.independent),
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
    let redundant: Vec<String> = model.redundant_rows.iter().map(|r| r.describe()).collect();
    let locked = &analysis.locked;
    let moving: Vec<&str> = (locked.moving.iter())
        .map(|&i| model.coordinates[i].declared.name.as_str())
        .collect();
    Section {
        key: "constraints",
        title: "Constraint analysis (Frobenius, Chow, Moore)",
        items: vec![
            fact(
                "redundant_rows",
                "redundant contact rows dropped",
                json!(
                    model
                        .redundant_rows
                        .iter()
                        .map(|r| json!({
                            "constraint": r.name,
                            "where": r.redundancy.describe(),
                        }))
                        .collect::<Vec<_>>()
                ),
                listed_or_none(&redundant),
            ),
            fact(
                "locked_bodies",
                "bodies unable to move",
                json!({"bodies": locked.bodies, "moving_coordinates": moving}),
                locked.describe(model).unwrap_or_else(|| "none".to_string()),
            ),
            coordinate_sets_fact(model, cx, analysis),
            names_fact("dependent_speeds", "dependent speeds", dependent),
            names_fact("independent_speeds", "independent speeds", independent),
            basis_item(cx, analysis),
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
            integrals_fact(model, cx, analysis),
        ],
    }
}

/// The combinations of rows that are exact, each with its function where
/// it is written out.
fn integrals_fact(model: &Model, cx: &Context, analysis: &ConstraintAnalysis) -> Item {
    let integrals = &analysis.integrals;
    let json: Vec<Value> = integrals
        .iter()
        .map(|integral| {
            let rows: Vec<Value> = (integral.rows.iter())
                .map(|(row, mu)| json!({"constraint": model.constraints[*row].name, "coefficient": mu.to_string()}))
                .collect();
            let function = integral.function.map(|f| cx.display(f).to_string());
            json!({"rows": rows, "function": function})
        })
        .collect();
    let text: Vec<String> = integrals.iter().map(|i| i.describe(model, cx)).collect();
    fact(
        "integrals",
        "integrals of the constraints (exact combinations of rows)",
        Value::Array(json),
        listed_or_none(&text),
    )
}

/// The sets where the mass matrix loses rank, each with its warning.
fn coordinate_sets_fact(model: &Model, cx: &Context, analysis: &ConstraintAnalysis) -> Item {
    let sets = &analysis.coordinate_sets;
    let json: Vec<Value> = sets
        .iter()
        .map(|set| {
            json!({
                "coordinates": [set.coordinate_name(model)],
                "set": set.describe(cx),
            })
        })
        .collect();
    let text: Vec<String> = sets.iter().map(|set| set.warning(model, cx)).collect();
    let text = match text.is_empty() {
        true => "none".to_string(),
        false => text.join("; "),
    };
    fact(
        "coordinate_singularities",
        "coordinate singularities",
        Value::Array(json),
        text,
    )
}

pub(super) fn dalembert_section(
    model: &Model,
    cx: &mut Context,
    derivation: &LagrangeDalembert,
) -> Section {
    let potential = cx.expression_of(&model.potential_energy);
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
            matrix_item(cx, "mass_matrix", label("g", "g"), &model.mass_matrix),
            expression_item(cx, "potential", label("V", "V"), potential),
            matrix_item(
                cx,
                "constraint_matrix",
                label("A", "A"),
                &model.constraint_matrix,
            ),
            matrix_item(cx, "input_matrix", label("B", "B"), &model.input_matrix),
            force_item(cx, &system.force),
            drift_item(cx, &system.drift),
            word_fact("solve", "acceleration computed by", solve),
        ],
    }
}

/// `B u - C - dV/dq` as a matrix when exact; a statement of how it is
/// computed when not.
fn force_item(cx: &mut Context, force: &lagrange_dalembert::Force) -> Item {
    let text = "B u - C - dV/dq";
    match &force.exact {
        Some(exact) => matrix_item(
            cx,
            "force",
            label(text, "B u - C - \\frac{\\partial V}{\\partial q}"),
            exact,
        ),
        None => word_fact(
            "force",
            text,
            "structured: the derivatives of the energies' expressions, not expanded \
             (the exact form is too large to derive)",
        ),
    }
}

/// `-Adot qdot` as a matrix when exact; a statement of how it is computed when not.
fn drift_item(cx: &mut Context, drift: &lagrange_dalembert::Drift) -> Item {
    match drift {
        lagrange_dalembert::Drift::Exact(drift) => matrix_item(
            cx,
            "drift",
            label("-Adot qdot", "-\\dot{A} \\dot{q}"),
            drift,
        ),
        lagrange_dalembert::Drift::Structured(_) => word_fact(
            "drift",
            "-Adot qdot",
            "structured: the derivatives of the rows along qdot, not expanded \
             (the exact form is too large to derive)",
        ),
    }
}

/// X as a matrix when exact; a statement of how it is computed when not.
fn basis_item(cx: &mut Context, analysis: &ConstraintAnalysis) -> Item {
    match &analysis.basis.fields {
        Some(fields) => matrix_item(
            cx,
            "basis",
            label("X = [X1 ... Xk], a basis of D", "X"),
            fields,
        ),
        None => word_fact(
            "basis",
            "X = [X1 ... Xk], a basis of D",
            "structured: the dependent speeds by elimination of A, not expanded \
             (the exact form is too large to derive)",
        ),
    }
}

pub(super) fn reduced_section(
    model: &Model,
    cx: &mut Context,
    reduced: &PortHamiltonian,
    rhs: &[ExprId],
) -> Section {
    let mut items = vec![
        flag_fact(
            "declared_basis",
            "momentum basis declared",
            reduced.declared_basis,
        ),
        names_fact("momenta", "momenta", reduced.momentum_names.clone()),
    ];
    match &reduced.exact {
        Some(exact) => items.extend(exact_items(model, cx, reduced, exact, rhs)),
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
    model: &Model,
    cx: &mut Context,
    reduced: &PortHamiltonian,
    exact: &Exact,
    rhs: &[ExprId],
) -> Vec<Item> {
    let hamiltonian = cx.expression_of(&exact.hamiltonian);
    let equations = rates(cx, &reduced.state(model), rhs);
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
        .map(|(key, symbol, matrix)| matrix_item(cx, key, symbol, matrix))
        .collect();
    items.extend([
        flag_fact("metric_constant", "gbar constant", reduced.metric_constant),
        flag_fact("metric_diagonal", "gbar diagonal", reduced.metric_diagonal),
        expression_item(cx, "hamiltonian", label("Hbar", "\\bar{H}"), hamiltonian),
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
            "structured (the exact form is too large to derive): h = X^T g, \
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

pub(super) fn momentum_section(
    model: &Model,
    cx: &mut Context,
    momentum: &Momentum,
    inputs: &[SymbolId],
) -> Section {
    let shape: Vec<String> = momentum
        .shape
        .iter()
        .map(|&i| model.coordinates[i].declared.name.clone())
        .collect();
    let names: Vec<Printed> = momentum
        .momenta
        .iter()
        .map(|&p| symbol_name(cx, p))
        .collect();
    let momenta: Vec<String> = names.iter().map(|name| name.text.clone()).collect();
    let mut items = vec![
        names_fact("shape", "shape coordinates r", shape),
        names_fact("momenta", "momenta p", momenta),
        matrix_item(cx, "basis", label("e", "e"), &momentum.basis),
        matrix_item(
            cx,
            "connection",
            label("A_nh", "A_{\\mathrm{nh}}"),
            &momentum.connection,
        ),
        matrix_item(
            cx,
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
                cx,
                &format!("{tensor}_{}", name.text),
                symbol,
                matrix,
            ));
        }
    }
    items.push(matrix_item(
        cx,
        "input_coupling",
        label("h B", "h B"),
        &momentum.input_coupling,
    ));
    let forced = forced_momentum_rhs(cx, momentum, inputs);
    items.push(Item::Equations {
        key: "equations".into(),
        lines: rates(cx, &momentum.momenta, &forced),
    });
    Section {
        key: "momentum",
        title: "Momentum equation (Bloch-Krishnaprasad-Marsden-Murray; Koon & Marsden)",
        items,
    }
}

/// `pdot_i = rhs_i + sum_j (h B)_ij u_j`.
fn forced_momentum_rhs(cx: &mut Context, momentum: &Momentum, inputs: &[SymbolId]) -> Vec<ExprId> {
    let coupling = &momentum.input_coupling;
    (0..momentum.rhs.len())
        .map(|i| {
            let mut terms = vec![cx.expression_of(&momentum.rhs[i])];
            for (j, &input) in inputs.iter().enumerate() {
                let entry = cx.expression_of(coupling.get(i, j));
                let u = cx.symbol(input);
                terms.push(cx.mul2(entry, u));
            }
            cx.add(&terms)
        })
        .collect()
}
