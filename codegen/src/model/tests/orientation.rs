//! `orient` frames: the unit constraint of their Euler parameters, the
//! kinetic energy's term along `e`, and the compile errors of their
//! declarations.

use super::{checked, errors};
use crate::sym::SymbolId;

const BALL: &str = include_str!("../../../../models/chaplygin_ball.model");

/// The Chaplygin ball's mass matrix in `(e0, e1, e2, e3)` is
/// `4 E^T I E + mu e e^T` with `E` of docs/MATH.md section 5 and
/// `mu = 4/3 (a + b + c)`, entry by entry at a point off the unit sphere.
#[test]
fn the_balls_metric_is_four_e_transpose_i_e_plus_mu_e_e_transpose() {
    let (model, mut cx) = checked(BALL);
    let (a, b, c) = (0.08, 0.1, 0.12);
    let e = [0.7, -0.3, 0.5, 0.2];
    let [e0, e1, e2, e3] = e;
    let rows = [[-e1, e0, e3, -e2], [-e2, -e3, e0, e1], [-e3, e2, -e1, e0]];
    let inertia = [a, b, c];
    let mu = 4.0 / 3.0 * (a + b + c);
    let point: Vec<(&str, f64)> = vec![
        ("x", 0.4),
        ("y", -1.2),
        ("e0", e0),
        ("e1", e1),
        ("e2", e2),
        ("e3", e3),
        ("m", 1.0),
        ("r", 0.5),
        ("a", a),
        ("b", b),
        ("c", c),
        ("g", 9.81),
    ];
    let symbols: Vec<(SymbolId, f64)> = (point.iter())
        .map(|&(name, value)| (cx.find_symbol(name).expect(name), value))
        .collect();
    let value_of = |symbol: SymbolId| {
        (symbols.iter().find(|(s, _)| *s == symbol)).map_or(f64::NAN, |&(_, value)| value)
    };
    for i in 0..4 {
        for j in 0..4 {
            let turning: f64 = (0..3)
                .map(|k| 4.0 * rows[k][i] * inertia[k] * rows[k][j])
                .sum();
            let expected = turning + mu * e[i] * e[j];
            let found = cx.evaluate_normal(model.mass_matrix.get(2 + i, 2 + j), &value_of);
            assert!(
                (found - expected).abs() < 1e-12,
                "g[{i}][{j}] = {found}, not {expected}"
            );
        }
    }
}

/// The tool adds `ball_unit: e0^2 + e1^2 + e2^2 + e3^2 - 1` to the
/// holonomic constraints, and its velocity form to the rows.
#[test]
fn an_orient_frame_adds_its_unit_constraint() {
    let (model, _) = checked(BALL);
    let names: Vec<&str> = (model.mechanism.holonomic.iter())
        .map(|d| d.name.as_str())
        .collect();
    assert_eq!(names, ["ball_unit"]);
    let rows: Vec<&str> = model.constraints.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(rows, ["rolling_1", "rolling_2", "ball_unit"]);
}

/// The ball's source with its frames section replaced.
fn ball_with(frames: &str) -> String {
    BALL.replace("frames: [ball = orient(ground, e0, e1, e2, e3)],", frames)
}

#[test]
fn a_bad_orient_frame_is_reported_at_its_token() {
    let not_a_coordinate = errors(&ball_with(
        "frames: [ball = orient(ground, e0, e1, e2, 2*e3)],",
    ));
    assert!(
        not_a_coordinate.contains("an Euler parameter is a coordinate declared in `coordinates`"),
        "{not_a_coordinate}"
    );
    let repeated = errors(&ball_with(
        "frames: [ball = orient(ground, e0, e1, e1, e3)],",
    ));
    assert!(
        repeated.contains("four different coordinates"),
        "{repeated}"
    );
    let shared = errors(&ball_with(
        "frames: [ball = orient(ground, e0, e1, e2, e3), twin = orient(ground, e3, x, y, e1)],",
    ));
    assert!(
        shared.contains("`e3` is already an Euler parameter of frame `ball`"),
        "{shared}"
    );
    let arity = errors(&ball_with("frames: [ball = orient(ground, e0, e1, e2)],"));
    assert!(
        arity.contains("`name = orient(parent, e0, e1, e2, e3)`"),
        "{arity}"
    );
    let clash = errors(&BALL.replace(
        "    gravity:",
        "    holonomic: [ball_unit = x],\n    gravity:",
    ));
    assert!(
        clash.contains("`ball_unit` names the unit constraint the tool adds"),
        "{clash}"
    );
}
