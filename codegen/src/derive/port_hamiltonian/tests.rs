//! Tests of the reduced port-Hamiltonian derivation.

use super::{Exact, PortHamiltonian, PortHamiltonianError, derive, prove_skew};
use crate::derive::constraints::distribution_basis;
use crate::model::{Model, check};
use crate::sym::Context;
use crate::sym::{ExprId, Matrix, Poly, RationalFunction};
use crate::syntax::parse_str;

const SLEIGH: &str = include_str!("../../../../models/sleigh.model");

/// The snakeboard with its momentum basis removed: the tool picks its own.
fn snakeboard_without_basis() -> String {
    let fixture = crate::fixtures::SNAKEBOARD;
    let start = fixture.find("    momentum_basis").expect("declared");
    let end = fixture.find("    symmetry").expect("declared");
    format!("{}{}", &fixture[..start], &fixture[end..])
}

fn sources() -> [String; 3] {
    [
        crate::fixtures::SNAKEBOARD.to_string(),
        snakeboard_without_basis(),
        SLEIGH.to_string(),
    ]
}

fn derived(source: &str) -> (Model, Context, PortHamiltonian) {
    let (model, mut cx) = check(&parse_str(source).expect("parses")).expect("checks");
    let basis = distribution_basis(&model, &mut cx).expect("regular at the defaults");
    let reduced = derive(&model, &mut cx, &basis).expect("derives");
    (model, cx, reduced)
}

fn exact(reduced: &PortHamiltonian) -> &Exact {
    reduced.exact.as_ref().expect("derived exactly")
}

/// True when the expressions equal the normal forms as rational functions.
fn equal(cx: &mut Context, expressions: &[ExprId], forms: &[RationalFunction]) -> bool {
    expressions.iter().zip(forms).all(|(&e, form)| {
        let structured = cx.normal(e).expect("normal form");
        let atoms = cx.atoms().clone();
        structured.sub(form, &atoms).is_zero()
    })
}

/// The structured derivation (the dh identity, `qdot = X alpha`, the flow
/// without `gbar gbar_inv`) against the exact one, on the models with the
/// tool's basis: every matrix and the flow equal as rational functions,
/// and the same facts.
#[test]
fn the_structured_form_equals_the_exact_form() {
    for source in [snakeboard_without_basis(), SLEIGH.to_string()] {
        let (model, mut cx, reduced) = derived(&source);
        assert!(reduced.exact.is_some(), "the exact form fits");
        let basis = distribution_basis(&model, &mut cx).expect("regular at the defaults");
        let structured =
            super::structured::derive(&model, &mut cx, &basis, &reduced.momenta, &reduced.inputs)
                .expect("derives");
        let exact = exact(&reduced).clone();
        let pairs: [(&str, &[ExprId], &[RationalFunction]); 9] = [
            (
                "X",
                structured.velocity_map.entries(),
                exact.velocity_map.entries(),
            ),
            (
                "P g",
                structured.momentum_map.entries(),
                exact.momentum_map.entries(),
            ),
            (
                "gbar_inv",
                structured.metric_inverse.entries(),
                exact.metric_inverse.entries(),
            ),
            ("gbar", structured.metric.entries(), exact.metric.entries()),
            (
                "Jbar",
                structured.structure.entries(),
                exact.structure.entries(),
            ),
            (
                "Bbar",
                structured.input_matrix.entries(),
                exact.input_matrix.entries(),
            ),
            ("dHbar/dx", &structured.gradient, &exact.gradient),
            ("xdot", &structured.rhs, &exact.rhs),
            ("y", &structured.output, &exact.output),
        ];
        for (name, structured, expanded) in pairs {
            assert!(equal(&mut cx, structured, expanded), "{name}");
        }
        assert!(equal(
            &mut cx,
            &[structured.hamiltonian],
            std::slice::from_ref(&exact.hamiltonian)
        ));
        let perturbed = cx.add2(structured.rhs[0], structured.rhs[1]);
        assert!(!equal(&mut cx, &[perturbed], &exact.rhs[..1]));
        let structured_facts =
            super::facts_at_points(&model, &mut cx, &structured.metric_inverse).expect("evaluates");
        assert_eq!(
            structured_facts,
            (reduced.metric_constant, reduced.metric_diagonal)
        );
    }
}

fn parameter(model: &Model, cx: &mut Context, name: &str) -> RationalFunction {
    let symbol = model
        .parameters
        .iter()
        .find(|p| p.variable.declared.name == name)
        .expect("declared")
        .variable
        .symbol;
    RationalFunction::from_poly(Poly::atom(cx.symbol_atom(symbol)))
}

#[test]
fn the_snakeboard_metric_is_exactly_diag_m_jt_jw() {
    let (model, mut cx, reduced) = derived(crate::fixtures::SNAKEBOARD);
    let mut expected = Matrix::zeros(3, 3);
    for (i, name) in ["m", "jt", "jw"].into_iter().enumerate() {
        expected.set(i, i, parameter(&model, &mut cx, name));
    }
    assert_eq!(exact(&reduced).metric, expected);
    assert!(reduced.metric_constant && reduced.metric_diagonal);
    assert!(reduced.declared_basis);
    assert_eq!(reduced.momentum_names, ["group", "torso", "wheels"]);
}

