use super::{Format, UnknownFormat, derive_document};
use crate::fixtures::SNAKEBOARD;
use crate::ir::Interpreter;
use serde_json::Value;

const SLEIGH: &str = include_str!("../../../models/sleigh.model");

/// A free particle in the plane: no constraints, no symmetry.
const PARTICLE: &str = r#"
pub struct Particle {
    coordinates: [x, y],
    parameters: [m = 2.0],
    kinetic_energy: m/2*(dot(x)^2 + dot(y)^2),
}
"#;

fn document(source: &str, format: Format) -> String {
    derive_document(source, format, &Interpreter).expect("the model compiles")
}

/// MATH.md 3.1 with alpha = (group, torso, wheels), u = (u_torso,
/// u_wheels): `xdot = (alpha1/m) cos phi cos theta`, ...,
/// `alpha1dot = -(sin phi / r) u1`, `alpha2dot = u1`, `alpha3dot = u2`,
/// written as the printer orders factors (functions last, the
/// denominator's factors after the fraction bar).
#[test]
fn the_snakeboard_latex_has_the_reduced_equations_of_math_3_1() {
    let latex = document(SNAKEBOARD, Format::Latex);
    let equations = [
        r"\dot{x} &= \frac{\mathrm{group} \cos\phi \cos\theta}{m}",
        r"\dot{y} &= \frac{\mathrm{group} \cos\phi \sin\theta}{m}",
        r"\dot{\theta} &= \frac{\mathrm{group} \sin\phi}{m r}",
        r"\dot{\psi} &= \frac{\mathrm{torso}}{\mathrm{jt}} - \frac{\mathrm{group} \sin\phi}{m r}",
        r"\dot{\phi} &= \frac{\mathrm{wheels}}{\mathrm{jw}}",
        r"\dot{\mathrm{group}} &= -\frac{u_{\mathrm{torso}} \sin\phi}{r}",
        r"\dot{\mathrm{torso}} &= u_{\mathrm{torso}}",
        r"\dot{\mathrm{wheels}} &= u_{\mathrm{wheels}}",
    ];
    for equation in equations {
        assert!(latex.contains(equation), "{equation} not in\n{latex}");
    }
    let metric = r"\bar{g} = \begin{bmatrix} m & 0 & 0 \\ 0 & \mathrm{jt} & 0 \\ 0 & 0 & \mathrm{jw} \end{bmatrix}";
    assert!(latex.contains(metric), "{latex}");
    assert!(latex.starts_with("\\documentclass{article}"));
    assert!(latex.ends_with("\\end{document}\n"));
}

/// MATH.md 4.1: `pdot = (m r Jt cos phi / Delta) psidot phidot + (Jt sin
/// phi cos phi / Delta) phidot p`, `Delta = m r^2 + Jt sin^2 phi`; the
/// document's denominator is `Jt + m r^2 - Jt cos^2 phi = Delta`.
#[test]
fn the_snakeboard_momentum_equation_is_that_of_math_4_1() {
    let latex = document(SNAKEBOARD, Format::Latex);
    let equation = r"\dot{p}_{1} &= \frac{\dot{\psi} \dot{\phi} m r \mathrm{jt} \cos\phi + \dot{\phi} \mathrm{jt} p_{1} \cos\phi \sin\phi}{\mathrm{jt} + m r^{2} - \mathrm{jt} \cos^{2}\phi}";
    assert!(latex.contains(equation), "{latex}");
    let text = document(SNAKEBOARD, Format::Text);
    assert!(
        text.contains("  e =\n    [cos(phi), 0, sin(phi)/r]\n"),
        "{text}"
    );
}

#[test]
fn the_json_document_has_every_section() {
    let json: Value =
        serde_json::from_str(&document(SNAKEBOARD, Format::Json)).expect("valid JSON");
    assert_eq!(json["model"], "Snakeboard");
    assert_eq!(
        json["names"]["coordinates"],
        serde_json::json!(["x", "y", "theta", "psi", "phi"])
    );
    assert_eq!(
        json["names"]["momenta"],
        serde_json::json!(["group", "torso", "wheels"])
    );
    assert_eq!(json["sizes"]["s"], 8);
    assert_eq!(
        json["constraints"]["growth_vector"],
        serde_json::json!([3, 4, 5])
    );
    assert_eq!(json["constraints"]["integrable"], false);
    assert_eq!(
        json["constraints"]["classification"],
        "completely nonholonomic"
    );
    assert_eq!(json["constraints"]["basis"]["columns"], 3);
    let dalembert = &json["lagrange_dalembert"];
    assert_eq!(dalembert["mass_matrix"]["rows"], 5);
    assert_eq!(dalembert["mass_matrix"]["text"][2][2], "jt + m*r^2");
    assert_eq!(dalembert["potential"]["text"], "0");
    assert_eq!(
        dalembert["input_matrix"]["text"][3],
        serde_json::json!(["1", "0"])
    );
    assert_eq!(dalembert["equations"].as_array().map(Vec::len), Some(2));
    let reduced = &json["port_hamiltonian"];
    for key in [
        "momentum_basis",
        "metric",
        "gyroscopic",
        "structure_matrix",
        "input_matrix",
        "hamiltonian",
    ] {
        assert!(reduced[key].is_object(), "{key}");
    }
    let equations = reduced["equations"].as_array().expect("equations");
    assert_eq!(equations.len(), 8);
    assert_eq!(equations[5]["lhs"]["text"], "dot(group)");
    assert_eq!(equations[5]["rhs"]["text"], "-sin(phi)*u_torso/r");
    assert_eq!(json["momentum"]["momenta"], serde_json::json!(["p1"]));
    assert_eq!(
        json["momentum"]["equations"].as_array().map(Vec::len),
        Some(1)
    );
    let report = json["report"]["text"].as_str().expect("the report");
    assert!(report.starts_with("Snakeboard\n"));
    assert!(report.contains("growth vector (3, 4, 5)"));
}

