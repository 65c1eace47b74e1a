//! Inputs as linear forms of coordinate names: each column equals the one
//! written out position by position, a wrong term is reported at its
//! token, and a robot driven by such forms accelerates as one driven
//! wheel by wheel.

use crate::interpret::InterpretedModel;
use crate::model::check;
use crate::syntax::parse_str;

/// The differential-drive robot (`models/differential_drive.model`)
/// without its drawing, with the inputs `inputs`.
fn robot(inputs: &str) -> String {
    format!(
        "pub struct Robot {{
    coordinates: [x, y, theta, phi_r, phi_l],
    parameters: [m = 4.0, j = 0.1, r = 0.05, b = 0.15, jw = 0.002],
    define: [half_track = b/2],
    kinetic_energy: m/2*(dot(x)^2 + dot(y)^2) + j/2*dot(theta)^2
        + jw/2*(dot(phi_r)^2 + dot(phi_l)^2),
    constraints: [
        lateral = -sin(theta)*dot(x) + cos(theta)*dot(y),
        right = cos(theta)*dot(x) + sin(theta)*dot(y) + b*dot(theta) - r*dot(phi_r),
        left = cos(theta)*dot(x) + sin(theta)*dot(y) - b*dot(theta) - r*dot(phi_l),
    ],
    inputs: [{inputs}],
}}"
    )
}

/// Each pair of inputs `(form, column)` gives the same column of B(q),
/// exactly: the difference of their normal forms is zero.
#[test]
fn a_linear_form_is_the_column_written_out() {
    let pairs = [
        ("phi_l + phi_r", "[0, 0, 0, 1, 1]"),
        (
            "cos(theta)*x + sin(theta)*y",
            "[cos(theta), sin(theta), 0, 0, 0]",
        ),
        (
            "-x*sin(theta) - (-y)*cos(theta)",
            "[-sin(theta), cos(theta), 0, 0, 0]",
        ),
        (
            "b*(2*x)*m/r^2 - theta/j + phi_l/(m + x^2)",
            "[2*b*m/r^2, 0, -1/j, 0, 1/(m + x^2)]",
        ),
        (
            "phi_r - 3*phi_r/2 + half_track*theta",
            "[0, 0, b/2, -1/2, 0]",
        ),
        ("theta", "[0, 0, 1, 0, 0]"),
    ];
    let inputs: Vec<String> = (pairs.iter().enumerate())
        .flat_map(|(i, (form, column))| [format!("f{i} = {form}"), format!("c{i} = {column}")])
        .collect();
    let source = robot(&inputs.join(", "));
    let (model, cx) = check(&parse_str(&source).expect("parses")).expect("checks");
    let b = &model.input_matrix;
    for (i, (form, _)) in pairs.iter().enumerate() {
        for row in 0..5 {
            let difference = b.get(row, 2 * i).sub(b.get(row, 2 * i + 1), cx.atoms());
            assert!(difference.is_zero(), "{form}, row {row}");
        }
    }
}

/// The one error of the robot with `inputs`, with the text before it
/// (`m.model:line:column: error: `) checked against `token`'s position.
fn assert_error_at(inputs: &str, token: &str, message: &str) {
    let source = robot(inputs);
    let errors = check(&parse_str(&source).expect("parses"))
        .map(|_| ())
        .expect_err("rejected");
    let rendered = errors.render("m.model");
    let offset = source.rfind(token).expect("the token is in the source");
    let line = source[..offset].matches('\n').count() + 1;
    let column = offset - source[..offset].rfind('\n').map_or(0, |i| i + 1) + 1;
    let expected = format!("m.model:{line}:{column}: error: ");
    assert!(
        rendered.starts_with(&expected),
        "{rendered}\nexpected {expected}"
    );
    assert!(rendered.contains(message), "{rendered}");
}

#[test]
fn a_term_without_one_coordinate_name_as_a_factor_is_an_error() {
    assert_error_at(
        "turn = phi_r - y*x",
        "x]",
        "this term has two, `y` and `x`, and either could be the direction",
    );
    assert_error_at(
        "turn = phi_r + 2*(x + y)",
        "2*(x",
        "this term has no coordinate name as a factor",
    );
    assert_error_at(
        "turn = phi_r + m/x",
        "m/x",
        "this term has no coordinate name as a factor",
    );
    assert_error_at("turn = phi_r + dot(theta)*x", "dot(theta)", "no velocities");
    assert_error_at(
        "turn = phi_r + x/(m - m)",
        "m - m)",
        "divides by an expression that is exactly zero",
    );
}

/// The robot driven by `drive = phi_r + phi_l` and `turn = phi_r - phi_l`
/// accelerates as the one driven wheel by wheel with `drive + turn` on the
/// right wheel and `drive - turn` on the left.
#[test]
fn a_robot_driven_by_linear_forms_runs() {
    let by_forms =
        InterpretedModel::from_source(&robot("drive = phi_r + phi_l, turn = phi_r - phi_l"))
            .expect("derives");
    let by_wheels =
        InterpretedModel::from_source(&robot("u_right = phi_r, u_left = phi_l")).expect("derives");
    let q = [0.3, -1.2, 0.7, 2.0, -0.4];
    let theta: f64 = 0.7;
    let (speed, turning) = (0.8, -0.5);
    let qdot = [
        speed * theta.cos(),
        speed * theta.sin(),
        turning,
        (speed + 0.15 * turning) / 0.05,
        (speed - 0.15 * turning) / 0.05,
    ];
    let (drive, turn) = (0.02, -0.005);
    let (forms, _) = by_forms
        .acceleration(&q, &qdot, &[drive, turn])
        .expect("runs");
    let (wheels, _) = by_wheels
        .acceleration(&q, &qdot, &[drive + turn, drive - turn])
        .expect("runs");
    for (a, b) in forms.iter().zip(&wheels) {
        assert!(
            (a - b).abs() <= 1e-12 * (1.0 + b.abs()),
            "{forms:?} vs {wheels:?}"
        );
    }
    assert!(forms.iter().any(|a| a.abs() > 1e-3), "{forms:?}");
}