#[test]
fn the_snakeboard_has_no_gyroscopic_terms() {
    let (_, _, reduced) = derived(crate::fixtures::SNAKEBOARD);
    assert!(exact(&reduced).gyroscopic.is_zero());
}

#[test]
fn the_projection_is_a_left_inverse_of_the_basis() {
    for source in sources() {
        let (_, cx, reduced) = derived(&source);
        let exact = exact(&reduced);
        let product = exact
            .projection
            .mul(&exact.basis.transpose(), cx.atoms())
            .expect("fits");
        assert_eq!(product, Matrix::identity(reduced.momenta.len()));
    }
}

#[test]
fn the_structure_matrix_is_exactly_skew() {
    for source in sources() {
        let (_, cx, reduced) = derived(&source);
        let atoms = cx.atoms();
        let structure = &exact(&reduced).structure;
        assert!(structure.is_skew(atoms));
        let sum = structure.add(&structure.transpose(), atoms).expect("fits");
        assert!(sum.is_zero());
    }
}

#[test]
fn a_matrix_that_is_not_skew_is_reported() {
    let mut lopsided = Matrix::zeros(2, 2);
    lopsided.set(0, 1, RationalFunction::one());
    let atoms = crate::sym::Atoms::default();
    assert_eq!(
        prove_skew(&lopsided, &atoms),
        Err(PortHamiltonianError::NotSkew { row: 0, column: 1 })
    );
    assert_eq!(
        prove_skew(
            &Matrix::identity(2)
                .neg()
                .add(&Matrix::identity(2), &atoms)
                .unwrap(),
            &atoms
        ),
        Ok(())
    );
}

/// The tool's own basis for the sleigh, chosen in the body frame:
/// `X = [(cos theta, sin theta, 0), (0, 0, 1)]` (forward speed and turning
/// rate). By hand, with `g` the sleigh's mass matrix: `h = (g X)^T` has rows
/// `m (cos, sin, 0)` and `(-m a sin, m a cos, inertia + m a^2)`,
/// `gbar_inv = X^T g X = diag(m, inertia + m a^2)`, the bracket
/// `[X_1, X_2] = (sin, -cos, 0)` gives `X^T g [X_1, X_2] = (0, -m a)`, so
/// `S_12 = m a alpha2` and `Gamma_12 = a alpha2 / (inertia + m a^2)`: with
/// `alpha = (v, omega)`, `vdot = a omega^2` and
/// `(inertia + m a^2) omegadot = -m a v omega`, the sleigh's equations.
#[test]
fn the_sleigh_gets_the_tools_basis_in_the_body_frame() {
    let (model, mut cx, reduced) = derived(SLEIGH);
    assert!(!reduced.declared_basis);
    assert_eq!(reduced.momentum_names, ["alpha1", "alpha2"]);
    let exact = exact(&reduced).clone();
    let mut text = |entries: &[&str]| -> Vec<RationalFunction> {
        entries
            .iter()
            .map(|e| model.normal_of_text(&mut cx, e).expect("parses"))
            .collect()
    };
    let basis = text(&[
        "m*cos(theta)",
        "m*sin(theta)",
        "0",
        "-m*a*sin(theta)",
        "m*a*cos(theta)",
        "inertia + m*a^2",
    ]);
    let metric = text(&["1/m", "0", "0", "1/(inertia + m*a^2)"]);
    let coupling = text(&["a/(inertia + m*a^2)"]);
    let alpha2 = cx.symbol(reduced.momenta[1]);
    let alpha2 = cx.normal(alpha2).expect("normal");
    let atoms = cx.atoms().clone();
    let gamma_12 = coupling[0].mul(&alpha2, &atoms);
    let gyroscopic = [
        RationalFunction::zero(),
        gamma_12.clone(),
        gamma_12.neg(),
        RationalFunction::zero(),
    ];
    for (derived, expected) in [
        (&exact.basis, &basis[..]),
        (&exact.metric, &metric[..]),
        (&exact.gyroscopic, &gyroscopic[..]),
    ] {
        for (entry, expected) in derived.entries().iter().zip(expected) {
            assert!(entry.sub(expected, &atoms).is_zero());
        }
    }
    assert!(reduced.metric_constant && reduced.metric_diagonal);
}

#[test]
fn the_snakeboard_without_a_basis_gets_the_tools() {
    let (_, mut cx, reduced) = derived(&snakeboard_without_basis());
    assert!(!reduced.declared_basis);
    assert_eq!(reduced.momentum_names, ["alpha1", "alpha2", "alpha3"]);
    let exact = exact(&reduced);
    for (name, matrix) in [("gbar", &exact.metric), ("Gamma", &exact.gyroscopic)] {
        for (i, entry) in matrix.entries().iter().enumerate() {
            let expression = cx.expression_of(entry);
            println!(
                "snakeboard (own basis) {name}[{i}] = {}",
                cx.display(expression)
            );
        }
    }
    assert!(!reduced.metric_constant && !reduced.metric_diagonal);
    assert!(!exact.gyroscopic.is_zero());
}

#[test]
fn momenta_of_inputs_never_capture_a_parameter() {
    let source = crate::fixtures::SNAKEBOARD.replace("u_torso = psi", "m = psi");
    let (_, cx, reduced) = derived(&source);
    let input = cx.symbol_info(reduced.inputs[0]);
    assert_eq!(input.name, "m'");
    assert_eq!(input.kind, crate::sym::SymbolKind::Auxiliary);
}