#[test]
fn the_sleigh_document_states_its_classification_and_growth() {
    let text = document(SLEIGH, Format::Text);
    assert!(
        text.contains("  classification: completely nonholonomic\n"),
        "{text}"
    );
    assert!(text.contains("  growth vector: (2, 3)\n"), "{text}");
    assert!(
        text.contains("  integrable (A [X_i, X_j] = 0 for all i, j): no\n"),
        "{text}"
    );
    let json: Value = serde_json::from_str(&document(SLEIGH, Format::Json)).expect("valid JSON");
    assert_eq!(
        json["constraints"]["growth_vector"],
        serde_json::json!([2, 3])
    );
    assert_eq!(
        json["names"]["momenta"],
        serde_json::json!(["alpha1", "alpha2"])
    );
}

#[test]
fn a_model_without_symmetry_has_a_null_momentum_section() {
    let json: Value = serde_json::from_str(&document(PARTICLE, Format::Json)).expect("valid JSON");
    assert_eq!(json["momentum"], Value::Null);
    assert_eq!(json["constraints"]["classification"], "unconstrained");
    assert_eq!(json["lagrange_dalembert"]["constraint_matrix"]["rows"], 0);
    let text = document(PARTICLE, Format::Text);
    assert!(text.contains("  B = (empty, 2 x 0)\n"), "{text}");
    assert!(!text.contains("Momentum equation"));
}

#[test]
fn a_broken_model_is_its_diagnostics() {
    let broken = SLEIGH.replace("dot(x) - a", "dot(z) - a");
    let diagnostics =
        derive_document(&broken, Format::Text, &Interpreter).expect_err("z is not declared");
    assert!(diagnostics.render("sleigh.model").contains("sleigh.model:"));
}

#[test]
fn formats_are_named_as_on_the_command_line() {
    assert_eq!("text".parse(), Ok(Format::Text));
    assert_eq!("latex".parse(), Ok(Format::Latex));
    assert_eq!("json".parse(), Ok(Format::Json));
    assert_eq!("pdf".parse::<Format>(), Err(UnknownFormat("pdf".into())));
}

/// A chain of three wheeled links: its reduced form is structured, and the
/// document says how it is computed instead of printing expanded matrices.
#[test]
fn a_structured_reduced_form_is_described_not_expanded() {
    let text = document(&crate::fixtures::chain_of_links(3), Format::Text);
    assert!(text.contains("reduced form derived: structured"), "{text}");
    assert!(text.contains("gbar facts decided"), "{text}");
    assert!(text.contains("X = [X1 ... Xk], a basis of D ="), "{text}");
    assert!(!text.contains("Jbar ="), "{text}");
    let json: Value =
        serde_json::from_str(&document(&crate::fixtures::chain_of_links(3), Format::Json))
            .expect("valid JSON");
    assert!(json["port_hamiltonian"].is_object(), "{json}");
}

/// The sleigh's basis of D is chosen on the body rows: its speeds are the
/// blade's forward and sideways velocities along the body's axes and the
/// turning rate, named after the se2 factor's coordinates.
#[test]
fn a_body_frame_basis_names_its_speeds_after_the_body_velocity() {
    let text = document(SLEIGH, Format::Text);
    assert!(text.contains("dependent speeds: v_y_body"), "{text}");
    assert!(
        text.contains("independent speeds: v_x_body, omega_theta"),
        "{text}"
    );
    let latex = document(SLEIGH, Format::Latex);
    assert!(
        latex.contains(r"\item[independent speeds] v\_x\_body, omega\_theta"),
        "{latex}"
    );
    let json: Value = serde_json::from_str(&document(SLEIGH, Format::Json)).expect("JSON");
    assert_eq!(
        json["constraints"]["independent_speeds"],
        serde_json::json!(["v_x_body", "omega_theta"])
    );
    // without a symmetry the speeds are the coordinates' own
    let plain = document(
        &SLEIGH.replace("symmetry: se2(x, y, theta),", ""),
        Format::Text,
    );
    assert!(
        plain.contains("independent speeds: dot(x), dot(theta)"),
        "{plain}"
    );
}
